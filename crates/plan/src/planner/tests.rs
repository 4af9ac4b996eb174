//! Tests of the planner: its rules and fallbacks, and that its choice is
//! exact (equal to the oracle on non-tie pixels) on every hard case.

use hider_oracle::DEFAULT_TIE_TOLERANCE;
use hider_scene::{Frame, PrepareOptions, ScreenScene, prepare, procedural};
use hider_testkit::{hard_cases, reference};

use super::*;
use crate::analyze::analyze;
use crate::{AlgoName, Knob, PlanError};

const ALL: &[&str] = &[
    "zbuffer-tiled",
    "zbuffer",
    "zbuffer-f64",
    "zbuffer-reversed",
    "abuffer",
    "ssaa-8",
    "ssaa-sorted",
    "painter-naive",
    "painter",
    "scanline",
    "warnock",
    "oracle",
];

fn fx(scene: &Scene, options: RenderOptions) -> Effects {
    analyze(scene, &options.with_size(48, 48)).unwrap()
}

#[test]
fn opaque_scene_without_aa_gets_the_one_sample_zbuffer() {
    let effects = fx(&procedural::uv_sphere(16), RenderOptions::default());
    // Without the tiled z-buffer, the plain one, saying so.
    let p = plan_among(&effects, &["zbuffer", "scanline"]);
    assert_eq!(p.algo, "zbuffer");
    assert!(
        p.notes[0].contains("zbuffer-tiled is not registered"),
        "{:?}",
        p.notes
    );
    let p = plan_among(&effects, ALL);
    assert_eq!(p.algo, "zbuffer-tiled");
    // 480 triangles on 48 x 48 pixels: too small for culling to pay.
    assert!(!p.cull_back_faces);
    let coarse = plan_among(
        &fx(&procedural::uv_sphere(4), RenderOptions::default()),
        ALL,
    );
    assert!(
        coarse.cull_back_faces,
        "a closed sphere hides its back faces"
    );
    assert_eq!(
        p.stages,
        Stages {
            lighting: true,
            ..Stages::default()
        },
        "no texture, no transparency: only the head light's shading"
    );
    assert!(p.notes.is_empty());
    assert!(
        p.summary().starts_with("auto: zbuffer-tiled ("),
        "{}",
        p.summary()
    );
}

#[test]
fn transparency_and_antialiasing_pick_compositing_hiders_with_fallbacks() {
    let mut glass = procedural::cube();
    glass.materials[0].opacity = 0.5;
    let effects = fx(&glass, RenderOptions::default());
    let p = plan_among(&effects, ALL);
    assert_eq!(p.algo, "abuffer");
    assert!(!p.cull_back_faces, "back faces show through glass");
    assert!(p.stages.transparency);
    let p = plan_among(&effects, &["zbuffer", "ssaa-sorted"]);
    assert_eq!(p.algo, "ssaa-sorted");
    assert!(
        p.notes[0].contains("abuffer is not registered"),
        "{:?}",
        p.notes
    );
    let p = plan_among(&effects, &["zbuffer"]);
    assert_eq!(p.algo, "zbuffer");
    assert!(
        p.notes.iter().any(|n| n.contains("NOT composited")),
        "{:?}",
        p.notes
    );

    let aa = fx(
        &procedural::cube(),
        RenderOptions::default().with_antialiasing(true),
    );
    assert_eq!(plan_among(&aa, ALL).algo, "abuffer");
    assert_eq!(plan_among(&aa, &["zbuffer", "ssaa-16"]).algo, "ssaa-16");
}

#[test]
fn ordered_polygons_splits_only_when_it_must() {
    let vector = RenderOptions::default().with_ordered_polygons(true);
    let cyclic = fx(&procedural::cyclic_triple(), vector);
    assert_eq!(plan_among(&cyclic, ALL).algo, "painter");
    let crossing = fx(&procedural::intersecting_pair(), vector);
    let p = plan_among(&crossing, ALL);
    assert_eq!(p.algo, "painter");
    assert!(p.reason.contains("1 intersecting pairs"), "{}", p.reason);
    let sphere = fx(&procedural::uv_sphere(16), vector);
    assert_eq!(plan_among(&sphere, ALL).algo, "painter-naive");
    assert_eq!(plan_among(&sphere, &["zbuffer", "painter"]).algo, "painter");
    // Without any painter the raster choice stands, and says so.
    let p = plan_among(&cyclic, &["zbuffer"]);
    assert_eq!(p.algo, "zbuffer");
    assert!(p.notes.iter().any(|n| n.contains("no painter")));
}

