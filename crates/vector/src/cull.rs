//! Culling what no pixel can show, before the exact geometry.
//!
//! On an overlapping scene most triangles are buried: with depth
//! complexity `d` over a fixed image, `n` triangles make about `n d`
//! overlapping pairs, and `d` grows with `n`, so the pair phase, the
//! booleans and the intersection lines grow with the square of the input
//! while the drawing stays the same. A hierarchical z-buffer would find
//! the buried triangles, but its depths hold at sample points only, and
//! the vector output must stay exact between them. So the image is cut
//! into square tiles, and each tile keeps a conservative *occluder depth*:
//! over the triangles that contain the whole tile (closed, decided exactly
//! on the fixed-point corners), the least of their largest depth over it
//! (a depth plane is affine, so its largest value over a rectangle is at a
//! corner). A triangle is culled when, in every tile its closed area
//! meets, its least depth over the tile is beyond that occluder depth by a
//! margin: some triangle is then strictly nearer at every point of it.
//!
//! Why it is safe, for both outputs:
//! - The nearest covering triangle of a tile is never culled itself (its
//!   least depth there is at most the occluder depth), so the union of the
//!   triangles, and the covered set, is unchanged.
//! - A culled `T` hides nothing the covering `U` does not hide: where `T`
//!   is nearer than some `V` (or ties with it and wins), `U` is nearer than
//!   `V` by more than the margin, which exceeds twice the tie tolerance.
//! - The lines are decided against the unsnapped triangles, whose corners
//!   the front end moved by up to 1/512 pixel: the tiles are therefore
//!   widened by twice that before the tests. An unsnapped triangle's depth
//!   at a point equals its snapped plane's at a point at most 1/512 pixel
//!   away (the same barycentric weights), which lies in the widened tile,
//!   so the bounds hold for the unsnapped triangles too, and the margin
//!   covers the lines' tolerance, which is relative to the distance along
//!   the ray (`far / (far - near)` converts it to window depth).
//!
//! What survives is what is near the front in some tile: bounded by the
//! image, not by the input. The cull is off when hidden lines are drawn
//! (`VectorOptions::dashed_hidden`): they want every hidden edge.

use glam::DVec3;
use hider_scene::ScreenScene;
use i_overlay::i_float::int::point::IntPoint;

use crate::grid::Grid;

/// Most tiles along the image's longer side at the coarsest level.
const COARSE_TILES: i64 = 16;

/// Most tiles along the image's longer side at the finest level.
const FINE_TILES: i64 = 512;

/// How far the tiles are widened, in the front end's 1/256 pixel: twice
/// the most its snapping moves a corner (1/512 pixel), twice over.
const SLACK: i64 = 2;

/// Depth margin on top of the tolerance's: rounding of the plane
/// evaluations (window depths lie in [0, 1]).
const MARGIN: f64 = 1e-7;

/// Which triangles the cull removed, and the tiles' bounds it used.
pub(crate) struct Culled {
    /// Per screen triangle: nearer triangles hide it at every point.
    pub hidden: Vec<bool>,
    /// How many are hidden.
    pub count: u64,
    /// The occluder depths, and the margin over them that hides.
    bounds: Option<(Pyramid, f64)>,
}

impl Culled {
    /// No triangle culled.
    pub fn none(n: usize) -> Self {
        Self {
            hidden: vec![false; n],
            count: 0,
            bounds: None,
        }
    }

    /// Whether the window-space segment `p -> q` (`(x, y, depth)`,
    /// pixels; window depth is affine along it) is hidden at every point
    /// by the tiles' occluders, so that no part of a line on it is
    /// drawn. The same bounds as for triangles: its least depth over each
    /// widened tile it meets is at an end of its part in that tile.
    pub fn buries_segment(&self, grid: &Grid, p: DVec3, q: DVec3) -> bool {
        let Some((pyramid, margin)) = &self.bounds else {
            return false;
        };
        let unit = grid.units_per_pixel();
        let (p, q) = (
            DVec3::new(p.x * unit, p.y * unit, p.z),
            DVec3::new(q.x * unit, q.y * unit, q.z),
        );
        if !(p.is_finite() && q.is_finite()) {
            return false;
        }
        let l = &pyramid.levels[0];
        let cell = |v: f64, n: i64| ((v / l.side as f64).floor() as i64).clamp(0, n - 1);
        let (c0, c1) = (cell(p.x.min(q.x), l.cols), cell(p.x.max(q.x), l.cols));
        let (r0, r1) = (cell(p.y.min(q.y), l.rows), cell(p.y.max(q.y), l.rows));
        (r0..=r1).all(|r| (c0..=c1).all(|c| pyramid.buries_segment(p, q, *margin, (0, c, r))))
    }
}

