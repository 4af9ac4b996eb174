//! Per-primitive colours and opacities, computed once per frame (or on
//! first use), and the final conversion to sRGB.

use std::sync::OnceLock;

use hider_scene::shade::{SetupCache, prim_color, to_srgb8};
use hider_scene::{ScreenScene, ShadeMode, TextureOptions, TextureSampler};

/// `[r, g, b, opacity]` (linear, opacity clamped to [0, 1]) of `prim`.
#[inline]
pub(crate) fn prim_rgba(scene: &ScreenScene, prim: u32, mode: ShadeMode) -> [f32; 4] {
    let (rgb, alpha) = prim_color(scene, prim, mode);
    [rgb[0], rgb[1], rgb[2], alpha.clamp(0.0, 1.0)]
}

/// The sampler of a frame drawn under `mode`: `Some` when some
/// primitive's colour varies across it (a texture, vertex normals,
/// highlights: [`ScreenScene::varies`]) and the mode shows it (Lambert; id
/// colours are flat).
pub(crate) fn sampler(scene: &ScreenScene, mode: ShadeMode) -> Option<TextureSampler> {
    if mode != ShadeMode::Lambert {
        return None;
    }
    let sampler = TextureSampler::new(scene, TextureOptions::default());
    scene.varies(&sampler).then_some(sampler)
}

/// The colour of primitive `prim` at window point `(x, y)` when its colour
/// varies and the frame is shaded per point (`sampler`, see [`sampler`]);
/// `rgba`, its flat colour, otherwise. The opacity is the flat one (`d`),
/// times the texture alpha at the point for a material with partial alpha
/// ([`ScreenScene::partial_alpha_at`]). The primitive's shading setup
/// comes from `setups` (built there on first use).
#[inline]
pub(crate) fn at_point(
    scene: &ScreenScene,
    sampler: Option<&TextureSampler>,
    setups: &mut SetupCache,
    prim: u32,
    rgba: [f32; 4],
    x: f64,
    y: f64,
) -> [f32; 4] {
    let Some(sampler) = sampler else {
        return rgba;
    };
    let base = [rgba[0], rgba[1], rgba[2]];
    let [r, g, b] = scene.surface_rgb_cached(sampler, setups, prim, base, x, y);
    let a = scene
        .partial_alpha_at_cached(sampler, setups, prim, x, y)
        .map_or(rgba[3], |a| rgba[3] * a);
    [r, g, b, a]
}

/// The centre of pixel `(i, j)` in window coordinates: the A-buffer
/// shades a fragment once, there, whatever its coverage, as multisample
/// rasterisers shade (supersampling shades every sample, see
/// [`sample_point`]).
#[inline]
pub(crate) fn pixel_centre((i, j): (u32, u32)) -> (f64, f64) {
    (f64::from(i) + 0.5, f64::from(j) + 0.5)
}

/// The window coordinates of the sample of pixel `(i, j)` at `pos` (1/256
/// pixel inside the pixel, as [`crate::SamplePattern::positions`] gives
/// them).
#[inline]
pub(crate) fn sample_point((i, j): (u32, u32), pos: (i32, i32)) -> (f64, f64) {
    (
        f64::from(i) + f64::from(pos.0) / 256.0,
        f64::from(j) + f64::from(pos.1) / 256.0,
    )
}

/// The conversion table: `thresholds[v - 1]` is the smallest `f32` in
/// `[0, 1]` (as bits) that `to_srgb8` maps to `v` or more, for `v =
/// 1..=255`; `base[b >> 16]` is the value at the start of the bucket of
/// bits `b` (a bucket of 2^16 consecutive floats spans at most a step or
/// two, so a lookup is one load and a short scan of `steps` compares).
pub(crate) struct Table {
    /// The 255 thresholds, then `u32::MAX` (no value passes 255).
    thresholds: [u32; 256],
    base: Vec<u8>,
    /// The most thresholds inside one bucket: the scan's fixed length.
    steps: u32,
}

