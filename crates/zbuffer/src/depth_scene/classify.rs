//! The integer classification of a batch of eight triangles, written lane
//! by lane and without branches: orientation, facing, pixel box and the
//! exact test of the (at most four) pixel centres of a small box.
//!
//! This is the portable definition; `simd/classify.rs` computes the same
//! [`Lanes`] with AVX2 intrinsics. The pixel box, the centres and the fill
//! rule are hider-geom's ([`first_center_from`], [`last_center_upto`],
//! [`pixel_center`], [`top_left_bias`]), the same functions
//! [`Viewport::pixel_bounds`](hider_geom::Viewport::pixel_bounds) and the
//! edge functions of [`hider_geom::edge`] stand for.

use hider_geom::FEW_CENTRES;
use hider_geom::edge::top_left_bias;
use hider_geom::fixed::{SUBPIXEL_SCALE, first_center_from, last_center_upto, pixel_center};

#[cfg(test)]
use super::depth_tri::SmallSetup;

// The centre tests are written out for the first four centres.
const _: () = assert!(FEW_CENTRES == 4);

/// Triangles per batch.
pub(crate) const LANES: usize = 8;

/// `CENTRE_AT[w]`: the columns and the rows, from the box's first pixel,
/// of the first [`FEW_CENTRES`] centres (row-major) of a box `w` centres
/// wide: `j % w` and `j / w`, without the division (its latency showed
/// per fragment).
pub(crate) const CENTRE_AT: [[[i32; FEW_CENTRES]; 2]; FEW_CENTRES + 1] = {
    let mut at = [[[0; FEW_CENTRES]; 2]; FEW_CENTRES + 1];
    let mut w = 1;
    while w <= FEW_CENTRES {
        let mut j = 0;
        while j < FEW_CENTRES {
            at[w][0][j] = (j % w) as i32;
            at[w][1][j] = (j / w) as i32;
            j += 1;
        }
        w += 1;
    }
    at
};

/// The integer classification of a batch, lane by lane.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Lanes {
    /// How many lanes are dropped for a zero area, for facing away, and
    /// for covering no centre (in that order of precedence, as the
    /// triangle pass's one-by-one path tests).
    pub(crate) degenerate: u64,
    pub(crate) back_faces: u64,
    pub(crate) empty: u64,
    /// Bit `i`: lane `i` is kept.
    pub(crate) keep: u8,
    /// Bit `i`: lane `i`'s last two corners must be swapped for positive
    /// order.
    pub(crate) swap: u8,
    /// Bit `i`: lane `i`'s box holds at most [`FEW_CENTRES`] centres; then,
    /// when the box is not empty, bit `j` of `covered[i]` says whether its
    /// `j`-th centre (row-major) is covered (zero in the other lanes).
    pub(crate) few: u8,
    pub(crate) covered: [u8; LANES],
    /// The box's first pixel and its width.
    pub(crate) corner: [(u32, u32, u32); LANES],
}

impl Lanes {
    /// The counts and the kept lanes from the per-lane reasons to drop,
    /// in the order of the one-by-one path's tests: a zero area first,
    /// then the facing, then the centres.
    #[inline(always)]
    pub(crate) fn drop_reasons(&mut self, zero: u8, back: u8, empty: u8) {
        let back = back & !zero;
        let empty = empty & !zero & !back;
        self.degenerate = u64::from(zero.count_ones());
        self.back_faces = u64::from(back.count_ones());
        self.empty = u64::from(empty.count_ones());
        self.keep = !(zero | back | empty);
    }

    /// `orient2d`, `Viewport::pixel_bounds` and
    /// `Viewport::covered_centres`, written lane-wise and without
    /// branches. Corners are snapped window positions (below 2^23 in
    /// magnitude), so their differences fit `i32` and every product fits
    /// `i64` exactly, as in the scalar functions.
    #[inline(always)]
    pub(crate) fn classify(
        x: &[[i32; LANES]; 3],
        y: &[[i32; LANES]; 3],
        (width, height): (u32, u32),
        cull: bool,
    ) -> Self {
        let last = (width as i32 - 1, height as i32 - 1);
        let mut zero = [false; LANES];
        let mut back = [false; LANES];
        let mut swap = [false; LANES];
        let mut few = [false; LANES];
        let mut covered = [0u8; LANES];
        let mut empty = [false; LANES];
        let mut corner = [(0, 0, 0); LANES];
        let mask = |b: &[bool; LANES]| b.iter().rev().fold(0u8, |m, &b| m << 1 | u8::from(b));
        for i in 0..LANES {
            let l = lane(
                [x[0][i], x[1][i], x[2][i]],
                [y[0][i], y[1][i], y[2][i]],
                last,
            );
            zero[i] = l.area == 0;
            back[i] = cull & (l.area > 0);
            swap[i] = l.area < 0;
            few[i] = l.count <= FEW_CENTRES as i32;
            let tested = few[i] & (l.cols > 0) & (l.rows > 0);
            covered[i] = if tested { l.covered } else { 0 };
            empty[i] = (l.cols <= 0) | (l.rows <= 0) | (few[i] & (l.covered == 0));
            corner[i] = (l.x0 as u32, l.y0 as u32, l.cols as u32);
        }
        let mut lanes = Self {
            degenerate: 0,
            back_faces: 0,
            empty: 0,
            keep: 0,
            swap: mask(&swap),
            few: mask(&few),
            covered,
            corner,
        };
        lanes.drop_reasons(mask(&zero), mask(&back), mask(&empty));
        lanes
    }
}

