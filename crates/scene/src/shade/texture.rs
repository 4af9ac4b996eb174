//! Diffuse textures (`map_Kd`): decoding (PNG files row by row with the
//! `png` crate, other formats with the `image` crate) and sampling,
//! nearest or bilinear, with repeat wrapping, from the mip level that fits
//! the pixel's footprint ([`super::mip`]), within the texture memory
//! budget ([`super::budget`]).
//!
//! Without the crate's `image` feature no image file is read: every
//! texture file is not loaded, with an error saying so ([`probe`],
//! [`Texture::load`], [`TextureRef::problem`]); textures built from bytes
//! ([`Texture::from_srgb8`]) still sample.
//!
//! Texels are kept as sRGB bytes and sampled in linear light, so that
//! bilinear filtering averages light, not sRGB codes. Texture coordinates
//! follow OBJ: `(0, 0)` is the *bottom*-left of the image, `v` grows
//! upward (tinyrenderer's z-buffer lesson, lesson 3, reads `vt` the same
//! way).
//!
//! The size is read from the file header and checked against
//! [`MAX_TEXTURE_SIDE`] and the texture budget before any texel is
//! decoded.
//!
//! An image's alpha channel is kept and classified once ([`AlphaClass`]):
//! opaque, a cut-out (alpha only 0 or 255) or partial. The cut-out stage
//! ([`super::cutout`]) tests it at pixel centres.
//!
//! A material names its texture with a [`TextureRef`]: the path, and the
//! texture decoded on first use, down to the mip level the first sample
//! needs (again, finer, when a later sample needs a finer level). Decoding
//! is lazy so that a texture that no visible pixel samples costs nothing,
//! and it is shared: clones of a material (every front end copies the
//! scene's materials) and materials naming the same file share one decode.

mod decode;
mod reference;
mod sample;

pub use decode::probe;
pub use reference::{TextureRef, TextureTransform};

use super::budget::Reservation;
use super::mip::{self, Level};
use crate::{Error, Result};

/// Largest texture side accepted, in texels (checked before decoding).
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// How a texture is sampled between texel centres.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// The texel containing the point.
    Nearest,
    /// The weighted mean of the four nearest texels (the accurate default).
    #[default]
    Bilinear,
}

/// What a texture's alpha channel holds, classified once from the image's
/// own texels (level 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum AlphaClass {
    /// No alpha channel, or every texel fully opaque.
    #[default]
    Opaque,
    /// Alpha only 0 or 255: a cut-out (a leaf card, a fence). Drawn opaque
    /// where alpha is at least one half and not at all elsewhere, by the
    /// alpha test at each pixel centre; the surface stays opaque for the
    /// planner.
    Cutout,
    /// Some texel between 0 and 255: translucency, which only compositing
    /// hiders can show; single-sample hiders alpha-test it at one half.
    Partial,
}

/// A texture: sRGB bytes sampled in linear light, with an optional alpha
/// channel, held as its mip levels from [`Self::base_level`] down to 1 x 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Level 0's size (the image's).
    width: u32,
    height: u32,
    /// The first level held.
    base: u32,
    /// Levels `base..`.
    levels: Vec<Level>,
    alpha: AlphaClass,
    /// Level-0 texels whose alpha is strictly between 0 and 1.
    partial: u64,
    reservation: Reservation,
}

/// [`srgb_to_linear`] of every byte.
#[inline]
pub(crate) fn linear_table() -> &'static [f32; 256] {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|c| srgb_to_linear(c as u8)))
}

/// sRGB byte to linear light.
pub fn srgb_to_linear(c: u8) -> f32 {
    let s = f32::from(c) / 255.0;
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// Checks a texture's size against [`MAX_TEXTURE_SIDE`].
fn check_size(width: u32, height: u32) -> Result<()> {
    for (what, v) in [("texture width", width), ("texture height", height)] {
        if v == 0 || v > MAX_TEXTURE_SIDE {
            return Err(Error::OutOfRange {
                what,
                expected: "1 to 8192 texels",
                value: v.to_string(),
            });
        }
    }
    Ok(())
}

/// What level 0's alpha bytes hold: their class and how many are
/// partial (strictly between 0 and 255), added up row by row.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct AlphaCount {
    pub(crate) class: AlphaClass,
    pub(crate) partial: u64,
}

impl AlphaCount {
    /// Adds `alpha`'s bytes.
    pub(crate) fn add(&mut self, alpha: &[u8]) {
        let mut cut = false;
        for &a in alpha {
            cut |= a == 0;
            self.partial += u64::from(a != 0 && a != 255);
        }
        if self.partial > 0 {
            self.class = AlphaClass::Partial;
        } else if cut {
            self.class = self.class.max(AlphaClass::Cutout);
        }
    }

    fn of(alpha: &[u8]) -> Self {
        let mut count = Self::default();
        count.add(alpha);
        count
    }
}

