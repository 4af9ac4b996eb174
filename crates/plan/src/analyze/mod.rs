//! Scene analysis: which effects a scene actually calls for, each with its
//! evidence, so that a renderer simulates those and pays for nothing else.
//!
//! [`analyze`] prepares the scene for the view once and looks for:
//!
//! | effect | present when | evidence |
//! |---|---|---|
//! | transparency | a triangle on screen uses a material with opacity < 1 and, one sample per pixel, some pixel centre shows it in front of every opaque surface | triangles, materials |
//! | textures | a triangle on screen has uvs and a `map_Kd` whose image loads | triangles, textures that fail |
//! | lighting | shading is asked (the scene's lights, or the head light) | lights, meshes with normals |
//! | anti-aliasing | asked | — |
//! | intersections | two triangles in view pierce each other ([`intersect`]) | pairs, count |
//! | cyclic overlap | the "in front of" graph in view has a cycle ([`overlap`]) | cycles |
//! | back faces | a back-facing triangle on screen is not certainly hidden ([`backface`]) | triangles, meshes |
//!
//! It also reports coplanar overlaps (depth ties) and whether a naive
//! farthest-vertex sort already orders every overlapping pair. When back
//! faces are certainly hidden (so a renderer may cull them), the overlap
//! graph is built on the front faces only: that is what will be painted. The two
//! searches over pairs stop at [`RenderOptions::pair_budget`]; an
//! unfinished search reports its effect as *present but not certain*, so a
//! planner stays on the safe side. Only ordered polygons needs them, so a
//! raster render may leave them out ([`RenderOptions::pair_searches`]).
//!
//! [`analyze_prepared`] also hands back the scene it prepared, so a caller
//! that renders next does not run the front end a second time.

pub mod backface;
mod effects;
mod evidence;
pub mod intersect;
mod options;
pub mod overlap;
pub mod predicates;
mod quick;
mod report;
mod search;
pub mod splits;
#[cfg(test)]
mod star_tests;
mod stars;

use std::time::Instant;

use hider_geom::Projection;
use hider_scene::{Scene, ScreenScene, ScreenTri, View, prepare};

pub use effects::{AnalysisTimes, AnalysisWork, Effects, Evidence};
pub use options::{DEFAULT_PAIR_BUDGET, RenderOptions};

use crate::error::Result;

/// An analysis with what it prepared: the effects, the view they were
/// found for, and the scene through the front end with every triangle
/// (back faces kept, whatever [`RenderOptions::prepare`] says), ready to
/// render.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// The effects found.
    pub effects: Effects,
    /// The view analysed.
    pub view: View,
    /// The scene prepared for `view` with [`RenderOptions::prepare`],
    /// back-face culling off.
    pub screen: ScreenScene,
}

/// Analyses `scene` for `options` (see the module documentation).
pub fn analyze(scene: &Scene, options: &RenderOptions) -> Result<Effects> {
    analyze_prepared(scene, options).map(|a| a.effects)
}

/// [`analyze`], handing back the prepared scene and the view as well.
pub fn analyze_prepared(scene: &Scene, options: &RenderOptions) -> Result<Analysis> {
    let started = Instant::now();
    let view = options.view(scene)?;
    // Analyse what every triangle does: culling is something the analysis
    // may recommend, not assume.
    let screen = prepare(scene, &view, &options.prepare.with_cull_back_faces(false))?;
    let prepare_ms = ms(started);
    let ex = options.max_examples;
    let in_view = evidence::InView::of(&screen);
    let mut fx = Effects {
        triangles: scene.triangle_count() as u64,
        pixels: u64::from(options.width) * u64::from(options.height),
        on_screen: screen.tris.len() as u64,
        ordered_polygons: options.ordered_polygons,
        depth_ratio: depth_ratio(&view, &screen, &in_view),
        transparency: evidence::transparency(&screen, &in_view, !options.antialiasing, ex),
        textures: evidence::textures(&screen, &in_view, ex),
        cutouts: hider_scene::shade::cutout::scene_has_cutouts(scene),
        lighting: evidence::lighting(scene, options.shading),
        antialiasing: evidence::antialiasing(options.antialiasing),
        ..Effects::default()
    };
    fx.add_partial_alpha(&screen, &in_view.ids, ex);

    if raster_only(options) && !crate::planner::culling_pays(fx.triangles, fx.pixels) {
        // The plan will not cull (see `culling_pays`): the proof would be
        // paid for nothing.
        fx.back_faces = back_faces_not_examined(fx.triangles, fx.pixels);
    } else {
        fx.back_faces = evidence::back_faces(scene, &view, &screen, ex);
        fx.cull_back_faces_exact =
            !fx.back_faces.present && fx.back_faces.count > 0 && !fx.transparency.present;
    }
    if options.pair_searches || options.ordered_polygons {
        pair_searches(scene, &screen, &in_view, options, &mut fx);
        options.cancel.poll()?;
    } else {
        let skipped = Evidence {
            present: true,
            certain: false,
            detail: "not searched: only ordered polygons needs it".to_owned(),
            ..Evidence::default()
        };
        fx.intersections = skipped.clone();
        fx.coplanar_overlaps = skipped.clone();
        fx.cyclic_overlap = skipped.clone();
        fx.naive_order_violations = skipped;
    }
    fx.times.prepare_ms = prepare_ms;
    fx.times.total_ms = ms(started);
    Ok(Analysis {
        effects: fx,
        view,
        screen,
    })
}

