//! Regions of the subdivision and where their samples lie.
//!
//! A region is a half-open rectangle of *cells* of a [`Grid`]: pixels in the
//! pixel pass, sub-pixel samples inside one pixel in the anti-aliased pass.
//! What the classification needs is not the region's area but the sample
//! points it contains: every cell holds samples, and the extreme ones span a
//! [`SampleRect`] whose four corners bound every sample of the region. Since
//! edge functions and depth planes are affine, their extremes over all those
//! samples are reached at the corners, which is what makes a four-corner
//! test exact for the whole region.

use hider_geom::fixed::{HALF_PIXEL, SUBPIXEL_SCALE, pixel_center};

/// A pixel's side in fixed-point units.
const PIXEL: i64 = SUBPIXEL_SCALE as i64;

/// Half a pixel in fixed-point units.
const HALF: i64 = HALF_PIXEL as i64;

/// Cells of the subdivision in 1/256-pixel (fixed-point) units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Grid {
    /// Fixed-point x of cell column 0's left side.
    pub origin_x: i64,
    /// Fixed-point y of cell row 0's top side.
    pub origin_y: i64,
    /// Side of a cell in fixed-point units.
    pub cell: i64,
    /// Offset of a cell's first sample from the cell's left or top side.
    pub first: i64,
    /// Offset of a cell's last sample from the cell's left or top side.
    pub last: i64,
}

impl Grid {
    /// Cells are pixels, each sampled at its centre
    /// ([`hider_geom::fixed::pixel_center`]).
    pub(crate) fn pixel_centres() -> Self {
        let centre = i64::from(pixel_center(0));
        Self {
            origin_x: 0,
            origin_y: 0,
            cell: PIXEL,
            first: centre,
            last: centre,
        }
    }

    /// Cells are pixels, each holding `n x n` samples at offsets
    /// `(2k + 1) * 128 / n` (fixed point, 256 to the pixel): the first at
    /// `128 / n`, the last at `256 - 128 / n`.
    pub(crate) fn pixels_with_samples(n: u32) -> Self {
        let half = HALF / i64::from(n);
        Self {
            origin_x: 0,
            origin_y: 0,
            cell: PIXEL,
            first: half,
            last: PIXEL - half,
        }
    }

    /// Cells are the `n x n` samples of pixel `(i, j)`, each one sample.
    pub(crate) fn samples_of_pixel(i: u32, j: u32, n: u32) -> Self {
        let step = PIXEL / i64::from(n);
        Self {
            origin_x: i64::from(i) * PIXEL,
            origin_y: i64::from(j) * PIXEL,
            cell: step,
            first: step / 2,
            last: step / 2,
        }
    }

    /// Whether each cell holds exactly one sample (pixel centres, or the
    /// samples inside a pixel), so that a one-cell region is one sample.
    pub(crate) fn one_sample_per_cell(&self) -> bool {
        self.first == self.last
    }

    /// The fixed-point x of the first sample of cell column `u`.
    #[inline]
    pub(crate) fn sample_x(&self, u: u32) -> i64 {
        self.origin_x + i64::from(u) * self.cell + self.first
    }

    /// The fixed-point y of the first sample of cell row `v`.
    #[inline]
    pub(crate) fn sample_y(&self, v: u32) -> i64 {
        self.origin_y + i64::from(v) * self.cell + self.first
    }

    /// The part of `r` whose cells hold samples inside the fixed-point box
    /// `[min_x, max_x] x [min_y, max_y]` (a triangle's vertex bounds), or
    /// `None` if no sample of `r` lies in it.
    pub(crate) fn cells_touching(
        &self,
        r: &Region,
        (min_x, max_x): (i64, i64),
        (min_y, max_y): (i64, i64),
    ) -> Option<Region> {
        // Cell c holds samples in [origin + c*cell + first, origin + c*cell
        // + last]: it meets [min, max] when its last sample is >= min and
        // its first <= max.
        let first_cell =
            |min: i64, origin: i64| -(-(min - origin - self.last)).div_euclid(self.cell);
        let last_cell = |max: i64, origin: i64| (max - origin - self.first).div_euclid(self.cell);
        let clamp = |c: i64, lo: u32, hi: u32| c.clamp(i64::from(lo), i64::from(hi)) as u32;
        let u0 = clamp(first_cell(min_x, self.origin_x), r.u0, r.u1);
        let u1 = clamp(last_cell(max_x, self.origin_x) + 1, r.u0, r.u1);
        let v0 = clamp(first_cell(min_y, self.origin_y), r.v0, r.v1);
        let v1 = clamp(last_cell(max_y, self.origin_y) + 1, r.v0, r.v1);
        (u0 < u1 && v0 < v1).then_some(Region::new(u0, v0, u1, v1))
    }

