//! Every registered hider, and the analysis behind `auto`, stops on its
//! cancel token: a token cancelled before the render returns
//! [`Cancelled::Requested`], one whose deadline has passed
//! [`Cancelled::TimedOut`], and the same hider renders the next frame once
//! the token is reset.

use std::time::Duration;

use hider_plan::{HiderConfig, PlanError, RenderOptions, auto, registry};
use hider_scene::{
    Cancel, Cancelled, Error, Frame, PrepareOptions, Scene, ScreenScene, View, generated,
};

const SIZE: u32 = 64;

/// A scene with intersecting, overlapping triangles, so that every hider
/// has real work (the painter splits, the pair searches find pairs).
fn scene() -> Scene {
    generated("soup:200:7").expect("a generated scene")
}

/// What rendering `scene` with `algo` under `cancel` returns.
fn render(algo: &str, scene: &Scene, cancel: Cancel) -> hider_scene::Result<()> {
    let entry = registry::find(algo).expect("a registered hider");
    let mut hider = entry
        .build(&HiderConfig::default().with_cancel(cancel))
        .expect("no knob refused");
    let view = View::for_scene(scene, SIZE, SIZE)?;
    let mut screen = ScreenScene::empty(&view);
    let mut frame = Frame::new(SIZE, SIZE)?;
    hider
        .render_scene(
            scene,
            &view,
            &PrepareOptions::default(),
            &mut screen,
            &mut frame,
        )
        .map(|_| ())
}

#[test]
fn every_hider_stops_on_a_cancelled_or_timed_out_token() {
    let scene = scene();
    for name in registry::names() {
        let token = Cancel::new();
        token.cancel();
        match render(name, &scene, token) {
            Err(Error::Cancelled(Cancelled::Requested)) => {}
            other => panic!("{name} with a cancelled token: {other:?}"),
        }
        token.reset();
        let late = token.with_timeout(Duration::ZERO);
        match render(name, &scene, late) {
            Err(Error::Cancelled(Cancelled::TimedOut { timeout })) => {
                assert_eq!(timeout, Duration::ZERO, "{name}");
            }
            other => panic!("{name} past its deadline: {other:?}"),
        }
        token.reset();
        render(name, &scene, token).unwrap_or_else(|e| panic!("{name} after reset: {e}"));
    }
}

#[test]
fn the_cancel_error_is_one_line_saying_why() {
    let token = Cancel::new();
    token.cancel();
    let e = render("painter", &scene(), token).unwrap_err();
    assert_eq!(e.to_string(), "render cancelled");
    let late = Cancel::new().with_timeout(Duration::ZERO);
    let e = render("oracle", &scene(), late).unwrap_err();
    assert_eq!(e.to_string(), "render timed out after 0ns");
}

#[test]
fn the_pair_searches_stop_on_the_token() {
    let scene = scene();
    let options = |cancel| {
        RenderOptions::default()
            .with_size(SIZE, SIZE)
            .with_pair_searches(true)
            .with_cancel(cancel)
    };
    let token = Cancel::new();
    token.cancel();
    match auto(&scene, &options(token)) {
        Err(PlanError::Scene(Error::Cancelled(Cancelled::Requested))) => {}
        other => panic!(
            "analysis with a cancelled token: {:?}",
            other.map(|p| p.plan.algo)
        ),
    }
    let late = Cancel::new().with_timeout(Duration::ZERO);
    match auto(&scene, &options(late)) {
        Err(PlanError::Scene(Error::Cancelled(Cancelled::TimedOut { .. }))) => {}
        other => panic!(
            "analysis past its deadline: {:?}",
            other.map(|p| p.plan.algo)
        ),
    }
    assert!(auto(&scene, &options(Cancel::default())).is_ok());
}
