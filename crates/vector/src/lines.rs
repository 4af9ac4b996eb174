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
use crate::chain::{Piece, join_segments};
use crate::document::ObjectGroups;
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
    /// Its object group ([`crate::ObjectGroups`]; 0 when drawn without
    /// groups): the group of the first primitive it lies on.
    pub group: u32,
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
    /// The distance in pixels the pen travels lifted when a plotter draws
    /// the polylines in the order given (the visible ones, then the
    /// hidden ones, as the SVG holds them): the sum of the gaps from each
    /// polyline's last point to the next one's first, the move to the
    /// first left out.
    pub fn pen_up_travel(&self) -> f64 {
        pen_up_travel(self.visible.iter().chain(&self.hidden))
    }

    /// The number of straight segments over all visible polylines.
    pub fn visible_segments(&self) -> usize {
        self.visible
            .iter()
            .map(|p| p.points.len().saturating_sub(1))
            .sum()
    }
}

/// The pen-up travel of polylines drawn in the given order: see
/// [`LineDrawing::pen_up_travel`].
pub fn pen_up_travel<'a>(lines: impl IntoIterator<Item = &'a Polyline>) -> f64 {
    let mut total = 0.0;
    let mut pen: Option<(f64, f64)> = None;
    for l in lines {
        let (Some(&first), Some(&last)) = (l.points.first(), l.points.last()) else {
            continue;
        };
        if let Some(p) = pen {
            total += (first.0 - p.0).hypot(first.1 - p.1);
        }
        pen = Some(last);
    }
    total
}

/// A segment that is a line of the drawing, before visibility: in window
/// space `(x, y, depth)` at both ends (ends snapped to 1/256 pixel like
/// the front end's corners), the primitives it lies on (never counted as
/// hiding it), and why it is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feature {
    /// Both ends, `(x, y, window depth)`.
    pub ends: [DVec3; 2],
    /// Both ends in camera space (unsnapped): visibility is decided
    /// there, against the unsnapped triangles.
    pub camera: [DVec3; 2],
    /// The primitives it lies on (twice the same for a boundary edge).
    pub own: [u32; 2],
    /// Why it is a line.
    pub kind: LineKind,
}

/// Every line of the drawing of `scene` before visibility: the feature
/// edges of its meshes and the intersection segments of `map`'s cut
/// pairs. [`hidden_lines`] splits each into its visible and hidden parts;
/// the tests compare those with a brute-force reference.
pub fn line_features(
    scene: &ScreenScene,
    map: &RegionMap,
    options: &VectorOptions,
) -> Result<Vec<Feature>> {
    options.validate()?;
    let mut features = edge_features(scene, options.crease_degrees);
    for &(a, b) in &map.cut_pairs {
        let (ta, tb) = (&scene.tris[a as usize], &scene.tris[b as usize]);
        if let Some([p, q]) = intersection_segment(ta, tb, a as usize, b as usize) {
            let ends = [DVec3::new(p.0, p.1, p.2), DVec3::new(q.0, q.1, q.2)];
            features.push(Feature {
                ends,
                camera: ends.map(|w| unproject(scene, w)),
                own: [ta.prim, tb.prim],
                kind: LineKind::Intersection,
            });
        }
    }
    Ok(features)
}

/// The visible and hidden parts of one [`Feature`], as parameter
/// intervals `(from, to)` along its window-space segment (0 at
/// `ends[0]`, 1 at `ends[1]`), ascending and disjoint.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Visibility {
    /// The parts drawn.
    pub visible: Vec<(f64, f64)>,
    /// The parts some other surface hides.
    pub hidden: Vec<(f64, f64)>,
}

/// Splits every feature into its visible and hidden parts (what
/// [`hidden_lines`] draws, before joining): the part one triangle hides
/// is one interval, decided in camera space against the unsnapped
/// triangle (its shadow volume from the eye; see `docs/vector.md`).
pub fn feature_visibility(
    scene: &ScreenScene,
    map: &RegionMap,
    features: &[Feature],
    options: &VectorOptions,
) -> Result<Vec<Visibility>> {
    options.validate()?;
    let mut stats = LineStats::default();
    Ok(split_all(scene, map, features, options, &mut stats))
}

