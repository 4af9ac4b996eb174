//! Scene analysis: which effects a scene actually calls for, each with its
//! evidence, so that a renderer simulates those and pays for nothing else.
//!
//! [`analyze`] prepares the scene for the view once and looks for:
//!
//! | effect | present when | evidence |
//! |---|---|---|
//! | transparency | a triangle on screen uses a material with opacity < 1 | triangles, materials |
//! | textures | a triangle on screen has uvs and a `map_Kd` whose image loads | triangles, textures that fail |
//! | lighting | shading is asked and the scene has lights or normals | lights, meshes with normals |
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
//! planner stays on the safe side.

pub mod backface;
pub mod intersect;
pub mod overlap;
pub mod predicates;
mod report;

use std::collections::HashSet;
use std::time::Instant;

use glam::DVec3;
use hider_geom::{Camera, Projection};

use crate::error::Result;
use crate::model::Scene;
use crate::prepare::{PrepareOptions, ScreenScene, ScreenTri, prepare};
use crate::texture;
use crate::view::View;

/// Default of [`RenderOptions::pair_budget`].
pub const DEFAULT_PAIR_BUDGET: u64 = 50_000_000;

/// What the caller wants rendered: the inputs of the analysis besides the
/// scene. `Default` is a 512 x 512 shaded raster image without
/// anti-aliasing from the scene's own (or the fit) camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The camera; `None` for the scene's camera or else the fit camera.
    pub camera: Option<Camera>,
    /// Whether a shaded picture is asked for (false: ids / false colours
    /// only, so lighting is never needed).
    pub shading: bool,
    /// Whether anti-aliased edges are asked for.
    pub antialiasing: bool,
    /// Whether vector output (an ordered polygon list, SVG) is asked for.
    pub vector_output: bool,
    /// The front end's options.
    pub prepare: PrepareOptions,
    /// Most candidate pairs each pair search examines.
    pub pair_budget: u64,
    /// Most examples kept per effect.
    pub max_examples: usize,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            camera: None,
            shading: true,
            antialiasing: false,
            vector_output: false,
            prepare: PrepareOptions::default(),
            pair_budget: DEFAULT_PAIR_BUDGET,
            max_examples: 5,
        }
    }
}

impl RenderOptions {
    /// Sets the image size.
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        (self.width, self.height) = (width, height);
        self
    }
    /// Sets [`Self::camera`].
    pub fn with_camera(mut self, camera: Option<Camera>) -> Self {
        self.camera = camera;
        self
    }
    /// Sets [`Self::shading`].
    pub fn with_shading(mut self, shading: bool) -> Self {
        self.shading = shading;
        self
    }
    /// Sets [`Self::antialiasing`].
    pub fn with_antialiasing(mut self, antialiasing: bool) -> Self {
        self.antialiasing = antialiasing;
        self
    }
    /// Sets [`Self::vector_output`].
    pub fn with_vector_output(mut self, vector_output: bool) -> Self {
        self.vector_output = vector_output;
        self
    }
    /// Sets [`Self::prepare`].
    pub fn with_prepare(mut self, prepare: PrepareOptions) -> Self {
        self.prepare = prepare;
        self
    }
    /// Sets [`Self::pair_budget`].
    pub fn with_pair_budget(mut self, budget: u64) -> Self {
        self.pair_budget = budget;
        self
    }

    /// The view these options describe for `scene` (size checked).
    pub fn view(&self, scene: &Scene) -> Result<View> {
        match self.camera {
            Some(c) => View::new(c, self.width, self.height),
            None => View::for_scene(scene, self.width, self.height),
        }
    }
}

/// One effect: whether it is needed and why.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Evidence {
    /// Whether the effect is present (must be simulated).
    pub present: bool,
    /// False when the search ran out of budget: `present` is then the safe
    /// assumption, not a finding.
    pub certain: bool,
    /// How many instances were found (triangles, pairs, cycles...; see
    /// [`Evidence::detail`]).
    pub count: u64,
    /// Examples as groups of primitive ids: one id, a pair, or a cycle.
    pub examples: Vec<Vec<u32>>,
    /// One sentence saying what was found.
    pub detail: String,
}

