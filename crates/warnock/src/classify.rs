//! Warnock's four relations between a polygon and a region, decided exactly
//! on the region's samples, and the depth test that lets a surrounding
//! polygon hide the others.
//!
//! Warnock (1969) classifies each polygon against a window as
//! *surrounding* (it covers the whole window), *intersecting* (it covers
//! part of it), *contained* (it lies inside it) or *disjoint* (it misses
//! it). Here a region is a set of sample points, so the relations are
//! about samples: disjoint means the polygon covers none of the region's
//! samples, surrounding means it covers all of them. Both are decided with
//! the shared integer edge functions at the region's four extreme samples:
//! an edge function is affine, so its smallest and largest values over the
//! sample rectangle are at its corners, and the `i64` arithmetic is exact.
//! The test is conservative only in one direction: a polygon that misses
//! every sample but passes the rectangle test is kept as intersecting, and a
//! smaller region settles it.

use hider_geom::edge::top_left_bias;
use hider_geom::fixed::FIXED_LIMIT;
use hider_geom::{EdgeFunction, FixedPt, PlaneEq};
use hider_scene::ScreenTri;

use crate::grid::SampleRect;

/// What classification reads of a triangle, set up once per frame: its
/// three fixed-point vertices (and the primitive id, filling the record to
/// 32 bytes).
///
/// Classification is the inner loop, and on a deep pile every level of the
/// subdivision streams every candidate's record through the cache, so the
/// record is kept to what the four relations need: the bounding box and
/// the edge functions are recomputed from the vertices, exactly (the
/// shared [`EdgeFunction::new`] in `i64`), which costs a few integer
/// multiplications and saves half the memory traffic of storing them. The
/// depth plane, read only for surrounders and samples, lives apart in
/// [`Setups::depth`].
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(crate) struct TriSetup {
    /// The vertices on the fixed-point screen lattice, positively oriented.
    pub v: [FixedPt; 3],
    /// Primitive id written to the frame.
    pub prim: u32,
}

impl TriSetup {
    /// The classification record of a screen triangle; `None` if a vertex
    /// lies beyond [`FIXED_LIMIT`], where the edge functions' `i64`
    /// products could overflow (the front end's guard band never lets one
    /// through).
    pub(crate) fn new(t: &ScreenTri) -> Option<Self> {
        let inside = |p: &FixedPt| p.x.abs() <= FIXED_LIMIT && p.y.abs() <= FIXED_LIMIT;
        t.v.iter().all(inside).then_some(Self {
            v: t.v,
            prim: t.prim,
        })
    }

    /// The three edge functions with the fill rule: the shared ones
    /// ([`ScreenTri::edges`]), recomputed from the vertices.
    #[inline]
    pub(crate) fn edges(&self) -> [EdgeFunction; 3] {
        let v = &self.v;
        [
            EdgeFunction::new(v[0], v[1]),
            EdgeFunction::new(v[1], v[2]),
            EdgeFunction::new(v[2], v[0]),
        ]
    }

    /// Whether the fixed-point sample `(x, y)` is covered: the shared
    /// edge functions under the fill rule, the one coverage decision
    /// every hider makes.
    #[inline]
    pub(crate) fn covers(&self, x: i64, y: i64) -> bool {
        self.edges().iter().all(|e| e.eval(x, y) > 0)
    }

    /// The vertex bounding box.
    #[inline]
    pub(crate) fn bounding_box(&self) -> BoundingBox {
        let (min_x, max_x) = self.x_bounds();
        let (min_y, max_y) = self.y_bounds();
        BoundingBox {
            min_x,
            max_x,
            min_y,
            max_y,
        }
    }

    /// The vertex bounds in x, fixed point.
    #[inline]
    pub(crate) fn x_bounds(&self) -> (i64, i64) {
        let [a, b, c] = self.v.map(|p| p.x);
        (i64::from(a.min(b).min(c)), i64::from(a.max(b).max(c)))
    }

