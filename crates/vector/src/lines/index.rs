//! The occluder candidates of a line segment: the live triangles whose
//! snapped polygons come within a margin of it, found through bins shaped
//! like the triangles.
//!
//! Square bins cost the square of the input on long parallel slivers: a
//! segment along one crosses `W / s` bins of side `s`, each holding the
//! `s / d` slivers of its row (`d` their spacing), so every segment visits
//! `W / d` entries, which grows with `N` whatever `s` is. Bins as
//! elongated as the triangles hold about one sliver per row, so a segment
//! visits about as many entries as it has neighbours. The bins are
//! [`Bins::covering`] in a frame shrunk along the triangles' long axis
//! (their summed box widths over their summed box heights); the margin
//! absorbs the rounding of that shrink.

use glam::DVec3;
use hider_scene::ScreenScene;
use i_overlay::i_float::int::point::IntPoint;

use crate::grid::{Bins, Grid};

/// Largest elongation of the bins (either way): beyond it a bin row is
/// thinner than the grid's units can tell apart at any image size.
const MAX_STRETCH: f64 = (1u64 << 20) as f64;

/// The bins of the occluders, in a frame shrunk by `(sx, sy)`.
pub(super) struct OccluderIndex {
    bins: Bins,
    /// Grid units per shrunk unit, along x and y (one of them 1).
    shrink: (i64, i64),
    /// Grid units per pixel of the region grid.
    unit: f64,
    /// How far (pixels) a snapped occluder may lie from the segment it
    /// hides part of: see [`OccluderIndex::new`].
    margin: f64,
}

impl OccluderIndex {
    /// Bins of `polys[k]` where `live[k]` (the triangles' polygons on
    /// `grid`, clipped to the image).
    ///
    /// Lines are decided against the unsnapped triangles and segments,
    /// candidates found from the snapped ones: a candidate may lie as far
    /// from the segment as a snapped corner from its unsnapped
    /// projection (measured here over the scene, at least the front end's
    /// 1/512 pixel), plus the feature ends' own snapping (1/512 pixel),
    /// plus the clip's rounding to the grid; the margin is that with
    /// half as much again to spare.
    /// `unsnapped[p]` tells whether primitive `p` is tested unsnapped
    /// (not clipped by the near or far plane).
    pub fn new(
        scene: &ScreenScene,
        grid: &Grid,
        live: &[bool],
        polys: &[Vec<IntPoint>],
        unsnapped: &[bool],
    ) -> Self {
        let (mut wide, mut tall) = (0.0f64, 0.0f64);
        for (p, _) in polys.iter().zip(live).filter(|(p, l)| **l && !p.is_empty()) {
            let (lo, hi) = crate::grid::bounds(p).expect("a polygon with points");
            wide += f64::from(hi.x - lo.x) + 1.0;
            tall += f64::from(hi.y - lo.y) + 1.0;
        }
        let stretch = if tall > 0.0 { wide / tall } else { 1.0 };
        let stretch = stretch.clamp(1.0 / MAX_STRETCH, MAX_STRETCH);
        let shrink = if stretch >= 1.0 {
            (stretch.round() as i64, 1)
        } else {
            (1, (1.0 / stretch).round() as i64)
        };
        let shrunk_grid = Grid {
            // Bins as fine as the count asks for: the pixel floor of
            // `Bins::covering` would keep a sliver's row a pixel tall.
            shift: 0,
            width: grid.width / shrink.0 + 1,
            height: grid.height / shrink.1 + 1,
        };
        let shrunk: Vec<Vec<IntPoint>> = polys
            .iter()
            .zip(live)
            .map(|(p, &l)| {
                if l {
                    p.iter().map(|&q| shrink_point(q, shrink)).collect()
                } else {
                    Vec::new()
                }
            })
            .collect();
        let items: Vec<Vec<&[IntPoint]>> = shrunk
            .iter()
            .map(|p| {
                if p.is_empty() {
                    Vec::new()
                } else {
                    vec![p.as_slice()]
                }
            })
            .collect();
        let unit = grid.units_per_pixel();
        let snap = corner_deviation(scene, unsnapped).max(1.0 / 512.0);
        Self {
            bins: Bins::covering(&shrunk_grid, &items),
            shrink,
            unit,
            margin: 1.5 * (snap + 1.0 / 512.0 + 1.0 / unit),
        }
    }

    /// Calls `visit` with every occluder binned within the margin of the
    /// window segment `p -> q` (pixels; an occluder may come more than
    /// once).
    pub fn query(&self, p: DVec3, q: DVec3, visit: impl FnMut(u32)) {
        let (p, q) = if p.x <= q.x { (p, q) } else { (q, p) };
        // In shrunk units, the margin plus one unit for the floor of the
        // binned corners and one for this hexagon's own rounding.
        let to = |x: f64, s: i64| x * self.unit / s as f64;
        let (mx, my) = (
            to(self.margin, self.shrink.0) + 2.0,
            to(self.margin, self.shrink.1) + 2.0,
        );
        let (px, py) = (to(p.x, self.shrink.0), to(p.y, self.shrink.1));
        let (qx, qy) = (to(q.x, self.shrink.0), to(q.y, self.shrink.1));
        // The segment swept by the margin's rectangle: a hexagon, its
        // corners taken from the rectangle's sides the segment leans to.
        let s = if qy >= py { 1.0 } else { -1.0 };
        let hexagon = [
            (px - mx, py - s * my),
            (px + mx, py - s * my),
            (qx + mx, qy - s * my),
            (qx + mx, qy + s * my),
            (qx - mx, qy + s * my),
            (px - mx, py + s * my),
        ];
        let limit = f64::from(i32::MAX / 2);
        let contour: Vec<IntPoint> = hexagon
            .iter()
            .map(|&(x, y)| {
                let c = |v: f64| v.round().clamp(-limit, limit) as i32;
                IntPoint::new(c(x), c(y))
            })
            .collect();
        self.bins.query_covering(&[contour.as_slice()], visit);
    }
}

/// A grid point in the shrunk frame (rounded down: within one unit of
/// the exact shrink, which the query's margin allows for).
fn shrink_point(p: IntPoint, (sx, sy): (i64, i64)) -> IntPoint {
    IntPoint::new(
        i64::from(p.x).div_euclid(sx) as i32,
        i64::from(p.y).div_euclid(sy) as i32,
    )
}

/// The largest distance (pixels, along x or y) between a snapped corner
/// of a primitive tested unsnapped and the nearest of its corners
/// projected unsnapped.
fn corner_deviation(scene: &ScreenScene, unsnapped: &[bool]) -> f64 {
    let m = scene.projection_matrix;
    let window = |c: DVec3| {
        let k = m * c.extend(1.0);
        scene.viewport.ndc_to_window(k.truncate() / k.w)
    };
    let mut worst = 0.0f64;
    for t in scene.tris.iter().filter(|t| unsnapped[t.prim as usize]) {
        let corners = scene.prims[t.prim as usize].camera.map(window);
        for v in t.v {
            let (x, y) = v.to_pixels();
            let d = corners
                .iter()
                .map(|c| (c.x - x).abs().max((c.y - y).abs()))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
    }
    worst
}