impl Evidence {
    fn found(present: bool, count: u64, examples: Vec<Vec<u32>>, detail: String) -> Self {
        Self {
            present,
            certain: true,
            count,
            examples,
            detail,
        }
    }
}

/// Wall-clock time of the analysis steps, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AnalysisTimes {
    /// Front end (prepare).
    pub prepare_ms: f64,
    /// Triangle–triangle intersection search.
    pub intersections_ms: f64,
    /// Screen overlap graph and cycles.
    pub overlaps_ms: f64,
    /// Everything.
    pub total_ms: f64,
}

/// The effects a scene calls for under given [`RenderOptions`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Effects {
    /// Triangles in the scene.
    pub triangles: u64,
    /// Screen triangles after the front end.
    pub on_screen: u64,
    /// Translucent materials in view: needs compositing (A-buffer).
    pub transparency: Evidence,
    /// Textured triangles in view: needs the texture stage.
    pub textures: Evidence,
    /// Lights or normals with shading asked: needs the Lambert stage.
    pub lighting: Evidence,
    /// Anti-aliasing asked: needs multi-sample coverage.
    pub antialiasing: Evidence,
    /// Whether vector output is asked.
    pub vector_output: bool,
    /// Interpenetrating triangle pairs in view.
    pub intersections: Evidence,
    /// Coplanar overlapping pairs in view (depth ties, any hider's answer
    /// is a tie-break).
    pub coplanar_overlaps: Evidence,
    /// Cycles of the "in front of" relation in view.
    pub cyclic_overlap: Evidence,
    /// Back-facing triangles on screen that may be visible.
    pub back_faces: Evidence,
    /// Overlapping pairs a naive farthest-vertex sort paints in the wrong
    /// order.
    pub naive_order_violations: Evidence,
    /// Whether dropping back faces in the front end is exact and saves
    /// work: there are back faces on screen, all certainly hidden, and no
    /// transparency shows them.
    pub cull_back_faces_exact: bool,
    /// Distance of the farthest corner in view over the near distance, for
    /// a perspective camera (1 for orthographic): an f32 window-depth
    /// buffer resolves relative view distances of about `2^-24` times
    /// this at that corner.
    pub depth_ratio: f64,
    /// Time spent.
    pub times: AnalysisTimes,
}

