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

mod edges;
mod index;
mod order;
mod sectors;
mod visibility;

use glam::DVec3;
use hider_scene::{Result, ScreenScene};

use crate::VectorOptions;
use crate::chain::join_segments;
use crate::document::ObjectGroups;
use crate::pairs::intersection_segment;
use crate::regions::RegionMap;
use edges::{edge_features, unproject};
use order::{drop_doubles, plot_order};
use visibility::{Occlusion, split_all};

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
        /// Feature edges left out before visibility: they lie on culled
        /// triangles only, or the cull's tiles hide them all along (see
        /// the method in `docs/vector.md`).
        pub culled_features: u64 => "culled feature edges",
        /// Bin entries the feature segments looked at to find their
        /// occluders (an occluder counted once per bin it shares with
        /// the segment's neighbourhood).
        pub occluder_candidates: u64 => "occluder candidates",
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
    let occlusion = Occlusion::new(scene, &map.grid, options);
    split_all(scene, &occlusion, features, options, &mut stats)
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
    let mut features = line_features(scene, map, options)?;
    let mut stats = LineStats {
        feature_edges: features.len() as u64,
        ..LineStats::default()
    };
    let occlusion = Occlusion::new(scene, &map.grid, options);
    // A line on culled primitives only, or under the cull's tiles all
    // along, is hidden (see `crate::cull`): nothing of it would be drawn.
    features.retain(|f| !occlusion.buries(&map.grid, f));
    stats.culled_features = stats.feature_edges - features.len() as u64;
    let split = split_all(scene, &occlusion, &features, options, &mut stats)?;
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
fn point_at(f: &Feature, t: f64) -> [f64; 3] {
    f.ends[0].lerp(f.ends[1], t).to_array()
}
