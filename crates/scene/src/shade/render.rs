//! One coloured frame in one call: what the command line does with a
//! hider, for library users.

use super::cutout::cutout_stage;
use super::prims::{Prims, ScenePrims};
use super::stages::{Shader, Stages};
use super::{ShadeMode, id_frame};
use crate::error::Result;
use crate::frame::Frame;
use crate::hider::{DynHider, StatsTable};
use crate::model::Scene;
use crate::prepare::{PrepareOptions, ScreenScene};
use crate::view::View;

/// Renders `scene` through `view` with `hider` and colours the frame, as
/// `hider render` does: the hider's own pipeline
/// ([`DynHider::render_scene`], the one path every frame takes), then,
/// the alpha test of cut-outs when `stages` has it ([`Stages::cutout`],
/// [`super::cutout`]), and, unless the hider resolved colour itself, the
/// colour pass over its ids
/// with `stages` under Lambert shading (reading the primitives from the
/// world-space scene, so it works after any front end) or the id colours.
/// `screen` is the hider's scratch (reused across frames); `mode` must be
/// the one the hider was built with when it resolves colour.
///
/// ```
/// use hider_scene::shade::{Stages, render_frame};
/// use hider_scene::{Frame, Hider, PrepareOptions, ScreenScene, ShadeMode, View, procedural};
///
/// # #[derive(Default)] struct Flat;
/// # hider_scene::hider_stats! { #[derive(Clone, Debug, Default)] pub struct FlatStats { pub n: u64 => "n", } }
/// # impl Hider for Flat {
/// #     type Options = (); type Stats = FlatStats;
/// #     fn new(_: ()) -> Self { Flat }
/// #     fn options(&self) -> &() { &() }
/// #     fn name(&self) -> &str { "flat" }
/// #     fn render(&mut self, s: &ScreenScene, f: &mut Frame) -> hider_scene::Result<FlatStats> {
/// #         f.clear();
/// #         for t in &s.tris { t.for_each_centre(s.viewport, |x, y, inside| if inside { let i = f.index(x, y); f.ids[i] = t.prim; }); }
/// #         Ok(FlatStats::default())
/// #     }
/// # }
/// let scene = procedural::cube();
/// let view = View::for_scene(&scene, 32, 32)?;
/// let mut hider = Flat; // any hider: `hider_zbuffer::TiledZBuffer`, ...
/// let mut screen = ScreenScene::empty(&view);
/// let mut frame = Frame::new(32, 32)?;
/// let stages = Stages::for_scene(&scene, true);
/// render_frame(&mut hider, &scene, &view, &PrepareOptions::default(), &stages,
///              ShadeMode::Lambert, &mut screen, &mut frame)?;
/// assert!(frame.color.iter().any(|c| c[..3] != [0, 0, 0]));
/// # Ok::<(), hider_scene::Error>(())
/// ```
#[expect(
    clippy::too_many_arguments,
    reason = "the pipeline's inputs: hider, scene, view, front end, stages, mode and the reused buffers"
)]
pub fn render_frame(
    hider: &mut dyn DynHider,
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    stages: &Stages,
    mode: ShadeMode,
    screen: &mut ScreenScene,
    frame: &mut Frame,
) -> Result<StatsTable> {
    let mut stats = hider.render_scene(scene, view, options, screen, frame)?;
    if stages.cutout {
        cutout_stage(hider, scene, view, options, frame, &mut stats)?;
    }
    if !hider.resolves_color() {
        match mode {
            ShadeMode::Lambert => {
                let prims = ScenePrims::new(scene, view)?;
                Shader::default().shade(Prims::Scene(&prims), frame, stages);
            }
            ShadeMode::Ids => id_frame(frame),
        }
    }
    Ok(stats)
}
