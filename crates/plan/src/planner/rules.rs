//! The planner's rules: for each effect, the registry entries exact for it
//! from cheapest to dearest, and the sentence saying why.

use crate::analyze::{Effects, Evidence};

/// Above this [`Effects::depth_ratio`] (farthest corner in view over the
/// near distance) an f32 window-depth buffer is not trusted. Window depth
/// is `z = f/(f-n) (1 - n/d)`, so `dz/dd ~ n/d^2`; rounding `z` to f32
/// near 1 (spacing `2^-24`) moves the distance by a relative `2^-24 d/n`,
/// about `6e-6` at `d/n = 100`, still under the oracle's tie tolerance
/// `1e-5`. The fit camera stays below 35.
pub const MAX_F32_DEPTH_RATIO: f64 = 100.0;

/// Fewest pixels per triangle for which a raster plan proves back faces
/// hidden (and culls them). The proof (closed, consistently oriented,
/// outward shells) costs about 50-60 ns per triangle on this project's
/// machine, more than the tiled z-buffer's whole work per triangle
/// (10-20 ns); culling saves the back faces' triangle work and their fill
/// (a nanosecond or so per fragment with hierarchical depth). So it pays
/// only when the triangles are large on screen: a 2-million-triangle
/// sphere at 2048 x 2048 spent 116 ms proving what saved 8 ms of render.
/// Culling is an optimisation, never needed for a right image, so below
/// this the proof is skipped. Ordered polygons (the painter, hundreds of
/// nanoseconds per triangle) always cull when exact.
pub const MIN_PIXELS_PER_TRIANGLE_TO_CULL: u64 = 64;

/// Whether proving back faces hidden can pay for itself in a raster
/// render of `triangles` triangles on `pixels` pixels (see
/// [`MIN_PIXELS_PER_TRIANGLE_TO_CULL`]).
pub fn culling_pays(triangles: u64, pixels: u64) -> bool {
    triangles.saturating_mul(MIN_PIXELS_PER_TRIANGLE_TO_CULL) <= pixels
}

/// Picks the first available entry of a chain, noting a fallback.
pub(crate) struct Picker<'a> {
    /// Registry names that may be chosen.
    available: &'a [&'static str],
    /// Fallbacks taken and effects left unsimulated, in order.
    pub(crate) notes: Vec<String>,
}

impl<'a> Picker<'a> {
    /// A picker among `available`.
    pub(crate) fn new(available: &'a [&'static str]) -> Self {
        Self {
            available,
            notes: Vec::new(),
        }
    }

    /// The first name of `chain` that is available; a note when it is not
    /// the first.
    fn pick(&mut self, chain: &[&'static str]) -> Option<&'static str> {
        let found = chain.iter().copied().find(|n| self.available.contains(n))?;
        if found != chain[0] {
            self.notes.push(format!(
                "{} is not registered, fell back to {found}",
                chain[0]
            ));
        }
        Some(found)
    }

    /// The first available name of `chain` with `why`, or `None` with the
    /// note `missing`.
    fn rule(
        &mut self,
        chain: &[&'static str],
        why: String,
        missing: &str,
    ) -> Option<(&'static str, String)> {
        match self.pick(chain) {
            Some(name) => Some((name, why)),
            None => {
                self.notes.push(missing.to_owned());
                None
            }
        }
    }

    /// Vector output: a painter, splitting only when intersections or
    /// cycles call for it.
    pub(crate) fn vector(&mut self, effects: &Effects) -> Option<(&'static str, String)> {
        if !effects.ordered_polygons {
            return None;
        }
        let hard = effects.intersections.present || effects.cyclic_overlap.present;
        let (chain, why): (&[&'static str], String) = if hard {
            (
                &["painter"],
                format!(
                    "ordered polygons with {} and {}: painter's with splitting",
                    count(&effects.intersections, "intersecting pairs"),
                    count(&effects.cyclic_overlap, "overlap cycles")
                ),
            )
        } else if !effects.naive_order_violations.present {
            (
                &["painter-naive", "painter"],
                "ordered polygons, no intersections or cycles and the farthest-vertex order is \
                 already right: painter's without splitting or tests"
                    .to_owned(),
            )
        } else {
            (
                &["painter"],
                format!(
                    "ordered polygons, no intersections or cycles but {}: painter's reordering, \
                     no splits needed",
                    count(
                        &effects.naive_order_violations,
                        "pairs the naive sort gets wrong"
                    )
                ),
            )
        };
        self.rule(chain, why, "no painter registered: raster output only")
    }

    /// Transparency: a hider compositing every surface in a pixel.
    pub(crate) fn transparency(&mut self, effects: &Effects) -> Option<(&'static str, String)> {
        if !effects.transparency.present {
            return None;
        }
        let why = format!(
            "{}: compositing every surface in a pixel",
            effects.transparency.detail
        );
        self.rule(
            &["abuffer", "ssaa-sorted"],
            why,
            "transparency NOT composited: no compositing hider registered",
        )
    }

    /// Anti-aliasing: coverage masks, else the fewest samples that do.
    pub(crate) fn antialiasing(&mut self, effects: &Effects) -> Option<(&'static str, String)> {
        if !effects.antialiasing.present {
            return None;
        }
        self.rule(
            &["abuffer", "ssaa-8", "ssaa-16", "ssaa-32", "ssaa-4"],
            "anti-aliasing asked: coverage masks per fragment".to_owned(),
            "anti-aliasing NOT done: no multi-sample hider registered",
        )
    }

    /// Opaque, one sample: a z-buffer, reversed-Z when the depth range
    /// calls for it; the oracle when nothing else is registered.
    pub(crate) fn raster(&mut self, effects: &Effects) -> (&'static str, String) {
        if effects.depth_ratio > MAX_F32_DEPTH_RATIO {
            let why = format!(
                "opaque, one sample, but geometry reaches {:.1e} x the near distance: \
                 reversed-Z keeps depth precision",
                effects.depth_ratio
            );
            let n = self.pick(&["zbuffer-reversed", "zbuffer-f64", "zbuffer"]);
            (n.unwrap_or("oracle"), why)
        } else {
            let n = self.pick(&[
                "zbuffer-tiled",
                "zbuffer",
                "zbuffer-f64",
                "scanline",
                "warnock",
            ]);
            (
                n.unwrap_or("oracle"),
                "opaque, no anti-aliasing: one depth test per covered pixel".to_owned(),
            )
        }
    }
}

/// "N what", or "what not ruled out" when the search did not finish.
fn count(e: &Evidence, what: &str) -> String {
    if e.certain {
        format!("{} {what}", e.count)
    } else {
        format!("{what} not ruled out")
    }
}
