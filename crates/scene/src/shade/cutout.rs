//! Alpha cut-outs: the alpha test at pixel centres, for every
//! single-sample hider without changing any of them.
//!
//! A material whose diffuse texture (`map_Kd`) has an alpha channel is a
//! cut-out (a leaf card, a fence): where the texture's alpha at a pixel
//! centre is below one half, the surface is not there, and the pixel shows
//! what is behind it. The alpha is sampled exactly as the colour is
//! ([`TextureSampler::alpha_at`]): perspective-correct texture coordinates
//! at the pixel centre, the mip level of the pixel's footprint, the
//! texture filter.
//!
//! The hiders decide visibility without reading textures, so the test runs
//! after them, as a stage of the colour pass ([`resolve_cutouts`]): for
//! each pixel whose visible primitive fails the test, it finds the nearest
//! primitive at that pixel centre that covers it (the shared exact edge
//! functions) and passes the test, and writes its id and depth. Nearest
//! is by window depth evaluated in `f64` at the centre, the lower
//! primitive id winning an exact tie: the rule of every exact hider, so
//! the stage's answer is the one a hider testing alpha itself would give,
//! at every pixel centre, for the z-buffers, the painter's raster, Warnock
//! and scanline alike. Candidates come from a screen-space bin grid over
//! the screen triangles, built only when some pixel fails the test. The
//! oracle applies the same test natively ([`AlphaTest`]).
//!
//! A texture's alpha is the product of the diffuse texture's alpha
//! channel and the dissolve texture's value (`map_d`, read as a mask:
//! [`crate::TextureRef::as_mask`]); the material's `d` multiplies it where
//! the surface is composited.
//!
//! Hiders that resolve colour from several samples per pixel (the
//! A-buffer, supersampling, anti-aliased Warnock) test each of their own
//! samples ([`AlphaTest::passes_at`]) and skip this stage. A texture with
//! partial alpha ([`AlphaClass::Partial`]) is translucency: the A-buffer
//! composites it with opacity `d` times the texture alpha at the
//! fragment's pixel centre ([`AlphaTest::opacity`]); the others
//! alpha-test it at one half, with a warning.

use std::sync::OnceLock;

use hider_geom::fixed::{SUBPIXEL_BITS, SUBPIXEL_SCALE};

use super::setup::SurfaceSetup;
use super::surface::{TextureOptions, TextureSampler};
use super::texture::{AlphaClass, TextureRef};
use crate::error::Result;
use crate::frame::{Frame, NO_ID};
use crate::hider::{DynHider, StatsTable};
use crate::model::{Material, Scene};
use crate::prepare::{PrepareOptions, ScreenScene, prepare};
use crate::view::View;

/// Whether `scene` calls for the alpha test: a mesh with texture
/// coordinates whose material's diffuse texture declares an alpha channel
/// in its header (read, never decoded).
pub fn scene_has_cutouts(scene: &Scene) -> bool {
    scene.meshes.iter().any(|mesh| {
        !mesh.uvs.is_empty()
            && scene
                .mesh_materials(mesh)
                .any(|m| m.is_some_and(material_may_cut_out))
    })
}

/// Whether `material`'s textures may make it cut out: a diffuse texture
/// whose header declares an alpha channel, or a readable dissolve texture
/// (`map_d`) (reads headers, never decodes).
pub fn material_may_cut_out(material: &Material) -> bool {
    alpha_textures(material).any(TextureRef::may_have_alpha)
}

/// The textures whose alpha make up `material`'s: `map_Kd` and `map_d`.
pub(super) fn alpha_textures(material: &Material) -> impl Iterator<Item = &TextureRef> {
    [&material.diffuse_texture, &material.alpha_texture]
        .into_iter()
        .flatten()
}

/// What `material`'s texture alpha holds, from every texel of its alpha
/// textures (decoding them at their coarsest level if they were not
/// decoded: [`TextureRef::alpha_class`]): the most translucent class of
/// the two; a texture that does not load counts as opaque.
pub fn material_alpha_class(material: &Material) -> AlphaClass {
    alpha_textures(material)
        .filter_map(TextureRef::alpha_class)
        .max()
        .unwrap_or_default()
}

/// The alpha textures of `material` with partial alpha, and the share of
/// their texels that is partial (decoding as [`material_alpha_class`]):
/// the planner's evidence of translucency.
pub fn material_partial_alpha(material: &Material) -> Vec<(String, f64)> {
    alpha_textures(material)
        .filter(|t| t.alpha_class() == Some(AlphaClass::Partial))
        .map(|t| {
            let share = t.get_level(u32::MAX).map_or(0.0, |d| d.partial_share());
            (t.path().display().to_string(), share)
        })
        .collect()
}

