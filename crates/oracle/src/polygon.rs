//! Convex polygon clipping in `f64`: the one tool [`crate::coverage`]
//! needs.
//!
//! Polygons are vertex lists in window pixels (x right, y down), convex,
//! either orientation. Clipping against a half-plane is Sutherland and
//! Hodgman's re-entrant step (1974) for one plane; subtracting a convex
//! polygon splits the subject along each of the clipper's edges in turn,
//! which keeps every piece convex.

/// A point in pixels.
pub type Point = [f64; 2];

/// A half-plane `a x + b y + c >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfPlane {
    /// Coefficient of x.
    pub a: f64,
    /// Coefficient of y.
    pub b: f64,
    /// Constant term.
    pub c: f64,
}

impl HalfPlane {
    /// The signed value at `p` (non-negative inside).
    #[inline]
    pub fn eval(&self, p: Point) -> f64 {
        self.a * p[0] + self.b * p[1] + self.c
    }

    /// The complementary half-plane (`a x + b y + c <= 0`).
    pub fn flipped(&self) -> Self {
        Self {
            a: -self.a,
            b: -self.b,
            c: -self.c,
        }
    }

    /// The half-plane to the inside of the directed edge `p -> q` of a
    /// polygon whose signed area has sign `orientation` (+1 or -1).
    pub fn inside_of_edge(p: Point, q: Point, orientation: f64) -> Self {
        let a = -(q[1] - p[1]) * orientation;
        let b = (q[0] - p[0]) * orientation;
        Self {
            a,
            b,
            c: -(a * p[0] + b * p[1]),
        }
    }
}

/// Twice the signed area of a polygon (shoelace formula); positive for
/// counter-clockwise order in a y-up frame (clockwise on a y-down screen).
pub fn signed_area2(poly: &[Point]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum()
}

/// The area of a polygon.
pub fn area(poly: &[Point]) -> f64 {
    if poly.len() < 3 {
        0.0
    } else {
        0.5 * signed_area2(poly).abs()
    }
}

/// Clips `poly` to the half-plane `h`, writing the result into `out`
/// (cleared first). Points exactly on the boundary are kept.
pub fn clip(poly: &[Point], h: HalfPlane, out: &mut Vec<Point>) {
    out.clear();
    let n = poly.len();
    if n == 0 {
        return;
    }
    for k in 0..n {
        let (p, q) = (poly[k], poly[(k + 1) % n]);
        let (fp, fq) = (h.eval(p), h.eval(q));
        if fp >= 0.0 {
            out.push(p);
        }
        if (fp >= 0.0) != (fq >= 0.0) {
            // The edge crosses the boundary: the crossing point, computed
            // from the side that is inside so it never leaves the edge.
            let t = fp / (fp - fq);
            out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
        }
    }
    if out.len() < 3 {
        out.clear();
    }
}

/// Pieces smaller than this (in square pixels) are dropped: they are
/// rounding dust from splitting along nearly coincident lines, far below
/// what any sampling hider can resolve (a 64 x 64 grid sample is 2.4e-4).
pub const DUST: f64 = 1e-14;

/// Clipper edges shorter than this (pixels, L1) are repeated vertices.
const MIN_EDGE: f64 = 1e-12;

/// Replaces `pieces` (convex, pairwise disjoint) by their parts outside the
/// convex polygon `clipper`.
pub fn subtract(pieces: &mut Vec<Vec<Point>>, clipper: &[Point]) {
    if clipper.len() < 3 || pieces.is_empty() {
        return;
    }
    let orientation = signed_area2(clipper).signum();
    if orientation == 0.0 {
        return;
    }
    let mut result = Vec::with_capacity(pieces.len());
    let mut inside = Vec::new();
    let mut outside = Vec::new();
    for mut piece in pieces.drain(..) {
        let n = clipper.len();
        for k in 0..n {
            let (p, q) = (clipper[k], clipper[(k + 1) % n]);
            if (q[0] - p[0]).abs() + (q[1] - p[1]).abs() <= MIN_EDGE {
                // A repeated vertex has no edge (its half-plane would be
                // everything, on both sides).
                continue;
            }
            let h = HalfPlane::inside_of_edge(p, q, orientation);
            clip(&piece, h.flipped(), &mut outside);
            if area(&outside) > DUST {
                result.push(outside.clone());
            }
            clip(&piece, h, &mut inside);
            if area(&inside) <= DUST {
                break;
            }
            std::mem::swap(&mut piece, &mut inside);
        }
        // Whatever is left after the last edge lies inside the clipper and
        // is dropped.
    }
    *pieces = result;
}

/// The square `[x, x+1] x [y, y+1]` of pixel `(x, y)`.
pub fn pixel_square(x: u32, y: u32) -> [Point; 4] {
    let (x, y) = (f64::from(x), f64::from(y));
    [[x, y], [x + 1.0, y], [x + 1.0, y + 1.0], [x, y + 1.0]]
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNIT: [Point; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    #[test]
    fn areas_of_simple_shapes() {
        assert_eq!(area(&UNIT), 1.0);
        assert_eq!(area(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]), 0.5);
        assert_eq!(area(&[[0.0, 0.0], [1.0, 0.0]]), 0.0);
    }

    #[test]
    fn clipping_a_square_by_its_diagonal_halves_it() {
        // x + y <= 1, i.e. -x - y + 1 >= 0.
        let mut out = Vec::new();
        clip(
            &UNIT,
            HalfPlane {
                a: -1.0,
                b: -1.0,
                c: 1.0,
            },
            &mut out,
        );
        assert!((area(&out) - 0.5).abs() < 1e-15);
        clip(
            &UNIT,
            HalfPlane {
                a: 0.0,
                b: 0.0,
                c: -1.0,
            },
            &mut out,
        );
        assert!(out.is_empty());
    }

    #[test]
    fn subtracting_keeps_the_complement_in_convex_pieces() {
        let mut pieces = vec![UNIT.to_vec()];
        let centre = [[0.25, 0.25], [0.75, 0.25], [0.75, 0.75], [0.25, 0.75]];
        subtract(&mut pieces, &centre);
        let total: f64 = pieces.iter().map(|p| area(p)).sum();
        assert!((total - 0.75).abs() < 1e-15, "{total}");
        // Either orientation of the clipper works.
        let mut reversed = centre;
        reversed.reverse();
        let mut pieces = vec![UNIT.to_vec()];
        subtract(&mut pieces, &reversed);
        let total: f64 = pieces.iter().map(|p| area(p)).sum();
        assert!((total - 0.75).abs() < 1e-15);
        // A repeated vertex in the clipper changes nothing.
        let repeated = [
            [0.25, 0.25],
            [0.75, 0.25],
            [0.75, 0.25],
            [0.75, 0.75],
            [0.25, 0.75],
        ];
        let mut pieces = vec![UNIT.to_vec()];
        subtract(&mut pieces, &repeated);
        let total: f64 = pieces.iter().map(|p| area(p)).sum();
        assert!((total - 0.75).abs() < 1e-15, "{total}");
        // A clipper covering everything leaves nothing.
        let big = [[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]];
        subtract(&mut pieces, &big);
        assert!(pieces.is_empty());
    }
}
