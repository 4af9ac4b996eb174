//! The hiders as WebAssembly for the explorable page in `web/`.
//!
//! Built for `wasm32-unknown-unknown` and bound to JavaScript with
//! `wasm-bindgen` (`web/build.sh`); natively it is an ordinary library,
//! which is how its tests run. On wasm32 the portable code paths run: the
//! AVX2 modules are compiled only for x86_64, and rayon, which cannot
//! start threads there, runs every parallel loop on the calling thread,
//! so every frame is the one a native portable build draws (the browser
//! tests compare the page's ids with the `hider` command line's).
//!
//! [`Page`] is what the page calls: load a scene ([`Page::load_spec`],
//! [`Page::add_file`] and [`Page::load_files`]), set the size and the
//! orbit camera, render with any registered hider ([`Page::render`]), and
//! score a frame against the oracle ([`Page::score`]).

pub mod inspect;
pub mod orbit;
pub mod painter_steps;
pub mod precision;
pub mod scanline_steps;
pub mod scenes;
pub mod session;
pub mod steps;
pub mod warnock_steps;
pub mod ybuffer;

use wasm_bindgen::prelude::*;

use crate::orbit::{Orbit, cli_flags};
use crate::painter_steps::PainterSteps;
use crate::session::{Rendered, Scored, Session};
use crate::warnock_steps::WarnockSteps;

/// A `Result` whose error reaches JavaScript as an `Error` with the
/// message.
type JsResult<T> = Result<T, JsError>;

fn js(message: String) -> JsError {
    JsError::new(&message)
}

/// The page's handle: one scene, one view, the hiders and the oracle.
#[wasm_bindgen]
#[derive(Default)]
pub struct Page {
    session: Session,
    files: Vec<(String, Vec<u8>)>,
    ztrace: hider_zbuffer::ZBufferTrace,
    scanline: scanline_steps::ScanlineSteps,
    painter: PainterSteps,
    warnock: WarnockSteps,
}