/// The table, or `None` if the conversion is found not to be monotonic
/// around a threshold.
///
/// `to_srgb8` clamps, applies the sRGB curve (a `powf`) and rounds; it is
/// non-decreasing (checked over every `f32` of `[0, 1]` with the platform's
/// `powf` when this table was introduced), so the 255 thresholds found by
/// bisection reproduce it exactly: the value of `x` is the number of
/// thresholds at or below it. Each threshold is also checked against its
/// neighbour below; should a platform's `powf` break monotonicity there,
/// the table is dropped and [`to_pixel`] calls `to_srgb8`.
fn table() -> Option<&'static Table> {
    static TABLE: OnceLock<Option<Table>> = OnceLock::new();
    TABLE
        .get_or_init(|| {
            let one = 1.0f32.to_bits();
            let level = |bits: u32| to_srgb8(f32::from_bits(bits));
            let mut thresholds = [u32::MAX; 256];
            for (k, t) in thresholds[..255].iter_mut().enumerate() {
                let v = k as u8 + 1;
                let (mut lo, mut hi) = (0u32, one);
                while lo < hi {
                    let mid = lo + (hi - lo) / 2;
                    if level(mid) >= v {
                        hi = mid;
                    } else {
                        lo = mid + 1;
                    }
                }
                if level(lo) != v || (lo > 0 && level(lo - 1) != v - 1) {
                    return None;
                }
                *t = lo;
            }
            let below = |bits: u32| thresholds.partition_point(|&t| t <= bits);
            let base = (0..=one >> 16).map(|key| below(key << 16) as u8).collect();
            let steps = (0..=one >> 16)
                .map(|key| (below(key << 16 | 0xffff) - below(key << 16)) as u32)
                .max()
                .unwrap_or(0);
            Some(Table {
                thresholds,
                base,
                steps,
            })
        })
        .as_ref()
}

/// `to_srgb8(x)`, exactly, from the table.
#[inline]
fn srgb8(table: &Table, x: f32) -> u8 {
    if x > 0.0 && x < 1.0 {
        let bits = x.to_bits();
        let mut v = table.base[(bits >> 16) as usize];
        // A fixed number of compares, not a loop that stops at the value:
        // how many thresholds a colour passes in its bucket varies from
        // pixel to pixel, and the loop's exit mispredicted.
        for _ in 0..table.steps {
            v += u8::from(table.thresholds[usize::from(v)] <= bits);
        }
        v
    } else {
        to_srgb8(x)
    }
}

/// Converts a linear colour (already composited over the black background)
/// to an opaque sRGB pixel: `to_srgb8` per channel.
pub(crate) fn to_pixel(rgb: [f32; 3]) -> [u8; 4] {
    Srgb::new().pixel(rgb)
}

/// [`to_pixel`] with the table looked up once, for loops over pixels.
#[derive(Clone, Copy)]
pub(crate) struct Srgb(Option<&'static Table>);

impl Srgb {
    /// The converter (builds the table on first use).
    pub(crate) fn new() -> Self {
        Srgb(table())
    }

    /// [`to_pixel`].
    #[inline]
    pub(crate) fn pixel(self, rgb: [f32; 3]) -> [u8; 4] {
        match self.0 {
            Some(t) => [srgb8(t, rgb[0]), srgb8(t, rgb[1]), srgb8(t, rgb[2]), 255],
            None => [to_srgb8(rgb[0]), to_srgb8(rgb[1]), to_srgb8(rgb[2]), 255],
        }
    }
}

impl Default for Srgb {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for Srgb {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("Srgb").field(&self.0.is_some()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table gives `to_srgb8`'s value around every threshold and on a
    /// dense sweep of `[0, 1]` and beyond.
    #[test]
    fn the_table_is_to_srgb8() {
        let t = table().expect("monotonic conversion");
        // The scan is short (it runs for every channel of every pixel).
        assert!((1..=4).contains(&t.steps), "{} steps", t.steps);
        for &b in &t.thresholds[..255] {
            for bits in b.saturating_sub(3)..=b + 3 {
                let x = f32::from_bits(bits);
                assert_eq!(srgb8(t, x), to_srgb8(x), "{x:e}");
            }
        }
        for k in 0..=200_000u32 {
            let x = k as f32 / 190_000.0 - 0.01;
            assert_eq!(srgb8(t, x), to_srgb8(x), "{x:e}");
        }
        // Every bucket start and end.
        for key in 0..=1.0f32.to_bits() >> 16 {
            for bits in [key << 16, (key << 16) | 0xffff] {
                let x = f32::from_bits(bits);
                assert_eq!(srgb8(t, x), to_srgb8(x), "{x:e}");
            }
        }
        for x in [
            f32::NAN,
            -0.0,
            0.0,
            1.0,
            f32::INFINITY,
            -1.0,
            2.0,
            f32::MIN_POSITIVE,
        ] {
            assert_eq!(srgb8(t, x), to_srgb8(x), "{x:e}");
        }
        assert_eq!(to_pixel([0.0, 0.5, 1.0]), [0, to_srgb8(0.5), 255, 255]);
    }
}
