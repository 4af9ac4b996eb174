//! The occluder candidates of a line segment: the live triangles whose
//! snapped polygons come within a margin of it, from bins shaped like
//! the triangles ([`Bins`], whose bins are shaped like their items: on
//! long parallel slivers square bins give a segment every sliver of its
//! bin row), and from the stars' sectors for the triangles around a
//! shared vertex ([`super::sectors`]).

use glam::DVec3;
use hider_scene::ScreenScene;
use i_overlay::i_float::int::point::IntPoint;

use super::sectors::{StarOccluders, convex_hull};
use crate::grid::{Bins, Grid};
use crate::stars::{NONE, StarPairs, star_pairs};

/// The bins of the occluders and the margin a segment's query reaches.
pub(super) struct OccluderIndex {
    /// The triangles in no star, then one item per star (its members'
    /// convex hull), numbered from `tris`.
    bins: Bins,
    /// The number of triangles.
    tris: usize,
    /// The stars whose members are found by their sectors.
    stars: Vec<StarOccluders>,
    /// The stars' pairs (each triangle's group, and the partners the
    /// sectors' search needs).
    pairs: StarPairs,
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
        let n = scene.tris.len();
        let on: Vec<bool> = live.iter().map(Option::is_some).collect();
        let corners: Vec<_> = scene.tris.iter().map(|t| t.v).collect();
        let pairs = star_pairs(&corners, &on);
        let mut by_group: Vec<Vec<u32>> = Vec::new();
        for t in (0..n).filter(|&t| on[t]) {
            let g = pairs.group(t);
            if g != NONE {
                let g = g as usize;
                if by_group.len() <= g {
                    by_group.resize_with(g + 1, Vec::new);
                }
                by_group[g].push(t as u32);
            }
        }
        let mut star_of = vec![NONE; n];
        let mut stars = Vec::new();
        for (g, members) in by_group.iter().enumerate() {
            if let Some(star) = StarOccluders::new(grid, &corners, g as u32, members) {
                for &t in members {
                    star_of[t as usize] = stars.len() as u32;
                }
                stars.push(star);
            }
        }
        let hulls: Vec<Vec<IntPoint>> = by_group
            .iter()
            .enumerate()
            .filter(|(_, m)| m.first().is_some_and(|&t| star_of[t as usize] != NONE))
            .map(|(_, m)| {
                convex_hull(
                    m.iter()
                        .flat_map(|&t| polys[t as usize].iter().copied())
                        .collect(),
                )
            })
            .collect();
        let items: Vec<Vec<&[IntPoint]>> = (0..n)
            .map(|t| {
                if on[t] && star_of[t] == NONE {
                    vec![polys[t].as_slice()]
                } else {
                    Vec::new()
                }
            })
            .chain(hulls.iter().map(|h| vec![h.as_slice()]))
            .collect();
        Self {
            bins: Bins::covering(grid, &items),
            tris: n,
            stars,
            pairs,
            unit,
            margin: 1.5 * (snap + 1.0 / 512.0 + 1.0 / unit),
            most: (grid.width + grid.height) as f64,
        }
    }

    /// Calls `visit` with every occluder binned within the margin of the
    /// window segment `p -> q` (pixels, within the image; an occluder may
    /// come more than once), and with every member of a star sharing a
    /// bin with it whose sector there meets the margin's directions;
    /// `found` is scratch for the stars.
    pub fn query(&self, p: DVec3, q: DVec3, found: &mut Vec<u32>, mut visit: impl FnMut(u32)) {
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
        found.clear();
        self.bins.query_covering(&[contour.as_slice()], |k| {
            if (k as usize) < self.tris {
                visit(k);
            } else {
                found.push(k - self.tris as u32);
            }
        });
        found.sort_unstable();
        found.dedup();
        for &h in found.iter() {
            self.stars[h as usize].query(
                &contour,
                &self.pairs,
                |t| self.pairs.group(t as usize),
                &mut visit,
            );
        }
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
