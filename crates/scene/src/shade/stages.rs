//! Effect stages that run only when a scene calls for them.
//!
//! After a pixel-centre hider has decided which primitive each pixel shows,
//! colour is a separate pass over the id buffer. [`Shader`] runs it with
//! only the stages [`Stages`] switches on — normally those the scene
//! analysis of `hider-plan` found, or [`Stages::for_scene`]. It reads the
//! primitives from a prepared scene or, after a hider with a lean front end
//! of its own, from the world-space scene ([`Prims`]): the same colours
//! either way.
//! - **texture**: perspective-correct `map_Kd` sampling. For each pixel the
//!   camera-space ray through its centre is intersected with the source
//!   triangle, and the uvs are interpolated with the barycentrics of that
//!   point: exact perspective (scratchapixel's depth-buffer lesson and the
//!   perspective-correct interpolation blog post: attributes are affine in
//!   camera space, not on the screen). [`Mapping::Affine`](super::Mapping::Affine) interpolates on
//!   the screen instead, labelled as the error those texts warn about, to
//!   show it.
//! - **lighting**: flat two-sided Lambert
//!   ([`super::flat_color`]); per pixel ([`super::shade_point`]) where a
//!   primitive's colour varies: vertex normals, highlights, textures.
//!   Without it a primitive shows its material's diffuse colour.
//!
//! The two other effects are not colour passes but choices of hider, made
//! by a planner from the same [`Stages`]: **transparency** needs
//! compositing of every surface in a pixel (the A-buffer), and
//! **multisample** coverage needs several samples per pixel. A scene that
//! needs none of the four pays for none: the pass is then one cached flat
//! colour per primitive.

use super::prims::Prims;
use super::setup::SurfaceSetup;
use super::surface::TextureOptions;
use super::texture::TextureRef;
use super::{flat_color, to_srgb8};
use crate::frame::{BACKGROUND, Frame, NO_ID};
use crate::hider::DynHider;
use crate::model::Scene;

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
    /// The alpha test of cut-out textures at pixel centres, after the
    /// hider's visibility ([`super::cutout`]): the scene has a `map_Kd`
    /// with an alpha channel on a mesh with texture coordinates.
    pub cutout: bool,
}

impl Stages {
    /// Every stage on.
    pub const ALL: Self = Self {
        texture: true,
        lighting: true,
        transparency: true,
        multisample: true,
        cutout: true,
    };

    /// The colour stages `scene` calls for, found without the full
    /// analysis (for a hider named on the command line): texture when a
    /// material has a `map_Kd` and a mesh has texture coordinates,
    /// lighting whenever `shading` is asked (lights, or the head light).
    pub fn for_scene(scene: &Scene, shading: bool) -> Self {
        Self {
            texture: shading && scene.is_textured(),
            lighting: shading,
            transparency: scene.materials.iter().any(|m| m.opacity < 1.0),
            multisample: false,
            cutout: super::cutout::scene_has_cutouts(scene),
        }
    }

    /// The names of the stages that are on.
    pub fn names(&self) -> Vec<&'static str> {
        [
            (self.texture, "texture"),
            (self.lighting, "lighting"),
            (self.transparency, "transparency"),
            (self.multisample, "multisample"),
            (self.cutout, "cutout"),
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
    /// Pixels shaded at their centre rather than with their primitive's
    /// flat colour (textures, smooth normals, highlights).
    pub points: u64,
    /// Primitives whose Lambert light was computed.
    pub lit_prims: u64,
    /// Textures decoded in this pass (textures decode on first use, once).
    pub textures_loaded: u64,
    /// Textures that failed to load (the material colour is used), with
    /// the reason: those this pass tried to sample.
    pub texture_failures: Vec<String>,
}

/// The shading pass. Keeps its per-primitive colour cache between frames.
#[derive(Clone, Debug, Default)]
pub struct Shader {
    options: ShaderOptions,
    prims: Vec<Option<[f32; 3]>>,
}

impl Shader {
    /// A shader with the given options.
    pub fn new(options: ShaderOptions) -> Self {
        Self {
            options,
            prims: Vec::new(),
        }
    }

    /// The options.
    pub fn options(&self) -> &ShaderOptions {
        &self.options
    }

