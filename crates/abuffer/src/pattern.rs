//! Sub-pixel sample positions: Carpenter's 8 x 4 mask grid and its
//! subsets.
//!
//! The A-buffer paper (Carpenter 1984; scratchapixel's depth-buffer lesson,
//! in its section on the z-buffer's limitations and history, describes the
//! same 8 columns x 4 rows mask) gives every fragment a 32-bit coverage
//! mask, one bit per cell of an 8 x 4 grid over the pixel. Here each cell is sampled at its centre, on the 1/256-pixel
//! fixed-point grid of the front end, so a mask bit is decided by the same
//! exact integer edge functions and fill rule as every other hider:
//!
//! ```text
//! cell (column c, row r), c in 0..8, r in 0..4:
//!     x = c * 32 + 16,  y = r * 64 + 32   (1/256 pixel, inside the pixel)
//! ```
//!
//! The smaller patterns used by the supersampling baseline and the
//! convergence tables are subsets of that grid (so an N-sample z-buffer and
//! the A-buffer look at the same points), chosen as N-rooks patterns
//! (every column used at most once for N <= 8) symmetric under a half turn
//! about the pixel centre, so none is biased towards a side:
//!
//! | N  | cells (column, row)                                        |
//! |----|------------------------------------------------------------|
//! | 1  | the pixel centre (128, 128) itself, not a grid cell        |
//! | 4  | (2,0) (7,1) (0,2) (5,3)                                    |
//! | 8  | (1,0) (5,0) (3,1) (7,1) (0,2) (4,2) (2,3) (6,3)            |
//! | 16 | checkerboard: even columns in rows 0 and 2, odd in 1 and 3 |
//! | 32 | every cell                                                 |
//!
//! Bit `k` of a mask is sample `k` of the pattern's [`SamplePattern::positions`].

use hider_scene::{Error, Result};

/// Most samples a mask holds (one `u32`).
pub(crate) const MAX_SAMPLES: usize = 32;
/// The pixel centre, in 1/256 pixel inside the pixel.
pub(crate) const CENTRE: (i32, i32) = (128, 128);

/// The position of grid cell `(column, row)` in 1/256 pixel inside the
/// pixel: the cell's centre.
pub(crate) const fn cell_position(column: i32, row: i32) -> (i32, i32) {
    (column * 32 + 16, row * 64 + 32)
}

const fn positions_of<const N: usize>(cells: [(i32, i32); N]) -> [(i32, i32); N] {
    let mut out = [(0, 0); N];
    let mut k = 0;
    while k < N {
        out[k] = cell_position(cells[k].0, cells[k].1);
        k += 1;
    }
    out
}

/// The bounding box of `positions` and the centre.
const fn hull_of(positions: &[(i32, i32)]) -> (i32, i32, i32, i32) {
    let (mut x0, mut y0, mut x1, mut y1) = (CENTRE.0, CENTRE.1, CENTRE.0, CENTRE.1);
    let mut k = 0;
    while k < positions.len() {
        let (x, y) = positions[k];
        if x < x0 {
            x0 = x;
        }
        if y < y0 {
            y0 = y;
        }
        if x > x1 {
            x1 = x;
        }
        if y > y1 {
            y1 = y;
        }
        k += 1;
    }
    (x0, y0, x1, y1)
}

const CENTRE_ONLY: [(i32, i32); 1] = [CENTRE];
const GRID4: [(i32, i32); 4] = positions_of([(2, 0), (7, 1), (0, 2), (5, 3)]);
const GRID8: [(i32, i32); 8] = positions_of([
    (1, 0),
    (5, 0),
    (3, 1),
    (7, 1),
    (0, 2),
    (4, 2),
    (2, 3),
    (6, 3),
]);
const GRID16: [(i32, i32); 16] = {
    let mut cells = [(0, 0); 16];
    let mut k = 0;
    while k < 16 {
        let row = (k / 4) as i32;
        let column = 2 * (k % 4) as i32 + row % 2;
        cells[k] = (column, row);
        k += 1;
    }
    positions_of(cells)
};
const GRID32: [(i32, i32); 32] = {
    let mut cells = [(0, 0); 32];
    let mut k = 0;
    while k < 32 {
        cells[k] = ((k % 8) as i32, (k / 8) as i32);
        k += 1;
    }
    positions_of(cells)
};