/// The part of `p -> q` inside the closed rectangle (Liang-Barsky), as
/// parameters; `None` when it misses.
fn clip_segment(p: DVec3, q: DVec3, (x0, y0, x1, y1): Rect) -> Option<(f64, f64)> {
    let (mut a, mut b) = (0.0f64, 1.0f64);
    for (g0, g1) in [
        (p.x - x0 as f64, q.x - x0 as f64),
        (x1 as f64 - p.x, x1 as f64 - q.x),
        (p.y - y0 as f64, q.y - y0 as f64),
        (y1 as f64 - p.y, y1 as f64 - q.y),
    ] {
        if g0 < 0.0 && g1 < 0.0 {
            return None;
        } else if g0 < 0.0 {
            a = a.max(g0 / (g0 - g1));
        } else if g1 < 0.0 {
            b = b.min(g0 / (g0 - g1));
        }
    }
    (a <= b).then_some((a, b))
}

/// One level of the tile pyramid: square tiles of `side` grid units and
/// each tile's occluder depth.
struct Level {
    side: i64,
    cols: i64,
    rows: i64,
    front: Vec<f64>,
}

/// The tile pyramid over the image, coarse to fine (each tile split in
/// four at the next level), in grid units.
struct Pyramid {
    levels: Vec<Level>,
    slack: i64,
    width: i64,
    height: i64,
}

/// A closed rectangle `(x0, y0, x1, y1)` in grid units.
type Rect = (i64, i64, i64, i64);

impl Pyramid {
    fn new(grid: &Grid) -> Self {
        let unit = grid.units_per_pixel() as i64;
        let long = grid.width.max(grid.height).max(1);
        let pixels = (long + unit - 1) / unit;
        // Coarsest: a power of two pixels, at most COARSE_TILES across.
        let coarse = ((pixels + COARSE_TILES - 1) / COARSE_TILES) as u64;
        let mut side = unit * coarse.next_power_of_two() as i64;
        let mut levels = Vec::new();
        loop {
            let cols = (grid.width + side - 1) / side;
            let rows = (grid.height + side - 1) / side;
            levels.push(Level {
                side,
                cols: cols.max(1),
                rows: rows.max(1),
                front: vec![f64::INFINITY; (cols.max(1) * rows.max(1)) as usize],
            });
            // Down to half a pixel, or FINE_TILES across.
            if side / 2 < unit / 2 || long / (side / 2) > FINE_TILES || side % 2 != 0 {
                break;
            }
            side /= 2;
        }
        Self {
            levels,
            slack: SLACK << grid.shift,
            width: grid.width,
            height: grid.height,
        }
    }

    /// The coarsest tiles `(c0, r0, c1, r1)` a box meets (inclusive).
    fn range(&self, lo: IntPoint, hi: IntPoint) -> (i64, i64, i64, i64) {
        let l = &self.levels[0];
        let cell = |v: i32, n: i64| (i64::from(v) / l.side).clamp(0, n - 1);
        (
            cell(lo.x, l.cols),
            cell(lo.y, l.rows),
            cell(hi.x, l.cols),
            cell(hi.y, l.rows),
        )
    }

    /// Tile `(c, r)` of level `k`, widened by the slack when `widen`.
    fn rect(&self, k: usize, c: i64, r: i64, widen: bool) -> Rect {
        let side = self.levels[k].side;
        let s = if widen { self.slack } else { 0 };
        (
            c * side - s,
            r * side - s,
            ((c + 1) * side).min(self.width) + s,
            ((r + 1) * side).min(self.height) + s,
        )
    }

    /// The four tiles of level `k + 1` inside tile `(c, r)` of level `k`
    /// (fewer at the image's border).
    fn children(&self, k: usize, c: i64, r: i64) -> impl Iterator<Item = (i64, i64)> + use<> {
        let next = &self.levels[k + 1];
        let (cols, rows) = (next.cols, next.rows);
        (0..4)
            .map(move |q| (2 * c + q % 2, 2 * r + q / 2))
            .filter(move |&(x, y)| x < cols && y < rows)
    }

