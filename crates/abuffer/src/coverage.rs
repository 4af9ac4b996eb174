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

use hider_geom::edge::triangle_edges;
use hider_geom::fixed::SUBPIXEL_SCALE;
use hider_geom::{EdgeFunction, FixedPt, PlaneEq};
use hider_scene::ScreenTri;

use crate::pattern::{CENTRE, SamplePattern};

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

/// Edge coefficients `|a|`, `|b|` below this take the 32-bit mask path:
/// every offset `a*sx + b*sy` inside a pixel then stays below `2^29`.
const NARROW: i64 = 1 << 20;
/// Clamp of the negated edge value on the 32-bit path: beyond it the edge
/// is decided for every sample of the pixel, so clamping keeps the answer.
const CLAMP: i64 = 1 << 30;

/// Rows longer than this many pixels are clipped to [`TriCoverage::span`]
/// before their pixels are tested.
const SPAN_MIN: u32 = 8;

/// Truncation towards zero without a library call (baseline x86-64 has no
/// rounding instruction): exact for `|x| < 2^62`, and values beyond only
/// widen the span they bound after clamping.
trait TruncFast {
    fn trunc_fast(self) -> f64;
}

impl TruncFast for f64 {
    #[inline]
    fn trunc_fast(self) -> f64 {
        // `as` saturates (and maps NaN to 0); the span is clamped after.
        (self as i64) as f64
    }
}

/// How the sample hull of a pixel lies against a triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// Every sample and the centre are covered.
    Full,
    /// Nothing is covered.
    Empty,
    /// Some edge crosses the hull: test the samples.
    Partial,
}

/// Per-triangle set-up for mask generation.
///
/// Masks are computed on the 8 x 4 grid, row by row: sample `(c, r)` is
/// inside edge `e` when `E_e(pixel corner) + a_e*x_c + b_e*y_r > 0`, i.e.
/// when `-E_e - a_e*x_c - b_e*y_r < 0`. When the triangle's coefficients
/// are small enough (every edge shorter than 4096 pixels) and the edge
/// crosses the sample hull, all those values fit in `i32`, so the 32
/// samples are 3 x 32 lane-parallel adds and `and`s (the offsets are
/// precomputed per triangle) whose sign bits are gathered with one
/// multiply per row; otherwise the same test runs in `i64`.
/// Either way each bit is exactly the shared `contains` test. Patterns
/// smaller than 32 pick their cells out of the grid mask.
#[derive(Clone, Debug)]
pub struct TriCoverage {
    edges: [EdgeFunction; 3],
    /// `-(a * x_c + b * y_r)` for each edge and grid cell `r * 8 + c`
    /// (32-bit path).
    noff: [[i32; 32]; 3],
    narrow: bool,
    /// `1 / (256 a)` per edge (0 when `a == 0`), for [`Self::span`].
    inv_step: [f64; 3],
    centre: [i64; 3],
    hull_min: [i64; 3],
    hull_max: [i64; 3],
    pattern: SamplePattern,
    full: u32,
}

/// x of grid column `c` and y of grid row `r`, in 1/256 pixel.
const fn grid_x(c: usize) -> i64 {
    c as i64 * 32 + 16
}
const fn grid_y(r: usize) -> i64 {
    r as i64 * 64 + 32
}

impl TriCoverage {
    /// Sets up `tri` for sampling with `pattern`.
    pub fn new(tri: &ScreenTri, pattern: SamplePattern) -> Self {
        let mut setup = Self {
            edges: [EdgeFunction { a: 0, b: 0, c: 0 }; 3],
            noff: [[0; 32]; 3],
            narrow: false,
            inv_step: [0.0; 3],
            centre: [0; 3],
            hull_min: [0; 3],
            hull_max: [0; 3],
            pattern,
            full: 0,
        };
        setup.reset(tri, pattern);
        setup
    }

    /// [`Self::new`] in place, reusing this set-up's memory.
    #[inline]
    pub fn reset(&mut self, tri: &ScreenTri, pattern: SamplePattern) {
        self.reset_vertices(&tri.v, pattern);
    }

