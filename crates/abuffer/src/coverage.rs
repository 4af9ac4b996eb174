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
use hider_geom::isa::Avx2;
use hider_geom::{EdgeFunction, FixedPt};
use hider_scene::ScreenTri;

use crate::pattern::{CENTRE, SamplePattern};
#[cfg(target_arch = "x86_64")]
use crate::simd::coverage as avx2;

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
    pub(crate) fn is_empty(&self) -> bool {
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
pub(crate) enum Class {
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
/// multiply per row (on a CPU with AVX2, one register and one
/// `movemask` per row: `simd/coverage.rs`); otherwise the same test runs
/// in `i64`.
/// Either way each bit is exactly the shared `contains` test. Patterns
/// smaller than 32 pick their cells out of the grid mask.
#[derive(Clone, Debug)]
pub struct TriCoverage {
    edges: [EdgeFunction; 3],
    /// `-(a * x_c + b * y_r)` for each edge and grid cell `r * 8 + c`
    /// (32-bit path).
    noff: [[i32; 32]; 3],
    narrow: bool,
    centre: [i64; 3],
    hull_min: [i64; 3],
    hull_max: [i64; 3],
    pattern: SamplePattern,
    full: u32,
    /// The instruction-set token of the AVX2 mask, when the CPU has it.
    #[cfg_attr(
        not(target_arch = "x86_64"),
        expect(dead_code, reason = "only the x86_64 build has the AVX2 path")
    )]
    avx2: Option<Avx2>,
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
        Self::from_vertices(&tri.v, pattern)
    }

    /// [`Self::new`] from the triangle's snapped vertices alone.
    pub(crate) fn from_vertices(v: &[FixedPt; 3], pattern: SamplePattern) -> Self {
        let mut setup = Self {
            edges: [EdgeFunction { a: 0, b: 0, c: 0 }; 3],
            noff: [[0; 32]; 3],
            narrow: false,
            centre: [0; 3],
            hull_min: [0; 3],
            hull_max: [0; 3],
            pattern,
            full: 0,
            avx2: Avx2::detect(),
        };
        setup.reset_vertices(v, pattern);
        setup
    }

    /// [`Self::new`] in place, reusing this set-up's memory.
    #[cfg(test)]
    #[inline]
    pub(crate) fn reset(&mut self, tri: &ScreenTri, pattern: SamplePattern) {
        self.reset_vertices(&tri.v, pattern);
    }

    /// [`Self::new`] in place from the triangle's vertices alone, reusing
    /// this set-up's memory.
    #[inline]
    pub(crate) fn reset_vertices(&mut self, v: &[FixedPt; 3], pattern: SamplePattern) {
        let edges = triangle_edges(v);
        let (hx0, hy0, hx1, hy1) = pattern.hull();
        let narrow = edges
            .iter()
            .all(|e| e.a.abs() < NARROW && e.b.abs() < NARROW);
        if narrow {
            self.fill_offsets(&edges);
        }
        for (e, edge) in edges.iter().enumerate() {
            let off = |x: i32, y: i32| edge.a * i64::from(x) + edge.b * i64::from(y);
            self.centre[e] = off(CENTRE.0, CENTRE.1);
            // The offset is affine: its extremes over the hull are at the
            // corners given by the signs of a and b.
            let (xl, xh) = if edge.a >= 0 { (hx0, hx1) } else { (hx1, hx0) };
            let (yl, yh) = if edge.b >= 0 { (hy0, hy1) } else { (hy1, hy0) };
            self.hull_min[e] = off(xl, yl);
            self.hull_max[e] = off(xh, yh);
        }
        self.edges = edges;
        self.narrow = narrow;
        self.pattern = pattern;
        self.full = pattern.full_mask();
    }

    /// Fills [`Self::noff`] for `edges` (32-bit path): with AVX2 when the
    /// CPU has it, the same values.
    #[inline]
    fn fill_offsets(&mut self, edges: &[EdgeFunction; 3]) {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            avx2::offsets(avx2, edges, &mut self.noff);
            return;
        }
        for (e, edge) in edges.iter().enumerate() {
            let col: [i32; 8] = std::array::from_fn(|c| -(edge.a * grid_x(c)) as i32);
            let row: [i32; 4] = std::array::from_fn(|r| -(edge.b * grid_y(r)) as i32);
            for (cells, r) in self.noff[e].chunks_exact_mut(8).zip(row) {
                let sums: [i32; 8] = std::array::from_fn(|c| col[c].wrapping_add(r));
                cells.copy_from_slice(&sums);
            }
        }
    }

    /// The three biased edge values at the top-left corner of pixel
    /// `(i, j)` (fixed point `(i*256, j*256)`).
    #[inline]
    pub(crate) fn corner_values(&self, i: u32, j: u32) -> [i64; 3] {
        let (x, y) = (
            i64::from(i) * i64::from(SUBPIXEL_SCALE),
            i64::from(j) * i64::from(SUBPIXEL_SCALE),
        );
        self.edges.map(|e| e.eval(x, y))
    }

    /// How much the corner values change from one pixel to the next in x.
    #[inline]
    pub(crate) fn step_x(&self) -> [i64; 3] {
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
    pub(crate) fn span(&self, x0: u32, x1: u32, j: u32) -> (u32, u32) {
        let base = self.corner_values(0, j);
        let (mut lo, mut hi) = (f64::from(x0), f64::from(x1));
        for (e, edge) in self.edges.iter().enumerate() {
            let k = (base[e] + self.hull_max[e]) as f64;
            // Divided here, not at set-up: most triangles never ask for a
            // span (the sample buffer walks blocks), and three divisions
            // per triangle were a measurable share of its set-up.
            let t = -k / (edge.a * i64::from(SUBPIXEL_SCALE)) as f64;
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
    pub(crate) fn row_span(&self, x0: u32, x1: u32, j: u32) -> (u32, u32) {
        if x1 >= x0 + SPAN_MIN {
            self.span(x0, x1, j)
        } else {
            (x0, x1)
        }
    }

    /// The pixels `x0..=x1` of row `j` that this triangle touches, with
    /// their coverage, left to right. A long row is first clipped to the
    /// pixels no edge rejects outright; along it the edge values are stepped incrementally
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
    pub(crate) fn at(&self, base: [i64; 3]) -> Coverage {
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
    pub(crate) fn classify(&self, base: [i64; 3]) -> Class {
        if (0..3).all(|e| base[e] + self.hull_min[e] > 0) {
            Class::Full
        } else if (0..3).any(|e| base[e] + self.hull_max[e] <= 0) {
            Class::Empty
        } else {
            Class::Partial
        }
    }

    /// [`Self::classify`] of the 8 pixels of a row from the one whose
    /// corner values are `base` on, as bits (bit `k` = pixel `k`): those
    /// [`Class::Full`], and those not [`Class::Empty`]. Branch-free.
    #[inline(always)]
    pub(crate) fn classify_run(&self, base: [i64; 3]) -> (u32, u32) {
        let step = self.step_x();
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            return avx2::classify_run(avx2, base, step, (self.hull_min, self.hull_max));
        }
        let (mut full, mut touched) = (0u32, 0u32);
        for k in 0..8 {
            let mut f = true;
            let mut t = true;
            for e in 0..3 {
                let v = base[e] + k as i64 * step[e];
                f &= v + self.hull_min[e] > 0;
                t &= v + self.hull_max[e] > 0;
            }
            full |= u32::from(f) << k;
            touched |= u32::from(t) << k;
        }
        (full, touched)
    }

    /// [`Self::classify`] for every pixel of `(x0, y0)` to `(x1, y1)` at
    /// once: [`Class::Full`] when each of them is full, [`Class::Empty`]
    /// when one edge rejects each of them, else [`Class::Partial`] (then
    /// classify pixel by pixel). An edge value is affine in the pixel, so
    /// its extremes over the rectangle are at the corners its signs pick.
    #[inline]
    pub(crate) fn classify_rect(&self, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> Class {
        let s = i64::from(SUBPIXEL_SCALE);
        let mut full = true;
        for (e, edge) in self.edges.iter().enumerate() {
            let (xl, xh) = if edge.a >= 0 { (x0, x1) } else { (x1, x0) };
            let (yl, yh) = if edge.b >= 0 { (y0, y1) } else { (y1, y0) };
            let high = edge.eval(i64::from(xh) * s, i64::from(yh) * s) + self.hull_max[e];
            if high <= 0 {
                return Class::Empty;
            }
            let low = edge.eval(i64::from(xl) * s, i64::from(yl) * s) + self.hull_min[e];
            full &= low > 0;
        }
        if full { Class::Full } else { Class::Partial }
    }

    /// The second step of [`Self::at`] for a [`Class::Partial`] pixel: its
    /// mask and centre, tested sample by sample (possibly empty).
    #[inline]
    pub(crate) fn partial(&self, base: [i64; 3]) -> Coverage {
        // Non-short-circuit `&`: whether the centre is covered is a coin
        // toss on a partial pixel, and as branches the three tests
        // mispredicted.
        let centre = (base[0] + self.centre[0] > 0)
            & (base[1] + self.centre[1] > 0)
            & (base[2] + self.centre[2] > 0);
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
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            return avx2::grid_mask(avx2, &self.noff, nb);
        }
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
    pixel_range_of(&tri.v, pattern, width, height)
}

/// [`pixel_range`] of the triangle with snapped vertices `v`.
pub(crate) fn pixel_range_of(
    v: &[FixedPt; 3],
    pattern: SamplePattern,
    width: u32,
    height: u32,
) -> Option<(u32, u32, u32, u32)> {
    let (hx0, hy0, hx1, hy1) = pattern.hull();
    let min_x = v.iter().map(|p| p.x).min()?;
    let max_x = v.iter().map(|p| p.x).max()?;
    let min_y = v.iter().map(|p| p.y).min()?;
    let max_y = v.iter().map(|p| p.y).max()?;
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

#[cfg(test)]
mod tests;