/// Analyses `scene` for `options` (see the module documentation).
pub fn analyze(scene: &Scene, options: &RenderOptions) -> Result<Effects> {
    let started = Instant::now();
    let view = options.view(scene)?;
    // Analyse what every triangle does: culling is something the analysis
    // may recommend, not assume.
    let screen = prepare(scene, &view, &options.prepare.with_cull_back_faces(false))?;
    let prepare_ms = ms(started);
    let ex = options.max_examples;
    let in_view = prims_in_view(&screen);

    let mut fx = Effects {
        triangles: scene.triangle_count() as u64,
        on_screen: screen.tris.len() as u64,
        vector_output: options.vector_output,
        depth_ratio: match view.camera.projection {
            Projection::Perspective { near, far, .. } => {
                let deepest = in_view
                    .iter()
                    .flat_map(|&p| screen.prims[p as usize].camera)
                    .map(|c| -c.z)
                    .fold(near, f64::max);
                deepest.min(far) / near
            }
            Projection::Orthographic { .. } => 1.0,
        },
        ..Effects::default()
    };
    fx.transparency = transparency(&screen, &in_view, ex);
    fx.textures = textures(&screen, &in_view, ex);
    fx.lighting = lighting(scene, options.shading);
    fx.antialiasing = Evidence::found(
        options.antialiasing,
        u64::from(options.antialiasing),
        Vec::new(),
        if options.antialiasing {
            "asked for: multi-sample coverage".into()
        } else {
            "not asked for: one sample per pixel".into()
        },
    );

    // Intersections among the triangles in view, in world space.
    let t0 = Instant::now();
    let world: Vec<(u32, [DVec3; 3])> = scene
        .triangles()
        .filter(|(id, _, _)| in_view.contains(id))
        .map(|(id, m, t)| (id, scene.triangle_positions(m, t)))
        .collect();
    let pairs = intersect::find_pairs(&world, options.pair_budget);
    fx.times.intersections_ms = ms(t0);
    let pair_examples = |v: &[(u32, u32)]| v.iter().take(ex).map(|&(a, b)| vec![a, b]).collect();
    fx.intersections = Evidence {
        present: !pairs.interpenetrating.is_empty() || !pairs.complete,
        certain: pairs.complete,
        count: pairs.interpenetrating.len() as u64,
        examples: pair_examples(&pairs.interpenetrating),
        detail: format!(
            "{} interpenetrating pairs among {} triangles in view ({} exact tests{})",
            pairs.interpenetrating.len(),
            world.len(),
            pairs.tests,
            if pairs.complete {
                ""
            } else {
                ", budget exhausted"
            }
        ),
    };
    fx.coplanar_overlaps = Evidence {
        present: !pairs.coplanar.is_empty(),
        certain: pairs.complete,
        count: pairs.coplanar.len() as u64,
        examples: pair_examples(&pairs.coplanar),
        detail: format!(
            "{} coplanar overlapping pairs (depth ties)",
            pairs.coplanar.len()
        ),
    };

    // The "in front of" graph on screen.
    let t1 = Instant::now();
    // Interpenetrating pairs have no order (they are reported above); a
    // pair the search did not reach is ordered like any other.
    let crossing: HashSet<(u32, u32)> = pairs.interpenetrating.iter().copied().collect();
    // Back faces first: when culling them is exact, the order that matters
    // is the one among the front faces.
    fx.back_faces = back_faces(scene, &view, &screen, ex);
    fx.cull_back_faces_exact =
        !fx.back_faces.present && fx.back_faces.count > 0 && !fx.transparency.present;
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
    let graph = overlap::overlap_graph(
        graph_tris,
        screen.viewport,
        |a, b| crossing.contains(&(a.min(b), a.max(b))),
        options.pair_budget,
        ex,
    );
    fx.times.overlaps_ms = ms(t1);
    fx.cyclic_overlap = Evidence {
        present: graph.cycles > 0 || !graph.complete,
        certain: graph.complete,
        count: graph.cycles,
        examples: graph.examples.clone(),
        detail: format!(
            "{} cycles through {} triangles among {} overlapping pairs ({} ordered, {} ties{})",
            graph.cycles,
            graph.prims_on_cycles,
            graph.overlapping_pairs,
            graph.edges,
            graph.ties,
            if graph.complete {
                ""
            } else {
                ", budget exhausted"
            }
        ),
    };
    fx.naive_order_violations = Evidence {
        present: graph.naive_violations > 0 || !graph.complete,
        certain: graph.complete,
        count: graph.naive_violations,
        examples: graph
            .naive_example
            .map(|(a, b)| vec![a, b])
            .into_iter()
            .collect(),
        detail: format!(
            "{} overlapping pairs painted in the wrong order by a farthest-vertex sort",
            graph.naive_violations
        ),
    };

    fx.times.prepare_ms = prepare_ms;
    fx.times.total_ms = ms(started);
    Ok(fx)
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// Primitive ids with at least one screen triangle.
fn prims_in_view(screen: &ScreenScene) -> HashSet<u32> {
    screen.tris.iter().map(|t| t.prim).collect()
}

fn sorted(ids: &HashSet<u32>) -> Vec<u32> {
    let mut v: Vec<u32> = ids.iter().copied().collect();
    v.sort_unstable();
    v
}

fn transparency(screen: &ScreenScene, in_view: &HashSet<u32>, ex: usize) -> Evidence {
    let ids: Vec<u32> = sorted(in_view)
        .into_iter()
        .filter(|&p| screen.material(p).opacity < 1.0)
        .collect();
    let mut names: Vec<&str> = ids
        .iter()
        .map(|&p| screen.material(p).name.as_str())
        .collect();
    names.sort_unstable();
    names.dedup();
    Evidence::found(
        !ids.is_empty(),
        ids.len() as u64,
        ids.iter().take(ex).map(|&p| vec![p]).collect(),
        if ids.is_empty() {
            "every material in view is opaque".into()
        } else {
            format!(
                "{} translucent triangles in view (materials {})",
                ids.len(),
                names.join(", ")
            )
        },
    )
}

fn textures(screen: &ScreenScene, in_view: &HashSet<u32>, ex: usize) -> Evidence {
    let mut probe: Vec<Option<std::result::Result<(u32, u32), String>>> =
        vec![None; screen.materials.len()];
    let mut ids = Vec::new();
    let mut failures: Vec<String> = Vec::new();
    for p in sorted(in_view) {
        let prim = &screen.prims[p as usize];
        let k = prim.material as usize;
        let Some(path) = &screen.materials[k].diffuse_texture else {
            continue;
        };
        let r = probe[k].get_or_insert_with(|| {
            texture::probe(path).map_err(|e| {
                let msg = e.to_string();
                failures.push(msg.clone());
                msg
            })
        });
        if r.is_ok() && prim.uvs.is_some() {
            ids.push(p);
        }
    }
    let mut detail = if ids.is_empty() {
        "no triangle in view has both uvs and a loadable map_Kd".to_owned()
    } else {
        format!(
            "{} triangles in view with uvs and a loadable map_Kd",
            ids.len()
        )
    };
    if !failures.is_empty() {
        detail.push_str(&format!(
            "; textures that do not load: {}",
            failures.join("; ")
        ));
    }
    Evidence::found(
        !ids.is_empty(),
        ids.len() as u64,
        ids.iter().take(ex).map(|&p| vec![p]).collect(),
        detail,
    )
}

fn lighting(scene: &Scene, shading: bool) -> Evidence {
    let lights = scene.lights.len() as u64;
    let with_normals = scene
        .meshes
        .iter()
        .filter(|m| !m.normals.is_empty())
        .count() as u64;
    let present = shading && (lights > 0 || with_normals > 0);
    let detail = if !shading {
        "shading not asked for".to_owned()
    } else {
        format!("{lights} lights, {with_normals} meshes with normals")
    };
    Evidence::found(present, lights + with_normals, Vec::new(), detail)
}

fn back_faces(scene: &Scene, view: &View, screen: &ScreenScene, ex: usize) -> Evidence {
    let hidden = backface::hidden_back_faces(scene, view);
    // Mesh index of each primitive id.
    let mut mesh_of = Vec::with_capacity(scene.triangle_count());
    for (m, mesh) in scene.meshes.iter().enumerate() {
        mesh_of.extend(std::iter::repeat_n(m, mesh.indices.len()));
    }
    let back: Vec<u32> = screen
        .tris
        .iter()
        .filter(|t| !t.front_facing)
        .map(|t| t.prim)
        .collect();
    let exposed: Vec<u32> = back
        .iter()
        .copied()
        .filter(|&p| !hidden[mesh_of[p as usize]])
        .collect();
    let closed = hidden.iter().filter(|h| **h).count();
    Evidence::found(
        !exposed.is_empty(),
        back.len() as u64,
        exposed.iter().take(ex).map(|&p| vec![p]).collect(),
        format!(
            "{} back-facing triangles on screen, {} of them possibly visible; {} of {} meshes \
             closed, outward and uncut (their back faces are hidden)",
            back.len(),
            exposed.len(),
            closed,
            scene.meshes.len()
        ),
    )
}
