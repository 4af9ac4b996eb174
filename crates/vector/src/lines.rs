//! Hidden-line drawings: the visible parts of the edges that are real
//! lines (silhouettes, open boundaries, creases, material boundaries) and
//! of the curves where surfaces intersect.
//!
//! Visibility is decided exactly along each segment, not by sampling: in
//! screen space a segment's window depth is affine in its parameter, and
//! so is every triangle's depth plane, so the part of a segment that one
//! triangle hides is one interval (the segment clipped to the triangle,
//! then to where the triangle is nearer). The union of those intervals is
//! the hidden part; the rest is drawn. This is Appel's quantitative
//! invisibility reduced to its two values, seen / not seen, computed per
//! occluder instead of propagated.

use glam::{DVec3, DVec4};
use hider_scene::{Result, ScreenScene, ScreenTri};
use i_overlay::i_float::int::point::IntPoint;

use hider_geom::fixed::SUBPIXEL_SCALE;

use crate::VectorOptions;
use crate::chain::join_segments;
use crate::grid::{Bins, ClippedTris, Grid};
use crate::pairs::intersection_segment;
use crate::regions::RegionMap;

/// Why an edge is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LineKind {
    /// Between a front-facing and a back-facing triangle.
    Silhouette,
    /// An edge with one triangle only (or more than two).
    Boundary,
    /// A shared edge whose dihedral angle is above the crease threshold.
    Crease,
    /// A shared edge between two materials.
    Material,
    /// Where two surfaces pass through each other.
    Intersection,
}

/// A polyline in pixels (window coordinates, y down).
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// Why it is drawn.
    pub kind: LineKind,
    /// The points, joined end to end; collinear interior points removed.
    pub points: Vec<(f64, f64)>,
    /// Window depth at each point (for depth cueing, and for checking).
    pub depths: Vec<f64>,
}

hider_scene::hider_stats! {
    /// What [`hidden_lines`] did.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct LineStats {
        /// Edges (and intersection segments) that are lines.
        pub feature_edges: u64 => "feature edges",
        /// Occluder intervals tested.
        pub occluder_tests: u64 => "occluder tests",
        /// Visible pieces before joining.
        pub visible_pieces: u64 => "visible pieces",
        /// Visible polylines after joining.
        pub polylines: u64 => "polylines",
    }
}

/// A hidden-line drawing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineDrawing {
    /// The visible parts, joined into polylines.
    pub visible: Vec<Polyline>,
    /// The hidden parts (only when [`VectorOptions::dashed_hidden`]).
    pub hidden: Vec<Polyline>,
    /// Work counters.
    pub stats: LineStats,
}

impl LineDrawing {
    /// The number of straight segments over all visible polylines.
    pub fn visible_segments(&self) -> usize {
        self.visible
            .iter()
            .map(|p| p.points.len().saturating_sub(1))
            .sum()
    }
}

/// A segment in window space: `(x, y, depth)` at both ends, the primitives
/// it lies on (never counted as hiding it), and why it is drawn.
#[derive(Clone, Copy, Debug)]
struct Feature {
    ends: [DVec3; 2],
    own: [u32; 2],
    kind: LineKind,
}

/// The line drawing of `scene`; `map` supplies the intersection pairs
/// found while computing the visible regions.
pub fn hidden_lines(
    scene: &ScreenScene,
    map: &RegionMap,
    options: &VectorOptions,
) -> Result<LineDrawing> {
    options.validate()?;
    let mut features = edge_features(scene, options.crease_degrees);
    for &(a, b) in &map.cut_pairs {
        let (ta, tb) = (&scene.tris[a as usize], &scene.tris[b as usize]);
        if let Some([p, q]) = intersection_segment(ta, tb, a as usize, b as usize) {
            features.push(Feature {
                ends: [DVec3::new(p.0, p.1, p.2), DVec3::new(q.0, q.1, q.2)],
                own: [ta.prim, tb.prim],
                kind: LineKind::Intersection,
            });
        }
    }
    let grid = map.grid;
    let bins = ClippedTris::new(scene, &grid).bins;
    let mut stats = LineStats {
        feature_edges: features.len() as u64,
        ..LineStats::default()
    };
    let mut visible = Vec::new();
    let mut hidden = Vec::new();
    for f in &features {
        let (shown, unseen) =
            split_visibility(scene, &grid, &bins, f, options.depth_tolerance, &mut stats);
        for (a, b) in shown {
            visible.push((point_at(f, a), point_at(f, b), f.kind));
        }
        if options.dashed_hidden {
            for (a, b) in unseen {
                hidden.push((point_at(f, a), point_at(f, b), f.kind));
            }
        }
    }
    stats.visible_pieces = visible.len() as u64;
    let visible = join_segments(&visible);
    let hidden = join_segments(&hidden);
    stats.polylines = visible.len() as u64;
    Ok(LineDrawing {
        visible,
        hidden,
        stats,
    })
}

