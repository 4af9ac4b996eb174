//! Visible regions: for every primitive, the exact part of the image where
//! it is the nearest surface, as integer polygons on the refined grid.
//!
//! The method is object-space differencing: a triangle `T` is visible
//! wherever no other triangle is nearer, and for each overlapping
//! triangle `U` the part of `U` nearer than `T` is all of `U`, nothing, or
//! `U` cut by a straight line (the two depth planes' crossing, see
//! [`crate::pairs`]). So `visible(T) = T - union(nearer parts of U)`, one
//! boolean difference per triangle done by the polygon library on integer
//! coordinates. No depth order is needed, so interpenetration and cycles
//! need no splitting. Triangles nothing overlaps in front (most of a
//! closed mesh's front faces) skip the boolean entirely.

use std::collections::HashMap;

use hider_geom::edge::orient2d;
use hider_scene::{Result, ScreenScene, ScreenTri, ShadeMode};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

use crate::VectorOptions;
use crate::close::{close_to_cover, outline};
use crate::closed::hidden_back_faces;
use crate::cover::{Cover, decide, loops, unmatched_edges};
use crate::cull::{Culled, cull};
use crate::grid::{Bins, Grid, bounds, clip_all};
use crate::group::group_regions;
use crate::ownership::settle_ownership;
use crate::pairs::{Relation, interiors_overlap, relation};
use crate::parts::BooleanWork;
use crate::snap::snap_round;
use crate::splitter::IntShapes;
use crate::splitter::Overlay;
use crate::splitter::new_overlay;
use crate::stars::star_pairs;
use crate::subtract::{BATCH, is_sliver, subtract};

hider_scene::hider_stats! {
    /// What [`visible_regions`] did.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct RegionStats {
        /// Screen triangles with some area inside the image.
        pub triangles: u64 => "triangles",
        /// Pairs of triangles sharing a bin (each counted from both
        /// sides): what the pair phase looks at. It grows with the square
        /// of the triangles meeting at one vertex (the centre of a fan),
        /// which no bin separates (see `docs/vector.md`).
        pub candidate_pairs: u64 => "candidate pairs",
        /// Bin entries the pair phase looked at: each candidate once per
        /// bin the two share. Bins square while the triangles are long
        /// and thin (parallel slivers) make this grow with the square of
        /// the input while the candidate pairs stay few.
        pub bin_visits: u64 => "bin visits",
        /// Candidate pairs whose interiors overlap.
        pub overlapping_pairs: u64 => "overlapping pairs",
        /// Pairs whose depth planes cross inside their common area.
        pub cut_pairs: u64 => "cut pairs",
        /// Boolean differences run (triangles with something in front).
        pub differences: u64 => "differences",
        /// Back faces of closed solids seen from outside, skipped (see
        /// the method in `docs/vector.md`).
        pub hidden_back_faces: u64 => "hidden back faces",
        /// Triangles culled before the pair phase: nearer triangles that
        /// contain whole screen tiles hide them at every point (see the
        /// method in `docs/vector.md`).
        pub culled: u64 => "culled",
        /// Triangles with occluders decided without a boolean: buried
        /// under, or clear of, their occluders' union.
        pub decided: u64 => "decided without boolean",
        /// Primitives whose region the snap rounding rerouted (see
        /// [`visible_regions`]).
        pub snapped: u64 => "snapped regions",
        /// Distinct region edges the map-wide snap rounding rounds.
        pub snap_segments: u64 => "snap segments",
        /// Event points of the snap rounding's crossing sweep (segment
        /// ends and crossings; see `docs/vector.md`).
        pub sweep_events: u64 => "sweep events",
        /// Neighbouring edges the sweep tested for a crossing.
        pub sweep_tests: u64 => "sweep tests",
        /// Pairs of region edges crossing properly (hot pixels they make).
        pub snap_crossings: u64 => "snap crossings",
        /// Hot pixel quadtree nodes the region edges visited to find the
        /// hot pixels they pass.
        pub snap_nodes: u64 => "snap nodes visited",
        /// Boolean differences of the ownership pass.
        pub ownership_differences: u64 => "ownership differences",
        /// Segments sent into the ownership pass's differences, summed:
        /// each takes as clips only the earlier regions that overlap some
        /// region (see `docs/vector.md`, step 6).
        pub ownership_segments: u64 => "ownership segments",
        /// On-screen triangles sent into the union that outlines the
        /// covered set: those neither culled, skipped as back faces, nor
        /// proven inside one nearer triangle or inside the union of whole
        /// nearer triangles (see [`visible_regions`]).
        pub outline_triangles: u64 => "outline triangles",
        /// Polygon vertices of the per-primitive regions and the covered
        /// set's outline sent into the map-wide passes (snap rounding,
        /// ownership, closing); compared with
        /// [`VectorOptions::max_region_points`](crate::VectorOptions::max_region_points).
        pub region_points: u64 => "region points",
        /// Map-wide booleans run (the covered set's outline, ownership,
        /// closing and face-group unions), each over one part of shapes
        /// whose boxes chain together (see `docs/vector.md`, step 6).
        pub map_booleans: u64 => "map booleans",
        /// Segments sent into the map-wide booleans, summed.
        pub map_boolean_segments: u64 => "map boolean segments",
        /// The most segments sent into one map-wide boolean.
        pub largest_boolean: u64 => "largest boolean",
        /// Primitives with a visible region.
        pub visible_prims: u64 => "visible prims",
        /// Face groups (paths of the regions SVG).
        pub groups: u64 => "groups",
        /// Polygon vertices over all group paths.
        pub path_points: u64 => "path points",
    }
}