    /// The extreme samples and the area of `region`.
    pub(crate) fn sample_rect(&self, r: &Region) -> SampleRect {
        let lo = |origin: i64, c: u32| origin + i64::from(c) * self.cell;
        SampleRect {
            x0: lo(self.origin_x, r.u0) + self.first,
            x1: lo(self.origin_x, r.u1 - 1) + self.last,
            y0: lo(self.origin_y, r.v0) + self.first,
            y1: lo(self.origin_y, r.v1 - 1) + self.last,
            area_x0: lo(self.origin_x, r.u0),
            area_x1: lo(self.origin_x, r.u1),
            area_y0: lo(self.origin_y, r.v0),
            area_y1: lo(self.origin_y, r.v1),
        }
    }
}

/// A half-open rectangle of grid cells `[u0, u1) x [v0, v1)`, never empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Region {
    /// First cell column.
    pub u0: u32,
    /// First cell row.
    pub v0: u32,
    /// One past the last cell column.
    pub u1: u32,
    /// One past the last cell row.
    pub v1: u32,
}

impl Region {
    /// The region `[u0, u1) x [v0, v1)`.
    pub(crate) const fn new(u0: u32, v0: u32, u1: u32, v1: u32) -> Self {
        Self { u0, v0, u1, v1 }
    }

    /// Width in cells.
    #[inline]
    pub(crate) fn width(&self) -> u32 {
        self.u1 - self.u0
    }

    /// Height in cells.
    #[inline]
    pub(crate) fn height(&self) -> u32 {
        self.v1 - self.v0
    }

    /// Number of cells.
    pub(crate) fn cells(&self) -> u64 {
        u64::from(self.width()) * u64::from(self.height())
    }

    /// Whether the region is a single cell.
    #[inline]
    pub(crate) fn is_single_cell(&self) -> bool {
        self.width() == 1 && self.height() == 1
    }

    /// Warnock's split into quadrants at the midpoints. A side of one cell
    /// is not split, so a 1-cell-wide strip splits in two. Returns the
    /// children in reading order (top-left first) and their count (0 for a
    /// single cell).
    pub(crate) fn quadrants(&self) -> ([Region; 4], usize) {
        let mut out = [*self; 4];
        let xs = split(self.u0, self.u1);
        let ys = split(self.v0, self.v1);
        let mut n = 0;
        for &(v0, v1) in ys.iter().flatten() {
            for &(u0, u1) in xs.iter().flatten() {
                out[n] = Region::new(u0, v0, u1, v1);
                n += 1;
            }
        }
        if n == 1 { (out, 0) } else { (out, n) }
    }
}

/// One side cut at its midpoint, or left whole when it is one cell.
fn split(a0: u32, a1: u32) -> [Option<(u32, u32)>; 2] {
    if a1 - a0 <= 1 {
        return [Some((a0, a1)), None];
    }
    let mid = a0 + (a1 - a0).div_ceil(2);
    [Some((a0, mid)), Some((mid, a1))]
}

/// The extreme sample positions of a region (inclusive, fixed point) and
/// its area (half-open, fixed point).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SampleRect {
    /// x of the leftmost samples.
    pub x0: i64,
    /// x of the rightmost samples.
    pub x1: i64,
    /// y of the top samples.
    pub y0: i64,
    /// y of the bottom samples.
    pub y1: i64,
    /// Left side of the region's area.
    pub area_x0: i64,
    /// Right side (exclusive) of the region's area.
    pub area_x1: i64,
    /// Top side of the region's area.
    pub area_y0: i64,
    /// Bottom side (exclusive) of the region's area.
    pub area_y1: i64,
}