fn split_all(
    scene: &ScreenScene,
    map: &RegionMap,
    features: &[Feature],
    options: &VectorOptions,
    stats: &mut LineStats,
) -> Vec<Visibility> {
    let grid = map.grid;
    let bins = ClippedTris::new(scene, &grid).bins;
    let occluders: Vec<Occluder> = scene
        .prims
        .iter()
        .map(|p| Occluder::new(scene, p.camera))
        .collect();
    let context = Context {
        scene,
        grid: &grid,
        bins: &bins,
        occluders: &occluders,
        tolerance: options.depth_tolerance,
    };
    features
        .iter()
        .map(|f| split_visibility(&context, f, stats))
        .collect()
}

/// The line drawing of `scene`; `map` supplies the intersection pairs
/// found while computing the visible regions. All lines are in object
/// group 0; [`hidden_lines_in`] layers them by object.
pub fn hidden_lines(
    scene: &ScreenScene,
    map: &RegionMap,
    options: &VectorOptions,
) -> Result<LineDrawing> {
    hidden_lines_in(scene, map, options, &ObjectGroups::default())
}

/// [`hidden_lines`] with every polyline in the object group of the first
/// primitive it lies on (lines of different groups or kinds are never
/// joined), fragments shorter than [`VectorOptions::min_fragment`]
/// dropped, and the polylines of each layer ordered for a pen plotter
/// (greedy nearest neighbour, reversing a polyline when its far end is
/// nearer; see [`LineDrawing::pen_up_travel`]).
pub fn hidden_lines_in(
    scene: &ScreenScene,
    map: &RegionMap,
    options: &VectorOptions,
    groups: &ObjectGroups,
) -> Result<LineDrawing> {
    let features = line_features(scene, map, options)?;
    let mut stats = LineStats {
        feature_edges: features.len() as u64,
        ..LineStats::default()
    };
    let split = split_all(scene, map, &features, options, &mut stats);
    let mut visible = Vec::new();
    let mut hidden = Vec::new();
    for (f, parts) in features.iter().zip(&split) {
        let group = groups.group_of(f.own[0]);
        for &(a, b) in &parts.visible {
            visible.push((point_at(f, a), point_at(f, b), f.kind, group));
        }
        if options.dashed_hidden {
            for &(a, b) in &parts.hidden {
                hidden.push((point_at(f, a), point_at(f, b), f.kind, group));
            }
        }
    }
    let (visible, hidden) = drop_doubles(visible, hidden);
    stats.visible_pieces = visible.len() as u64;
    let visible = plot_order(join_segments(&visible), options.min_fragment, (0.0, 0.0));
    let pen = visible
        .last()
        .and_then(|l| l.points.last().copied())
        .unwrap_or((0.0, 0.0));
    let hidden = plot_order(join_segments(&hidden), options.min_fragment, pen);
    stats.polylines = visible.len() as u64;
    Ok(LineDrawing {
        visible,
        hidden,
        stats,
    })
}