/// Where a pixel is sampled: the centre alone, or 4 to 32 cells of the
/// 8 x 4 mask grid (see the module documentation for the positions).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SamplePattern {
    /// One sample at the pixel centre: a mask reduced to what a pixel-centre
    /// z-buffer sees.
    Centre,
    /// 4 cells of the grid.
    Grid4,
    /// 8 cells of the grid.
    Grid8,
    /// 16 cells of the grid (checkerboard).
    Grid16,
    /// All 32 cells: Carpenter's 8 x 4 mask (the default).
    #[default]
    Grid32,
}

impl SamplePattern {
    /// Every pattern, by increasing sample count.
    pub const ALL: [SamplePattern; 5] = [
        SamplePattern::Centre,
        SamplePattern::Grid4,
        SamplePattern::Grid8,
        SamplePattern::Grid16,
        SamplePattern::Grid32,
    ];

    /// The pattern with `count` samples (1, 4, 8, 16 or 32).
    pub fn with_count(count: u32) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|p| p.count() as u32 == count)
            .ok_or_else(|| Error::OutOfRange {
                what: "sample count",
                expected: "1, 4, 8, 16 or 32",
                value: count.to_string(),
            })
    }

    /// The sample positions in 1/256 pixel inside the pixel; bit `k` of a
    /// mask is `positions()[k]`.
    pub fn positions(self) -> &'static [(i32, i32)] {
        match self {
            SamplePattern::Centre => &CENTRE_ONLY,
            SamplePattern::Grid4 => &GRID4,
            SamplePattern::Grid8 => &GRID8,
            SamplePattern::Grid16 => &GRID16,
            SamplePattern::Grid32 => &GRID32,
        }
    }

    /// Number of samples.
    pub fn count(self) -> usize {
        self.positions().len()
    }

    /// The mask with every sample set.
    pub fn full_mask(self) -> u32 {
        match self.count() {
            32 => u32::MAX,
            n => (1u32 << n) - 1,
        }
    }

    /// The bounding box `(min x, min y, max x, max y)` of the samples and
    /// the pixel centre, in 1/256 pixel inside the pixel. A triangle that
    /// contains its four corners contains every sample and the centre
    /// (half-planes are convex): the full-coverage fast path.
    #[inline]
    pub fn hull(self) -> (i32, i32, i32, i32) {
        // Computed at compile time: the depth bounds ask for it per pixel.
        const HULLS: [(i32, i32, i32, i32); 5] = [
            hull_of(&CENTRE_ONLY),
            hull_of(&GRID4),
            hull_of(&GRID8),
            hull_of(&GRID16),
            hull_of(&GRID32),
        ];
        HULLS[self as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_masks() {
        for (p, n) in SamplePattern::ALL.into_iter().zip([1, 4, 8, 16, 32]) {
            assert_eq!(p.count(), n);
            assert_eq!(p.full_mask().count_ones() as usize, n);
            assert_eq!(SamplePattern::with_count(n as u32).unwrap(), p);
        }
        assert!(SamplePattern::with_count(2).is_err());
    }

    #[test]
    fn grid_patterns_are_distinct_grid_cells_symmetric_about_the_centre() {
        for p in &SamplePattern::ALL[1..] {
            let pos = p.positions();
            for (k, &(x, y)) in pos.iter().enumerate() {
                assert_eq!((x - 16) % 32, 0);
                assert_eq!((y - 32) % 64, 0);
                assert!((0..256).contains(&x) && (0..256).contains(&y));
                assert!(!pos[..k].contains(&(x, y)), "{p:?} repeats {x},{y}");
                // Half-turn symmetry: (x, y) -> (256 - x, 256 - y).
                assert!(pos.contains(&(256 - x, 256 - y)), "{p:?} not symmetric");
            }
        }
        // Up to 8 samples no column is used twice (N-rooks).
        for p in [SamplePattern::Grid4, SamplePattern::Grid8] {
            let mut xs: Vec<_> = p.positions().iter().map(|q| q.0).collect();
            xs.sort_unstable();
            xs.dedup();
            assert_eq!(xs.len(), p.count());
        }
    }

    #[test]
    fn smaller_grids_are_subsets_of_the_full_grid() {
        for p in &SamplePattern::ALL[1..] {
            assert!(p.positions().iter().all(|q| GRID32.contains(q)));
        }
        assert_eq!(SamplePattern::Grid32.hull(), (16, 32, 240, 224));
        assert_eq!(SamplePattern::Centre.hull(), (128, 128, 128, 128));
    }
}