/// The visible region of one primitive.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimRegion {
    /// The primitive id.
    pub prim: u32,
    /// Index of its face group in [`RegionMap::groups`].
    pub group: u32,
    /// Disjoint polygons with holes (outer contour first), grid units.
    pub shapes: IntShapes,
}

/// One face group: coplanar primitives of one material and one fill
/// colour, merged into one path.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceGroup {
    /// The primitives in the group, ascending.
    pub prims: Vec<u32>,
    /// The fill colour, `#rrggbb` in sRGB.
    pub fill: String,
    /// Opacity of the material.
    pub opacity: f32,
    /// The union of the members' regions (or their concatenation when
    /// merging is off), grid units.
    pub shapes: IntShapes,
}

/// The visible-region map of one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionMap {
    /// The grid the polygons are on.
    pub grid: Grid,
    /// The visible primitives' regions, by ascending primitive id.
    pub prims: Vec<PrimRegion>,
    /// The face groups.
    pub groups: Vec<FaceGroup>,
    /// Work counters.
    pub stats: RegionStats,
    /// Pairs of triangle indices whose depth planes cross inside their
    /// common area (the lower index first): the intersection lines.
    pub cut_pairs: Vec<(u32, u32)>,
    /// The covered set: the union of the triangles on the grid, snap
    /// rounded together with the regions; the union of the regions is
    /// exactly this set.
    pub covered: IntShapes,
}

/// Computes the visible region of every primitive of `scene`, grouped and
/// coloured by `mode`. See the module documentation for the method.
///
/// ```
/// use hider_scene::{prepare, procedural, PrepareOptions, ShadeMode, View};
/// use hider_vector::{visible_regions, VectorOptions};
///
/// let scene = procedural::cube();
/// let screen = prepare(&scene, &View::for_scene(&scene, 64, 64)?, &PrepareOptions::default())?;
/// let map = visible_regions(&screen, &VectorOptions::default(), ShadeMode::Lambert)?;
/// // At most three faces of a cube are seen, two triangles each.
/// assert!(map.prims.len() <= 6);
/// assert!(map.groups.len() <= 3);
/// # Ok::<(), hider_scene::Error>(())
/// ```
pub fn visible_regions(
    scene: &ScreenScene,
    options: &VectorOptions,
    mode: ShadeMode,
) -> Result<RegionMap> {
    build(scene, options, mode, true)
}

/// What [`crate::hidden_lines`] needs of a [`RegionMap`], without the
/// regions: the grid and the intersection pairs, exactly those
/// [`visible_regions`] finds, but no boolean, snap rounding or grouping
/// (`prims`, `groups` and `covered` are empty). For a line drawing alone;
/// when the regions are wanted too, compute them once and pass that map.
pub fn line_pairs(scene: &ScreenScene, options: &VectorOptions) -> Result<RegionMap> {
    build(scene, options, ShadeMode::Ids, false)
}