#[test]
fn far_geometry_moves_to_reversed_z() {
    let deep = fx(
        &hard_cases::huge_depth_range(40, 1e5, 3),
        RenderOptions::default(),
    );
    assert!(
        deep.depth_ratio > MAX_F32_DEPTH_RATIO,
        "{}",
        deep.depth_ratio
    );
    assert_eq!(plan_among(&deep, ALL).algo, "zbuffer-reversed");
    assert_eq!(
        plan_among(&deep, &["zbuffer", "zbuffer-f64"]).algo,
        "zbuffer-f64"
    );
}

/// Renders with the plan (its hider through `render_scene`, with the
/// plan's front-end options) and compares with the oracle on the unculled
/// scene.
fn check_exact(name: &str, scene: &Scene, options: RenderOptions) {
    let options = options.with_size(48, 48);
    let Planned {
        effects,
        plan,
        view,
        prepare: planned,
        ..
    } = auto(scene, &options).unwrap();
    let full = prepare(scene, &view, &PrepareOptions::default()).unwrap();
    let reference = reference::ray_cast(&full);
    assert_eq!(
        planned,
        plan.prepare_options(PrepareOptions::default()),
        "{name}: the planned front end is the plan's"
    );
    let mut hider = plan
        .build(&HiderConfig::default())
        .expect("the plan names a registered hider");
    let mut frame = Frame::new(48, 48).unwrap();
    let mut screen = ScreenScene::empty(&view);
    hider
        .render_scene(scene, &view, &planned, &mut screen, &mut frame)
        .unwrap();
    let agreement = reference.compare(&frame.ids, DEFAULT_TIE_TOLERANCE);
    assert!(
        agreement.is_exact(),
        "{name}: {}\n{agreement:?}\n{effects}",
        plan.summary()
    );
}

#[test]
fn the_plan_is_exact_on_every_hard_case() {
    for (name, scene) in hard_cases::all(11) {
        check_exact(name, &scene, RenderOptions::default());
        check_exact(
            name,
            &scene,
            RenderOptions::default().with_ordered_polygons(true),
        );
    }
}

#[test]
fn the_plan_is_exact_with_transparency_and_antialiasing() {
    for (name, scene) in hard_cases::all(12).into_iter().step_by(3) {
        check_exact(
            name,
            &scene,
            RenderOptions::default().with_antialiasing(true),
        );
        let mut glass = scene.clone();
        for m in &mut glass.materials {
            m.opacity = 0.6;
        }
        check_exact(name, &glass, RenderOptions::default());
    }
}

#[test]
fn auto_refuses_depth_knobs_and_takes_threads_and_ordered_polygons() {
    use hider_zbuffer::{DepthFormat, DepthSource};
    for (config, refused) in [
        (
            HiderConfig::default().with_depth_format(DepthFormat::F64),
            Knob::DepthFormat,
        ),
        (
            HiderConfig::default().with_depth_source(DepthSource::LinearViewZ),
            Knob::DepthSource,
        ),
    ] {
        let e = check_config(&config).unwrap_err();
        assert!(
            matches!(&e, PlanError::KnobNotApplicable { hider: AlgoName::Auto, knob, .. } if *knob == refused),
            "{e:?}"
        );
    }
    let config = HiderConfig::default()
        .with_threads(2)
        .with_ordered_polygons(true);
    assert!(check_config(&config).is_ok());
    // Vector output asked: the plan is a painter, which takes the knob.
    let vector = RenderOptions::default().with_ordered_polygons(true);
    let planned = auto(&procedural::cyclic_triple(), &vector.with_size(32, 32)).unwrap();
    assert_eq!(planned.plan.algo, "painter");
    assert!(planned.plan.build(&config).is_ok());
}

#[test]
fn the_one_line_says_what_was_asked_and_what_was_chosen() {
    let scene = procedural::cube();
    let options = RenderOptions::default().with_size(32, 16);
    let line = auto(&scene, &options).unwrap().summary();
    assert!(
        line.starts_with("auto, asked for a shaded 32 x 16 image: zbuffer-tiled ("),
        "{line}"
    );
    let line = auto(&scene, &options.with_antialiasing(true))
        .unwrap()
        .summary();
    assert!(
        line.starts_with("auto, asked for an anti-aliased shaded 32 x 16 image: abuffer ("),
        "{line}"
    );
    let both = auto(
        &scene,
        &options.with_ordered_polygons(true).with_antialiasing(true),
    )
    .unwrap();
    assert!(
        both.summary().contains("the PNG is NOT anti-aliased"),
        "{}",
        both.summary()
    );
    let line = auto(
        &scene,
        &options.with_ordered_polygons(true).with_shading(false),
    )
    .unwrap()
    .summary();
    assert!(
        line.starts_with(
            "auto, asked for an id-coloured 32 x 16 image with ordered polygons: painter"
        ),
        "{line}"
    );
}