/// Whether only a raster plan is asked and nothing reads the pair
/// searches (what `hider render` asks without the painter's SVG).
fn raster_only(options: &RenderOptions) -> bool {
    !options.pair_searches && !options.ordered_polygons
}

/// The back-face evidence of a raster plan whose triangles are too small
/// on screen for culling to pay: not examined, so not ruled out.
fn back_faces_not_examined(triangles: u64, pixels: u64) -> Evidence {
    Evidence {
        present: true,
        certain: false,
        detail: format!(
            "not counted: {triangles} triangles over {pixels} pixels, fewer than {} pixels \
             each, so culling would save less than proving back faces hidden costs",
            crate::planner::MIN_PIXELS_PER_TRIANGLE_TO_CULL
        ),
        ..Evidence::default()
    }
}

/// The effects and view a plan needs: [`analyze_prepared`]'s, or, for a
/// raster plan that reads nothing of the prepared scene, the quick
/// analysis without the front end (see `quick.rs`: no translucent or
/// textured material, and either no mesh that the edge hash lets be
/// closed or every triangle in a shell that hides its back faces).
pub(crate) fn analyze_for_plan(scene: &Scene, options: &RenderOptions) -> Result<(Effects, View)> {
    let started = Instant::now();
    let view = options.view(scene)?;
    if let Some(mut fx) = quick::effects(scene, &view, options) {
        fx.times.total_ms = ms(started);
        return Ok((fx, view));
    }
    analyze_prepared(scene, options).map(|a| (a.effects, a.view))
}

/// The two searches over pairs: intersections and coplanar overlaps in
/// space, then cycles and naive-order violations of the overlap graph on
/// the screen (among the front faces when culling the back ones is exact,
/// since that is what will be painted).
fn pair_searches(
    scene: &Scene,
    screen: &ScreenScene,
    in_view: &evidence::InView,
    options: &RenderOptions,
    fx: &mut Effects,
) {
    let ex = options.max_examples;
    let t0 = Instant::now();
    let crossings = search::intersections(scene, in_view, options.pair_budget, ex, options.cancel);
    fx.times.intersections_ms = ms(t0);
    fx.work.intersection_candidates = crossings.candidates;
    fx.work.intersection_tests = crossings.tests;
    fx.painter_splits_at_least = crossings.painter_splits_at_least;
    fx.intersections = crossings.intersections;
    fx.coplanar_overlaps = crossings.coplanar;

    let t1 = Instant::now();
    let front: Vec<ScreenTri>;
    let graph_tris = if fx.cull_back_faces_exact {
        front = screen
            .tris
            .iter()
            .filter(|t| t.front_facing)
            .copied()
            .collect();
        &front[..]
    } else {
        &screen.tris[..]
    };
    let order = search::order(
        graph_tris,
        screen.viewport,
        &crossings.crossing,
        options.pair_budget,
        ex,
        options.cancel,
    );
    fx.times.overlaps_ms = ms(t1);
    fx.work.overlap_candidates = order.candidates;
    fx.work.overlap_tests = order.tests;
    fx.cyclic_overlap = order.cyclic;
    fx.naive_order_violations = order.naive_violations;
}

/// Distance of the farthest corner in view over the near distance (1 for
/// an orthographic camera): see [`Effects::depth_ratio`].
fn depth_ratio(view: &View, screen: &ScreenScene, in_view: &evidence::InView) -> f64 {
    match view.camera.projection {
        Projection::Perspective { near, far, .. } => {
            let deepest = in_view
                .ids
                .iter()
                .flat_map(|&p| screen.prims[p as usize].camera)
                .map(|c| -c.z)
                .fold(near, f64::max);
            deepest.min(far) / near
        }
        Projection::Orthographic { .. } => 1.0,
    }
}

/// Milliseconds since `since`.
fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}
