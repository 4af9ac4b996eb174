//! Effect stages that run only when a scene calls for them.
//!
//! After a pixel-centre hider has decided which primitive each pixel shows,
//! colour is a separate pass over the id buffer. [`Shader`] runs it with
//! only the stages [`Stages`] switches on — normally those the scene
//! analysis found ([`Stages::for_effects`]):
//! - **texture**: perspective-correct `map_Kd` sampling. For each pixel the
//!   camera-space ray through its centre is intersected with the source
//!   triangle, and the uvs are interpolated with the barycentrics of that
//!   point: exact perspective (scratchapixel's depth-buffer lesson and the
//!   perspective-correct interpolation blog post: attributes are affine in
//!   camera space, not on the screen). [`Mapping::Affine`] interpolates on
//!   the screen instead, labelled as the error those texts warn about, to
//!   show it.
//! - **lighting**: flat two-sided Lambert
//!   ([`hider_scene::shade::lambert_light`]).
//!   Without it a primitive shows its material's diffuse colour.
//!
//! The two other effects are not colour passes but choices of hider, made
//! by a planner from the same [`Stages`]: **transparency** needs
//! compositing of every surface in a pixel (the A-buffer), and
//! **multisample** coverage needs several samples per pixel. A scene that
//! needs none of the four pays for none: the pass is then one cached flat
//! colour per primitive.

use std::collections::HashMap;
use std::path::PathBuf;

use glam::{DMat4, DVec2, DVec3, DVec4};

use hider_scene::frame::BACKGROUND;
use hider_scene::shade::{lambert_light, to_srgb8};
use hider_scene::{Frame, NO_ID, ScreenScene};

use crate::analyze::Effects;
use crate::texture::{Filter, Texture};

/// Which effect stages run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stages {
    /// Sample `map_Kd` textures.
    pub texture: bool,
    /// Lambert shading.
    pub lighting: bool,
    /// Composite translucent surfaces (a hider's job: the A-buffer).
    pub transparency: bool,
    /// Several coverage samples per pixel (a hider's job).
    pub multisample: bool,
}

impl Stages {
    /// Every stage on.
    pub const ALL: Self = Self {
        texture: true,
        lighting: true,
        transparency: true,
        multisample: true,
    };

    /// Only the stages the analysed scene calls for.
    pub fn for_effects(effects: &Effects) -> Self {
        Self {
            texture: effects.textures.present,
            lighting: effects.lighting.present,
            transparency: effects.transparency.present,
            multisample: effects.antialiasing.present,
        }
    }

    /// The names of the stages that are on.
    pub fn names(&self) -> Vec<&'static str> {
        [
            (self.texture, "texture"),
            (self.lighting, "lighting"),
            (self.transparency, "transparency"),
            (self.multisample, "multisample"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }
}

/// How texture coordinates are interpolated across a triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Mapping {
    /// Barycentrics of the camera-space point seen through the pixel
    /// centre: correct under perspective (the default).
    #[default]
    PerspectiveCorrect,
    /// Barycentrics on the screen: *wrong* under perspective (straight
    /// texture lines bend at triangle edges); kept as a demonstration.
    Affine,
}

/// Options of [`Shader`]. `Default` is the accurate choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ShaderOptions {
    /// Texture filter.
    pub filter: Filter,
    /// Texture coordinate interpolation.
    pub mapping: Mapping,
}

impl ShaderOptions {
    /// Sets [`Self::filter`].
    pub fn with_filter(mut self, filter: Filter) -> Self {
        self.filter = filter;
        self
    }
    /// Sets [`Self::mapping`].
    pub fn with_mapping(mut self, mapping: Mapping) -> Self {
        self.mapping = mapping;
        self
    }
}

/// What a shading pass did: which stages ran and how much work they did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StageTrace {
    /// Names of the colour stages that ran (`"texture"`, `"lighting"`), in
    /// order; empty when the pass was flat colour only.
    pub ran: Vec<&'static str>,
    /// Covered pixels coloured.
    pub pixels: u64,
    /// Texture samples taken.
    pub texture_samples: u64,
    /// Primitives whose Lambert light was computed.
    pub lit_prims: u64,
    /// Textures decoded in this pass (cached ones are not counted).
    pub textures_loaded: u64,
    /// Textures that failed to load (the material colour is used), with
    /// the reason.
    pub texture_failures: Vec<String>,
}