/// The alpha test of a prepared scene's primitives at pixel centres.
#[derive(Clone, Debug)]
pub struct AlphaTest<'a> {
    scene: &'a ScreenScene,
    sampler: TextureSampler,
    /// Per material: whether it may cut out.
    cuts: Vec<bool>,
    /// Per material that may cut out: its alpha class, on first use.
    classes: Vec<OnceLock<AlphaClass>>,
}

impl<'a> AlphaTest<'a> {
    /// The test for `scene`'s primitives, sampling as `options` say (the
    /// colour pass's); `None` when no material may cut out, so that
    /// scenes without cut-outs pay nothing.
    pub fn new(scene: &'a ScreenScene, options: TextureOptions) -> Option<Self> {
        let cuts: Vec<bool> = scene.materials.iter().map(material_may_cut_out).collect();
        cuts.iter().any(|&c| c).then(|| Self {
            scene,
            sampler: TextureSampler::new(scene, options).with_stages(true, false),
            classes: vec![OnceLock::new(); cuts.len()],
            cuts,
        })
    }

    /// Whether primitive `prim` may fail the test somewhere (its material
    /// may cut out and it has texture coordinates).
    pub fn may_cut(&self, prim: u32) -> bool {
        let info = &self.scene.prims[prim as usize];
        self.cuts[info.material as usize] && info.uvs.is_some()
    }

    /// Whether primitive `prim` is there at the centre of pixel `(i, j)`:
    /// its texture's alpha there is at least one half.
    pub fn passes(&self, prim: u32, i: u32, j: u32) -> bool {
        self.passes_at(prim, f64::from(i) + 0.5, f64::from(j) + 0.5)
    }

    /// Whether primitive `prim` is there at window point `(x, y)` (pixels,
    /// y down: a hider's own sample): its texture's alpha there
    /// ([`Self::alpha`]) is at least one half.
    pub fn passes_at(&self, prim: u32, x: f64, y: f64) -> bool {
        !self.may_cut(prim) || self.alpha(prim, x, y) >= 0.5
    }

    /// The texture alpha of primitive `prim` at window point `(x, y)`: the
    /// diffuse texture's alpha times the dissolve texture's value, sampled
    /// as the colour is (perspective-correct coordinates at the point, the
    /// mip level of the pixel's footprint, the filter); 1 when it may not
    /// cut. The material's `d` is not in it.
    pub fn alpha(&self, prim: u32, x: f64, y: f64) -> f32 {
        if !self.may_cut(prim) {
            return 1.0;
        }
        let info = &self.scene.prims[prim as usize];
        let material = &self.scene.materials[info.material as usize];
        self.sampler.alpha_at(info, material, x, y)
    }

    /// The test of primitive `prim` at many points (a hider's samples in
    /// a pixel): its shading setup ([`SurfaceSetup`]) built once, the same
    /// answers as [`Self::passes_at`] and [`Self::alpha`].
    pub fn prim(&self, prim: u32) -> PrimAlphaTest<'_, 'a> {
        let setup = self
            .may_cut(prim)
            .then(|| SurfaceSetup::new(&self.sampler, &self.scene.prims[prim as usize]));
        PrimAlphaTest {
            test: self,
            prim,
            setup,
        }
    }

    /// The alpha class of primitive `prim`'s material
    /// ([`material_alpha_class`], found once per material, decoding its
    /// textures at their coarsest level if needed);
    /// [`AlphaClass::Opaque`] when it may not cut.
    pub fn class(&self, prim: u32) -> AlphaClass {
        if !self.may_cut(prim) {
            return AlphaClass::Opaque;
        }
        let m = self.scene.prims[prim as usize].material as usize;
        *self.classes[m].get_or_init(|| material_alpha_class(&self.scene.materials[m]))
    }

    /// For a primitive whose material has partial alpha (translucency,
    /// [`Self::class`]): `d` times its texture alpha at the centre of pixel
    /// `(i, j)`, the opacity a compositing hider gives its fragment there;
    /// `None` for the others (opaque, or cut-outs alpha-tested per
    /// sample).
    pub fn opacity(&self, prim: u32, (i, j): (u32, u32)) -> Option<f32> {
        if self.class(prim) != AlphaClass::Partial {
            return None;
        }
        let d = self.scene.material(prim).opacity.clamp(0.0, 1.0);
        Some(d * self.alpha(prim, f64::from(i) + 0.5, f64::from(j) + 0.5))
    }

    /// The materials' classes that the test met, decoded by now: whether
    /// some texture has partial alpha (translucency, which the test draws
    /// as a cut-out at one half).
    pub fn partial_alpha(&self) -> Vec<String> {
        partial_alpha_files(&self.scene.materials)
    }
}