/// Overlapping collinear pieces drawn once: distinct edges can project
/// onto one segment, or onto overlapping parts of one line (the long
/// edges of a sliver seen edge-on, a piece whose end was cut by one
/// occluder and whose neighbour's by another), and a plotter would draw
/// the overlap twice. Each piece keeps only what the pieces before it on
/// its line left uncovered: those found through buckets of direction
/// (1/1000 radian) and offset (2 pixels), neighbouring buckets included,
/// whose both ends lie within `ON_LINE` (1/500 pixel) of the piece's
/// line.
/// Visible pieces come first, in [`LineKind`]'s order, then the hidden
/// ones, so a hidden piece under a visible one is dropped. Pieces under
/// 1/100 pixel (their direction is not known well enough) are kept as
/// they are.
fn drop_doubles(mut visible: Vec<Piece>, mut hidden: Vec<Piece>) -> (Vec<Piece>, Vec<Piece>) {
    /// How far (pixels) a piece's ends may be from another's line and
    /// still count as on it: well inside any stroke.
    const ON_LINE: f64 = 2e-3;
    let order = |x: &Piece, y: &Piece| (x.2, x.3).cmp(&(y.2, y.3));
    visible.sort_by(order);
    hidden.sort_by(order);
    /// A direction and offset bucket, and the pieces in it by their ends.
    type Buckets = std::collections::HashMap<(i64, i64), Vec<([f64; 2], [f64; 2])>>;
    let mut lines = Buckets::new();
    let mut keep = |pieces: Vec<Piece>| {
        let mut out = Vec::with_capacity(pieces.len());
        for piece in pieces {
            let (a, b) = (piece.0, piece.1);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let length = dx.hypot(dy);
            if length < 1e-2 {
                out.push(piece);
                continue;
            }
            let (ux, uy) = (dx / length, dy / length);
            // The direction folded to [0, pi), and the offset along its
            // normal, bucketed.
            let mut angle = dy.atan2(dx);
            if angle < 0.0 {
                angle += std::f64::consts::PI;
            }
            let (fx, fy) = (angle.cos(), angle.sin());
            let offset = -fy * a[0] + fx * a[1];
            // Offsets are measured from the origin: a direction known to
            // 1e-3 radian moves them by up to 1e-3 times the distance
            // from it, so their buckets are wide.
            let bucket = ((angle / 1e-3).round() as i64, (offset / 2.0).round() as i64);
            let along = |p: [f64; 2]| ux * (p[0] - a[0]) + uy * (p[1] - a[1]);
            let across = |p: [f64; 2]| (-uy * (p[0] - a[0]) + ux * (p[1] - a[1])).abs();
            // What of [0, length] no earlier piece on the line holds.
            let mut free = vec![(0.0, length)];
            let n = (std::f64::consts::PI / 1e-3).round() as i64;
            for da in -1..=1 {
                for dc in -1..=1 {
                    // Directions near 0 and near pi are the same line
                    // with opposite offsets.
                    let mut key = (bucket.0 + da, bucket.1 + dc);
                    if key.0 < 0 || key.0 >= n {
                        key = (key.0.rem_euclid(n), -bucket.1 + dc);
                    }
                    let Some(taken) = lines.get(&key) else {
                        continue;
                    };
                    for &(p, q) in taken {
                        if across(p) > ON_LINE || across(q) > ON_LINE {
                            continue;
                        }
                        let (c, d) = (along(p).min(along(q)), along(p).max(along(q)));
                        free = free
                            .into_iter()
                            .flat_map(|(x, y)| {
                                if d <= x || c >= y {
                                    vec![(x, y)]
                                } else {
                                    [(x, c.max(x)), (d.min(y), y)]
                                        .into_iter()
                                        .filter(|(p, q)| q - p > 1e-4)
                                        .collect()
                                }
                            })
                            .collect();
                    }
                }
            }
            lines
                .entry(bucket)
                .or_default()
                .push(([a[0], a[1]], [b[0], b[1]]));
            let at = |t: f64| {
                let f = t / length;
                [a[0] + f * dx, a[1] + f * dy, a[2] + f * (b[2] - a[2])]
            };
            for (x, y) in free {
                if x == 0.0 && y == length {
                    out.push(piece);
                } else {
                    out.push((at(x), at(y), piece.2, piece.3));
                }
            }
        }
        out
    };
    let visible = keep(visible);
    let hidden = keep(hidden);
    (visible, hidden)
}

/// The length of a polyline in pixels.
fn length(line: &Polyline) -> f64 {
    line.points
        .windows(2)
        .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
        .sum()
}

