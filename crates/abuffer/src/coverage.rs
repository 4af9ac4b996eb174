//! Coverage masks from the exact integer edge functions.
//!
//! For a triangle and a pixel, [`TriCoverage::at`] returns the mask of the
//! pattern's samples the triangle covers, plus whether it covers the pixel
//! centre (which ids and depths are reported at). Each bit is exactly the
//! shared coverage decision `tri.edges()[e].contains(x, y)` for all three
//! edges at the sample's fixed-point position, so masks agree bit for bit
//! with any other hider that samples the same points.
//!
//! Cost per pixel: three `i64` edge values, stepped incrementally along a
//! row, then a full-coverage fast path (the four corners of the sample
//! hull inside all three edges: every bit set, no per-sample test), a
//! trivial reject (all corners outside one edge), and only otherwise the
//! per-sample tests: one add and one compare per edge and sample against
//! offsets `a*sx + b*sy` precomputed per triangle.

use hider_geom::EdgeFunction;
use hider_geom::fixed::SUBPIXEL_SCALE;
use hider_scene::ScreenTri;

use crate::pattern::{CENTRE, MAX_SAMPLES, SamplePattern};

/// What a triangle covers in one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Coverage {
    /// Covered samples of the pattern (bit `k` = sample `k`).
    pub mask: u32,
    /// Whether the pixel centre is covered.
    pub centre: bool,
    /// Whether the fast path decided it (every sample and the centre).
    pub full: bool,
}

impl Coverage {
    /// Whether nothing is covered.
    pub fn is_empty(&self) -> bool {
        self.mask == 0 && !self.centre
    }
}

/// Per-triangle set-up for mask generation.
#[derive(Clone, Debug)]
pub struct TriCoverage {
    edges: [EdgeFunction; 3],
    /// `a*sx + b*sy` for each edge and sample.
    offsets: [[i64; MAX_SAMPLES]; 3],
    centre: [i64; 3],
    hull_min: [i64; 3],
    hull_max: [i64; 3],
    count: usize,
    full: u32,
}

impl TriCoverage {
    /// Sets up `tri` for sampling with `pattern`.
    pub fn new(tri: &ScreenTri, pattern: SamplePattern) -> Self {
        let edges = tri.edges();
        let positions = pattern.positions();
        let (hx0, hy0, hx1, hy1) = pattern.hull();
        let corners = [(hx0, hy0), (hx1, hy0), (hx0, hy1), (hx1, hy1)];
        let mut offsets = [[0i64; MAX_SAMPLES]; 3];
        let mut centre = [0i64; 3];
        let mut hull_min = [i64::MAX; 3];
        let mut hull_max = [i64::MIN; 3];
        for (e, edge) in edges.iter().enumerate() {
            let off = |(x, y): (i32, i32)| edge.a * i64::from(x) + edge.b * i64::from(y);
            for (k, &p) in positions.iter().enumerate() {
                offsets[e][k] = off(p);
            }
            centre[e] = off(CENTRE);
            for &c in &corners {
                hull_min[e] = hull_min[e].min(off(c));
                hull_max[e] = hull_max[e].max(off(c));
            }
        }
        Self {
            edges,
            offsets,
            centre,
            hull_min,
            hull_max,
            count: positions.len(),
            full: pattern.full_mask(),
        }
    }

    /// The three biased edge values at the top-left corner of pixel
    /// `(i, j)` (fixed point `(i*256, j*256)`).
    #[inline]
    pub fn corner_values(&self, i: u32, j: u32) -> [i64; 3] {
        let (x, y) = (
            i64::from(i) * i64::from(SUBPIXEL_SCALE),
            i64::from(j) * i64::from(SUBPIXEL_SCALE),
        );
        self.edges.map(|e| e.eval(x, y))
    }

    /// How much the corner values change from one pixel to the next in x.
    #[inline]
    pub fn step_x(&self) -> [i64; 3] {
        self.edges.map(|e| e.a * i64::from(SUBPIXEL_SCALE))
    }

    /// The pixels `x0..=x1` of row `j` that this triangle touches, with
    /// their coverage, left to right. The edge values are stepped
    /// incrementally (one add per edge and pixel); empty pixels are skipped.
    #[inline]
    pub fn row(&self, x0: u32, x1: u32, j: u32) -> impl Iterator<Item = (u32, Coverage)> + '_ {
        let step = self.step_x();
        let mut base = self.corner_values(x0, j);
        (x0..=x1).filter_map(move |i| {
            let c = self.at(base);
            base = [0, 1, 2].map(|e| base[e] + step[e]);
            (!c.is_empty()).then_some((i, c))
        })
    }

    /// The coverage of the pixel whose corner values are `base`.
    #[inline]
    pub fn at(&self, base: [i64; 3]) -> Coverage {
        if (0..3).all(|e| base[e] + self.hull_min[e] > 0) {
            return Coverage {
                mask: self.full,
                centre: true,
                full: true,
            };
        }
        if (0..3).any(|e| base[e] + self.hull_max[e] <= 0) {
            return Coverage::default();
        }
        let mut mask = 0u32;
        for k in 0..self.count {
            let inside = (base[0] + self.offsets[0][k] > 0)
                & (base[1] + self.offsets[1][k] > 0)
                & (base[2] + self.offsets[2][k] > 0);
            mask |= u32::from(inside) << k;
        }
        let centre = (0..3).all(|e| base[e] + self.centre[e] > 0);
        Coverage {
            mask,
            centre,
            full: false,
        }
    }
}