fn point_at(f: &Feature, t: f64) -> [f64; 3] {
    f.ends[0].lerp(f.ends[1], t).to_array()
}

/// Fixed-point units per pixel.
const SCALE: f64 = SUBPIXEL_SCALE as f64;

/// Visible or hidden pieces shorter than this (pixels) are dropped.
const MIN_LENGTH: f64 = 1e-3;

/// Pieces shorter than this (in parameter) are dropped: they come from
/// occluders that only touch the segment at a shared vertex.
const MIN_PIECE: f64 = 1e-9;

/// A parameter interval `(from, to)` along a segment.
type Interval = (f64, f64);

/// An edge of a mesh: the keys of its two vertices, in ascending order.
type EdgeKey = ([u64; 3], [u64; 3]);

/// The visible and hidden parameter intervals of one feature segment.
fn split_visibility(
    scene: &ScreenScene,
    grid: &Grid,
    bins: &Bins,
    f: &Feature,
    tolerance: f64,
    stats: &mut LineStats,
) -> (Vec<Interval>, Vec<Interval>) {
    let [p, q] = f.ends;
    let (gx0, gy0) = grid.from_pixels(p.x.min(q.x), p.y.min(q.y));
    let (gx1, gy1) = grid.from_pixels(p.x.max(q.x), p.y.max(q.y));
    let clamp = |v: f64| v.clamp(-1.0, f64::from(i32::MAX)) as i32;
    let lo = IntPoint::new(clamp(gx0.floor()), clamp(gy0.floor()));
    let hi = IntPoint::new(clamp(gx1.ceil()), clamp(gy1.ceil()));
    let mut cover: Vec<(f64, f64)> = Vec::new();
    let mut last = u32::MAX;
    let mut seen = std::collections::HashSet::new();
    bins.query(lo, hi, |k| {
        if k == last || !seen.insert(k) {
            return;
        }
        last = k;
        let t = &scene.tris[k as usize];
        if f.own.contains(&t.prim) {
            return;
        }
        stats.occluder_tests += 1;
        if let Some(iv) = hidden_interval(t, p, q, tolerance) {
            cover.push(iv);
        }
    });
    cover.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Pieces under a thousandth of a pixel are where faces merely touch
    // the segment at a shared corner.
    let length = (q.x - p.x).hypot(q.y - p.y);
    let min_piece = (MIN_LENGTH / length).max(MIN_PIECE);
    let mut shown = Vec::new();
    let mut unseen = Vec::new();
    let mut at = 0.0;
    for (a, b) in cover {
        if a > at + min_piece {
            shown.push((at, a));
        }
        if b > at {
            if b - a.max(at) > min_piece {
                unseen.push((a.max(at), b));
            }
            at = b;
        }
    }
    if 1.0 > at + min_piece {
        shown.push((at, 1.0));
    }
    (shown, unseen)
}

/// The parameter interval of the segment `p -> q` (window space) that
/// triangle `t` hides: inside the triangle and behind its depth plane by
/// more than `tolerance`.
fn hidden_interval(t: &ScreenTri, p: DVec3, q: DVec3, tolerance: f64) -> Option<(f64, f64)> {
    let (mut a, mut b) = (0.0f64, 1.0f64);
    let v = t.v.map(|v| v.to_pixels());
    // Keep where g(s) = g0 + s * (g1 - g0) > 0, for affine g.
    let mut keep = |g0: f64, g1: f64| {
        if g0 <= 0.0 && g1 <= 0.0 {
            b = -1.0;
        } else if g0 <= 0.0 {
            a = a.max(g0 / (g0 - g1));
        } else if g1 <= 0.0 {
            b = b.min(g0 / (g0 - g1));
        }
    };
    for k in 0..3 {
        let (e0, e1) = (v[k], v[(k + 1) % 3]);
        let side = |x: f64, y: f64| (e1.0 - e0.0) * (y - e0.1) - (e1.1 - e0.1) * (x - e0.0);
        keep(side(p.x, p.y), side(q.x, q.y));
    }
    // Behind: the segment's depth minus the triangle's, beyond tolerance.
    let behind = |s: DVec3| s.z - t.depth.eval(s.x, s.y) - tolerance;
    keep(behind(p), behind(q));
    (b - a > MIN_PIECE).then_some((a, b))
}