/// Per-primitive shading data, built lazily.
#[derive(Clone, Copy, Debug)]
struct PrimShade {
    /// Linear colour: diffuse, times the light when lighting runs.
    color: [f32; 3],
    /// Index into the shader's textures when the primitive is textured.
    texture: Option<usize>,
}

/// The shading pass. Keeps decoded textures and its per-primitive cache
/// between frames.
#[derive(Clone, Debug, Default)]
pub struct Shader {
    options: ShaderOptions,
    textures: Vec<Texture>,
    by_path: HashMap<PathBuf, Option<usize>>,
    prims: Vec<Option<PrimShade>>,
}

impl Shader {
    /// A shader with the given options.
    pub fn new(options: ShaderOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The options.
    pub fn options(&self) -> &ShaderOptions {
        &self.options
    }

    /// Fills `frame.color` from `frame.ids`, running only the colour stages
    /// `stages` switches on (`transparency` and `multisample` are the
    /// hider's and ignored here).
    pub fn shade(&mut self, scene: &ScreenScene, frame: &mut Frame, stages: &Stages) -> StageTrace {
        let mut trace = StageTrace::default();
        if stages.texture {
            trace.ran.push("texture");
        }
        if stages.lighting {
            trace.ran.push("lighting");
        }
        self.prims.clear();
        self.prims.resize(scene.prims.len(), None);
        let rays = RayGen::new(scene);
        let (w, h) = (frame.width(), frame.height());
        for y in 0..h {
            for x in 0..w {
                let i = frame.index(x, y);
                let id = frame.ids[i];
                if id == NO_ID || id as usize >= scene.prims.len() {
                    frame.color[i] = BACKGROUND;
                    continue;
                }
                trace.pixels += 1;
                let ps = match self.prims[id as usize] {
                    Some(ps) => ps,
                    None => {
                        let ps = self.prim_shade(scene, id, stages, &mut trace);
                        self.prims[id as usize] = Some(ps);
                        ps
                    }
                };
                let mut c = ps.color;
                if let Some(k) = ps.texture {
                    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    if let Some(uv) = self.uv_at(scene, &rays, id, cx, cy) {
                        let t = self.textures[k].sample(uv.x, uv.y, self.options.filter);
                        c = [c[0] * t[0], c[1] * t[1], c[2] * t[2]];
                        trace.texture_samples += 1;
                    }
                }
                frame.color[i] = [to_srgb8(c[0]), to_srgb8(c[1]), to_srgb8(c[2]), 255];
            }
        }
        trace
    }

    fn prim_shade(
        &mut self,
        scene: &ScreenScene,
        prim: u32,
        stages: &Stages,
        trace: &mut StageTrace,
    ) -> PrimShade {
        let material = scene.material(prim);
        let mut color = material.diffuse;
        if stages.lighting {
            let lit = lambert_light(scene, prim);
            color = std::array::from_fn(|k| (f64::from(color[k]) * lit[k]) as f32);
            trace.lit_prims += 1;
        }
        let mut texture = None;
        if stages.texture
            && scene.prims[prim as usize].uvs.is_some()
            && let Some(path) = &material.diffuse_texture
        {
            texture = match self.by_path.get(path) {
                Some(k) => *k,
                None => {
                    let k = match Texture::load(path) {
                        Ok(t) => {
                            self.textures.push(t);
                            trace.textures_loaded += 1;
                            Some(self.textures.len() - 1)
                        }
                        Err(e) => {
                            trace.texture_failures.push(e.to_string());
                            None
                        }
                    };
                    self.by_path.insert(path.clone(), k);
                    k
                }
            };
        }
        PrimShade { color, texture }
    }

    /// The texture coordinates of primitive `prim` seen at window point
    /// `(x, y)`.
    fn uv_at(
        &self,
        scene: &ScreenScene,
        rays: &RayGen,
        prim: u32,
        x: f64,
        y: f64,
    ) -> Option<DVec2> {
        let info = &scene.prims[prim as usize];
        let uv = info.uvs?.map(|t| t.as_dvec2());
        let c = info.camera;
        let b = match self.options.mapping {
            Mapping::PerspectiveCorrect => {
                let (o, d) = rays.ray(x, y);
                let n = (c[1] - c[0]).cross(c[2] - c[0]);
                let denom = n.dot(d);
                if denom == 0.0 {
                    return None;
                }
                let p = o + d * (n.dot(c[0] - o) / denom);
                barycentric3(c, n, p)
            }
            Mapping::Affine => {
                let w = c.map(|q| rays.to_window(q));
                barycentric2(w, DVec2::new(x, y))?
            }
        };
        Some(uv[0] * b[0] + uv[1] * b[1] + uv[2] * b[2])
    }
}

/// Barycentrics of `p` (on the plane of `c` with normal `n`).
fn barycentric3(c: [DVec3; 3], n: DVec3, p: DVec3) -> [f64; 3] {
    let nn = n.length_squared();
    let b0 = n.dot((c[2] - c[1]).cross(p - c[1])) / nn;
    let b1 = n.dot((c[0] - c[2]).cross(p - c[2])) / nn;
    [b0, b1, 1.0 - b0 - b1]
}

/// Barycentrics of `p` in the 2D triangle `w`.
fn barycentric2(w: [DVec2; 3], p: DVec2) -> Option<[f64; 3]> {
    let area = (w[1] - w[0]).perp_dot(w[2] - w[0]);
    if area == 0.0 {
        return None;
    }
    let b0 = (w[2] - w[1]).perp_dot(p - w[1]) / area;
    let b1 = (w[0] - w[2]).perp_dot(p - w[2]) / area;
    Some([b0, b1, 1.0 - b0 - b1])
}

/// Camera-space rays through window points, with the projection inverted
/// once per frame.
struct RayGen {
    inverse: DMat4,
    projection: DMat4,
    width: f64,
    height: f64,
    perspective: bool,
}

impl RayGen {
    fn new(scene: &ScreenScene) -> Self {
        Self {
            inverse: scene.projection_matrix.inverse(),
            projection: scene.projection_matrix,
            width: f64::from(scene.viewport.width),
            height: f64::from(scene.viewport.height),
            perspective: scene.is_perspective(),
        }
    }

