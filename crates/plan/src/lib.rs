//! Choosing and building hiders: the registry of every hidden-surface
//! algorithm of the workspace, the scene analysis that says which effects
//! a scene calls for, and the planner that picks the cheapest exact hider
//! for those effects (the `hider` tool's `--algo auto`). It plans and
//! nothing else: loading and all appearance (materials, textures, lights,
//! the effect stages and the colour pass) live in `hider-scene`
//! ([`hider_scene::load`], [`hider_scene::shade`]).
//!
//! - [`registry`]: every hider by name, built from its crate's typed
//!   options; [`HiderConfig`] carries the knobs a caller sets across hiders
//!   (depth format, depth source, threads, ordered polygons, shade mode),
//!   applied where they apply and refused with a typed error
//!   ([`PlanError::KnobNotApplicable`] naming the [`Knob`]) where they do
//!   not.
//! - [`analyze()`](analyze::analyze): transparency, textures, lighting,
//!   anti-aliasing, intersections, cyclic overlaps, back faces, each with
//!   its evidence.
//! - [`auto`]: analysis plus plan. A [`Plan`] is options: the hider to
//!   build, the front end's options ([`Plan::prepare_options`], back-face
//!   culling when it is exact) and the colour stages; the caller renders
//!   with them through [`DynHider::render_scene`](hider_scene::DynHider),
//!   the one path every frame takes.
//!
//! # Example
//!
//! Plan for a scene, build the chosen hider and render with the plan's
//! front-end options:
//!
//! ```
//! use hider_plan::{HiderConfig, RenderOptions, auto};
//! use hider_scene::{Frame, PrepareOptions, ScreenScene, load_model};
//!
//! let scene = load_model("gen:intersecting")?;
//! let options = RenderOptions::default().with_size(48, 48);
//! let planned = auto(&scene, &options)?;
//! assert_eq!(planned.effects.intersections.count, 1);
//! println!("{}", planned.summary());
//!
//! let mut hider = planned.plan.build(&HiderConfig::default())?;
//! let prepare = planned.plan.prepare_options(PrepareOptions::default());
//! let mut screen = ScreenScene::empty(&planned.view);
//! let mut frame = Frame::new(48, 48)?;
//! let stats = hider.render_scene(&scene, &planned.view, &prepare, &mut screen, &mut frame)?;
//! println!("{}: {stats}", hider.name());
//! # Ok::<(), hider_plan::PlanError>(())
//! ```

mod algo;
pub mod analyze;
mod config;
mod error;
pub mod planner;
pub mod registry;

pub use algo::AlgoName;
pub use analyze::{
    Analysis, AnalysisWork, Effects, Evidence, RenderOptions, analyze, analyze_prepared,
};
pub use config::HiderConfig;
pub use error::{Knob, PlanError, Result, error_line};
pub use planner::{Plan, Planned, auto, plan};