    /// [`Self::reset`] from the triangle's vertices alone.
    #[inline]
    pub fn reset_vertices(&mut self, v: &[FixedPt; 3], pattern: SamplePattern) {
        let edges = triangle_edges(v);
        let (hx0, hy0, hx1, hy1) = pattern.hull();
        let narrow = edges
            .iter()
            .all(|e| e.a.abs() < NARROW && e.b.abs() < NARROW);
        for (e, edge) in edges.iter().enumerate() {
            if narrow {
                let col: [i32; 8] = std::array::from_fn(|c| -(edge.a * grid_x(c)) as i32);
                let row: [i32; 4] = std::array::from_fn(|r| -(edge.b * grid_y(r)) as i32);
                for (cells, r) in self.noff[e].chunks_exact_mut(8).zip(row) {
                    let sums: [i32; 8] = std::array::from_fn(|c| col[c].wrapping_add(r));
                    cells.copy_from_slice(&sums);
                }
            }
            let off = |x: i32, y: i32| edge.a * i64::from(x) + edge.b * i64::from(y);
            self.centre[e] = off(CENTRE.0, CENTRE.1);
            // The offset is affine: its extremes over the hull are at the
            // corners given by the signs of a and b.
            let (xl, xh) = if edge.a >= 0 { (hx0, hx1) } else { (hx1, hx0) };
            let (yl, yh) = if edge.b >= 0 { (hy0, hy1) } else { (hy1, hy0) };
            self.hull_min[e] = off(xl, yl);
            self.hull_max[e] = off(xh, yh);
            self.inv_step[e] = if edge.a == 0 {
                0.0
            } else {
                1.0 / (edge.a * i64::from(SUBPIXEL_SCALE)) as f64
            };
        }
        self.edges = edges;
        self.narrow = narrow;
        self.pattern = pattern;
        self.full = pattern.full_mask();
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

    /// A sub-range of the pixels `x0..=x1` of row `j` outside which the
    /// triangle covers nothing (possibly empty: `start > end`).
    ///
    /// Pixel `i` is rejected when some edge is non-positive at all four
    /// hull corners, i.e. `E(i) + hull_max <= 0`, and `E(i)` is affine in
    /// `i`; each edge with `a != 0` thus bounds the range on one side at
    /// `i = -(E(0) + hull_max) / (256 a)`. The bound is computed in `f64`
    /// and widened by two pixels, so it is conservative: the exact test
    /// still decides every pixel inside.
    #[inline]
    pub fn span(&self, x0: u32, x1: u32, j: u32) -> (u32, u32) {
        let base = self.corner_values(0, j);
        let (mut lo, mut hi) = (f64::from(x0), f64::from(x1));
        for (e, edge) in self.edges.iter().enumerate() {
            let k = (base[e] + self.hull_max[e]) as f64;
            let t = -k * self.inv_step[e];
            // Truncation moves t by less than one: two pixels of margin.
            match edge.a.signum() {
                1 => lo = lo.max(t.trunc_fast() - 2.0),
                -1 => hi = hi.min(t.trunc_fast() + 2.0),
                _ if k <= 0.0 => return (1, 0),
                _ => {}
            }
        }
        if lo > hi {
            return (1, 0);
        }
        (lo as u32, hi as u32)
    }

    /// [`Self::span`] for rows long enough for it to pay, else `x0..=x1`.
    #[inline]
    pub fn row_span(&self, x0: u32, x1: u32, j: u32) -> (u32, u32) {
        if x1 >= x0 + SPAN_MIN {
            self.span(x0, x1, j)
        } else {
            (x0, x1)
        }
    }

    /// The pixels `x0..=x1` of row `j` that this triangle touches, with
    /// their coverage, left to right. The row is first clipped to
    /// [`Self::span`]; along it the edge values are stepped incrementally
    /// (one add per edge and pixel); empty pixels are skipped.
    #[inline]
    pub fn row(&self, x0: u32, x1: u32, j: u32) -> impl Iterator<Item = (u32, Coverage)> + '_ {
        // Short rows are cheaper to test pixel by pixel.
        let (x0, x1) = self.row_span(x0, x1, j);
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
        match self.classify(base) {
            Class::Full => Coverage {
                mask: self.full,
                centre: true,
                full: true,
            },
            Class::Empty => Coverage::default(),
            Class::Partial => self.partial(base),
        }
    }

    /// The first step of [`Self::at`]: whether the four corners of the
    /// sample hull are inside all three edges (every sample and the centre
    /// covered), all outside one edge (nothing covered), or neither.
    #[inline]
    pub fn classify(&self, base: [i64; 3]) -> Class {
        if (0..3).all(|e| base[e] + self.hull_min[e] > 0) {
            Class::Full
        } else if (0..3).any(|e| base[e] + self.hull_max[e] <= 0) {
            Class::Empty
        } else {
            Class::Partial
        }
    }