impl Texture {
    /// Loads an image file (PNG or JPEG) at full resolution with its mip
    /// levels, size and budget checked first.
    ///
    /// Without the `image` feature: an error naming the file and the
    /// feature.
    pub fn load(path: &std::path::Path) -> Result<Self> {
        decode::load_level(path, 0, false)
    }

    /// A texture from sRGB bytes, 3 per texel, top row first.
    pub fn from_srgb8(width: u32, height: u32, bytes: &[u8]) -> Result<Self> {
        Self::from_srgb8_vec(width, height, bytes.to_vec())
    }

    /// [`Self::from_srgb8`], taking the bytes without copying them.
    pub fn from_srgb8_vec(width: u32, height: u32, bytes: Vec<u8>) -> Result<Self> {
        check_size(width, height)?;
        let n = width as usize * height as usize;
        if bytes.len() != 3 * n {
            return Err(Error::OutOfRange {
                what: "texture data",
                expected: "3 bytes per texel",
                value: format!("{} bytes for {width}x{height}", bytes.len()),
            });
        }
        Ok(Self::from_levels(
            width,
            height,
            mip::chain(width, height, &bytes, None, 0),
            AlphaCount::default(),
            None,
        ))
    }

    /// A texture from sRGB bytes with alpha, 4 per texel (RGBA, straight
    /// alpha), top row first.
    pub fn from_srgba8(width: u32, height: u32, bytes: &[u8]) -> Result<Self> {
        check_size(width, height)?;
        let n = width as usize * height as usize;
        if bytes.len() != 4 * n {
            return Err(Error::OutOfRange {
                what: "texture data",
                expected: "4 bytes per texel",
                value: format!("{} bytes for {width}x{height}", bytes.len()),
            });
        }
        let rgb: Vec<u8> = bytes
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        let alpha: Vec<u8> = bytes.chunks_exact(4).map(|p| p[3]).collect();
        let count = AlphaCount::of(&alpha);
        let levels = mip::chain(width, height, &rgb, Some(&alpha), 0);
        Ok(Self::from_levels(width, height, levels, count, None))
    }

    /// A texture holding `levels` (from level `levels[0]`'s place in the
    /// chain), counted against the budget by `reservation` (or now, for
    /// bytes the caller built in memory).
    fn from_levels(
        width: u32,
        height: u32,
        levels: Vec<Level>,
        alpha: AlphaCount,
        reservation: Option<Reservation>,
    ) -> Self {
        let count = mip::level_count(width, height);
        let base = count - levels.len() as u32;
        let bytes: usize = levels.iter().map(Level::bytes).sum();
        Self {
            width,
            height,
            base,
            levels,
            alpha: alpha.class,
            partial: alpha.partial,
            reservation: reservation.unwrap_or_else(|| Reservation::force(bytes as u64)),
        }
    }

    /// Width in texels (of the image, level 0).
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels (of the image, level 0).
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The finest mip level held (0: the full image).
    pub fn base_level(&self) -> u32 {
        self.base
    }

    /// Number of levels of the whole chain, level 0 to 1 x 1.
    pub fn level_count(&self) -> u32 {
        self.base + self.levels.len() as u32
    }

    /// Whether the image has texels that are not fully opaque.
    pub fn has_alpha(&self) -> bool {
        self.alpha != AlphaClass::Opaque
    }

    /// What the alpha channel holds.
    pub fn alpha_class(&self) -> AlphaClass {
        self.alpha
    }

    /// The share of the image's texels (level 0) whose alpha is strictly
    /// between 0 and 1: the translucent part of a [`AlphaClass::Partial`]
    /// texture (0 for the others).
    pub fn partial_share(&self) -> f64 {
        self.partial as f64 / (f64::from(self.width) * f64::from(self.height))
    }

    /// Bytes held (every level kept, alpha included).
    pub fn bytes(&self) -> usize {
        self.levels.iter().map(Level::bytes).sum()
    }

    /// The level held that is nearest to `level` (the base when it asks
    /// for a finer one).
    #[inline]
    fn level(&self, level: u32) -> &Level {
        let k = level.saturating_sub(self.base) as usize;
        &self.levels[k.min(self.levels.len() - 1)]
    }

    /// The linear colour at texture coordinates `(u, v)` (OBJ convention,
    /// repeat wrapping), from the finest level held. Non-finite
    /// coordinates give the first texel.
    pub fn sample(&self, u: f64, v: f64, filter: Filter) -> [f32; 3] {
        self.sample_wrapped(u, v, filter, false)
    }

    /// [`Self::sample`], with coordinates outside [0, 1] clamped to the
    /// image's edge texels when `clamp` (MTL's `-clamp on`) instead of
    /// repeating.
    pub fn sample_wrapped(&self, u: f64, v: f64, filter: Filter, clamp: bool) -> [f32; 3] {
        self.sample_level(u, v, filter, clamp, 0).0
    }

