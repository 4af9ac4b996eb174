//! The exact integer edge walker the active edge list advances.
//!
//! The shared edge function `E(x, y) = a x + b y + c` (top-left rule folded
//! into `c`, [`hider_geom::EdgeFunction`]) evaluated at the centre of pixel
//! `(i, j)`, `x = 256 i + 128`, `y = 256 j + 128`
//! ([`hider_geom::fixed::pixel_center`]), is `E = S i + R_j` with `S = 256 a`
//! and `R_j = 128 a + b (256 j + 128) + c`. Solving `E > 0` for `i` with
//! integer division:
//! - `a > 0` (the edge goes up the screen: a *left* edge): `i >= floor(-R_j / S) + 1`;
//! - `a < 0` (going down: a *right* edge): `i <= floor((R_j - 1) / -S)`.
//!
//! Both are `floor(N_j / D)` (plus a constant) with `D > 0` and `N_j` growing
//! by `-+256 b` per row, so the bound is walked like a Bresenham line: a
//! quotient and a remainder in `[0, D)`, updated with one add and one compare
//! per row. The bound is bit for bit the one the per-pixel edge test gives,
//! so the scanline covers exactly the z-buffer's pixels.

use hider_geom::EdgeFunction;
use hider_geom::fixed::{SUBPIXEL_SCALE, pixel_center};

/// Which end of a polygon's run on a row an edge bounds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Side {
    /// The edge gives the first covered pixel (`a > 0`).
    #[default]
    Left,
    /// The edge gives the last covered pixel (`a < 0`).
    Right,
}

/// An edge of the edge table / active edge list, with its exact walker.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Edge {
    /// Slot of its polygon in the polygon table.
    pub poly: u32,
    /// Its index in the edge table (bucket order), for the trace.
    pub id: u32,
    /// Which bound it gives.
    pub side: Side,
    /// Last row on which it is active.
    pub last_row: u32,
    /// The bound on the current row: first (left) or last (right) covered
    /// pixel column, unclamped.
    q: i64,
    /// `N_j - D * floor(N_j / D)`, in `[0, d)`.
    rem: i64,
    /// The positive divisor `|256 a|`.
    d: i64,
    /// Whole part of the per-row step of `N_j / D`.
    step_q: i64,
    /// Remainder part of the per-row step, in `[0, d)`.
    step_r: i64,
}

impl Edge {
    /// The walker of `e` (which must not be horizontal) positioned on `row`.
    pub(crate) fn start(e: &EdgeFunction, poly: u32, row: u32, last_row: u32) -> Self {
        let y = i64::from(pixel_center(row as i32));
        let r = i64::from(pixel_center(0)) * e.a + e.b * y + e.c;
        let scale = i64::from(SUBPIXEL_SCALE);
        let per_row = scale * e.b;
        let (side, d, n, step, offset) = if e.a > 0 {
            (Side::Left, scale * e.a, -r, -per_row, 1)
        } else {
            (Side::Right, -scale * e.a, r - 1, per_row, 0)
        };
        let (q, rem) = floor_div(n, d);
        // Most edges of a finely tessellated mesh live on one row: skip the
        // step's division for them (it is never used).
        let (step_q, step_r) = if last_row > row {
            floor_div(step, d)
        } else {
            (0, 0)
        };
        Self {
            poly,
            id: 0,
            side,
            last_row,
            q: q + offset,
            rem,
            d,
            step_q,
            step_r,
        }
    }

    /// The bound on the current row (first or last covered column).
    #[inline]
    pub fn bound(&self) -> i64 {
        self.q
    }

    /// Steps to the next row: `floor((N + step) / D)` from `floor(N / D)`.
    #[inline]
    pub fn advance(&mut self) {
        self.q += self.step_q;
        self.rem += self.step_r;
        if self.rem >= self.d {
            self.rem -= self.d;
            self.q += 1;
        }
    }
}

/// `(floor(n / d), n - d * floor(n / d))` for `d > 0`, exactly.
///
/// Integer division is the slowest instruction of the edge table's set-up
/// (tens of cycles per `i64` division, four per edge), so the quotient is
/// estimated in `f64` and then corrected in integers. While `|n| < 2^53`
/// both operands convert exactly and the rounded quotient is within one of
/// the true floor (relative error `2^-53` of a quotient below `2^45`), so one
/// correction step makes it exact; larger `n` (never produced from
/// coordinates inside [`MAX_COORD`]) take the integer division.
#[inline]
fn floor_div(n: i64, d: i64) -> (i64, i64) {
    const EXACT: i64 = 1 << 53;
    if n.abs() >= EXACT || d >= EXACT {
        return (n.div_euclid(d), n.rem_euclid(d));
    }
    let mut q = (n as f64 / d as f64).floor() as i64;
    let mut r = n - q * d;
    if r < 0 {
        q -= 1;
        r += d;
    } else if r >= d {
        q += 1;
        r -= d;
    }
    (q, r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::FixedPt;

    /// The walker's bounds against the per-pixel edge test, row by row.
    fn check_edge(from: FixedPt, to: FixedPt, rows: std::ops::Range<i32>) {
        let f = EdgeFunction::new(from, to);
        if f.a == 0 {
            return;
        }
        let mut e = Edge::start(&f, 0, rows.start as u32, rows.end as u32);
        for j in rows {
            let y = i64::from(pixel_center(j));
            let inside = |i: i64| f.contains(i64::from(pixel_center(i as i32)), y);
            let b = e.bound();
            match e.side {
                Side::Left => assert!(inside(b) && !inside(b - 1), "left {from:?}->{to:?} row {j}"),
                Side::Right => assert!(
                    inside(b) && !inside(b + 1),
                    "right {from:?}->{to:?} row {j}"
                ),
            }
            e.advance();
        }
    }

    #[test]
    fn walker_matches_edge_test() {
        let pts = [
            (0, 0),
            (1000, 7000),
            (-300, 2560),
            (128, 128),
            (640, 128),
            (129, 5000),
            (5000, 129),
            (-7000, -9),
            (37, 12345),
        ];
        for &(ax, ay) in &pts {
            for &(bx, by) in &pts {
                let (a, b) = (FixedPt::new(ax, ay), FixedPt::new(bx, by));
                if a != b {
                    check_edge(a, b, 0..60);
                }
            }
        }
    }

    #[test]
    fn floor_division_rounds_down_with_a_non_negative_remainder() {
        let check = |n: i64, d: i64| {
            assert_eq!(
                floor_div(n, d),
                (n.div_euclid(d), n.rem_euclid(d)),
                "{n} / {d}"
            );
        };
        for n in -20..20 {
            for d in 1..7 {
                check(n, d);
            }
        }
        // Quotients near integers at the edge of f64 precision, and the
        // integer fallback beyond it.
        let mut rng = hider_scene::procedural::SplitMix64::new(3);
        for _ in 0..20_000 {
            let d = 256 * (1 + (rng.next_u64() % (1 << 26)) as i64);
            let bound = (1i64 << 52) / d;
            let q = (rng.next_u64() % (2 * bound as u64)) as i64 - bound;
            let r = (rng.next_u64() % 3) as i64 - 1;
            check(q * d + r, d);
            check((rng.next_u64() >> 11) as i64 - (1 << 52), d);
        }
        check(i64::MAX, 256);
        check(i64::MIN + 1, 3);
        check((1 << 53) + 1, 768);
    }
}