    /// The vertex bounds in y, fixed point.
    #[inline]
    pub(crate) fn y_bounds(&self) -> (i64, i64) {
        let [a, b, c] = self.v.map(|p| p.y);
        (i64::from(a.min(b).min(c)), i64::from(a.max(b).max(c)))
    }
}

/// Window depth at the fixed-point sample `(x, y)` on `plane`, evaluated
/// exactly as the z-buffer evaluates it at a pixel centre.
#[inline]
pub(crate) fn depth_at(plane: &PlaneEq, x: i64, y: i64) -> f64 {
    plane.eval(x as f64 / 256.0, y as f64 / 256.0)
}

/// The set-up of every triangle of a frame, in drawing order: the compact
/// classification records ([`TriSetup`], read at every level) and, apart,
/// the depth planes (read only for surrounders and samples).
#[derive(Clone, Debug, Default)]
pub(crate) struct Setups {
    /// Classification records, indexed by triangle.
    pub tris: Vec<TriSetup>,
    /// Window depth planes, indexed by triangle.
    pub depth: Vec<PlaneEq>,
}

impl Setups {
    /// Bytes of set-up per triangle.
    pub(crate) const BYTES_PER_TRIANGLE: usize =
        std::mem::size_of::<TriSetup>() + std::mem::size_of::<PlaneEq>();

    /// Triangle `t`: its record and its depth plane.
    #[inline]
    pub(crate) fn get(&self, t: u32) -> Tri<'_> {
        Tri {
            setup: &self.tris[t as usize],
            depth: &self.depth[t as usize],
        }
    }

    /// Bytes held (capacity).
    pub(crate) fn bytes(&self) -> usize {
        self.tris.capacity() * std::mem::size_of::<TriSetup>()
            + self.depth.capacity() * std::mem::size_of::<PlaneEq>()
    }
}

/// One triangle's set-up: what the sinks draw with.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri<'a> {
    /// The classification record.
    pub setup: &'a TriSetup,
    /// The window depth plane.
    pub depth: &'a PlaneEq,
}

impl Tri<'_> {
    /// Primitive id written to the frame.
    #[inline]
    pub(crate) fn prim(&self) -> u32 {
        self.setup.prim
    }

    /// See [`TriSetup::covers`].
    #[inline]
    pub(crate) fn covers(&self, x: i64, y: i64) -> bool {
        self.setup.covers(x, y)
    }

    /// Window depth at the fixed-point sample `(x, y)` ([`depth_at`]).
    #[inline]
    pub(crate) fn depth_at(&self, x: i64, y: i64) -> f64 {
        depth_at(self.depth, x, y)
    }
}

/// Warnock's relation of a polygon to a region, about the region's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// Covers none of the region's samples: dropped from the region's list.
    Disjoint,
    /// Covers every sample of the region.
    Surrounding,
    /// Lies inside the region's area (may still miss some samples).
    Contained,
    /// Everything else: covers some samples, or cannot be ruled out yet.
    Intersecting,
}

/// Classifies triangle `t` against the region whose samples span `r` (the
/// tests' entry: the subdivision calls [`classify_in_box`]).
#[cfg(test)]
pub(crate) fn classify(t: &TriSetup, r: &SampleRect) -> Class {
    classify_in_box(t, &t.bounding_box(), r)
}

