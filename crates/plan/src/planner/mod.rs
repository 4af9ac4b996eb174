//! The planner behind `--algo auto`: the cheapest registered hider (and
//! front-end options) that is exact for the effects a scene calls for.
//!
//! [`analyze`](crate::analyze()) finds the effects; [`plan`] turns them
//! into a choice by walking, for the first rule that applies, a list of
//! registry entries from cheapest to dearest and taking the first one
//! registered, so a hider that is not registered falls back to the next
//! exact one:
//!
//! | effects | choice (first registered) | why |
//! |---|---|---|
//! | ordered polygons, intersections or cycles | `painter` | only splitting resolves them |
//! | ordered polygons, naive order already right | `painter-naive`, `painter` | one sort, no tests, no splits |
//! | ordered polygons otherwise | `painter` | Newell's tests reorder; no split is needed |
//! | transparency | `abuffer`, `ssaa-sorted` | every surface in a pixel must be composited |
//! | anti-aliasing | `abuffer`, `ssaa-8`, `ssaa-16`, `ssaa-32`, `ssaa-4` | coverage masks cost less than samples |
//! | geometry far beyond the near plane | `zbuffer-reversed`, `zbuffer-f64`, `zbuffer` | f32 window depth runs out of bits near 1 |
//! | none of these | `zbuffer-tiled`, `zbuffer`, `zbuffer-f64`, `scanline`, `warnock` | one depth test per covered pixel; the tiled z-buffer gives `zbuffer`'s frame bit for bit, binned, with hierarchical depth and on as many threads as asked |
//!
//! On top of the hider, back faces are culled in the front end when the
//! analysis proved them hidden (closed, outward, uncut meshes and no
//! transparency) and, for a raster image, the triangles are large enough
//! on screen for the proof to pay ([`culling_pays`]), and only the colour stages the scene needs run
//! ([`Effects::stages`]).
//!
//! A plan is options, nothing else: the caller builds the hider
//! ([`Plan::build`]) and renders through its
//! [`render_scene`](hider_scene::DynHider::render_scene) with the front
//! end's options the plan gives ([`Plan::prepare_options`]); the planner
//! never edits a prepared scene.

mod rules;

#[cfg(test)]
mod tests;

use hider_scene::{DynHider, PrepareOptions, Scene, Stages, View};

pub use rules::{MAX_F32_DEPTH_RATIO, MIN_PIXELS_PER_TRIANGLE_TO_CULL, culling_pays};

use crate::analyze::{Effects, RenderOptions, analyze_for_plan};
use crate::config::HiderConfig;
use crate::error::Result;
use crate::registry::{self, Kind, Knobs};

/// What the planner chose.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Registry name of the hider (`hider render --algo NAME`).
    pub algo: &'static str,
    /// Whether the front end should drop back faces (exact here).
    pub cull_back_faces: bool,
    /// The effect stages the scene calls for: the colour stages the colour
    /// pass runs, transparency when some pixel shows a translucent surface,
    /// multisample when anti-aliasing is asked. The stages that *run* add
    /// multisample whenever the chosen hider samples coverage
    /// ([`Plan::stages_run`]).
    pub stages: Stages,
    /// Why, in one sentence.
    pub reason: String,
    /// Fallbacks taken and effects that no registered hider simulates.
    pub notes: Vec<String>,
}

impl Plan {
    /// The chosen hider, built with `config` (see
    /// [`Entry::build`](crate::registry::Entry::build)).
    pub fn build(&self, config: &HiderConfig) -> Result<Box<dyn DynHider>> {
        let entry = registry::find(self.algo)?;
        entry.build(&config.budgets_for(entry.knobs))
    }

    /// `base` with the plan's front-end choices applied.
    pub fn prepare_options(&self, base: PrepareOptions) -> PrepareOptions {
        base.with_cull_back_faces(base.cull_back_faces || self.cull_back_faces)
    }

    /// The stages that run: [`Plan::stages`], with multisample exactly
    /// when the chosen hider resolves several samples per pixel (the
    /// A-buffer anti-aliases its edges whether or not that was asked).
    pub fn stages_run(&self) -> Stages {
        Stages {
            multisample: anti_aliases(self.algo),
            ..self.stages
        }
    }

    /// One line: the choice and why, and the stages that run.
    pub fn summary(&self) -> String {
        let mut s = format!("auto: {} ({})", self.algo, self.reason);
        if self.cull_back_faces {
            s.push_str("; back faces culled (all hidden)");
        }
        let stages = self.stages_run().names();
        s.push_str(&format!(
            "; stages: {}",
            if stages.is_empty() {
                "none (flat colour)".to_owned()
            } else {
                stages.join(", ")
            }
        ));
        for n in &self.notes {
            s.push_str("; ");
            s.push_str(n);
        }
        s
    }
}

/// An analysed and planned scene, ready to render.
#[derive(Clone, Debug)]
pub struct Planned {
    /// The effects the analysis found.
    pub effects: Effects,
    /// The choice.
    pub plan: Plan,
    /// The view analysed.
    pub view: View,
    /// The front end's options to render with: the analysis's `prepare`
    /// with the plan's choices ([`Plan::prepare_options`]).
    pub prepare: PrepareOptions,
    /// What the caller asked for, in words
    /// ([`RenderOptions::requested`]).
    pub requested: String,
}

impl Planned {
    /// One line: what was asked for, the choice and why
    /// ([`Plan::summary`] after the request).
    pub fn summary(&self) -> String {
        let plan = self.plan.summary();
        let choice = plan.strip_prefix("auto: ").unwrap_or(&plan);
        format!("auto, asked for {}: {choice}", self.requested)
    }
}