/// Drops polylines shorter than `min_length` and orders the rest for a
/// pen plotter, keeping each object group contiguous (the SVG's layers):
/// from the pen's position, greedily the object holding the nearest
/// polyline end, in it the nearest polyline (of any kind), reversed when
/// its last point is the nearer end. Objects are compact on the page, so
/// finishing one before the next travels less than sweeping the page once
/// per kind: on the spider at 1024 pixels, 2,727 pixels of pen-up travel
/// this way, 3,661 with each kind contiguous within its object, 5,343 with
/// each kind contiguous over the page (and 1,455 with no grouping at all).
/// `O(n^2)` in the polylines, small next to the visibility work.
fn plot_order(lines: Vec<Polyline>, min_length: f64, start: (f64, f64)) -> Vec<Polyline> {
    let mut left: Vec<Option<Polyline>> = lines
        .into_iter()
        .filter(|l| length(l) >= min_length)
        .map(Some)
        .collect();
    let mut out = Vec::with_capacity(left.len());
    let mut pen = start;
    let mut object: Option<u32> = None;
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    for _ in 0..left.len() {
        // The nearest end in the current object, else anywhere.
        let mut best = [(f64::INFINITY, 0, false); 2];
        for (k, l) in left.iter().enumerate() {
            let Some(l) = l else { continue };
            let (Some(&first), Some(&last)) = (l.points.first(), l.points.last()) else {
                continue;
            };
            let level = usize::from(object != Some(l.group));
            for (d, reversed) in [(dist(pen, first), false), (dist(pen, last), true)] {
                if d < best[level].0 {
                    best[level] = (d, k, reversed);
                }
            }
        }
        let Some(&(_, k, reversed)) = best.iter().find(|b| b.0.is_finite()) else {
            break;
        };
        let Some(mut l) = left[k].take() else { break };
        if reversed {
            l.points.reverse();
            l.depths.reverse();
        }
        pen = *l.points.last().unwrap_or(&pen);
        object = Some(l.group);
        out.push(l);
    }
    out
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

/// How far (in barycentric terms) outside its edges an occluder still
/// holds a point: rounding of the camera-space products, so that a
/// segment lying exactly under the common edge of two occluders (a cube's
/// side edge under its front face's diagonal, seen head-on) is inside
/// both, not between them.
const ON_EDGE: f64 = 1e-12;

/// A triangle this close to edge-on (|det| against the product of its
/// corners' lengths) covers no solid angle worth testing.
const EDGE_ON: f64 = 1e-14;

/// An edge of a mesh: the keys of its two vertices, in ascending order.
type EdgeKey = ([u64; 3], [u64; 3]);

/// How a primitive hides line points.
///
/// Lines are decided against the unsnapped camera-space triangle, not its
/// snapped screen triangle: near a smooth mesh's silhouette the front
/// faces are almost edge-on, their snapped projections (moved by up to
/// 1/512 pixel) cross the silhouette edges, and their ill-conditioned
/// depth planes put them in front there (on the 200-segment sphere at
/// 512 pixels that cut its outline into 12 pieces). In camera space a
/// point is hidden by a triangle exactly when it lies in the triangle's
/// shadow volume from the eye: three planes through the eye and an edge,
/// and the triangle's plane. Each is an affine function of the point, so
/// along a segment the hidden part is again one interval.
#[derive(Clone, Copy, Debug)]
enum Occluder {
    /// Affine forms `a . X + d` (as `(a, d)`) of a camera-space point:
    /// three edge sides, >= 0 inside (scaled so the opposite corner is
    /// 1), and the distance behind the plane, relative to the distance of
    /// the plane along the ray (perspective) or in camera units along the
    /// view direction (orthographic).
    Camera([DVec4; 4]),
    /// The front end clipped the triangle (it crosses the near or far
    /// plane): its screen pieces are what is drawn, so they are tested.
    Screen,
    /// Edge-on: hides nothing.
    Nothing,
}

impl Occluder {
    fn new(scene: &ScreenScene, c: [DVec3; 3]) -> Self {
        let m = scene.projection_matrix;
        let inside = c.iter().all(|p| {
            let k = m * p.extend(1.0);
            k.w > 0.0 && k.z >= -k.w && k.z <= k.w
        });
        if !inside {
            return Self::Screen;
        }
        let n = (c[1] - c[0]).cross(c[2] - c[0]);
        let form = |a: DVec3, d: f64| a.extend(d);
        if scene.is_perspective() {
            // det = c0 . (c1 x c2) = n . c0; (ci x cj) . ck = det.
            let det = n.dot(c[0]);
            let scale = c[0].length() * c[1].length() * c[2].length();
            // NaN corners fail the test too.
            if det.abs() <= EDGE_ON * scale || det.is_nan() {
                return Self::Nothing;
            }
            let side = |i: usize, j: usize| form(c[i].cross(c[j]) / det, 0.0);
            // n . X / det is 1 on the plane and 0 at the eye: minus 1 it
            // is how much farther X is than the plane along its ray.
            Self::Camera([side(1, 2), side(2, 0), side(0, 1), form(n / det, -1.0)])
        } else {
            let d = DVec3::NEG_Z;
            let nd = n.dot(d);
            if nd.abs() <= EDGE_ON * n.length() || nd.is_nan() {
                return Self::Nothing;
            }
            let side = |i: usize, j: usize, k: usize| {
                let a = (c[j] - c[i]).cross(d);
                let s = a.dot(c[k] - c[i]);
                form(a / s, -a.dot(c[i]) / s)
            };
            // X = hit + t d: t = n . (X - c0) / (n . d).
            Self::Camera([
                side(1, 2, 0),
                side(2, 0, 1),
                side(0, 1, 2),
                form(n / nd, -n.dot(c[0]) / nd),
            ])
        }
    }
}

/// What [`split_visibility`] reads.
struct Context<'a> {
    scene: &'a ScreenScene,
    grid: &'a Grid,
    bins: &'a Bins,
    occluders: &'a [Occluder],
    tolerance: f64,
}