/// [`visible_regions`], or only its pair phase when `regions` is false.
fn build(
    scene: &ScreenScene,
    options: &VectorOptions,
    mode: ShadeMode,
    regions: bool,
) -> Result<RegionMap> {
    options.validate()?;
    let grid = Grid::for_scene(scene, options.refine_bits)?;

    let (polys, boxes) = clip_all(scene, &grid);
    let mut stats = RegionStats {
        triangles: boxes.iter().flatten().count() as u64,
        ..RegionStats::default()
    };
    let hidden = hidden_back_faces(scene);
    let culled = if options.dashed_hidden {
        // Hidden lines are drawn: the intersection lines of buried
        // triangles are wanted too.
        Culled::none(scene.tris.len())
    } else {
        cull(scene, &grid, &boxes, &hidden, options.depth_tolerance)
    };
    stats.culled = culled.count;
    // Culled triangles are neither regions nor occluders: the tiles'
    // nearer triangles hide whatever they would.
    let live: Vec<_> = boxes
        .iter()
        .zip(&culled.hidden)
        .map(|(b, &c)| if c { None } else { *b })
        .collect();
    // Triangles sharing a star (a fan's centre, two fans on one centre)
    // are paired by their sectors there, not by the bins, which would
    // pair all of them (see `stars.rs`).
    let on: Vec<bool> = live.iter().map(Option::is_some).collect();
    let corners: Vec<_> = scene.tris.iter().map(|t| t.v).collect();
    let stars = star_pairs(&corners, &on);
    let bins = Bins::covering_live(&grid, &live, &polys)
        .with_groups((0..scene.tris.len()).map(|t| stars.group(t)).collect());
    let mut per_prim: HashMap<u32, IntShapes> = HashMap::new();
    let mut region_points = 0u64;
    let mut cut_pairs = Vec::new();
    let mut seen = vec![u32::MAX; scene.tris.len()];
    let mut occluders: Vec<Vec<IntPoint>> = Vec::new();
    // Triangles proven inside the union of other whole triangles: they
    // add nothing to the covered set's outline (see below).
    let mut inside = vec![false; scene.tris.len()];
    // One overlay for all differences: its buffers are kept between uses.
    let mut overlay = new_overlay(64);
    for (ti, t) in scene.tris.iter().enumerate() {
        // A triangle's pairs (a bin query, booleans) cost far more than
        // the poll.
        options.cancel.poll()?;
        let Some((lo, hi)) = boxes[ti] else { continue };
        if hidden[ti] {
            stats.hidden_back_faces += 1;
            continue;
        }
        if culled.hidden[ti] {
            continue;
        }
        if stats.overlapping_pairs > options.max_pairs {
            return Err(hider_scene::Error::Limit {
                what: crate::options::PAIRS_LIMIT,
                value: stats.overlapping_pairs,
                limit: options.max_pairs,
            });
        }
        occluders.clear();
        // Set when one nearer triangle covers all of `t`: nothing of `t`
        // is visible, and the remaining candidates need no test.
        let mut buried = false;
        // Whether some occluder is only the part of a triangle beyond a
        // cut line, whose ends are rounded to the grid.
        let mut cut = false;
        let mut visit = |ui: u32| {
            stats.bin_visits += 1;
            let u_idx = ui as usize;
            // A skipped back face hides nothing its solid's nearer front
            // faces do not hide already.
            if buried || hidden[u_idx] || seen[u_idx] == ti as u32 || u_idx == ti {
                return;
            }
            seen[u_idx] = ti as u32;
            stats.candidate_pairs += 1;
            let u = &scene.tris[u_idx];
            let Some((ulo, uhi)) = boxes[u_idx] else {
                return;
            };
            let apart = uhi.x <= lo.x || ulo.x >= hi.x || uhi.y <= lo.y || ulo.y >= hi.y;
            if u.prim == t.prim || apart || !interiors_overlap(t, u) {
                return;
            }
            stats.overlapping_pairs += 1;
            let rel = relation(
                &grid,
                (ti, t),
                (u_idx, u),
                &polys[u_idx],
                options.depth_tolerance,
            );
            match rel {
                Relation::Behind => {}
                Relation::Front => {
                    buried = covers(u, t);
                    occluders.push(polys[u_idx].clone());
                }
                Relation::Cut(part) => {
                    cut = true;
                    occluders.push(part);
                    // From either side: a buried triangle stops early.
                    cut_pairs.push((ti.min(u_idx) as u32, ti.max(u_idx) as u32));
                }
            }
        };
        bins.query_covering_skipping(&[&polys[ti]], &stars.stars_of(ti), &mut visit);
        for &ui in stars.partners(ti) {
            visit(ui);
        }
        if !regions {
            continue;
        }
        let shapes = if buried {
            inside[ti] = true;
            Vec::new()
        } else if occluders.is_empty() {
            vec![vec![polys[ti].clone()]]
        } else {
            let decided = stats.decided;
            let shapes = visible_part(&mut overlay, &polys[ti], &mut occluders, &mut stats);
            // The cover test is exact on the occluders' polygons: with
            // whole triangles only, `t` lies in their union.
            inside[ti] = shapes.is_empty() && stats.decided > decided && !cut;
            shapes
        };
        region_points += shapes.iter().flatten().map(|c| c.len() as u64).sum::<u64>();
        if region_points > options.max_region_points {
            return Err(region_points_error(region_points, options));
        }
        if !shapes.is_empty() {
            per_prim.entry(t.prim).or_default().extend(shapes);
        }
    }
    cut_pairs.sort_unstable();
    cut_pairs.dedup();
    stats.cut_pairs = cut_pairs.len() as u64;
    if !regions {
        return Ok(RegionMap {
            grid,
            prims: Vec::new(),
            groups: Vec::new(),
            stats,
            cut_pairs,
            covered: Vec::new(),
        });
    }
    // The culled triangles lie inside their tiles' covering triangles:
    // leaving them out changes no point of the union.
    // A triangle inside one nearer triangle, or inside the union of
    // whole nearer triangles (decided exactly by the cover test), adds no
    // point either. On piles of large triangles the union's cost is the
    // arrangement of every triangle sent, so this keeps it to the ones
    // that can reach the outline.
    let skip: Vec<bool> = hidden
        .iter()
        .zip(&culled.hidden)
        .zip(&inside)
        .map(|((&h, &c), &i)| h || c || i)
        .collect();
    stats.outline_triangles = boxes
        .iter()
        .zip(&skip)
        .filter(|(b, s)| b.is_some() && !**s)
        .count() as u64;
    let outline_points: u64 = polys
        .iter()
        .zip(&skip)
        .filter(|(_, s)| !**s)
        .map(|(p, _)| p.len() as u64)
        .sum();
    stats.region_points = region_points + outline_points;
    if stats.region_points > options.max_region_points {
        return Err(region_points_error(stats.region_points, options));
    }
    let mut work = BooleanWork::default();
    let outline = outline(&grid, &polys, &skip, &mut work);
    let (mut prims, covered) = settle(&grid, per_prim, outline, &mut stats, &mut work);

    let groups = group_regions(
        scene,
        &grid,
        &mut prims,
        mode,
        options.merge_groups,
        &mut work,
    );
    stats.map_booleans = work.booleans;
    stats.map_boolean_segments = work.segments;
    stats.largest_boolean = work.largest;
    stats.visible_prims = prims.len() as u64;
    stats.groups = groups.len() as u64;
    stats.path_points = groups
        .iter()
        .flat_map(|g| g.shapes.iter().flatten())
        .map(|c| c.len() as u64)
        .sum();
    Ok(RegionMap {
        grid,
        prims,
        groups,
        stats,
        cut_pairs,
        covered,
    })
}