impl SampleRect {
    /// The four corner samples in pixels (x, y): top-left, top-right,
    /// bottom-left, bottom-right. Fixed point divided by 256 is exact in
    /// `f64`.
    pub(crate) fn corners_in_pixels(&self) -> [(f64, f64); 4] {
        let p = |v: i64| v as f64 / PIXEL as f64;
        [
            (p(self.x0), p(self.y0)),
            (p(self.x1), p(self.y0)),
            (p(self.x0), p(self.y1)),
            (p(self.x1), p(self.y1)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn pixel_centre_grid_matches_the_convention() {
        let g = Grid::pixel_centres();
        let r = g.sample_rect(&Region::new(2, 3, 5, 4));
        assert_eq!(
            (r.x0, r.x1, r.y0, r.y1),
            (
                i64::from(pixel_center(2)),
                i64::from(pixel_center(4)),
                i64::from(pixel_center(3)),
                i64::from(pixel_center(3))
            )
        );
        assert_eq!((r.area_x0, r.area_x1), (512, 1280));
    }

    #[test]
    fn sub_pixel_samples_are_centred_in_their_cells() {
        // 4 x 4 samples: offsets 32, 96, 160, 224.
        let outer = Grid::pixels_with_samples(4);
        let r = outer.sample_rect(&Region::new(1, 0, 2, 1));
        assert_eq!((r.x0, r.x1), (256 + 32, 256 + 224));
        let inner = Grid::samples_of_pixel(1, 0, 4);
        let xs: Vec<i64> = (0..4).map(|u| inner.sample_x(u)).collect();
        assert_eq!(xs, vec![256 + 32, 256 + 96, 256 + 160, 256 + 224]);
        // The inner grid's whole-pixel rectangle is the outer one's.
        let whole = inner.sample_rect(&Region::new(0, 0, 4, 4));
        assert_eq!(
            (whole.x0, whole.x1, whole.y0, whole.y1),
            (r.x0, r.x1, r.y0, r.y1)
        );
    }

    #[test]
    fn a_single_cell_does_not_split_and_a_strip_splits_in_two() {
        assert_eq!(Region::new(3, 3, 4, 4).quadrants().1, 0);
        let (q, n) = Region::new(0, 0, 1, 5).quadrants();
        assert_eq!(n, 2);
        assert_eq!(&q[..2], &[Region::new(0, 0, 1, 3), Region::new(0, 3, 1, 5)]);
    }

    #[test]
    fn cells_touching_a_box_are_exactly_those_with_a_sample_in_it() {
        for g in [
            Grid::pixel_centres(),
            Grid::pixels_with_samples(4),
            Grid::samples_of_pixel(3, 2, 8),
        ] {
            let r = Region::new(1, 1, 7, 6);
            for (lo, hi) in [(0, 300), (400, 900), (-500, 100), (1000, 5000), (390, 391)] {
                let got = g.cells_touching(&r, (lo, hi), (lo, hi));
                let touches = |c: u32, s: fn(&Grid, u32) -> i64| {
                    let a = s(&g, c);
                    let b = a - g.first + g.last;
                    b >= lo && a <= hi
                };
                for v in r.v0..r.v1 {
                    for u in r.u0..r.u1 {
                        let want = touches(u, Grid::sample_x) && touches(v, Grid::sample_y);
                        let inside =
                            got.is_some_and(|b| u >= b.u0 && u < b.u1 && v >= b.v0 && v < b.v1);
                        assert_eq!(want, inside, "{g:?} box {lo}..{hi} cell {u},{v}");
                    }
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The quadrants tile their parent exactly: every cell in exactly
        /// one child, and each child strictly smaller.
        #[test]
        fn quadrants_tile_the_parent(u0 in 0u32..50, v0 in 0u32..50, w in 1u32..20, h in 1u32..20) {
            let r = Region::new(u0, v0, u0 + w, v0 + h);
            let (q, n) = r.quadrants();
            if w == 1 && h == 1 {
                prop_assert_eq!(n, 0);
                return Ok(());
            }
            let mut count = vec![0u8; (w * h) as usize];
            for c in &q[..n] {
                prop_assert!(c.cells() > 0 && c.cells() < r.cells());
                for v in c.v0..c.v1 {
                    for u in c.u0..c.u1 {
                        prop_assert!(u >= r.u0 && u < r.u1 && v >= r.v0 && v < r.v1);
                        count[((v - v0) * w + (u - u0)) as usize] += 1;
                    }
                }
            }
            prop_assert!(count.iter().all(|&c| c == 1));
        }
    }
}