    /// Records triangle `v` (corners in grid units) as the occluder of
    /// every tile it contains, widened, within tile `(c, r)` of level `k`:
    /// a contained tile takes its largest depth over the tile (`far`),
    /// others meeting the triangle are split. Only tiles along the edges
    /// are split, so this costs the triangle's perimeter over the finest
    /// tile side, not its area.
    fn occlude(
        &mut self,
        v: &[(i64, i64); 3],
        far: &impl Fn(Rect) -> f64,
        (k, c, r): (usize, i64, i64),
    ) {
        let rect = self.rect(k, c, r, true);
        let pts = corners(rect);
        if separated(v, &pts) {
            return;
        }
        let contained = (0..3).all(|e| {
            let (a, b) = (v[e], v[(e + 1) % 3]);
            pts.iter().all(|&p| orient(a, b, p) >= 0)
        });
        if contained {
            let depth = far(rect);
            let level = &mut self.levels[k];
            let slot = &mut level.front[(r * level.cols + c) as usize];
            if depth.is_finite() && depth < *slot {
                *slot = depth;
            }
        } else if k + 1 < self.levels.len() {
            for (x, y) in self.children(k, c, r) {
                self.occlude(v, far, (k + 1, x, y));
            }
        }
    }

    /// Makes every level's occluder depths complete: a tile contained in a
    /// triangle has its parent's bound too (the triangle contains it), and
    /// a parent is bounded by the farthest of its children's bounds (every
    /// point of it lies in one child, under that child's triangle).
    fn settle(&mut self) {
        for k in 1..self.levels.len() {
            let (upper, lower) = self.levels.split_at_mut(k);
            let (parent, child) = (&upper[k - 1], &mut lower[0]);
            for r in 0..child.rows {
                for c in 0..child.cols {
                    let p = parent.front[((r / 2) * parent.cols + c / 2) as usize];
                    let slot = &mut child.front[(r * child.cols + c) as usize];
                    *slot = slot.min(p);
                }
            }
        }
        for k in (1..self.levels.len()).rev() {
            for r in 0..self.levels[k - 1].rows {
                for c in 0..self.levels[k - 1].cols {
                    let far = self
                        .children(k - 1, c, r)
                        .map(|(x, y)| {
                            let l = &self.levels[k];
                            l.front[(y * l.cols + x) as usize]
                        })
                        .fold(f64::NEG_INFINITY, f64::max);
                    let l = &mut self.levels[k - 1];
                    let slot = &mut l.front[(r * l.cols + c) as usize];
                    *slot = slot.min(far);
                }
            }
        }
    }

    /// Whether the triangle `v`, whose least depth over a rectangle is
    /// `near`, is beyond the occluder depth by `margin` everywhere it
    /// meets tile `(c, r)` of level `k`: tested on the tile, then on its
    /// children where the tile's bound is not enough.
    fn buries(
        &self,
        v: &[(i64, i64); 3],
        near: &impl Fn(Rect) -> f64,
        margin: f64,
        (k, c, r): (usize, i64, i64),
    ) -> bool {
        if separated(v, &corners(self.rect(k, c, r, false))) {
            return true;
        }
        let level = &self.levels[k];
        let front = level.front[(r * level.cols + c) as usize];
        if front.is_finite() && near(self.rect(k, c, r, true)) > front + margin {
            return true;
        }
        k + 1 < self.levels.len()
            && self
                .children(k, c, r)
                .all(|(x, y)| self.buries(v, near, margin, (k + 1, x, y)))
    }
}

impl Pyramid {
    /// [`Self::buries`] for a segment in grid units (depth in window
    /// units): where it meets tile `(c, r)` of level `k`, its least depth
    /// over the widened tile is beyond the tile's bound by `margin`.
    fn buries_segment(
        &self,
        p: DVec3,
        q: DVec3,
        margin: f64,
        (k, c, r): (usize, i64, i64),
    ) -> bool {
        // Rounding of the clip: a segment touching the tile counts.
        if clip_segment(p, q, self.rect(k, c, r, false)).is_none() {
            return true;
        }
        let level = &self.levels[k];
        let front = level.front[(r * level.cols + c) as usize];
        if front.is_finite()
            && let Some((a, b)) = clip_segment(p, q, self.rect(k, c, r, true))
        {
            // Widened a little more against the rounding of the clip.
            let (a, b) = ((a - 1e-9).max(0.0), (b + 1e-9).min(1.0));
            let near = (p.z + a * (q.z - p.z)).min(p.z + b * (q.z - p.z));
            if near > front + margin {
                return true;
            }
        }
        k + 1 < self.levels.len()
            && self
                .children(k, c, r)
                .all(|(x, y)| self.buries_segment(p, q, margin, (k + 1, x, y)))
    }
}

