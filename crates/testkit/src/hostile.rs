//! Hostile inputs: turn arbitrary bytes into scenes and cameras, and check
//! the invariants every hider must keep on them. Shared by the `cargo fuzz`
//! targets in `fuzz/` and the workspace's hostile-input property tests, so
//! a crash the fuzzer finds replays as an ordinary test.
//!
//! Built with the `hostile` feature (it renders with every hider of
//! `hider-plan`'s registry).
//!
//! ```
//! use hider_testkit::hostile::{check_all_hiders, front_end_case};
//!
//! // 13 camera floats (eye, target, up, fovy, near, far), then corners.
//! let floats = [0.0f32, 0.0, 5.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 60.0, 60.0, 0.5, 50.0,
//!     -1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 0.0, 1.0, 0.0];
//! let mut bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
//! bytes[0] = 7; // the first bytes double as width, height and precision
//! let case = front_end_case(&bytes).expect("a valid camera");
//! let screen = hider_scene::prepare(&case.scene, &case.view, &case.options)?;
//! assert_eq!(check_all_hiders(&screen), Ok(()));
//! # Ok::<(), hider_scene::Error>(())
//! ```

use hider_scene::{Frame, Hider, NO_ID, ScreenScene};
use hider_zbuffer::{
    DepthFragment, DepthScene, DepthTri, TiledZBuffer, TiledZBufferOptions, ZBuffer,
    prepare_depth_into,
};

use crate::lean_reference::lean_reference;

pub use crate::front_end_input::{Case, front_end_case};

/// How far outside [0, 1] a written window depth may be. Vertex depths are
/// exact in [0, 1], but evaluating the affine depth plane at a pixel centre
/// rounds, so a covered centre next to a vertex on the near or far plane
/// can come out a few units of the last place outside (the fuzzer found
/// -2e-19). GL clamps fragment depth to the depth range; hider keeps the
/// plane value, which every hider computes identically, so their answers
/// stay comparable.
pub const DEPTH_SLACK: f32 = 1e-6;

/// Renders `screen` with every registered hider. A hider may refuse with an
/// error (a documented budget); what it draws must be well formed: ids of
/// existing primitives or background, depths in [0, 1] up to
/// [`DEPTH_SLACK`]. Returns the
/// first violation.
pub fn check_all_hiders(screen: &ScreenScene) -> Result<(), String> {
    let violations = all_violations(screen);
    match violations.into_iter().next() {
        Some(v) => Err(v),
        None => Ok(()),
    }
}

/// Every hider's first violation, one line each (for diagnosis).
pub fn all_violations(screen: &ScreenScene) -> Vec<String> {
    let mut out = Vec::new();
    let vp = screen.viewport;
    let mut frame = match Frame::new(vp.width, vp.height) {
        Ok(f) => f,
        Err(e) => return vec![e.to_string()],
    };
    'hiders: for entry in hider_plan::registry::all() {
        if std::env::var_os("HIDER_HOSTILE_TRACE").is_some() {
            eprintln!("hostile: {}", entry.name);
        }
        let mut hider = entry.make();
        if hider.render(screen, &mut frame).is_err() {
            continue;
        }
        for (&id, &d) in frame.ids.iter().zip(&frame.depth) {
            if id != NO_ID && id as usize >= screen.prims.len() {
                let n = screen.prims.len();
                out.push(format!("{}: id {id} of {n} primitives", entry.name));
                continue 'hiders;
            }
            if !(-DEPTH_SLACK..=1.0 + DEPTH_SLACK).contains(&d) {
                out.push(format!("{}: depth {d}", entry.name));
                continue 'hiders;
            }
        }
    }
    out
}

/// The lean front end and the fast z-buffer's own pipeline on a case whose
/// full front end gave `screen`: the depth scene must hold exactly
/// [`lean_reference`]'s triangles and fragments, bit for bit and in order,
/// and the tiled z-buffer drawing it must give `ZBuffer`'s frame on
/// `screen`.
pub fn check_lean_pipeline(case: &Case, screen: &ScreenScene) -> Result<(), String> {
    let mut lean = DepthScene::new();
    prepare_depth_into(&case.scene, &case.view, &case.options, &mut lean)
        .map_err(|e| format!("lean front end refused what prepare took: {e}"))?;
    let vp = screen.viewport;
    let (want, want_fragments) = lean_reference(screen);
    let got: Vec<DepthTri> = lean.tris().copied().collect();
    let got_fragments: Vec<DepthFragment> = lean.fragments().flatten().copied().collect();
    if got != want || got_fragments != want_fragments {
        return Err(format!(
            "lean front end: {got:?} {got_fragments:?}\nprepare: {want:?} {want_fragments:?}"
        ));
    }
    let mut want = Frame::new(vp.width, vp.height).map_err(|e| e.to_string())?;
    let mut got = want.clone();
    ZBuffer::default()
        .render(screen, &mut want)
        .map_err(|e| e.to_string())?;
    let mut tiled = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
    tiled
        .draw_depth_scene(&lean)
        .and_then(|_| tiled.read_into(&mut got))
        .map_err(|e| e.to_string())?;
    if got.ids != want.ids || got.depth != want.depth {
        return Err("tiled z-buffer on the lean scene differs from ZBuffer".to_owned());
    }
    Ok(())
}
