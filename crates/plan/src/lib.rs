//! Choosing and building hiders: the registry of every hidden-surface
//! algorithm of the workspace, the scene analysis that says which effects
//! a scene calls for, the colour stages that run only when called for, the
//! planner that picks the cheapest exact hider for those effects (the
//! `hider` tool's `--algo auto`), and model loading by name.
//!
//! - [`registry`]: every hider by name, built from its crate's typed
//!   options; [`HiderConfig`] carries the knobs a caller sets across hiders
//!   (depth format, depth source, threads, vector output), applied where
//!   they apply and refused, naming the knob, where they do not.
//! - [`analyze()`](analyze::analyze): transparency, textures, lighting,
//!   anti-aliasing, intersections, cyclic overlaps, back faces, each with
//!   its evidence.
//! - [`stages`] and [`texture`]: the colour pass over a frame's ids,
//!   texture and lighting only when the scene has them.
//! - [`auto`]: analysis plus plan, handing back the prepared scene so the
//!   render does not prepare it twice.
//! - [`load_model`]: an OBJ path or a generated `gen:` scene.
//!
//! # Example
//!
//! Plan for a scene, build the chosen hider and render with the scene the
//! analysis prepared:
//!
//! ```
//! use hider_plan::{HiderConfig, RenderOptions, auto, load_model};
//! use hider_scene::Frame;
//!
//! let scene = load_model("gen:intersecting")?;
//! let options = RenderOptions::default().with_size(48, 48);
//! let planned = auto(&scene, &options)?;
//! assert_eq!(planned.effects.intersections.count, 1);
//! println!("{}", planned.summary());
//!
//! let mut hider = planned.plan.build(&HiderConfig::default())?;
//! let mut frame = Frame::new(48, 48)?;
//! let stats = hider.render(&planned.screen, &mut frame)?;
//! println!("{}: {stats}", hider.name());
//! # Ok::<(), hider_plan::PlanError>(())
//! ```

pub mod analyze;
mod config;
mod error;
mod load;
pub mod planner;
pub mod registry;
pub mod stages;
pub mod texture;

pub use analyze::{Analysis, Effects, Evidence, RenderOptions, analyze, analyze_prepared};
pub use config::HiderConfig;
pub use error::{PlanError, Result, error_line};
pub use load::{MAX_SOUP_TRIANGLES, MAX_SPHERE_SEGMENTS, generated, load_model};
pub use planner::{Plan, Planned, auto, plan};
pub use stages::{Shader, ShaderOptions, StageTrace, Stages};
pub use texture::Texture;