/// The refusal of a region map past [`VectorOptions::max_region_points`].
fn region_points_error(points: u64, options: &VectorOptions) -> hider_scene::Error {
    hider_scene::Error::Limit {
        what: crate::options::REGION_POINTS_LIMIT,
        value: points,
        limit: options.max_region_points,
    }
}

/// What is left of `polygon` under `occluders` (reordered): decided by
/// the cover test when it can be, else by one boolean against the
/// occluders' outline when that is small, else by [`subtract`].
fn visible_part(
    overlay: &mut Overlay,
    polygon: &[IntPoint],
    occluders: &mut [Vec<IntPoint>],
    stats: &mut RegionStats,
) -> IntShapes {
    let unmatched = unmatched_edges(occluders);
    let decided = unmatched
        .as_ref()
        .and_then(|edges| decide(polygon, edges, occluders));
    match (decided, unmatched) {
        (Some(Cover::Buried), _) => {
            stats.decided += 1;
            Vec::new()
        }
        (Some(Cover::Clear), _) => {
            stats.decided += 1;
            vec![vec![polygon.to_vec()]]
        }
        (None, Some(edges)) if edges.len() <= 6 * BATCH => {
            // The occluders' outline: the same union in one small boolean.
            stats.differences += 1;
            // A loop whose box misses the polygon's winds zero over it.
            let (lo, hi) = bounds(polygon).unwrap_or_default();
            let mut parts: Vec<IntShapes> = loops(&edges)
                .into_iter()
                .filter(|contour| {
                    bounds(contour).is_some_and(|(clo, chi)| {
                        clo.x < hi.x && chi.x > lo.x && clo.y < hi.y && chi.y > lo.y
                    })
                })
                .map(|contour| vec![vec![contour]])
                .collect();
            parts.push(vec![vec![polygon.to_vec()]]);
            if occluders.iter().any(|o| is_sliver(o)) {
                snap_round(&mut parts);
            }
            overlay.clear();
            let (subject, clips) = parts.split_last().expect("the polygon was pushed");
            overlay.add_source(subject, ShapeType::Subject);
            for o in clips {
                overlay.add_source(o, ShapeType::Clip);
            }
            overlay.overlay(OverlayRule::Difference, FillRule::NonZero)
        }
        (None, _) => {
            stats.differences += 1;
            subtract(overlay, polygon, occluders)
        }
    }
}