/// Leaving out the pair searches (as a raster render does) changes no
/// plan: only the ordered-polygons rule reads them, and asking for the
/// ordered polygons runs them anyway.
#[test]
fn the_pair_searches_decide_only_vector_plans() {
    for (name, scene) in hard_cases::all(13) {
        let mut glass = scene.clone();
        for m in &mut glass.materials {
            m.opacity = 0.6;
        }
        for (scene, options) in [
            (&scene, RenderOptions::default()),
            (&scene, RenderOptions::default().with_antialiasing(true)),
            (&glass, RenderOptions::default()),
            (&scene, RenderOptions::default().with_ordered_polygons(true)),
        ] {
            let options = options.with_size(48, 48);
            let full = auto(scene, &options).unwrap();
            let lean = auto(scene, &options.with_pair_searches(false)).unwrap();
            assert_eq!(full.plan, lean.plan, "{name}: {options:?}");
            assert_eq!(full.prepare, lean.prepare, "{name}");
        }
    }
    let fx = analyze(
        &procedural::cyclic_triple(),
        &RenderOptions::default().with_pair_searches(false),
    )
    .unwrap();
    assert!(fx.cyclic_overlap.present && !fx.cyclic_overlap.certain);
    assert!(fx.cyclic_overlap.detail.contains("not searched"), "{fx}");
}

#[test]
fn a_raster_plan_culls_only_where_the_proof_pays() {
    // uv_sphere(16): 480 triangles, closed and outward. At 512 x 512 each
    // has 546 pixels: culled. At 128 x 128, 34: proving it would cost
    // more than culling saves, so the render analysis does not even look,
    // while `hider analyze` (pair searches on) still reports the proof.
    let sphere = procedural::uv_sphere(16);
    let at = |side: u32| RenderOptions::default().with_size(side, side);
    assert!(culling_pays(480, 512 * 512) && !culling_pays(480, 128 * 128));
    assert!(
        auto(&sphere, &at(512).with_pair_searches(false))
            .unwrap()
            .plan
            .cull_back_faces
    );
    let small = auto(&sphere, &at(128).with_pair_searches(false)).unwrap();
    assert!(!small.plan.cull_back_faces);
    assert!(
        small
            .effects
            .back_faces
            .detail
            .contains("culling would save less"),
        "{}",
        small.effects.back_faces.detail
    );
    let reported = analyze(&sphere, &at(128)).unwrap();
    assert!(
        reported.cull_back_faces_exact,
        "{}",
        reported.back_faces.detail
    );
    assert!(!plan(&reported).cull_back_faces);
    // The painter's ordered polygons cull whenever it is exact.
    let vector = analyze(&sphere, &at(128).with_ordered_polygons(true)).unwrap();
    assert!(plan(&vector).cull_back_faces);
}

#[test]
fn the_painter_is_refused_up_front_when_its_budget_cannot_hold() {
    let vector = RenderOptions::default().with_ordered_polygons(true);
    // One crossing pair: a split or two, far within the budget.
    let one = auto(&procedural::intersecting_pair(), &vector.with_size(48, 48)).unwrap();
    assert_eq!(one.plan.algo, "painter");
    assert_eq!(one.effects.painter_splits_at_least, 1);
    // The prediction against the budget, in one place.
    let mut effects = one.effects.clone();
    effects.on_screen = 2000;
    // With an opaque triangle in view, culling may remove any crossing:
    // the prediction is no bound, nothing is refused.
    effects.painter_splits_at_least = 100 * painter_split_budget(2000, None);
    assert!(check_painter_budget(&one.plan, &effects, None).is_ok());
    // Everything translucent: nothing is culled, the bound holds.
    effects.transparency.count = 2000;
    effects.painter_splits_at_least = painter_split_budget(2000, None) + 1;
    let refused = check_painter_budget(&one.plan, &effects, None).unwrap_err();
    let line = refused.to_string();
    assert!(matches!(refused, PlanError::PainterBudget { .. }), "{line}");
    assert!(line.contains("PainterOptions::max_splits"), "{line}");
    effects.painter_splits_at_least -= 1;
    assert!(check_painter_budget(&one.plan, &effects, None).is_ok());
    assert_eq!(painter_split_budget(0, None), 4096);
    assert_eq!(painter_split_budget(2000, None), 4096 + 128_000 + 131_072);
    // A budget the caller raised is the one compared.
    assert_eq!(painter_split_budget(2000, Some(10_000_000)), 10_000_000);
    effects.painter_splits_at_least = 9_000_000;
    assert!(check_painter_budget(&one.plan, &effects, Some(10_000_000)).is_ok());
    assert!(check_painter_budget(&one.plan, &effects, None).is_err());
}
