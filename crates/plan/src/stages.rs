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

use hider_scene::frame::BACKGROUND;
use hider_scene::shade::{lambert_light, to_srgb8};
use hider_scene::{Frame, NO_ID, Scene, ScreenScene, SurfaceTextures, TextureOptions};

pub use hider_scene::surface::Mapping;

use crate::analyze::Effects;

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

    /// The colour stages `scene` calls for, found without the full
    /// analysis (for a hider named on the command line): texture when a
    /// material has a `map_Kd` and a mesh has texture coordinates,
    /// lighting whenever `shading` is asked (lights, or the head light).
    pub fn for_scene(scene: &Scene, shading: bool) -> Self {
        let textured = scene.meshes.iter().any(|m| !m.uvs.is_empty())
            && scene.materials.iter().any(|m| m.diffuse_texture.is_some());
        Self {
            texture: shading && textured,
            lighting: shading,
            transparency: scene.materials.iter().any(|m| m.opacity < 1.0),
            multisample: false,
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

/// Options of [`Shader`]: how textures are sampled, the same options the
/// colour-resolving hiders sample with ([`TextureOptions`]). `Default` is
/// the accurate choice.
pub type ShaderOptions = TextureOptions;

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

/// The shading pass. Keeps decoded textures and its per-primitive colour
/// cache between frames.
#[derive(Clone, Debug, Default)]
pub struct Shader {
    options: ShaderOptions,
    textures: SurfaceTextures,
    prims: Vec<Option<[f32; 3]>>,
}

impl Shader {
    /// A shader with the given options.
    pub fn new(options: ShaderOptions) -> Self {
        Self {
            options,
            textures: SurfaceTextures::new(options),
            prims: Vec::new(),
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
            let load = self.textures.load(scene);
            trace.textures_loaded = load.loaded;
            trace.texture_failures = load.failures;
        } else {
            self.textures.deactivate();
        }
        if stages.lighting {
            trace.ran.push("lighting");
        }
        self.prims.clear();
        self.prims.resize(scene.prims.len(), None);
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
                let flat = match self.prims[id as usize] {
                    Some(c) => c,
                    None => {
                        let c = prim_shade(scene, id, stages, &mut trace);
                        self.prims[id as usize] = Some(c);
                        c
                    }
                };
                let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let mut c = flat;
                if self.textures.texture(scene, id).is_some() {
                    c = self.textures.rgb_at(scene, id, flat, cx, cy);
                    trace.texture_samples += 1;
                }
                frame.color[i] = [to_srgb8(c[0]), to_srgb8(c[1]), to_srgb8(c[2]), 255];
            }
        }
        trace
    }
}

/// The flat colour of `prim`: its diffuse colour, lit when lighting runs.
fn prim_shade(scene: &ScreenScene, prim: u32, stages: &Stages, trace: &mut StageTrace) -> [f32; 3] {
    let color = scene.material(prim).diffuse;
    if !stages.lighting {
        return color;
    }
    let lit = lambert_light(scene, prim);
    trace.lit_prims += 1;
    std::array::from_fn(|k| (f64::from(color[k]) * lit[k]) as f32)
}

/// The hiders that composite translucent surfaces: every other one keeps
/// one surface per sample (or per pixel centre) and draws them opaque.
pub const COMPOSITING_HIDERS: &[&str] = &["abuffer", "abuffer-carpenter", "ssaa-sorted"];

/// A warning when `hider` cannot apply the transparency stage the scene
/// calls for (it draws translucent surfaces opaque), naming the hider that
/// can; `None` when it can or when nothing is translucent.
pub fn transparency_warning(hider: &str, stages: &Stages) -> Option<String> {
    (stages.transparency && !COMPOSITING_HIDERS.contains(&hider)).then(|| {
        format!(
            "the scene has translucent materials, but {hider} keeps one surface per sample \
             and draws them opaque; --algo abuffer composites them"
        )
    })
}

/// Turns on in `screen` the stages a colour-resolving hider applies itself
/// (today: texture; lighting comes with its Lambert shade mode), so that
/// the A-buffer, supersampling and anti-aliased Warnock colour what the
/// scene calls for. Returns the textures that failed to load.
pub fn prepare_surface(screen: &mut ScreenScene, stages: &Stages) -> Vec<String> {
    if stages.texture {
        screen.load_textures(TextureOptions::default()).failures
    } else {
        screen.textures.deactivate();
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::{PrepareOptions, View, prepare, procedural};

    #[test]
    fn only_hiders_that_composite_are_silent_on_translucent_scenes() {
        let glass = Stages {
            transparency: true,
            ..Stages::default()
        };
        for name in crate::registry::names() {
            let warned = transparency_warning(name, &glass).is_some();
            assert_eq!(warned, !COMPOSITING_HIDERS.contains(&name), "{name}");
            assert!(transparency_warning(name, &Stages::default()).is_none());
        }
        let line = transparency_warning("ssaa-8", &glass).unwrap();
        assert!(
            line.contains("ssaa-8") && line.contains("--algo abuffer"),
            "{line}"
        );
    }

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