/// The alpha test of one primitive ([`AlphaTest::prim`]).
#[derive(Clone, Debug)]
pub struct PrimAlphaTest<'t, 'a> {
    test: &'t AlphaTest<'a>,
    prim: u32,
    /// `None` where the primitive may not cut.
    setup: Option<SurfaceSetup>,
}

impl PrimAlphaTest<'_, '_> {
    /// [`AlphaTest::alpha`] of this primitive at window point `(x, y)`.
    pub fn alpha(&mut self, x: f64, y: f64) -> f32 {
        match &mut self.setup {
            Some(setup) => {
                let material = self.test.scene.material(self.prim);
                setup.alpha_at(&self.test.sampler, material, x, y)
            }
            None => 1.0,
        }
    }

    /// [`AlphaTest::passes_at`] of this primitive at window point `(x, y)`.
    pub fn passes_at(&mut self, x: f64, y: f64) -> bool {
        self.setup.is_none() || self.alpha(x, y) >= 0.5
    }

    /// [`AlphaTest::passes`] of this primitive at the centre of pixel
    /// `(i, j)`.
    pub fn passes(&mut self, i: u32, j: u32) -> bool {
        self.passes_at(f64::from(i) + 0.5, f64::from(j) + 0.5)
    }

    /// [`AlphaTest::opacity`] of this primitive at the centre of pixel
    /// `(i, j)` (the same value).
    pub fn opacity(&mut self, (i, j): (u32, u32)) -> Option<f32> {
        if self.test.class(self.prim) != AlphaClass::Partial {
            return None;
        }
        let d = self.test.scene.material(self.prim).opacity.clamp(0.0, 1.0);
        Some(d * self.alpha(f64::from(i) + 0.5, f64::from(j) + 0.5))
    }
}

/// The cut-out stage as [`super::render_frame`] runs it after `hider`'s
/// pipeline rendered `scene` through `view` with `options` into `frame`:
/// nothing when the scene has no cut-outs ([`scene_has_cutouts`]); when
/// the hider resolves colour itself, nothing but the warning below (it
/// alpha-tested its own samples); else the alpha test over its ids
/// ([`resolve_cutouts`] on the scene prepared once more with `options`:
/// the ids of every front end are the shared one's), its counters added
/// to `stats`. Unless the hider composites transparency, a warning per
/// texture with partial alpha (drawn as a cut-out at one half). For
/// callers that run [`DynHider::render_scene`] themselves and want the ids
/// `render_frame` gives.
pub fn cutout_stage(
    hider: &dyn DynHider,
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    frame: &mut Frame,
    stats: &mut StatsTable,
) -> Result<()> {
    if !scene_has_cutouts(scene) {
        return Ok(());
    }
    if !hider.resolves_color() {
        let prepared = prepare(scene, view, options)?;
        let Some(test) = AlphaTest::new(&prepared, TextureOptions::default()) else {
            return Ok(());
        };
        let cut = resolve_cutouts(&prepared, frame, &test);
        stats.counters.extend([
            ("cut-out pixels tested", cut.pixels_tested),
            ("cut-out pixels replaced", cut.pixels_replaced),
            ("cut-out candidates", cut.candidates),
        ]);
    }
    if !hider.composites_transparency() {
        for file in partial_alpha_files(&scene.materials) {
            stats.warnings.push(format!(
                "{file}: partial alpha (translucency) is drawn as a cut-out at alpha one half \
                 by {}; the A-buffer (abuffer) composites translucent materials",
                hider.name()
            ));
        }
    }
    Ok(())
}

/// The alpha textures of `materials` (that may cut out) found to hold
/// partial alpha, by now decoded (never decodes), each file once.
fn partial_alpha_files(materials: &[Material]) -> Vec<String> {
    let mut files = Vec::new();
    for m in materials.iter().filter(|m| material_may_cut_out(m)) {
        for t in alpha_textures(m) {
            if t.decoded_alpha_class() == Some(AlphaClass::Partial) {
                let name = t.path().display().to_string();
                if !files.contains(&name) {
                    files.push(name);
                }
            }
        }
    }
    files
}

/// What the cut-out stage did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CutoutStats {
    /// Covered pixels whose visible primitive may cut out (tested).
    pub pixels_tested: u64,
    /// Pixels whose visible primitive failed the test and were given the
    /// nearest primitive that passes (or the background).
    pub pixels_replaced: u64,
    /// Candidate triangles whose coverage, depth or alpha was looked at.
    pub candidates: u64,
}

/// Side of a bin of the candidate grid, in pixels.
const BIN: u32 = 16;