/// Whether one edge of the positively oriented triangle `v` has all of
/// `pts` strictly outside (exact).
fn separated(v: &[(i64, i64); 3], pts: &[(i64, i64); 4]) -> bool {
    (0..3).any(|e| {
        let (a, b) = (v[e], v[(e + 1) % 3]);
        pts.iter().all(|&p| orient(a, b, p) < 0)
    })
}

/// `(b - a) x (c - a)`, exact.
fn orient(a: (i64, i64), b: (i64, i64), c: (i64, i64)) -> i128 {
    i128::from(b.0 - a.0) * i128::from(c.1 - a.1) - i128::from(b.1 - a.1) * i128::from(c.0 - a.0)
}

fn corners((x0, y0, x1, y1): Rect) -> [(i64, i64); 4] {
    [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
}

/// How many tolerances of window depth the margin holds, for `scene`'s
/// camera: `far / (far - near)` turns the lines' tolerance (relative to
/// the distance along the ray, or in camera units orthographically) into
/// window depth. `None` when the projection gives no finite bound.
fn depth_ratio(scene: &ScreenScene) -> Option<f64> {
    let m = scene.projection_matrix;
    let ratio = if scene.is_perspective() {
        (1.0 - m.z_axis.z) / 2.0
    } else {
        ((1.0 - m.w_axis.z) / 2.0).max(-m.z_axis.z / 2.0)
    };
    (ratio.is_finite() && ratio > 0.0).then_some(ratio.max(1.0))
}

/// The triangles of `scene` that nearer ones hide at every point (see the
/// module documentation). `boxes` are the triangles' image-clipped boxes
/// on `grid` (`None`: nothing on screen); triangles marked in `skip` are
/// neither culled nor used as occluders (the back faces the regions skip
/// already).
pub(crate) fn cull(
    scene: &ScreenScene,
    grid: &Grid,
    boxes: &[Option<(IntPoint, IntPoint)>],
    skip: &[bool],
    tolerance: f64,
) -> Culled {
    let n = scene.tris.len();
    let Some(ratio) = depth_ratio(scene) else {
        return Culled::none(n);
    };
    let margin = MARGIN + 16.0 * tolerance * ratio;
    let mut pyramid = Pyramid::new(grid);
    let unit = grid.units_per_pixel();
    let depth_at =
        |k: usize, (x, y): (i64, i64)| scene.tris[k].depth.eval(x as f64 / unit, y as f64 / unit);
    let live = |k: usize| boxes[k].filter(|_| !skip[k]);
    // Pass 1: the occluder depths.
    for k in 0..n {
        let Some((lo, hi)) = live(k) else { continue };
        let v = grid.tri_points(&scene.tris[k]);
        let far = |rect: Rect| {
            corners(rect)
                .iter()
                .map(|&p| depth_at(k, p))
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let (c0, r0, c1, r1) = pyramid.range(lo, hi);
        for r in r0..=r1 {
            for c in c0..=c1 {
                pyramid.occlude(&v, &far, (0, c, r));
            }
        }
    }
    pyramid.settle();
    // Pass 2: a triangle is culled when buried in every tile it meets.
    let mut hidden = vec![false; n];
    let mut count = 0;
    for (k, culled) in hidden.iter_mut().enumerate() {
        let Some((lo, hi)) = live(k) else { continue };
        let t = &scene.tris[k];
        let v = grid.tri_points(t);
        let floor = t.z[0].min(t.z[1]).min(t.z[2]);
        let s = pyramid.slack;
        let (bx0, by0, bx1, by1) = (
            i64::from(lo.x) - s,
            i64::from(lo.y) - s,
            i64::from(hi.x) + s,
            i64::from(hi.y) + s,
        );
        // Least depth over the part of a (widened) tile in the widened
        // box: a plane's least value over a rectangle is at a corner, and
        // never below the least corner depth of the triangle.
        let near = |(x0, y0, x1, y1): Rect| {
            corners((x0.max(bx0), y0.max(by0), x1.min(bx1), y1.min(by1)))
                .iter()
                .map(|&p| depth_at(k, p))
                .fold(f64::INFINITY, f64::min)
                .max(floor)
        };
        let (c0, r0, c1, r1) = pyramid.range(lo, hi);
        let buried =
            (r0..=r1).all(|r| (c0..=c1).all(|c| pyramid.buries(&v, &near, margin, (0, c, r))));
        if buried {
            *culled = true;
            count += 1;
        }
    }
    Culled {
        hidden,
        count,
        bounds: Some((pyramid, margin)),
    }
}