    /// The linear colour and the alpha (in [0, 1], 1 without an alpha
    /// channel) at `(u, v)` in mip level `level` (or the nearest level
    /// held), filtered with `filter`, repeating or clamped.
    #[inline(always)]
    pub fn sample_level(
        &self,
        u: f64,
        v: f64,
        filter: Filter,
        clamp: bool,
        level: u32,
    ) -> ([f32; 3], f32) {
        self.level(level).sample(u, v, filter, clamp)
    }

    /// [`Self::sample_level`]'s alpha alone (the same number), without
    /// reading the colour.
    #[inline(always)]
    pub fn sample_level_alpha(
        &self,
        u: f64,
        v: f64,
        filter: Filter,
        clamp: bool,
        level: u32,
    ) -> f32 {
        self.level(level).sample_alpha(u, v, filter, clamp)
    }
}

/// A checkerboard image: `squares x squares` squares of `square` texels,
/// alternating `a` and `b` (sRGB bytes, 3 per texel, top row first), `a`
/// in the top-left corner.
pub fn checkerboard(squares: u32, square: u32, a: [u8; 3], b: [u8; 3]) -> (u32, Vec<u8>) {
    let side = squares * square;
    let mut bytes = Vec::with_capacity(side as usize * side as usize * 3);
    for y in 0..side {
        for x in 0..side {
            let odd = (x / square + y / square) % 2 == 1;
            bytes.extend_from_slice(if odd { &b } else { &a });
        }
    }
    (side, bytes)
}

/// Name of the bundled checkerboard texture (`assets/checker.png`).
pub const CHECKER_PNG: &str = "checker.png";

/// The bundled checkerboard: 8 x 8 squares of 32 texels, light and dark.
pub fn checker_texture() -> (u32, Vec<u8>) {
    checkerboard(8, 32, [230, 230, 230], [40, 40, 40])
}

/// The OBJ and MTL text of the bundled textured asset
/// (`assets/checker_plane.obj`): one quad (two triangles) of 2 x 2 units,
/// tilted 14 degrees out of the XZ plane (`y = -z / 4`) so that the fit
/// camera sees it at a grazing angle, with uvs spanning the texture once
/// and a material whose `map_Kd` is `texture` (white `Kd`, so the texture
/// shows as it is).
pub fn checker_plane_text(mtl_name: &str, texture: &str) -> (String, String) {
    let obj = format!(
        "# written by hider: a checkerboard plane for perspective-correct texturing\n\
         mtllib {mtl_name}\n\
         o checker_plane\n\
         v -1 -0.25 1\nv 1 -0.25 1\nv 1 0.25 -1\nv -1 0.25 -1\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         usemtl checker\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    );
    let mtl = format!("newmtl checker\nKd 1 1 1\nd 1\nmap_Kd {texture}\n");
    (obj, mtl)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_and_bilinear_sampling_with_obj_orientation() {
        // 2 x 2: top row black, white; bottom row white, black.
        let t =
            Texture::from_srgb8(2, 2, &[0, 0, 0, 255, 255, 255, 255, 255, 255, 0, 0, 0]).unwrap();
        // v = 0.75 is the top row in OBJ convention.
        assert_eq!(t.sample(0.25, 0.75, Filter::Nearest), [0.0; 3]);
        assert_eq!(t.sample(0.75, 0.75, Filter::Nearest), [1.0; 3]);
        assert_eq!(t.sample(0.25, 0.25, Filter::Nearest), [1.0; 3]);
        // Repeat wrapping.
        assert_eq!(t.sample(1.25, -0.25, Filter::Nearest), [0.0; 3]);
        // At texel centres bilinear equals nearest; halfway it averages.
        assert_eq!(t.sample(0.25, 0.75, Filter::Bilinear), [0.0; 3]);
        let mid = t.sample(0.5, 0.75, Filter::Bilinear);
        assert!((mid[0] - 0.5).abs() < 1e-6, "{mid:?}");
        assert_eq!(t.sample(f64::NAN, 0.0, Filter::Bilinear), [0.0; 3]);
    }

    #[test]
    fn bad_sizes_and_files_are_errors() {
        assert!(Texture::from_srgb8(0, 1, &[]).is_err());
        assert!(Texture::from_srgb8(2, 2, &[0; 11]).is_err());
        let e = probe(std::path::Path::new("/no/such/texture.png"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("/no/such/texture.png"), "{e}");
        let dir = std::env::temp_dir().join(format!("hider-tex-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("bad.png");
        std::fs::write(&bad, b"not a png at all").unwrap();
        assert!(Texture::load(&bad).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn checkerboard_alternates() {
        let (side, bytes) = checkerboard(2, 3, [1, 1, 1], [2, 2, 2]);
        assert_eq!(side, 6);
        assert_eq!(bytes[0], 1);
        assert_eq!(bytes[3 * 3], 2); // x = 3, second square
        assert_eq!(bytes[3 * (3 * 6 + 3)], 1); // x = 3, y = 3
    }
}