/// Shrinks `(a, b)` to where the affine `g(s) = g0 + s (g1 - g0)` is
/// `> 0`, or `>= 0` when `closed`; `b < a` when nothing is left.
fn keep(span: &mut (f64, f64), g0: f64, g1: f64, closed: bool) {
    let out = |g: f64| if closed { g < 0.0 } else { g <= 0.0 };
    if out(g0) && out(g1) {
        span.1 = -1.0;
    } else if out(g0) {
        span.0 = span.0.max(g0 / (g0 - g1));
    } else if out(g1) {
        span.1 = span.1.min(g0 / (g0 - g1));
    }
}

/// The window-segment parameter of camera-segment parameter `u`: under
/// perspective, `w` is not constant along the segment.
fn window_parameter(scene: &ScreenScene, f: &Feature, u: f64) -> f64 {
    if !scene.is_perspective() || u <= 0.0 || u >= 1.0 {
        return u;
    }
    let m = scene.projection_matrix;
    let w0 = (m * f.camera[0].extend(1.0)).w;
    let w1 = (m * f.camera[1].extend(1.0)).w;
    u * w1 / ((1.0 - u) * w0 + u * w1)
}

/// The camera-segment parameter interval of `f` that occluder `o` hides.
fn camera_hidden(
    forms: &[DVec4; 4],
    f: &Feature,
    tolerance: f64,
    perspective: bool,
) -> Option<(f64, f64)> {
    let [x0, x1] = f.camera;
    let eval = |g: DVec4, x: DVec3| g.truncate().dot(x) + g.w;
    let mut span = (0.0f64, 1.0f64);
    for g in &forms[..3] {
        keep(
            &mut span,
            eval(*g, x0) + ON_EDGE,
            eval(*g, x1) + ON_EDGE,
            true,
        );
    }
    // Behind the plane by more than the tolerance (relative to the
    // distance along the ray, or to the point's depth orthographically).
    let behind = |x: DVec3| {
        let scale = if perspective { 1.0 } else { x.z.abs().max(1.0) };
        eval(forms[3], x) - tolerance * scale
    };
    keep(&mut span, behind(x0), behind(x1), false);
    (span.1 - span.0 > MIN_PIECE).then_some(span)
}

/// The visible and hidden parameter intervals of one feature segment.
fn split_visibility(c: &Context, f: &Feature, stats: &mut LineStats) -> Visibility {
    let [p, q] = f.ends;
    // A pixel of margin: candidates come from the snapped triangles'
    // bins, the test from the unsnapped ones.
    let (gx0, gy0) = c.grid.from_pixels(p.x.min(q.x) - 1.0, p.y.min(q.y) - 1.0);
    let (gx1, gy1) = c.grid.from_pixels(p.x.max(q.x) + 1.0, p.y.max(q.y) + 1.0);
    let clamp = |v: f64| v.clamp(-1.0, f64::from(i32::MAX)) as i32;
    let lo = IntPoint::new(clamp(gx0.floor()), clamp(gy0.floor()));
    let hi = IntPoint::new(clamp(gx1.ceil()), clamp(gy1.ceil()));
    let mut cover: Vec<(f64, f64)> = Vec::new();
    let mut seen_tris = std::collections::HashSet::new();
    let mut seen_prims = std::collections::HashSet::new();
    c.bins.query(lo, hi, |k| {
        if !seen_tris.insert(k) {
            return;
        }
        let t = &c.scene.tris[k as usize];
        if f.own.contains(&t.prim) {
            return;
        }
        match &c.occluders[t.prim as usize] {
            Occluder::Nothing => {}
            Occluder::Camera(forms) => {
                if !seen_prims.insert(t.prim) {
                    return;
                }
                stats.occluder_tests += 1;
                if let Some((a, b)) = camera_hidden(forms, f, c.tolerance, c.scene.is_perspective())
                {
                    cover.push((
                        window_parameter(c.scene, f, a),
                        window_parameter(c.scene, f, b),
                    ));
                }
            }
            Occluder::Screen => {
                stats.occluder_tests += 1;
                if let Some(iv) = hidden_interval(t, p, q, c.tolerance) {
                    cover.push(iv);
                }
            }
        }
    });
    cover.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Pieces under a thousandth of a pixel are where faces merely touch
    // the segment at a shared corner.
    let length = (q.x - p.x).hypot(q.y - p.y);
    let min_piece = (MIN_LENGTH / length).max(MIN_PIECE);
    let mut out = Visibility::default();
    // Only the part inside the image is drawn: outside it the occluders
    // are not binned (the regions clip them), and a plotter's page ends
    // there.
    let Some((from, to)) = inside_image(c.scene, p, q) else {
        return out;
    };
    let mut at = from;
    for (a, b) in cover {
        let (a, b) = (a.max(from), b.min(to));
        if b <= a {
            continue;
        }
        if a > at + min_piece {
            out.visible.push((at, a));
        }
        if b > at {
            if b - a.max(at) > min_piece {
                out.hidden.push((a.max(at), b));
            }
            at = b;
        }
    }
    if to > at + min_piece {
        out.visible.push((at, to));
    }
    out
}

