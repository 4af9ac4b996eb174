//! The planner behind `--algo auto`: the cheapest registered hider (and
//! front-end options) that is exact for the effects a scene calls for.
//!
//! [`hider_scene::analyze()`] finds the effects; [`plan`] turns them into a
//! choice by walking, for the first rule that applies, a list of registry
//! entries from cheapest to dearest and taking the first one registered,
//! so a hider that has not landed yet falls back to the next exact one:
//!
//! | effects | choice (first registered) | why |
//! |---|---|---|
//! | vector output, intersections or cycles | `painter` | only splitting resolves them |
//! | vector output, naive order already right | `painter-naive`, `painter` | one sort, no tests, no splits |
//! | vector output otherwise | `painter` | Newell's tests reorder; no split is needed |
//! | transparency | `abuffer`, `ssaa-sorted` | every surface in a pixel must be composited |
//! | anti-aliasing | `abuffer`, `ssaa-8`, `ssaa-16`, `ssaa-32`, `ssaa-4` | coverage masks cost less than samples |
//! | geometry far beyond the near plane | `zbuffer-reversed`, `zbuffer-f64`, `zbuffer` | f32 window depth runs out of bits near 1 |
//! | none of these | `zbuffer-tiled`, `zbuffer`, `zbuffer-f64`, `scanline`, `warnock` | one depth test per covered pixel; the tiled z-buffer gives `zbuffer`'s frame bit for bit, binned, with hierarchical depth and on every core |
//!
//! On top of the hider, back faces are culled in the front end when the
//! analysis proved them hidden (closed, outward, uncut meshes and no
//! transparency), and only the colour stages the scene needs run
//! ([`Stages::for_effects`]).

use hider_scene::{Effects, Hider, PrepareOptions, RenderOptions, Result, Scene, Stages, analyze};

use crate::registry;

/// Above this [`Effects::depth_ratio`] (farthest corner in view over the
/// near distance) an f32 window-depth buffer is not trusted. Window depth
/// is `z = f/(f-n) (1 - n/d)`, so `dz/dd ~ n/d^2`; rounding `z` to f32
/// near 1 (spacing `2^-24`) moves the distance by a relative `2^-24 d/n`,
/// about `6e-6` at `d/n = 100`, still under the oracle's tie tolerance
/// `1e-5`. The fit camera stays below 35.
pub const MAX_F32_DEPTH_RATIO: f64 = 100.0;

/// What the planner chose.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Registry name of the hider (`hider render --algo NAME`).
    pub algo: &'static str,
    /// Whether the front end should drop back faces (exact here).
    pub cull_back_faces: bool,
    /// The effect stages that run.
    pub stages: Stages,
    /// Why, in one sentence.
    pub reason: String,
    /// Fallbacks taken and effects that no registered hider simulates.
    pub notes: Vec<String>,
}

impl Plan {
    /// A fresh instance of the chosen hider.
    pub fn hider(&self) -> Option<Box<dyn Hider>> {
        registry::by_name(self.algo).map(|e| (e.make)())
    }

    /// `base` with the plan's front-end choices applied.
    pub fn prepare_options(&self, base: PrepareOptions) -> PrepareOptions {
        base.with_cull_back_faces(base.cull_back_faces || self.cull_back_faces)
    }

    /// One line: the choice and why.
    pub fn summary(&self) -> String {
        let mut s = format!("auto: {} ({})", self.algo, self.reason);
        if self.cull_back_faces {
            s.push_str("; back faces culled (all hidden)");
        }
        let stages = self.stages.names();
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

/// Analyses `scene` and plans for it with the registered hiders.
pub fn auto(scene: &Scene, options: &RenderOptions) -> Result<(Effects, Plan)> {
    let effects = analyze(scene, options)?;
    let plan = plan(&effects);
    Ok((effects, plan))
}

/// Plans with every hider in the registry.
pub fn plan(effects: &Effects) -> Plan {
    let names: Vec<&'static str> = registry::all().iter().map(|e| e.name).collect();
    plan_among(effects, &names)
}

/// Plans with only the hiders named in `available` (registry names).
pub fn plan_among(effects: &Effects, available: &[&'static str]) -> Plan {
    let mut notes = Vec::new();
    let pick = |chain: &[&'static str], notes: &mut Vec<String>| {
        let found = chain.iter().copied().find(|n| available.contains(n))?;
        if found != chain[0] {
            notes.push(format!(
                "{} is not registered, fell back to {found}",
                chain[0]
            ));
        }
        Some(found)
    };
    let count = |e: &hider_scene::Evidence, what: &str| {
        if e.certain {
            format!("{} {what}", e.count)
        } else {
            format!("{what} not ruled out")
        }
    };
    let mut choice: Option<(&'static str, String)> = None;
    if effects.vector_output {
        let hard = effects.intersections.present || effects.cyclic_overlap.present;
        let (chain, why): (&[&'static str], String) = if hard {
            (
                &["painter"],
                format!(
                    "vector output with {} and {}: painter's with splitting",
                    count(&effects.intersections, "intersecting pairs"),
                    count(&effects.cyclic_overlap, "overlap cycles")
                ),
            )
        } else if !effects.naive_order_violations.present {
            (
                &["painter-naive", "painter"],
                "vector output, no intersections or cycles and the farthest-vertex order is \
                 already right: painter's without splitting or tests"
                    .to_owned(),
            )
        } else {
            (
                &["painter"],
                format!(
                    "vector output, no intersections or cycles but {}: painter's reordering, \
                     no splits needed",
                    count(
                        &effects.naive_order_violations,
                        "pairs the naive sort gets wrong"
                    )
                ),
            )
        };
        match pick(chain, &mut notes) {
            Some(n) => choice = Some((n, why)),
            None => notes.push("no painter registered: raster output only".into()),
        }
    }
    if choice.is_none() && effects.transparency.present {
        let why = format!(
            "{}: compositing every surface in a pixel",
            effects.transparency.detail
        );
        match pick(&["abuffer", "ssaa-sorted"], &mut notes) {
            Some(n) => choice = Some((n, why)),
            None => {
                notes.push("transparency NOT composited: no compositing hider registered".into())
            }
        }
    }
    if choice.is_none() && effects.antialiasing.present {
        let why = "anti-aliasing asked: coverage masks per fragment".to_owned();
        match pick(
            &["abuffer", "ssaa-8", "ssaa-16", "ssaa-32", "ssaa-4"],
            &mut notes,
        ) {
            Some(n) => choice = Some((n, why)),
            None => notes.push("anti-aliasing NOT done: no multi-sample hider registered".into()),
        }
    }
    let (algo, reason) = choice.unwrap_or_else(|| {
        if effects.depth_ratio > MAX_F32_DEPTH_RATIO {
            let why = format!(
                "opaque, one sample, but geometry reaches {:.1e} x the near distance: reversed-Z keeps depth precision",
                effects.depth_ratio
            );
            let n = pick(&["zbuffer-reversed", "zbuffer-f64", "zbuffer"], &mut notes);
            (n.unwrap_or("oracle"), why)
        } else {
            let n = pick(
                &["zbuffer-tiled", "zbuffer", "zbuffer-f64", "scanline", "warnock"],
                &mut notes,
            );
            (
                n.unwrap_or("oracle"),
                "opaque, no anti-aliasing: one depth test per covered pixel".to_owned(),
            )
        }
    });
    Plan {
        algo,
        cull_back_faces: effects.cull_back_faces_exact,
        stages: Stages::for_effects(effects),
        reason,
        notes,
    }
}

#[cfg(test)]
#[path = "plan_tests.rs"]
mod tests;