    /// The second step of [`Self::at`] for a [`Class::Partial`] pixel: its
    /// mask and centre, tested sample by sample (possibly empty).
    #[inline]
    pub fn partial(&self, base: [i64; 3]) -> Coverage {
        let centre = (0..3).all(|e| base[e] + self.centre[e] > 0);
        let mask = match self.pattern {
            SamplePattern::Centre => u32::from(centre),
            SamplePattern::Grid32 => self.grid_mask(base),
            pattern => {
                let grid = self.grid_mask(base);
                let mut mask = 0u32;
                for (k, &(x, y)) in pattern.positions().iter().enumerate() {
                    let cell = (y - 32) / 64 * 8 + (x - 16) / 32;
                    mask |= (grid >> cell & 1) << k;
                }
                mask
            }
        };
        Coverage {
            mask,
            centre,
            full: false,
        }
    }

    /// The 8 x 4 grid mask (bit `r * 8 + c` = cell `(c, r)`) of the pixel
    /// whose corner values are `base`.
    #[inline]
    fn grid_mask(&self, base: [i64; 3]) -> u32 {
        if !self.narrow {
            return self.grid_mask_wide(base);
        }
        // -E clamped: an edge that far from the pixel is decided for every
        // sample, and the clamp keeps it decided the same way.
        let nb = base.map(|b| (-b).clamp(-CLAMP, CLAMP) as i32);
        let mut bytes = [0u8; 32];
        for (k, byte) in bytes.iter_mut().enumerate() {
            // Negative in all three edges = inside all three.
            let w =
                (nb[0] + self.noff[0][k]) & (nb[1] + self.noff[1][k]) & (nb[2] + self.noff[2][k]);
            *byte = (w >> 31) as u8;
        }
        // Gather the top bit of each byte: byte c of a row lands on bit
        // 56 + c of the product.
        let mut mask = 0u32;
        for (r, row) in bytes.chunks_exact(8).enumerate() {
            let x = u64::from_le_bytes(row.try_into().expect("8 bytes")) & 0x8080_8080_8080_8080;
            mask |= ((x.wrapping_mul(0x0002_0408_1020_4081) >> 56) as u32) << (8 * r);
        }
        mask
    }