/// The parameter interval of the window segment `p -> q` inside the image
/// (Liang-Barsky), `None` when it misses the image.
fn inside_image(scene: &ScreenScene, p: DVec3, q: DVec3) -> Option<(f64, f64)> {
    let (w, h) = (
        f64::from(scene.viewport.width),
        f64::from(scene.viewport.height),
    );
    let mut span = (0.0f64, 1.0f64);
    for (g0, g1) in [
        (p.x, q.x),
        (w - p.x, w - q.x),
        (p.y, q.y),
        (h - p.y, h - q.y),
    ] {
        keep(&mut span, g0, g1, true);
    }
    (span.1 > span.0).then_some(span)
}

/// The parameter interval of the segment `p -> q` (window space) that
/// the screen triangle `t` hides: inside the triangle and behind its depth
/// plane by more than `tolerance`.
fn hidden_interval(t: &ScreenTri, p: DVec3, q: DVec3, tolerance: f64) -> Option<(f64, f64)> {
    let mut span = (0.0f64, 1.0f64);
    let v = t.v.map(|v| v.to_pixels());
    // The triangle is closed: a segment lying exactly along its edge is
    // inside it (edge ends and corners are both on the 1/256-pixel grid,
    // so `side` is exact there and collinear means exactly 0).
    for k in 0..3 {
        let (e0, e1) = (v[k], v[(k + 1) % 3]);
        let side = |x: f64, y: f64| (e1.0 - e0.0) * (y - e0.1) - (e1.1 - e0.1) * (x - e0.0);
        keep(&mut span, side(p.x, p.y), side(q.x, q.y), true);
    }
    // Behind: the segment's depth minus the triangle's, beyond tolerance.
    let behind = |s: DVec3| s.z - t.depth.eval(s.x, s.y) - tolerance;
    keep(&mut span, behind(p), behind(q), false);
    (span.1 - span.0 > MIN_PIECE).then_some(span)
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
        if let Some((ends, camera)) = project_segment(scene, from_bits(key.0), from_bits(key.1)) {
            out.push(Feature {
                ends,
                camera,
                own,
                kind,
            });
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
/// near and far planes in clip space, and its clipped camera-space ends;
/// `None` when nothing is left.
fn project_segment(scene: &ScreenScene, a: DVec3, b: DVec3) -> Option<([DVec3; 2], [DVec3; 2])> {
    let m = scene.projection_matrix;
    let (mut ca, mut cb) = (m * a.extend(1.0), m * b.extend(1.0));
    let (mut a, mut b) = (a, b);
    // GL clip space: near is w + z >= 0, far is w - z >= 0.
    for plane in [
        DVec4::new(0.0, 0.0, 1.0, 1.0),
        DVec4::new(0.0, 0.0, -1.0, 1.0),
    ] {
        let (da, db) = (plane.dot(ca), plane.dot(cb));
        if da < 0.0 && db < 0.0 {
            return None;
        }
        // Clip space is linear in camera space: the same parameter cuts
        // both.
        if da < 0.0 {
            let t = da / (da - db);
            (ca, a) = (ca.lerp(cb, t), a.lerp(b, t));
        } else if db < 0.0 {
            let t = da / (da - db);
            (cb, b) = (ca.lerp(cb, t), a.lerp(b, t));
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
    Some(([win(ca), win(cb)], [a, b]))
}

/// The camera-space point of window position `(x, y, depth)`.
fn unproject(scene: &ScreenScene, w: DVec3) -> DVec3 {
    let vp = scene.viewport;
    let ndc = DVec4::new(
        2.0 * w.x / f64::from(vp.width) - 1.0,
        1.0 - 2.0 * w.y / f64::from(vp.height),
        2.0 * w.z - 1.0,
        1.0,
    );
    let c = scene.projection_matrix.inverse() * ndc;
    c.truncate() / c.w
}