/// Classifies triangle `t`, whose bounding box is `b`, against the region
/// whose samples span `r` (the subdivision unites the survivors' boxes, so
/// it computes each box once).
///
/// Each edge is evaluated relative to its first vertex, `a (x - fx) +
/// b (y - fy) + bias`: the same integer as [`EdgeFunction::eval`] (whose
/// constant term is `-a fx - b fy + bias`), without computing that term.
#[inline]
pub(crate) fn classify_in_box(t: &TriSetup, b: &BoundingBox, r: &SampleRect) -> Class {
    // Bounding boxes first: the cheap half of the 2-D separating-axis test.
    if b.misses(r) {
        return Class::Disjoint;
    }
    let mut all_inside = true;
    for k in 0..3 {
        let (from, to) = (t.v[k], t.v[(k + 1) % 3]);
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let bias = i64::from(top_left_bias(dx, dy));
        let (a, b) = (-i64::from(dy), i64::from(dx));
        let (fx, fy) = (i64::from(from.x), i64::from(from.y));
        let (ax0, ax1) = (a * (r.x0 - fx), a * (r.x1 - fx));
        let (by0, by1) = (b * (r.y0 - fy), b * (r.y1 - fy));
        // The largest value over the rectangle: if even that is outside,
        // no sample of the region is inside this edge.
        if bias + ax0.max(ax1) + by0.max(by1) <= 0 {
            return Class::Disjoint;
        }
        // The smallest value: if it is inside, every sample is.
        if bias + ax0.min(ax1) + by0.min(by1) <= 0 {
            all_inside = false;
        }
    }
    if all_inside {
        Class::Surrounding
    } else if b.min_x >= r.area_x0
        && b.max_x < r.area_x1
        && b.min_y >= r.area_y0
        && b.max_y < r.area_y1
    {
        Class::Contained
    } else {
        Class::Intersecting
    }
}

/// A vertex bounding box (or a union of them), fixed point, closed: a
/// sample outside it is covered by none of the triangles it bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct BoundingBox {
    /// Smallest x.
    pub min_x: i64,
    /// Largest x.
    pub max_x: i64,
    /// Smallest y.
    pub min_y: i64,
    /// Largest y.
    pub max_y: i64,
}

impl BoundingBox {
    /// The box of nothing: [`Self::union`] with it is the identity.
    pub(crate) const EMPTY: Self = Self {
        min_x: i64::MAX,
        max_x: i64::MIN,
        min_y: i64::MAX,
        max_y: i64::MIN,
    };

    /// The smallest box holding both.
    #[inline]
    pub(crate) fn union(&self, o: &Self) -> Self {
        Self {
            min_x: self.min_x.min(o.min_x),
            max_x: self.max_x.max(o.max_x),
            min_y: self.min_y.min(o.min_y),
            max_y: self.max_y.max(o.max_y),
        }
    }

    /// Whether every sample of the rectangle `r` lies in the box: what a
    /// triangle must satisfy to surround the region of `r`.
    #[inline]
    pub(crate) fn holds(&self, r: &SampleRect) -> bool {
        self.min_x <= r.x0 && self.max_x >= r.x1 && self.min_y <= r.y0 && self.max_y >= r.y1
    }

    /// Whether no sample of the rectangle `r` lies in the box.
    #[inline]
    pub(crate) fn misses(&self, r: &SampleRect) -> bool {
        self.max_x < r.x0 || self.min_x > r.x1 || self.max_y < r.y0 || self.min_y > r.y1
    }
}

/// Relative size of the rounding guard in [`certainly_behind`]: several
/// hundred times the error of evaluating a plane (a few ulps of the
/// magnitude of its terms).
const DEPTH_GUARD: f64 = 1e-13;

/// A depth plane evaluated at a region's four corner samples, with the
/// magnitude that bounds the rounding error of any evaluation inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CornerDepths {
    /// Depth at the corners (top-left, top-right, bottom-left, bottom-right).
    pub depth: [f64; 4],
    /// The largest `|value| + |dx (x - x0)| + |dy (y - y0)|` over the
    /// corners. That sum is convex, so it bounds the terms of the plane's
    /// evaluation at every sample of the region.
    pub magnitude: f64,
}

impl CornerDepths {
    /// Evaluates `plane` at the corners of `r`.
    pub(crate) fn new(plane: &PlaneEq, r: &SampleRect) -> Self {
        let mut depth = [0.0; 4];
        let mut magnitude: f64 = 0.0;
        for (d, (x, y)) in depth.iter_mut().zip(r.corners_in_pixels()) {
            *d = plane.eval(x, y);
            let m = plane.value.abs()
                + (plane.dx * (x - plane.x0)).abs()
                + (plane.dy * (y - plane.y0)).abs();
            magnitude = magnitude.max(m);
        }
        Self { depth, magnitude }
    }

