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
//! Hiders that resolve colour from several samples per pixel (the
//! A-buffer, supersampling) would need the test per sample inside their
//! resolve; they draw cut-outs opaque, and `render_frame` says so in a
//! warning naming the hider.

use super::surface::{TextureOptions, TextureSampler};
use super::texture::AlphaClass;
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

/// Whether `material`'s diffuse texture declares an alpha channel (reads
/// its header).
pub fn material_may_cut_out(material: &Material) -> bool {
    material
        .diffuse_texture
        .as_ref()
        .is_some_and(|t| t.may_have_alpha())
}

/// The alpha test of a prepared scene's primitives at pixel centres.
#[derive(Clone, Debug)]
pub struct AlphaTest<'a> {
    scene: &'a ScreenScene,
    sampler: TextureSampler,
    /// Per material: whether it may cut out.
    cuts: Vec<bool>,
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
        if !self.may_cut(prim) {
            return true;
        }
        let info = &self.scene.prims[prim as usize];
        let material = &self.scene.materials[info.material as usize];
        let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
        self.sampler.alpha_at(info, material, x, y) >= 0.5
    }

    /// The materials' classes that the test met, decoded by now: whether
    /// some texture has partial alpha (translucency, which the test draws
    /// as a cut-out at one half).
    pub fn partial_alpha(&self) -> Vec<String> {
        let mut files = Vec::new();
        for (m, &cuts) in self.scene.materials.iter().zip(&self.cuts) {
            if let Some(t) = m.diffuse_texture.as_ref().filter(|_| cuts)
                && t.decoded_alpha_class() == Some(AlphaClass::Partial)
            {
                let name = t.path().display().to_string();
                if !files.contains(&name) {
                    files.push(name);
                }
            }
        }
        files
    }
}

/// The cut-out stage as [`super::render_frame`] runs it after `hider`'s
/// pipeline rendered `scene` through `view` with `options` into `frame`:
/// nothing when the scene has no cut-outs ([`scene_has_cutouts`]); a
/// warning naming the hider when it resolves colour itself (it drew the
/// cut-outs opaque); else the alpha test over its ids ([`resolve_cutouts`]
/// on the scene prepared once more with `options`: the ids of every front
/// end are the shared one's), its counters added to `stats`, and a warning
/// per texture with partial alpha. For callers that run
/// [`DynHider::render_scene`] themselves and want the ids `render_frame`
/// gives.
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
    if hider.resolves_color() {
        stats.warnings.push(format!(
            "the scene has alpha cut-outs (a map_Kd with an alpha channel), but {} \
             resolves colour from several samples per pixel and draws them opaque; a \
             single-sample hider (zbuffer, zbuffer-tiled, painter, warnock, scanline) \
             alpha-tests them at pixel centres",
            hider.name()
        ));
        return Ok(());
    }
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
    for file in test.partial_alpha() {
        stats.warnings.push(format!(
            "{file}: partial alpha (translucency) is drawn as a cut-out at alpha one half \
             by {}; the A-buffer (abuffer) composites translucent materials",
            hider.name()
        ));
    }
    Ok(())
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
    let mut bins: Option<Bins> = None;
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
            let bins = bins.get_or_insert_with(|| Bins::new(scene));
            let (id, depth) = nearest_passing(scene, bins.at(i, j), test, i, j, &mut stats);
            frame.ids[k] = id;
            frame.depth[k] = depth;
        }
    }
    stats
}

/// The nearest of `candidates` covering the centre of `(i, j)` and passing
/// the test: its id and window depth, or the background's.
fn nearest_passing(
    scene: &ScreenScene,
    candidates: &[u32],
    test: &AlphaTest,
    i: u32,
    j: u32,
    stats: &mut CutoutStats,
) -> (u32, f32) {
    let (px, py) = (
        i64::from(hider_geom::fixed::pixel_center(i as i32)),
        i64::from(hider_geom::fixed::pixel_center(j as i32)),
    );
    let mut best: Option<(f64, u32)> = None;
    for &t in candidates {
        stats.candidates += 1;
        let tri = &scene.tris[t as usize];
        if !tri.edges().iter().all(|e| e.contains(px, py)) {
            continue;
        }
        let z = tri.depth.at_pixel(i, j);
        let nearer = best.is_none_or(|(bz, bid)| z < bz || (z == bz && tri.prim < bid));
        if nearer && test.passes(tri.prim, i, j) {
            best = Some((z, tri.prim));
        }
    }
    best.map_or((NO_ID, 1.0), |(z, id)| (id, z as f32))
}
