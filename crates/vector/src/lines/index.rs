//! The occluder candidates of a line segment: the live triangles whose
//! snapped polygons come within a margin of it, from bins shaped like
//! the triangles ([`Bins`], whose bins are shaped like their items: on
//! long parallel slivers square bins give a segment every sliver of its
//! bin row).

use glam::DVec3;
use hider_scene::ScreenScene;
use i_overlay::i_float::int::point::IntPoint;

use crate::grid::{Bins, Grid};

/// The bins of the occluders and the margin a segment's query reaches.
pub(super) struct OccluderIndex {
    bins: Bins,
    /// Grid units per pixel of the region grid.
    unit: f64,
    /// How far (pixels) a snapped occluder may lie from the segment it
    /// hides part of: see [`OccluderIndex::new`].
    margin: f64,
    /// A margin beyond which the query covers the whole image anyway
    /// (grid units).
    most: f64,
}

impl OccluderIndex {
    /// Bins of `polys[k]` where `live[k]` is some (the triangles'
    /// polygons on `grid`, clipped to the image); `unsnapped[p]` tells
    /// whether primitive `p` is tested unsnapped (not clipped by the
    /// near or far plane).
    ///
    /// Lines are decided against the unsnapped triangles and segments,
    /// candidates found from the snapped ones: a candidate may lie as far
    /// from the segment as a snapped corner from its unsnapped
    /// projection (measured here over the scene, at least the front end's
    /// 1/512 pixel), plus the feature ends' own snapping (1/512 pixel),
    /// plus the clip's rounding to the grid; the margin is that with
    /// half as much again to spare.
    pub fn new<T>(
        scene: &ScreenScene,
        grid: &Grid,
        live: &[Option<T>],
        polys: &[Vec<IntPoint>],
        unsnapped: &[bool],
    ) -> Self {
        let unit = grid.units_per_pixel();
        let snap = corner_deviation(scene, unsnapped).max(1.0 / 512.0);
        Self {
            bins: Bins::covering_live(grid, live, polys),
            unit,
            margin: 1.5 * (snap + 1.0 / 512.0 + 1.0 / unit),
            most: (grid.width + grid.height) as f64,
        }
    }

    /// Calls `visit` with every occluder binned within the margin of the
    /// window segment `p -> q` (pixels, within the image; an occluder may
    /// come more than once).
    pub fn query(&self, p: DVec3, q: DVec3, visit: impl FnMut(u32)) {
        let (p, q) = if p.x <= q.x { (p, q) } else { (q, p) };
        // In grid units, one more for the rounding of the corners.
        let m = (self.margin * self.unit + 1.0).min(self.most);
        let (px, py, qx, qy) = (
            p.x * self.unit,
            p.y * self.unit,
            q.x * self.unit,
            q.y * self.unit,
        );
        // The segment swept by the margin's square: a hexagon, its
        // corners taken from the square's sides the segment leans to.
        let s = if qy >= py { 1.0 } else { -1.0 };
        let hexagon = [
            (px - m, py - s * m),
            (px + m, py - s * m),
            (qx + m, qy - s * m),
            (qx + m, qy + s * m),
            (qx - m, qy + s * m),
            (px - m, py + s * m),
        ];
        let contour: Vec<IntPoint> = hexagon
            .iter()
            .map(|&(x, y)| IntPoint::new(x.round() as i32, y.round() as i32))
            .collect();
        self.bins.query_covering(&[contour.as_slice()], visit);
    }
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