    /// The sum of the corner depths: four times the depth at the centre of
    /// the sample rectangle, the key for picking the front surrounder.
    pub(crate) fn sum(&self) -> f64 {
        self.depth.iter().sum()
    }
}

/// Whether surface `p` is behind surface `s` at every sample of the region,
/// so certainly that a per-sample depth test (`LESS`, evaluated in `f64`
/// as the z-buffer does) would keep `s` at each one, whatever their order.
///
/// The depth difference of two planes is affine, so over the sample
/// rectangle it is smallest at a corner: a positive gap at all four corners
/// is a positive gap everywhere. Each corner gap must beat a guard that
/// covers the rounding of both the corner evaluations and of any interior
/// evaluation; when the planes cross inside the region, or come closer than
/// the guard, the answer is `false` and the caller subdivides further.
#[inline]
pub(crate) fn certainly_behind(p: &CornerDepths, s: &CornerDepths) -> bool {
    let guard = DEPTH_GUARD * (p.magnitude + s.magnitude);
    p.depth
        .iter()
        .zip(&s.depth)
        .all(|(&dp, &ds)| dp - ds > guard)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Grid, Region};
    use hider_geom::FixedPt;

    fn tri(v: [(i32, i32); 3], z: [f64; 3]) -> TriSetup {
        let v = v.map(|(x, y)| FixedPt::new(x * 256, y * 256));
        assert!(hider_geom::orient2d(v[0], v[1], v[2]) > 0);
        let depth = PlaneEq::from_points(&v, z).unwrap();
        let t = ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth,
            inv_w: PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        };
        let s = TriSetup::new(&t).unwrap();
        // The recomputed edge functions are the shared ones.
        assert_eq!(s.edges(), t.edges());
        for (x, y) in [(0, 0), (1000, -77), (-5000, 12345), (2560, 2560)] {
            assert_eq!(
                s.covers(x, y),
                hider_geom::edge::triangle_covers(&t.v, x, y)
            );
        }
        assert_eq!(std::mem::size_of::<TriSetup>(), 32);
        s
    }

    fn rect(u0: u32, v0: u32, u1: u32, v1: u32) -> SampleRect {
        Grid::pixel_centres().sample_rect(&Region::new(u0, v0, u1, v1))
    }

    /// Brute force: how many of the region's pixel centres `t` covers.
    fn covered(t: &TriSetup, u0: u32, v0: u32, u1: u32, v1: u32) -> usize {
        let g = Grid::pixel_centres();
        let mut n = 0;
        for v in v0..v1 {
            for u in u0..u1 {
                n += usize::from(t.covers(g.sample_x(u), g.sample_y(v)));
            }
        }
        n
    }

    #[test]
    fn the_four_relations() {
        // A big right triangle, legs 40 pixels along the top and left.
        let t = tri([(0, 0), (40, 0), (0, 40)], [0.5; 3]);
        assert_eq!(classify(&t, &rect(2, 2, 10, 10)), Class::Surrounding);
        assert_eq!(classify(&t, &rect(30, 30, 40, 40)), Class::Disjoint);
        assert_eq!(classify(&t, &rect(15, 15, 30, 30)), Class::Intersecting);
        assert_eq!(classify(&t, &rect(0, 0, 64, 64)), Class::Contained);
        // The claims are true of the samples.
        assert_eq!(covered(&t, 2, 2, 10, 10), 64);
        assert_eq!(covered(&t, 30, 30, 40, 40), 0);
        let n = covered(&t, 15, 15, 30, 30);
        assert!(n > 0 && n < 225);
    }

    #[test]
    fn a_single_sample_is_either_surrounded_or_disjoint() {
        let t = tri([(0, 0), (10, 0), (0, 10)], [0.5; 3]);
        for v in 0..12 {
            for u in 0..12 {
                let c = classify(&t, &rect(u, v, u + 1, v + 1));
                let inside = covered(&t, u, v, u + 1, v + 1) == 1;
                assert_eq!(
                    c,
                    if inside {
                        Class::Surrounding
                    } else {
                        Class::Disjoint
                    }
                );
            }
        }
    }

    #[test]
    fn surrounder_in_front_and_planes_crossing() {
        let r = rect(0, 0, 8, 8);
        let near = CornerDepths::new(&PlaneEq::constant(0.2), &r);
        let far = CornerDepths::new(&PlaneEq::constant(0.6), &r);
        assert!(certainly_behind(&far, &near));
        assert!(!certainly_behind(&near, &far));
        // A slanted plane crossing 0.2 inside the region: neither hides the
        // other everywhere.
        let slant = PlaneEq {
            x0: 4.0,
            y0: 4.0,
            value: 0.2,
            dx: 0.05,
            dy: 0.0,
        };
        let slant = CornerDepths::new(&slant, &r);
        assert!(!certainly_behind(&slant, &near));
        assert!(!certainly_behind(&near, &slant));
        // Equal planes are a tie, never "certainly behind".
        assert!(!certainly_behind(&near, &near));
    }

    /// The relations straight from the shared edge functions
    /// (`ScreenTri::edges`, constant terms included): what
    /// [`classify_in_box`] computes relative to each edge's first vertex.
    fn classify_reference(t: &ScreenTri, r: &SampleRect) -> Class {
        let xs = t.v.map(|p| i64::from(p.x));
        let ys = t.v.map(|p| i64::from(p.y));
        let (min_x, max_x) = (xs.iter().min().unwrap(), xs.iter().max().unwrap());
        let (min_y, max_y) = (ys.iter().min().unwrap(), ys.iter().max().unwrap());
        if *max_x < r.x0 || *min_x > r.x1 || *max_y < r.y0 || *min_y > r.y1 {
            return Class::Disjoint;
        }
        let corners = [(r.x0, r.y0), (r.x1, r.y0), (r.x0, r.y1), (r.x1, r.y1)];
        let mut all_inside = true;
        for e in t.edges() {
            let values = corners.map(|(x, y)| e.eval(x, y));
            if values.iter().all(|&v| v <= 0) {
                return Class::Disjoint;
            }
            all_inside &= values.iter().all(|&v| v > 0);
        }
        if all_inside {
            Class::Surrounding
        } else if *min_x >= r.area_x0
            && *max_x < r.area_x1
            && *min_y >= r.area_y0
            && *max_y < r.area_y1
        {
            Class::Contained
        } else {
            Class::Intersecting
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]
        /// Random triangles (up to 16 pixels wide) with corners on pixel
        /// centres (so edges pass
        /// exactly through the regions' corner samples, where the fill
        /// rule decides), a few scaled out towards the guard band, against
        /// random regions: the relative evaluation decides exactly as the
        /// shared edge functions do.
        #[test]
        fn classification_equals_the_shared_edge_functions(
            base in (12i32..50, 12i32..50),
            v in proptest::array::uniform3((-8i32..8, -8i32..8)),
            far in 0u32..4,
            (du, dv, w, h) in (-12i32..6, -12i32..6, 1u32..20, 1u32..20),
        ) {
            let scale = [1, 1, 3, 2000][far as usize];
            let centre = |b: i32, k: i32| (2 * (b + k * scale) + 1) * 128;
            let mut p = v.map(|(x, y)| FixedPt::new(centre(base.0, x), centre(base.1, y)));
            let o = hider_geom::orient2d(p[0], p[1], p[2]);
            proptest::prop_assume!(o != 0);
            if o < 0 {
                p.swap(1, 2);
            }
            let t = ScreenTri {
                v: p,
                z: [0.5; 3],
                w: [1.0; 3],
                depth: PlaneEq::constant(0.5),
                inv_w: PlaneEq::constant(1.0),
                prim: 0,
                front_facing: true,
            };
            let s = TriSetup::new(&t).unwrap();
            let (u0, v0) = ((base.0 + du) as u32, (base.1 + dv) as u32);
            let r = rect(u0, v0, u0 + w, v0 + h);
            proptest::prop_assert_eq!(classify(&s, &r), classify_reference(&t, &r));
        }
    }
}