/// Analyses `scene` and plans for it with the registered hiders.
///
/// ```
/// use hider_plan::{HiderConfig, RenderOptions, auto};
/// use hider_scene::{Frame, ScreenScene, procedural};
///
/// let scene = procedural::cube();
/// let planned = auto(&scene, &RenderOptions::default().with_size(32, 32))?;
/// assert_eq!(planned.plan.algo, "zbuffer-tiled");
/// let mut hider = planned.plan.build(&HiderConfig::default())?;
/// let mut screen = ScreenScene::empty(&planned.view);
/// let mut frame = Frame::new(32, 32)?;
/// hider.render_scene(&scene, &planned.view, &planned.prepare, &mut screen, &mut frame)?;
/// assert!(frame.covered_count() > 0);
/// # Ok::<(), hider_plan::PlanError>(())
/// ```
pub fn auto(scene: &Scene, options: &RenderOptions) -> Result<Planned> {
    let (effects, view) = analyze_for_plan(scene, options)?;
    let plan = plan(&effects);
    check_painter_budget(&plan, &effects, options.max_splits)?;
    Ok(Planned {
        effects,
        prepare: plan.prepare_options(options.prepare),
        plan,
        view,
        requested: options.requested(),
    })
}

/// The split budget the painter (`hider_painter::Painter`) has for a
/// scene of `triangles` triangles with `max_splits` (`None`: its automatic
/// budget; [`PainterOptions::split_budget`](hider_painter::PainterOptions::split_budget)).
pub fn painter_split_budget(triangles: u64, max_splits: Option<u64>) -> u64 {
    let options = hider_painter::PainterOptions::default();
    max_splits
        .map_or(options, |n| options.with_max_splits(n))
        .split_budget(triangles)
}

/// Refuses a plan that picks the painter when the analysis predicts it
/// will exceed its split budget ([`PlanError::PainterBudget`](crate::PlanError::PainterBudget)): better at
/// once than after minutes of splitting.
///
/// The prediction bounds the splits from below only when nothing in view
/// is opaque: the painter drops pieces hidden behind opaque triangles
/// before it orders them (`PainterOptions::cull_hidden`), and a crossing
/// that is hidden needs no split (2,000 random triangles crossing in a
/// cube: 559,400 crossing pairs, a few thousand splits after culling, in
/// half a second). With an opaque triangle in view nothing is refused.
pub fn check_painter_budget(plan: &Plan, effects: &Effects, max_splits: Option<u64>) -> Result<()> {
    let nothing_opaque = effects.transparency.count >= effects.on_screen;
    if plan.algo != "painter" || !nothing_opaque {
        return Ok(());
    }
    let budget = painter_split_budget(effects.on_screen, max_splits);
    if effects.painter_splits_at_least > budget {
        return Err(crate::PlanError::PainterBudget {
            needed: effects.painter_splits_at_least,
            pairs: effects.intersections.count,
            budget,
            triangles: effects.on_screen,
        });
    }
    Ok(())
}

/// Checks the knobs of `config` that `--algo auto` can honour: threads,
/// ordered polygons and the budgets (applied to the hider the plan picks
/// when it has them, see [`Plan::build`]); a depth format or source belongs
/// to a named z-buffer.
pub fn check_config(config: &HiderConfig) -> Result<()> {
    let auto = Knobs {
        threads: true,
        ordered_polygons: true,
        max_splits: true,
        fragment_lists: true,
        ..Knobs::NONE
    };
    match registry::refusal(crate::AlgoName::Auto, auto, config) {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// Whether the registered hider `algo` resolves several samples per pixel
/// (and so anti-aliases).
fn anti_aliases(algo: &str) -> bool {
    registry::find(algo).is_ok_and(|e| e.kind == Kind::MultiSample)
}

/// Plans with every hider in the registry.
pub fn plan(effects: &Effects) -> Plan {
    plan_among(effects, &registry::names())
}

/// Plans with only the hiders named in `available` (registry names).
pub fn plan_among(effects: &Effects, available: &[&'static str]) -> Plan {
    let mut picker = rules::Picker::new(available);
    let vector = picker.vector(effects);
    let ordered = vector.is_some();
    if vector.is_some() && effects.antialiasing.present {
        // The ordered-polygons rule wins; the painters draw the raster image one
        // sample per pixel.
        picker.notes.push(
            "the PNG is NOT anti-aliased: ordered polygons comes first (the SVG has exact edges)"
                .to_owned(),
        );
    }
    let (algo, reason) = vector
        .or_else(|| picker.transparency(effects))
        .or_else(|| picker.antialiasing(effects))
        .unwrap_or_else(|| picker.raster(effects));
    // A multi-sample hider picked for transparency anti-aliases its edges
    // too, asked or not: the plan line says so (`Plan::summary` names the
    // multisample stage).
    if anti_aliases(algo) && !effects.antialiasing.present {
        picker.notes.push(format!(
            "edges anti-aliased ({algo} samples coverage; not asked for)"
        ));
    }
    // A raster render culls only where the proof pays (the analysis for
    // a render skips it otherwise; `hider analyze` still reports it).
    let cull = effects.cull_back_faces_exact
        && (ordered || culling_pays(effects.triangles, effects.pixels));
    Plan {
        algo,
        cull_back_faces: cull,
        stages: effects.stages(),
        reason,
        notes: picker.notes,
    }
}