/// A mesh vertex identified by its exact camera-space coordinates.
fn vertex_key(p: DVec3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// The feature edges of the scene's meshes, projected and clipped to the
/// near and far planes.
fn edge_features(scene: &ScreenScene, crease_degrees: f64) -> Vec<Feature> {
    // (edge as sorted vertex keys, prim, edge runs forward), sorted so the
    // users of one edge are adjacent: cheaper than hashing 48-byte keys.
    let mut uses: Vec<(EdgeKey, u32, bool)> = Vec::with_capacity(3 * scene.prims.len());
    for (prim, info) in scene.prims.iter().enumerate() {
        let c = info.camera;
        if (c[1] - c[0]).cross(c[2] - c[0]).length_squared() == 0.0 {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (vertex_key(c[k]), vertex_key(c[(k + 1) % 3]));
            let key = if a < b { (a, b) } else { (b, a) };
            uses.push((key, prim as u32, a < b));
        }
    }
    uses.sort_unstable();
    let edges = uses.chunk_by(|x, y| x.0 == y.0).map(|run| {
        let users: Vec<(u32, bool)> = run.iter().map(|u| (u.1, u.2)).collect();
        (run[0].0, users)
    });
    let cos_crease = crease_degrees.to_radians().cos();
    let normal = |prim: u32| {
        let c = scene.prims[prim as usize].camera;
        (c[1] - c[0]).cross(c[2] - c[0]).normalize()
    };
    let facing = |prim: u32| {
        let c = scene.prims[prim as usize].camera;
        let n = (c[1] - c[0]).cross(c[2] - c[0]);
        if scene.is_perspective() {
            n.dot(-c[0]) > 0.0
        } else {
            n.z > 0.0
        }
    };
    let mut out = Vec::new();
    for (key, users) in edges {
        let kind = match users.as_slice() {
            [(a, fa), (b, fb)] => {
                let material =
                    scene.prims[*a as usize].material != scene.prims[*b as usize].material;
                // Consistent winding runs a shared edge in opposite
                // directions; otherwise one normal is flipped.
                let cos = normal(*a).dot(normal(*b)) * if fa != fb { 1.0 } else { -1.0 };
                let facing_differs = (facing(*a) != facing(*b)) == (fa != fb);
                if facing_differs {
                    Some(LineKind::Silhouette)
                } else if material {
                    Some(LineKind::Material)
                } else if cos < cos_crease {
                    Some(LineKind::Crease)
                } else {
                    None
                }
            }
            _ => Some(LineKind::Boundary),
        };
        let Some(kind) = kind else { continue };
        let from_bits = |k: [u64; 3]| {
            DVec3::new(
                f64::from_bits(k[0]),
                f64::from_bits(k[1]),
                f64::from_bits(k[2]),
            )
        };
        let own = [users[0].0, users.get(1).map_or(users[0].0, |u| u.0)];
        if let Some(ends) = project_segment(scene, from_bits(key.0), from_bits(key.1)) {
            out.push(Feature { ends, own, kind });
        }
    }
    // A stable order, whatever the hash map's.
    out.sort_by(|a, b| {
        (a.ends[0].x, a.ends[0].y, a.ends[1].x, a.ends[1].y)
            .partial_cmp(&(b.ends[0].x, b.ends[0].y, b.ends[1].x, b.ends[1].y))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    out
}

/// A camera-space segment in window space `(x, y, depth)`, clipped to the
/// near and far planes in clip space; `None` when nothing is left.
fn project_segment(scene: &ScreenScene, a: DVec3, b: DVec3) -> Option<[DVec3; 2]> {
    let m = scene.projection_matrix;
    let (mut ca, mut cb) = (m * a.extend(1.0), m * b.extend(1.0));
    // GL clip space: near is w + z >= 0, far is w - z >= 0.
    for plane in [
        DVec4::new(0.0, 0.0, 1.0, 1.0),
        DVec4::new(0.0, 0.0, -1.0, 1.0),
    ] {
        let (da, db) = (plane.dot(ca), plane.dot(cb));
        if da < 0.0 && db < 0.0 {
            return None;
        }
        if da < 0.0 {
            ca = ca.lerp(cb, da / (da - db));
        } else if db < 0.0 {
            cb = ca.lerp(cb, da / (da - db));
        }
    }
    if ca.w <= 0.0 || cb.w <= 0.0 {
        return None;
    }
    // Snapped to 1/256 pixel like the front end's vertices, so an edge
    // ends exactly where its triangles' corners are and the faces meeting
    // there do not hide a sliver of it.
    let snap = |v: f64| (v * SCALE).round() / SCALE;
    let win = |c: DVec4| {
        let w = scene.viewport.ndc_to_window(c.truncate() / c.w);
        DVec3::new(snap(w.x), snap(w.y), w.z)
    };
    Some([win(ca), win(cb)])
}