    /// `(origin, direction)` as [`ScreenScene::camera_ray`] gives them.
    fn ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let ndc_x = 2.0 * x / self.width - 1.0;
        let ndc_y = 1.0 - 2.0 * y / self.height;
        let near = self.inverse * DVec4::new(ndc_x, ndc_y, -1.0, 1.0);
        let near = near.truncate() / near.w;
        if self.perspective {
            (DVec3::ZERO, near)
        } else {
            let far = self.inverse * DVec4::new(ndc_x, ndc_y, 1.0, 1.0);
            (near, far.truncate() / far.w - near)
        }
    }

    /// A camera-space point's window position (pixels, y down).
    fn to_window(&self, p: DVec3) -> DVec2 {
        let clip = self.projection * p.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        DVec2::new(
            (ndc.x + 1.0) * 0.5 * self.width,
            (1.0 - ndc.y) * 0.5 * self.height,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::{PrepareOptions, View, prepare, procedural};

    #[test]
    fn flat_pass_runs_no_stage_and_matches_the_material_colour() {
        let scene = procedural::cube();
        let view = View::for_scene(&scene, 32, 32).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let mut frame = Frame::new(32, 32).unwrap();
        for t in &screen.tris {
            // Any covered pixel will do: paint a few ids by hand.
            if let Some((x, y, _, _)) = t.pixel_bounds(screen.viewport) {
                let i = frame.index(x, y);
                frame.ids[i] = t.prim;
            }
        }
        let mut shader = Shader::default();
        let trace = shader.shade(&screen, &mut frame, &Stages::default());
        assert!(trace.ran.is_empty());
        assert_eq!(trace.lit_prims, 0);
        assert!(trace.pixels > 0);
        let k = frame.ids.iter().position(|&id| id != NO_ID).unwrap();
        let kd = screen.material(frame.ids[k]).diffuse;
        assert_eq!(frame.color[k][..3], kd.map(to_srgb8));
        let lit = shader.shade(
            &screen,
            &mut frame,
            &Stages {
                lighting: true,
                ..Stages::default()
            },
        );
        assert_eq!(lit.ran, vec!["lighting"]);
        assert!(lit.lit_prims > 0);
    }
}