#[wasm_bindgen]
impl Page {
    /// A page showing the cube at 256 x 256.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Page {
        Page::default()
    }

    /// Every registered hider's name, in registry order.
    pub fn hiders() -> Vec<String> {
        hider_plan::registry::names()
            .into_iter()
            .map(str::to_owned)
            .collect()
    }

    /// One line saying what hider `name` is (its kind and description).
    pub fn describe(name: &str) -> String {
        hider_plan::registry::by_name(name)
            .map(|e| format!("{:?}: {}", e.kind, e.description))
            .unwrap_or_default()
    }

    /// The test kit's hard cases, for `hard:NAME`.
    pub fn hard_cases() -> Vec<String> {
        scenes::hard_case_names()
    }

    /// Loads `gen:NAME[:ARGS]` or `hard:NAME`.
    pub fn load_spec(&mut self, spec: &str) -> JsResult<()> {
        let scene = scenes::from_spec(spec).map_err(js)?;
        self.session.set_scene(scene);
        Ok(())
    }

    /// Holds a file (an OBJ, an MTL or a texture) for [`Page::load_files`].
    pub fn add_file(&mut self, name: &str, bytes: Vec<u8>) {
        self.files.retain(|(n, _)| n != name);
        self.files.push((name.to_owned(), bytes));
    }

    /// Loads the held OBJ `obj_name` with the held MTL files and textures,
    /// then forgets the files.
    pub fn load_files(&mut self, obj_name: &str) -> JsResult<()> {
        let files = std::mem::take(&mut self.files);
        let scene = scenes::from_files(files, obj_name).map_err(js)?;
        self.session.set_scene(scene);
        Ok(())
    }

    /// The loader's warnings for the scene shown, one per line.
    pub fn warnings(&self) -> String {
        self.session.scene().warnings.join("\n")
    }

    /// The scene's triangle count.
    pub fn triangles(&self) -> usize {
        self.session.scene().triangle_count()
    }

    /// The scene as OBJ text (its materials' colours in an MTL named
    /// `scene.mtl`), for running the command line on a generated scene.
    pub fn obj_text(&self) -> String {
        hider_scene::obj_write::to_obj_text(self.session.scene(), "scene.mtl").0
    }

    /// Sets the image size (1 to [`session::MAX_SIDE`] a side).
    pub fn set_size(&mut self, width: u32, height: u32) -> JsResult<()> {
        self.session.set_size(width, height).map_err(js)
    }

    /// Sets the orbit: yaw and pitch in radians, zoom as a power of two of
    /// the scene camera's distance, pan in units of the distance.
    pub fn set_orbit(&mut self, yaw: f64, pitch: f64, zoom: f64, pan_x: f64, pan_y: f64) {
        self.session.set_orbit(Orbit {
            yaw,
            pitch,
            zoom,
            pan: [pan_x, pan_y],
        });
    }

    /// The camera as the `hider render` flags that give the same view
    /// (`--eye x,y,z --target ... --far f`), one flag or value an item.
    pub fn camera_flags(&self) -> Vec<String> {
        cli_flags(&self.session.camera())
    }

    /// Renders the current view with the registered hider `name`.
    pub fn render(&mut self, name: &str) -> JsResult<Frame> {
        self.session.render(name).map(Frame).map_err(js)
    }

    /// Renders the current view with hider `name` without the colour pass
    /// or any copy (what `hider render --repeat` times), for timing;
    /// returns the covered pixel count.
    pub fn render_bare(&mut self, name: &str) -> JsResult<usize> {
        self.session.render_bare(name).map_err(js)
    }

    /// Records the plain z-buffer's trace of the current scene and camera
    /// at `side` x `side` (1 to 128); returns its number of steps (one per
    /// triangle drawn).
    pub fn zbuffer_trace(&mut self, side: u32) -> JsResult<usize> {
        let (trace, _) = steps::zbuffer_trace(&self.session, side).map_err(js)?;
        self.ztrace = trace;
        Ok(self.ztrace.steps.len())
    }

    /// Step `k` of the recorded z-buffer trace (0: before the first
    /// triangle).
    pub fn zbuffer_step(&self, k: usize) -> ZStep {
        ZStep(steps::zbuffer_step(&self.ztrace, k))
    }

    /// Records the painter's trace of the current scene and camera at
    /// `side` x `side` (1 to 128); returns its number of steps (events).
    pub fn painter_trace(&mut self, side: u32) -> JsResult<usize> {
        self.painter = PainterSteps::record(&self.session, side).map_err(js)?;
        Ok(self.painter.len())
    }

    /// The ids after the first `k` events of the painter's trace, -1 for
    /// background.
    pub fn painter_ids(&self, k: usize) -> Vec<i32> {
        self.painter.ids(k)
    }

    /// Event `k - 1` of the painter's trace: its kind (`test`, `blocked`,
    /// `move`, `cycle`, `split`, `culled`, `painted`, or `none` at step 0).
    pub fn painter_event_kind(&self, k: usize) -> String {
        self.painter.event(k).0
    }

    /// The pieces event `k - 1` names (-1 where none): P and Q for a test
    /// or a cycle, the piece and its halves for a split.
    pub fn painter_event_pieces(&self, k: usize) -> Vec<f64> {
        self.painter.event(k).1.iter().map(|&p| p as f64).collect()
    }

    /// Event `k - 1` in words.
    pub fn painter_event_text(&self, k: usize) -> String {
        self.painter.event(k).2
    }

    /// Piece `id`'s outline in window pixels, `x0 y0 x1 y1 ...`.
    pub fn painter_outline(&self, id: u32) -> Vec<f64> {
        self.painter.outline(id)
    }

    /// How often each Newell test settled a pair in the trace, one
    /// `test<TAB>count` a line.
    pub fn painter_test_counts(&self) -> String {
        self.painter.test_counts()
    }

    /// The painter's own frame ids of the recorded view.
    pub fn painter_frame_ids(&self) -> Vec<i32> {
        self.painter
            .frame()
            .map(|f| {
                f.ids
                    .iter()
                    .map(|&id| hider_scene::frame::id_to_i32(id))
                    .collect()
            })
            .unwrap_or_default()
    }

    /// Records Warnock's final windows for the current scene and camera
    /// at `side` x `side` (1 to 128); returns the number of steps (levels).
    pub fn warnock_trace(&mut self, side: u32) -> JsResult<usize> {
        self.warnock = WarnockSteps::record(&self.session, side).map_err(js)?;
        Ok(self.warnock.len())
    }

    /// After step `k`, per pixel: the code of the rule that decided its
    /// window (1 + its index in `Rule::ALL`, 0 not decided yet), plus 16
    /// when decided at this step.
    pub fn warnock_classes(&self, k: usize) -> Vec<u8> {
        self.warnock.step(k).0
    }

    /// After step `k`, the ids of the decided pixels (-1 elsewhere).
    pub fn warnock_ids(&self, k: usize) -> Vec<i32> {
        self.warnock.step(k).1
    }

    /// The windows decided by step `k`, `x0 y0 x1 y1` each.
    pub fn warnock_windows(&self, k: usize) -> Vec<u32> {
        self.warnock.windows(k)
    }

    /// The windows cut at step `k` (several polygons reach them, no rule
    /// settles them), `x0 y0 x1 y1` each.
    pub fn warnock_cuts(&self, k: usize) -> Vec<u32> {
        self.warnock.cuts(k)
    }

    /// Per rule, the windows it decided by step `k` and their pixels, one
    /// `rule<TAB>windows<TAB>pixels` a line.
    pub fn warnock_counts(&self, k: usize) -> String {
        self.warnock.counts(k)
    }

    /// Scores `frame` against the oracle's ids for the current view (the
    /// oracle runs once per view).
    pub fn score(&mut self, frame: &Frame) -> JsResult<Score> {
        self.session.score(&frame.0.ids()).map(Score).map_err(js)
    }
}