    /// Fills `frame.color` from `frame.ids`, running only the colour stages
    /// `stages` switches on (`transparency` and `multisample` are the
    /// hider's and ignored here), reading the primitives from `prims`.
    pub fn shade(
        &mut self,
        prims: Prims<'_, '_>,
        frame: &mut Frame,
        stages: &Stages,
    ) -> StageTrace {
        let mut trace = StageTrace::default();
        let sampler = prims
            .sampler(self.options)
            .with_stages(stages.texture, stages.lighting);
        let textures = prims.textures();
        let decoded_before = textures.iter().filter(|t| t.is_decoded()).count();
        if stages.texture {
            trace.ran.push("texture");
        }
        if stages.lighting {
            trace.ran.push("lighting");
        }
        self.prims.clear();
        self.prims.resize(prims.len(), None);
        let (w, h) = (frame.width(), frame.height());
        let mut info = None;
        // The shading setup of the last primitive shaded per point (its
        // barycentric planes and texture state, built once per run).
        let mut setup: Option<(u32, SurfaceSetup)> = None;
        for y in 0..h {
            for x in 0..w {
                let i = frame.index(x, y);
                let id = frame.ids[i];
                if id == NO_ID || id as usize >= prims.len() {
                    frame.color[i] = BACKGROUND;
                    continue;
                }
                trace.pixels += 1;
                // Runs of one primitive are the rule: one look-up per run.
                let prim = match info {
                    Some((last, p)) if last == id => p,
                    _ => {
                        let p = prims.info(id);
                        info = Some((id, p));
                        p
                    }
                };
                let flat = match self.prims[id as usize] {
                    Some(c) => c,
                    None => {
                        let c = prim_shade(&prims, id, stages, &mut trace);
                        self.prims[id as usize] = Some(c);
                        c
                    }
                };
                let material = prims.material(prim.material);
                let mut c = flat;
                if sampler.varies(&prim, material) {
                    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let setup = match &mut setup {
                        Some((last, s)) if *last == id => s,
                        slot => &mut slot.insert((id, SurfaceSetup::new(&sampler, &prim))).1,
                    };
                    if let Some(at) = setup.color_at(&sampler, material, prims.lights(), cx, cy) {
                        c = at;
                        trace.points += 1;
                    }
                    if sampler.texture(&prim, material).is_some() {
                        trace.texture_samples += 1;
                    }
                }
                frame.color[i] = [to_srgb8(c[0]), to_srgb8(c[1]), to_srgb8(c[2]), 255];
            }
        }
        let decoded = textures.iter().filter(|t| t.is_decoded()).count();
        trace.textures_loaded = decoded.saturating_sub(decoded_before) as u64;
        if stages.texture {
            trace.texture_failures = texture_failures(textures.iter().copied());
        }
        trace
    }
}

/// Why each texture that was tried and failed did not load, once per file
/// (never decodes anything).
pub fn texture_failures<'a>(textures: impl IntoIterator<Item = &'a TextureRef>) -> Vec<String> {
    let mut failures: Vec<String> = Vec::new();
    for t in textures {
        if let Some(why) = t.failure()
            && !failures.contains(&why)
        {
            failures.push(why);
        }
    }
    failures
}

/// The flat colour of `prim`: its diffuse colour, lit when lighting runs
/// ([`flat_color`]).
fn prim_shade(
    prims: &Prims<'_, '_>,
    prim: u32,
    stages: &Stages,
    trace: &mut StageTrace,
) -> [f32; 3] {
    let info = prims.info(prim);
    let material = prims.material(info.material);
    if !stages.lighting {
        return material.diffuse;
    }
    trace.lit_prims += 1;
    flat_color(material, &info.camera, prims.lights(), prims.perspective())
}

/// A warning when `hider` cannot apply the transparency stage the scene
/// calls for (it draws translucent surfaces opaque, see
/// [`DynHider::composites_transparency`]); `None` when it can or when
/// nothing is translucent.
pub fn transparency_warning(hider: &dyn DynHider, stages: &Stages) -> Option<String> {
    (stages.transparency && !hider.composites_transparency()).then(|| {
        format!(
            "the scene has translucent materials, but {} keeps one surface per sample \
             and draws them opaque; the A-buffer (abuffer) composites them",
            hider.name()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::{ScenePrims, ShadeMode, shade_frame};
    use crate::{PrepareOptions, View, prepare, procedural};

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
        let trace = shader.shade(Prims::Screen(&screen), &mut frame, &Stages::default());
        assert!(trace.ran.is_empty());
        assert_eq!(trace.lit_prims, 0);
        assert!(trace.pixels > 0);
        let k = frame.ids.iter().position(|&id| id != NO_ID).unwrap();
        let kd = screen.material(frame.ids[k]).diffuse;
        assert_eq!(frame.color[k][..3], kd.map(to_srgb8));
        let lighting = Stages {
            lighting: true,
            ..Stages::default()
        };
        let lit = shader.shade(Prims::Screen(&screen), &mut frame, &lighting);
        assert_eq!(lit.ran, vec!["lighting"]);
        assert!(lit.lit_prims > 0);
        // The lit pass is flat Lambert: what shade_frame gives.
        let mut flat = frame.clone();
        shade_frame(&screen, &mut flat, ShadeMode::Lambert).unwrap();
        assert_eq!(flat.color, frame.color);
        // Read from the world-space scene, the pass gives the same colours.
        let on_demand = ScenePrims::new(&scene, &view).unwrap();
        let mut again = frame.clone();
        again.color.fill([1, 2, 3, 4]);
        Shader::default().shade(Prims::Scene(&on_demand), &mut again, &lighting);
        assert_eq!(again.color, frame.color);
    }
}