/// The inclusive pixel rectangle `(x0, y0, x1, y1)` in which `tri` may
/// cover a sample of `pattern` or a pixel centre, clamped to a
/// `width x height` image; `None` if empty.
pub fn pixel_range(
    tri: &ScreenTri,
    pattern: SamplePattern,
    width: u32,
    height: u32,
) -> Option<(u32, u32, u32, u32)> {
    let (hx0, hy0, hx1, hy1) = pattern.hull();
    let min_x = tri.v.iter().map(|p| p.x).min()?;
    let max_x = tri.v.iter().map(|p| p.x).max()?;
    let min_y = tri.v.iter().map(|p| p.y).min()?;
    let max_y = tri.v.iter().map(|p| p.y).max()?;
    // Pixel i's samples span [i*256 + h0, i*256 + h1]: it can be hit when
    // i*256 + h1 >= min and i*256 + h0 <= max.
    let s = SUBPIXEL_SCALE;
    let first = |m: i32, h1: i32| (m - h1 + s - 1).div_euclid(s);
    let last = |m: i32, h0: i32| (m - h0).div_euclid(s);
    let x0 = first(min_x, hx1).max(0);
    let y0 = first(min_y, hy1).max(0);
    let x1 = last(max_x, hx0).min(width as i32 - 1);
    let y1 = last(max_y, hy0).min(height as i32 - 1);
    (x0 <= x1 && y0 <= y1).then_some((x0 as u32, y0 as u32, x1 as u32, y1 as u32))
}

/// The window depth of `tri` at sample `(sx, sy)` (1/256 pixel) of pixel
/// `(i, j)`: the affine depth plane evaluated in `f64`. Every hider of this
/// crate computes sample depths with this one function so that their depth
/// comparisons agree bit for bit; at the centre it is exactly
/// `tri.depth.at_pixel(i, j)`.
#[inline]
pub fn sample_depth(tri: &ScreenTri, i: u32, j: u32, (sx, sy): (i32, i32)) -> f64 {
    let scale = f64::from(SUBPIXEL_SCALE);
    tri.depth.eval(
        f64::from(i) + f64::from(sx) / scale,
        f64::from(j) + f64::from(sy) / scale,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::{FixedPt, PlaneEq, orient2d};
    use proptest::prelude::*;

    fn tri(v: [FixedPt; 3]) -> Option<ScreenTri> {
        let mut v = v;
        let area = orient2d(v[0], v[1], v[2]);
        if area == 0 {
            return None;
        }
        if area < 0 {
            v.swap(1, 2);
        }
        Some(ScreenTri {
            v,
            z: [0.5; 3],
            w: [1.0; 3],
            depth: PlaneEq::constant(0.5),
            inv_w: PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        })
    }

    fn brute(t: &ScreenTri, pattern: SamplePattern, i: u32, j: u32) -> (u32, bool) {
        let covers = |(sx, sy): (i32, i32)| {
            let x = i64::from(i) * 256 + i64::from(sx);
            let y = i64::from(j) * 256 + i64::from(sy);
            t.edges().iter().all(|e| e.contains(x, y))
        };
        let mask = pattern
            .positions()
            .iter()
            .enumerate()
            .fold(0, |m, (k, &p)| m | (u32::from(covers(p)) << k));
        (mask, covers(CENTRE))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Masks (fast path, reject and per-sample path alike) equal the
        /// per-sample shared coverage test, and nothing is covered outside
        /// `pixel_range`.
        #[test]
        fn masks_equal_the_shared_coverage_test(
            c in proptest::array::uniform6(-256i32..16 * 256),
            pattern_index in 0usize..5,
        ) {
            let v = [FixedPt::new(c[0], c[1]), FixedPt::new(c[2], c[3]), FixedPt::new(c[4], c[5])];
            let Some(t) = tri(v) else { return Ok(()) };
            let pattern = SamplePattern::ALL[pattern_index];
            let setup = TriCoverage::new(&t, pattern);
            let range = pixel_range(&t, pattern, 14, 14);
            for j in 0..14 {
                for i in 0..14 {
                    let got = setup.at(setup.corner_values(i, j));
                    let (mask, centre) = brute(&t, pattern, i, j);
                    prop_assert_eq!((got.mask, got.centre), (mask, centre), "pixel {} {}", i, j);
                    if got.full {
                        prop_assert_eq!(mask, pattern.full_mask());
                    }
                    let inside = range.is_some_and(|(x0, y0, x1, y1)| (x0..=x1).contains(&i) && (y0..=y1).contains(&j));
                    if !inside {
                        prop_assert!(mask == 0 && !centre, "pixel {} {} outside range {:?}", i, j, range);
                    }
                }
            }
        }
    }

    #[test]
    fn incremental_step_matches_direct_evaluation() {
        let t = tri([
            FixedPt::new(100, 50),
            FixedPt::new(3000, 700),
            FixedPt::new(900, 2900),
        ])
        .unwrap();
        let s = TriCoverage::new(&t, SamplePattern::Grid32);
        let mut base = s.corner_values(0, 5);
        for i in 0..12 {
            assert_eq!(base, s.corner_values(i, 5));
            let step = s.step_x();
            base = [0, 1, 2].map(|e| base[e] + step[e]);
        }
    }

    #[test]
    fn centre_sample_depth_is_the_pixel_centre_depth() {
        let mut t = tri([
            FixedPt::new(0, 0),
            FixedPt::new(2560, 0),
            FixedPt::new(0, 2560),
        ])
        .unwrap();
        t.depth = PlaneEq {
            x0: 0.3,
            y0: 0.7,
            value: 0.25,
            dx: 0.013,
            dy: -0.007,
        };
        assert_eq!(sample_depth(&t, 3, 4, CENTRE), t.depth.at_pixel(3, 4));
    }
}