/// One hider's frame.
#[wasm_bindgen]
pub struct Frame(Rendered);

#[wasm_bindgen]
impl Frame {
    /// The hider's name.
    pub fn name(&self) -> String {
        self.0.name.clone()
    }
    /// Visible primitive per pixel, -1 for background.
    pub fn ids(&self) -> Vec<i32> {
        self.0.ids()
    }
    /// Window depth per pixel, 1.0 for background.
    pub fn depth(&self) -> Vec<f32> {
        self.0.frame.depth.clone()
    }
    /// RGBA bytes, top row first.
    pub fn rgba(&self) -> Vec<u8> {
        self.0.rgba().to_vec()
    }
    /// The hider's counters, one `name value` a line.
    pub fn stats(&self) -> String {
        self.0.stats.clone()
    }
}

/// A frame's agreement with the oracle.
#[wasm_bindgen]
pub struct Score(Scored);

#[wasm_bindgen]
impl Score {
    /// Coverage mismatches and wrong ids off ties (the benchmark's count).
    pub fn wrong(&self) -> u32 {
        u32::try_from(self.0.wrong).unwrap_or(u32::MAX)
    }
    /// Pixels whose id differs from the oracle's, ties included.
    pub fn differing(&self) -> u32 {
        u32::try_from(self.0.differing).unwrap_or(u32::MAX)
    }
    /// 1 where the id differs from the oracle's, row-major.
    pub fn map(&self) -> Vec<u8> {
        self.0.map.clone()
    }
}

/// One step of the z-buffer's trace.
#[wasm_bindgen]
pub struct ZStep(steps::ZStep);

#[wasm_bindgen]
impl ZStep {
    /// Ids after the step, -1 for background.
    pub fn ids(&self) -> Vec<i32> {
        self.0.ids.clone()
    }
    /// Depth after the step, 1.0 for background.
    pub fn depth(&self) -> Vec<f32> {
        self.0.depth.clone()
    }
    /// The step's depth tests per pixel: 0 none, 1 passed, 2 failed.
    pub fn outcome(&self) -> Vec<u8> {
        self.0.outcome.clone()
    }
    /// The step's primitive id (-1 before the first).
    pub fn prim(&self) -> i32 {
        self.0.prim
    }
}