/// Screen triangles by the bins their pixel rectangles touch.
struct Bins {
    columns: u32,
    tris: Vec<Vec<u32>>,
}

impl Bins {
    fn new(scene: &ScreenScene) -> Self {
        let vp = scene.viewport;
        let columns = vp.width.div_ceil(BIN).max(1);
        let rows = vp.height.div_ceil(BIN).max(1);
        let mut tris = vec![Vec::new(); (columns * rows) as usize];
        for (k, t) in scene.tris.iter().enumerate() {
            if let Some((x0, y0, x1, y1)) = t.pixel_bounds(vp) {
                for by in y0 / BIN..=y1 / BIN {
                    for bx in x0 / BIN..=x1 / BIN {
                        tris[(by * columns + bx) as usize].push(k as u32);
                    }
                }
            }
        }
        Self { columns, tris }
    }

    fn at(&self, i: u32, j: u32) -> &[u32] {
        &self.tris[((j / BIN) * self.columns + i / BIN) as usize]
    }
}

/// The alpha test over a frame of ids (see the module documentation):
/// every pixel whose primitive fails it gets the nearest primitive of
/// `scene` at its centre that passes, with its window depth, or the
/// background. `scene` is the prepared scene the ids came from (the
/// shared front end with the hider's options); colour the frame after.
pub fn resolve_cutouts(scene: &ScreenScene, frame: &mut Frame, test: &AlphaTest) -> CutoutStats {
    let mut stats = CutoutStats::default();
    let mut bins: Option<CutoutSearch> = None;
    let (w, h) = (frame.width(), frame.height());
    for j in 0..h {
        for i in 0..w {
            let k = frame.index(i, j);
            let id = frame.ids[k];
            if id == NO_ID || id as usize >= scene.prims.len() || !test.may_cut(id) {
                continue;
            }
            stats.pixels_tested += 1;
            if test.passes(id, i, j) {
                continue;
            }
            stats.pixels_replaced += 1;
            let search = bins.get_or_insert_with(|| CutoutSearch::new(scene));
            let (px, py) = (
                i64::from(hider_geom::fixed::pixel_center(i as i32)),
                i64::from(hider_geom::fixed::pixel_center(j as i32)),
            );
            let (id, depth) = search
                .nearest_at(test, px, py, &mut stats.candidates)
                .map_or((NO_ID, 1.0), |(id, z)| (id, z as f32));
            frame.ids[k] = id;
            frame.depth[k] = depth;
        }
    }
    stats
}

/// The nearest primitive passing the alpha test at any window point: the
/// reference a hider's own samples are resolved by where a cut-out is
/// visible (the anti-aliased Warnock's sub-samples), and the search of
/// [`resolve_cutouts`] at pixel centres. Candidates come from a
/// screen-space bin grid over the screen triangles.
pub struct CutoutSearch<'a> {
    scene: &'a ScreenScene,
    bins: Bins,
}

impl<'a> CutoutSearch<'a> {
    /// The search over `scene`'s screen triangles (bins them).
    pub fn new(scene: &'a ScreenScene) -> Self {
        Self {
            scene,
            bins: Bins::new(scene),
        }
    }

    /// The nearest primitive of the scene covering the fixed-point window
    /// point `(px, py)` (1/256 pixel, the shared exact edge functions and
    /// fill rule) and passing `test` there, with its window depth there:
    /// nearest by depth in `f64`, the lower id winning an exact tie;
    /// `None` for the background. Adds the triangles looked at to
    /// `candidates`.
    pub fn nearest_at(
        &self,
        test: &AlphaTest,
        px: i64,
        py: i64,
        candidates: &mut u64,
    ) -> Option<(u32, f64)> {
        let vp = self.scene.viewport;
        let (i, j) = (px >> SUBPIXEL_BITS, py >> SUBPIXEL_BITS);
        if i < 0 || j < 0 || i >= i64::from(vp.width) || j >= i64::from(vp.height) {
            return None;
        }
        let scale = f64::from(SUBPIXEL_SCALE);
        let (x, y) = (px as f64 / scale, py as f64 / scale);
        let mut best: Option<(f64, u32)> = None;
        for &t in self.bins.at(i as u32, j as u32) {
            *candidates += 1;
            let tri = &self.scene.tris[t as usize];
            if !tri.edges().iter().all(|e| e.contains(px, py)) {
                continue;
            }
            let z = tri.depth.eval(x, y);
            let nearer = best.is_none_or(|(bz, bid)| z < bz || (z == bz && tri.prim < bid));
            if nearer && test.passes_at(tri.prim, x, y) {
                best = Some((z, tri.prim));
            }
        }
        best.map(|(z, id)| (id, z))
    }
}