/// The per-primitive regions made one partition: snap rounded together,
/// then made disjoint by [`settle_ownership`]; by ascending primitive id,
/// empty ones dropped.
fn settle(
    grid: &Grid,
    per_prim: HashMap<u32, IntShapes>,
    outline: IntShapes,
    stats: &mut RegionStats,
    work: &mut BooleanWork,
) -> (Vec<PrimRegion>, IntShapes) {
    let mut per_prim: Vec<(u32, IntShapes)> = per_prim.into_iter().collect();
    per_prim.sort_unstable_by_key(|r| r.0);
    let mut shapes: Vec<IntShapes> = per_prim
        .iter_mut()
        .map(|r| std::mem::take(&mut r.1))
        .collect();
    // The covered set's outline is rounded in the same arrangement, so
    // that the regions can be closed onto it exactly.
    shapes.push(outline);
    let (mut touched, snap) = snap_round(&mut shapes);
    stats.snap_segments = snap.segments;
    stats.sweep_events = snap.events;
    stats.sweep_tests = snap.tests;
    stats.snap_crossings = snap.crossings;
    stats.snap_nodes = snap.nodes;
    let covered = shapes.pop().unwrap_or_default();
    let _ = touched.pop();
    stats.snapped = touched.iter().filter(|&&t| t).count() as u64;
    let ownership = settle_ownership(grid, &mut shapes, &touched, work);
    stats.ownership_differences = ownership.differences;
    stats.ownership_segments = ownership.segments;
    close_to_cover(grid, &covered, &mut shapes, work);
    let prims = per_prim
        .iter()
        .zip(shapes)
        .filter(|(_, shapes)| !shapes.is_empty())
        .map(|(&(prim, _), shapes)| PrimRegion {
            prim,
            group: 0,
            shapes,
        })
        .collect();
    (prims, covered)
}

/// Whether triangle `outer` covers all of triangle `inner` (closed, exact
/// on the fixed-point vertices).
fn covers(outer: &ScreenTri, inner: &ScreenTri) -> bool {
    (0..3).all(|k| {
        let (a, b) = (outer.v[k], outer.v[(k + 1) % 3]);
        inner.v.iter().all(|&c| orient2d(a, b, c) >= 0)
    })
}