/// The small-box set-ups ([`SmallSetup`]) of a batch's triangles,
/// structure of arrays, as the AVX2 classification computes them
/// (`simd::classify::setups`): lane `i`'s box as two words (`bbox[0][i]`
/// its first column in the low 16 bits and first row in the high ones,
/// `bbox[1][i]` its last column and row: the bytes of
/// [`SmallSetup::bbox`]) and its edge values `e[k][i]`; the words of
/// [`SmallSetup::NONE`] in the lanes without one.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Setups {
    pub(crate) bbox: [[i32; LANES]; 2],
    pub(crate) e: [[i32; LANES]; 3],
}

impl Setups {
    /// The words of [`SmallSetup::NONE`]'s box.
    #[cfg_attr(
        not(target_arch = "x86_64"),
        expect(dead_code, reason = "read only by the x86-64 AVX2 code")
    )]
    pub(crate) const NONE_BBOX: [i32; 2] = [1, 0];

    /// Lane `i`'s set-up (the triangle pass moves the words into its
    /// records as they are, `simd::emit`).
    #[cfg(test)]
    pub(crate) fn get(&self, i: usize) -> SmallSetup {
        let [lo, hi] = [self.bbox[0][i], self.bbox[1][i]];
        SmallSetup {
            bbox: [lo as u16, (lo >> 16) as u16, hi as u16, (hi >> 16) as u16],
            e: [self.e[0][i], self.e[1][i], self.e[2][i]],
        }
    }
}

/// One triangle's integer quantities.
struct Lane {
    /// Twice the signed area.
    area: i64,
    /// The pixel box: first column and row, columns, rows (either may be
    /// zero or negative for an empty box), and their product.
    x0: i32,
    y0: i32,
    cols: i32,
    rows: i32,
    count: i32,
    /// Bit `j`: the box's `j`-th centre (row-major) is covered, for the
    /// first [`FEW_CENTRES`] centres that exist.
    covered: u8,
}

/// Classifies one triangle of corners `x`, `y` (fixed point) in an image
/// whose last column and row are `(w, h)`.
#[inline(always)]
fn lane(x: [i32; 3], y: [i32; 3], (w, h): (i32, i32)) -> Lane {
    let wide = |a: i32, b: i32| i64::from(a) * i64::from(b);
    let [ax, bx, cx] = x;
    let [ay, by, cy] = y;
    let area = wide(bx - ax, cy - ay) - wide(by - ay, cx - ax);
    // The pixel box, as `pixel_bounds` computes it.
    let x0 = first_center_from(ax.min(bx).min(cx)).max(0);
    let y0 = first_center_from(ay.min(by).min(cy)).max(0);
    let x1 = last_center_upto(ax.max(bx).max(cx)).min(w);
    let y1 = last_center_upto(ay.max(by).max(cy)).min(h);
    let (cols, rows) = (x1 - x0 + 1, y1 - y0 + 1);
    // Positive order, then the three edges with the fill rule's bias.
    let (bx, by, cx, cy) = if area < 0 {
        (cx, cy, bx, by)
    } else {
        (bx, by, cx, cy)
    };
    // Each edge at the box's first centre (bias included: inside iff
    // > 0) and its exact steps to the next column and the next row.
    let (px, py) = (pixel_center(x0), pixel_center(y0));
    let unit = i64::from(SUBPIXEL_SCALE);
    let edge = |fx: i32, fy: i32, tx: i32, ty: i32| {
        let (dx, dy) = (tx - fx, ty - fy);
        let at = wide(dx, py - fy) - wide(dy, px - fx) + i64::from(top_left_bias(dx, dy));
        (at, -i64::from(dy) * unit, i64::from(dx) * unit)
    };
    let edges = [
        edge(ax, ay, bx, by),
        edge(bx, by, cx, cy),
        edge(cx, cy, ax, ay),
    ];
    let hit = centre_hits(&edges, cols);
    let count = cols * rows;
    let mut covered = 0u8;
    for (j, &h) in hit.iter().enumerate() {
        covered |= u8::from(h & ((j as i32) < count)) << j;
    }
    Lane {
        area,
        x0,
        y0,
        cols,
        rows,
        count,
        covered,
    }
}

/// Whether each of the box's first [`FEW_CENTRES`] centres, row-major, is
/// inside all three `edges` (each its value at the first centre and its
/// steps per column and per row). The centres are reached as sums of the
/// steps picked by the box's width `cols` (no multiplication in the
/// lanes): a box one wide goes down, two wide goes right then down, wider
/// goes right.
#[inline(always)]
fn centre_hits(edges: &[(i64, i64, i64); 3], cols: i32) -> [bool; FEW_CENTRES] {
    let (one, two) = (cols == 1, cols == 2);
    let mut hit = [true; FEW_CENTRES];
    for &(at, sx, sy) in edges {
        let offset = [
            0,
            if one { sy } else { sx },
            if one {
                sy + sy
            } else if two {
                sy
            } else {
                sx + sx
            },
            if one {
                sy + sy + sy
            } else if two {
                sx + sy
            } else {
                sx + sx + sx
            },
        ];
        for (h, o) in hit.iter_mut().zip(offset) {
            *h &= at + o > 0;
        }
    }
    hit
}