    /// [`Self::grid_mask`] in `i64`, for triangles too large for `i32`.
    fn grid_mask_wide(&self, base: [i64; 3]) -> u32 {
        let mut mask = 0u32;
        for r in 0..4 {
            for c in 0..8 {
                let inside = self
                    .edges
                    .iter()
                    .zip(base)
                    .all(|(e, b)| b + e.a * grid_x(c) + e.b * grid_y(r) > 0);
                mask |= u32::from(inside) << (r * 8 + c);
            }
        }
        mask
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
/// crate computes sample depths with this one function (or
/// [`plane_depth`], the same expression) so that their depth comparisons
/// agree bit for bit; at the centre it is exactly
/// `tri.depth.at_pixel(i, j)`.
#[inline]
pub fn sample_depth(tri: &ScreenTri, i: u32, j: u32, pos: (i32, i32)) -> f64 {
    plane_depth(&tri.depth, i, j, pos)
}

/// [`sample_depth`] for a depth plane alone.
#[inline]
pub fn plane_depth(plane: &PlaneEq, i: u32, j: u32, (sx, sy): (i32, i32)) -> f64 {
    let scale = f64::from(SUBPIXEL_SCALE);
    plane.eval(
        f64::from(i) + f64::from(sx) / scale,
        f64::from(j) + f64::from(sy) / scale,
    )
}

/// Exact depth bounds of a fragment from a few plane evaluations.
///
/// [`plane_depth`] is monotonic in each coordinate: `x - x0`, the products
/// by `dx` and `dy` and the two sums are each rounded by a monotonic
/// rounding, so for a fixed row the computed depth never decreases along x
/// when `dx >= 0` and never increases when `dx < 0` (likewise along y).
/// Hence the nearest and farthest computed depths over any set of samples
/// of one grid row are at the row's first and last sample, and over a full
/// grid at two opposite corners: the bounds below are *equal* to the
/// minimum and maximum of the per-sample values, found with at most 4 (not
/// 32) evaluations each.
#[derive(Clone, Copy, Debug)]
pub struct DepthBounds {
    pattern: SamplePattern,
    /// Grid32 fast path applies (its rows are the grid's rows).
    grid: bool,
    /// Whether the computed depth never decreases along x / y.
    up_x: bool,
    up_y: bool,
    /// Full masks take the hull corners (min/max mode) instead of samples.
    hull_for_full: bool,
}

impl DepthBounds {
    /// Bounds for triangles with depth plane `plane`. With `hull_for_full`
    /// a full mask is bounded by the plane at the corners of the pattern's
    /// hull (which for the 8 x 4 grid are samples).
    #[inline]
    pub fn new(plane: &PlaneEq, pattern: SamplePattern, hull_for_full: bool) -> Self {
        Self {
            pattern,
            grid: pattern == SamplePattern::Grid32,
            up_x: plane.dx >= 0.0,
            up_y: plane.dy >= 0.0,
            hull_for_full,
        }
    }

    /// The nearest (`far == false`) or farthest computed depth over the
    /// samples of `c.mask` and, if covered, the centre (`centre_z`, which
    /// a full mask does not need: the centre lies inside the hull).
    #[inline(always)]
    pub fn bound(
        &self,
        plane: &PlaneEq,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
        far: bool,
    ) -> f64 {
        if c.full && (self.grid || self.hull_for_full) {
            // Along x (y) the bound is at the low end when the depth grows
            // in the direction we look for, i.e. when `up == far` is false.
            // The centre is inside the hull: it cannot pass the corner.
            let (x0, y0, x1, y1) = self.pattern.hull();
            let x = if self.up_x != far { x0 } else { x1 };
            let y = if self.up_y != far { y0 } else { y1 };
            return plane_depth(plane, i, j, (x, y));
        }
        self.bound_partial(plane, (i, j), c, centre_z, far)
    }

    /// Both bounds, `(nearest, farthest)`, in one pass: the same values as
    /// [`Self::bound`] with `far` false and true.
    #[inline(never)]
    pub fn range(
        &self,
        plane: &PlaneEq,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
    ) -> (f64, f64) {
        if c.full || !self.grid {
            return (
                self.bound(plane, (i, j), c, centre_z, false),
                self.bound(plane, (i, j), c, centre_z, true),
            );
        }
        let (mut lo, mut hi) = if c.centre {
            (centre_z, centre_z)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
        let (xi, yj) = (f64::from(i), f64::from(j));
        let mut mask = c.mask;
        for y in GRID_Y {
            let row = mask as u8;
            mask >>= 8;
            if row != 0 {
                let (first, last) = (row.trailing_zeros(), 7 - row.leading_zeros());
                // Along the row the depth runs from `first` to `last`.
                let (near, far) = if self.up_x {
                    (first, last)
                } else {
                    (last, first)
                };
                let y = yj + y;
                let zn = plane.eval(xi + GRID_X[near as usize], y);
                let zf = if first == last {
                    zn
                } else {
                    plane.eval(xi + GRID_X[far as usize], y)
                };
                if zn < lo {
                    lo = zn;
                }
                if zf > hi {
                    hi = zf;
                }
            }
        }
        (lo, hi)
    }

    /// [`Self::bound`] of a partial mask (or any mask of a pattern whose
    /// hull corners are not samples).
    #[inline(never)]
    fn bound_partial(
        &self,
        plane: &PlaneEq,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
        far: bool,
    ) -> f64 {
        let low_x = self.up_x != far;
        let mut z = if c.centre {
            centre_z
        } else if far {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        };
        // Plain comparisons: same value as `f64::min`/`max` for numbers.
        let mut pick = |v: f64| {
            if (far && v > z) || (!far && v < z) {
                z = v;
            }
        };
        if self.grid {
            let (xi, yj) = (f64::from(i), f64::from(j));
            let mut mask = c.mask;
            for y in GRID_Y {
                let row = mask as u8;
                mask >>= 8;
                if row != 0 {
                    let col = if low_x {
                        row.trailing_zeros()
                    } else {
                        7 - row.leading_zeros()
                    };
                    // Exactly `plane_depth`: the offsets are exact.
                    pick(plane.eval(xi + GRID_X[col as usize], yj + y));
                }
            }
            return z;
        }
        for (k, &pos) in self.pattern.positions().iter().enumerate() {
            if c.mask >> k & 1 == 1 {
                pick(plane_depth(plane, i, j, pos));
            }
        }
        z
    }
}

/// `x_c / 256` of the grid columns and `y_r / 256` of the grid rows
/// (exact in `f64`), as [`plane_depth`] adds them to the pixel corner.
const GRID_X: [f64; 8] = {
    let mut out = [0.0; 8];
    let mut c = 0;
    while c < 8 {
        out[c] = (c as f64 * 32.0 + 16.0) / SUBPIXEL_SCALE as f64;
        c += 1;
    }
    out
};
const GRID_Y: [f64; 4] = {
    let mut out = [0.0; 4];
    let mut r = 0;
    while r < 4 {
        out[r] = (r as f64 * 64.0 + 32.0) / SUBPIXEL_SCALE as f64;
        r += 1;
    }
    out
};

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

    /// Whether `row` (span clipping included) yields exactly the pixels of
    /// row `j` (0..14) that `at` finds non-empty.
    fn row_is_complete(setup: &TriCoverage, j: u32) -> bool {
        let from_row: Vec<(u32, Coverage)> = setup.row(0, 13, j).collect();
        let direct: Vec<(u32, Coverage)> = (0..14)
            .map(|i| (i, setup.at(setup.corner_values(i, j))))
            .filter(|(_, c)| !c.is_empty())
            .collect();
        from_row == direct
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
                    if i == 0 {
                        prop_assert!(row_is_complete(&setup, j), "row {}", j);
                    }
                    let inside = range.is_some_and(|(x0, y0, x1, y1)| (x0..=x1).contains(&i) && (y0..=y1).contains(&j));
                    if !inside {
                        prop_assert!(mask == 0 && !centre, "pixel {} {} outside range {:?}", i, j, range);
                    }
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Long edges (beyond the 32-bit path) and edges passing close to
        /// the pixels give the same masks as the shared test too.
        #[test]
        fn masks_of_huge_triangles_equal_the_shared_coverage_test(
            c in proptest::array::uniform6(-(1i32 << 23)..(1i32 << 23)),
            shift in proptest::array::uniform2(-2048i32..2048),
            pattern_index in 0usize..5,
        ) {
            // Move the first vertex near the 14 x 14 window so that edges
            // cross it.
            let v = [
                FixedPt::new(c[0] % 4096 + shift[0], c[1] % 4096 + shift[1]),
                FixedPt::new(c[2], c[3]),
                FixedPt::new(c[4], c[5]),
            ];
            let Some(t) = tri(v) else { return Ok(()) };
            let pattern = SamplePattern::ALL[pattern_index];
            let setup = TriCoverage::new(&t, pattern);
            for j in 0..14 {
                for i in 0..14 {
                    let got = setup.at(setup.corner_values(i, j));
                    prop_assert_eq!((got.mask, got.centre), brute(&t, pattern, i, j), "pixel {} {}", i, j);
                }
                prop_assert!(row_is_complete(&setup, j), "row {}", j);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// The bounds from a few evaluations equal the minimum and maximum
        /// of the per-sample depths (and the centre's) computed one by one,
        /// for every pattern, mask and plane (the monotonicity argument of
        /// `DepthBounds`), in both modes.
        #[test]
        fn depth_bounds_equal_the_extremes_of_the_sample_depths(
            plane in (-2.0f64..2.0, -0.5f64..0.5, -0.5f64..0.5, -300.0f64..300.0, -300.0f64..300.0),
            scale in prop_oneof![Just(1e-6f64), Just(1e-3), Just(1.0), Just(1e3)],
            ij in (0u32..2000, 0u32..2000),
            mask in any::<u32>(),
            centre in any::<bool>(),
            full in any::<bool>(),
            pattern_index in 0usize..5,
        ) {
            let plane = PlaneEq {
                x0: plane.3,
                y0: plane.4,
                value: plane.0,
                dx: plane.1 * scale,
                dy: plane.2 * scale,
            };
            let pattern = SamplePattern::ALL[pattern_index];
            let c = if full {
                Coverage { mask: pattern.full_mask(), centre: true, full: true }
            } else {
                Coverage { mask: mask & pattern.full_mask(), centre, full: false }
            };
            let (i, j) = ij;
            let centre_z = plane_depth(&plane, i, j, CENTRE);
            let cz = if c.centre { centre_z } else { f64::INFINITY };
            for hull_for_full in [false, true] {
                let b = DepthBounds::new(&plane, pattern, hull_for_full);
                // Brute force over the covered samples (all of the hull's
                // corners for a full mask in min/max mode) and the centre.
                let mut points: Vec<(i32, i32)> = pattern
                    .positions()
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| c.mask >> k & 1 == 1)
                    .map(|(_, &p)| p)
                    .collect();
                if c.centre {
                    points.push(CENTRE);
                }
                if c.full && hull_for_full {
                    let (x0, y0, x1, y1) = pattern.hull();
                    points.extend([(x0, y0), (x1, y0), (x0, y1), (x1, y1)]);
                }
                let zs: Vec<f64> = points.iter().map(|&p| plane_depth(&plane, i, j, p)).collect();
                let lo = zs.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                prop_assert_eq!(b.bound(&plane, (i, j), c, cz, false), lo);
                prop_assert_eq!(b.bound(&plane, (i, j), c, cz, true), hi);
                prop_assert_eq!(b.range(&plane, (i, j), c, cz), (lo, hi));
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
