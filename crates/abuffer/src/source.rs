//! What a frame is rendered from: the triangles, and how to colour a
//! primitive. Either the shared front end's [`ScreenScene`] (through
//! [`Hider::render`](hider_scene::Hider::render)) or the lean front end's
//! [`LeanScene`] with the world-space scene it came from (through
//! [`Hider::render_scene`](hider_scene::Hider::render_scene)); both give
//! the same triangles in the same order and the same colours, bit for bit,
//! so the frame does not depend on which one was used.

use hider_geom::Viewport;
use hider_scene::prepare::lean::{LeanScene, LeanTri, prepare_lean_into};
use hider_scene::shade::{SetupCache, SurfaceSetup};
use hider_scene::{
    Frame, Material, PrepareOptions, Result, Scene, ScreenScene, ShadeMode, TextureOptions,
    TextureSampler, View, check_frame, check_frame_size, prepare_into,
};

use crate::bins::BinItem;

use crate::palette;

/// Where the colours come from.
#[derive(Clone, Copy, Debug)]
enum Kind<'a> {
    /// `prepare`'s output, and the frame's texture sampler when it is
    /// textured.
    Screen(&'a ScreenScene, Option<&'a TextureSampler>),
    /// The lean front end's output, the scene it was prepared from, and
    /// the frame's texture sampler when it is shaded per point.
    Lean(&'a LeanScene, &'a Scene, Option<&'a TextureSampler>),
}

/// The triangles of a frame and their colours.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Source<'a> {
    /// The image size.
    pub(crate) viewport: Viewport,
    /// The triangles, in `prepare`'s order (none when the lean front end
    /// binned them as it set them up: [`crate::bins::BinRun`]).
    pub(crate) tris: &'a [LeanTri],
    /// The frame's binned triangles, in the same order, once binned: what
    /// the lists read of a fragment's triangle (its plane, vertices and
    /// facing) by its index.
    pub(crate) items: &'a [BinItem],
    kind: Kind<'a>,
}

impl<'a> Source<'a> {
    /// `scene`'s triangles as `tris` (converted by the caller), textured
    /// through `sampler` when it is given ([`palette::sampler`]).
    pub(crate) fn screen(
        scene: &'a ScreenScene,
        tris: &'a [LeanTri],
        sampler: Option<&'a TextureSampler>,
    ) -> Self {
        Self {
            viewport: scene.viewport,
            tris,
            items: &[],
            kind: Kind::Screen(scene, sampler),
        }
    }

    /// The lean front end's `lean`, prepared from `scene`, shaded per
    /// point through `sampler` when it is given ([`lean_sampler`]).
    pub(crate) fn lean(
        lean: &'a LeanScene,
        scene: &'a Scene,
        sampler: Option<&'a TextureSampler>,
    ) -> Self {
        Self {
            viewport: lean.viewport,
            tris: lean.tris(),
            items: &[],
            kind: Kind::Lean(lean, scene, sampler),
        }
    }

    /// This source with the frame's binned triangles, `items`.
    pub(crate) fn with_items(self, items: &'a [BinItem]) -> Self {
        Self { items, ..self }
    }

    /// The prepared scene, when the frame is rendered from one (the alpha
    /// test of cut-outs reads its primitives).
    pub(crate) fn screen_scene(&self) -> Option<&'a ScreenScene> {
        match self.kind {
            Kind::Screen(s, _) => Some(s),
            Kind::Lean(..) => None,
        }
    }

    /// The number of primitives (ids are below it).
    pub(crate) fn prims(&self) -> usize {
        match self.kind {
            Kind::Screen(s, _) => s.prims.len(),
            Kind::Lean(_, scene, _) => scene.triangle_count(),
        }
    }

    /// `[r, g, b, opacity]` (linear, opacity clamped to [0, 1]) of `prim`.
    pub(crate) fn prim_rgba(&self, prim: u32, mode: ShadeMode) -> [f32; 4] {
        match self.kind {
            Kind::Screen(s, _) => palette::prim_rgba(s, prim, mode),
            Kind::Lean(lean, scene, _) => {
                let (rgb, alpha) = lean.prim_color(scene, prim, mode);
                [rgb[0], rgb[1], rgb[2], alpha.clamp(0.0, 1.0)]
            }
        }
    }

    /// Fills `out` with [`Self::prim_rgba`] of every primitive, reusing
    /// its memory.
    pub(crate) fn prim_colors(&self, mode: ShadeMode, out: &mut Vec<[f32; 4]>) {
        out.clear();
        out.extend((0..self.prims() as u32).map(|prim| self.prim_rgba(prim, mode)));
    }

    /// The opacity of every primitive, clamped to [0, 1] (the last
    /// channel of [`Self::prim_rgba`]), as runs: `out[k] = (end, alpha)`
    /// gives `alpha` to the primitives from the previous run's end up to
    /// `end` (exclusive); neighbouring runs differ. From the materials
    /// alone, no shading: a mesh's primitives share its material, so the
    /// lean front end's scene needs one look-up per mesh, not one per
    /// triangle.
    pub(crate) fn opacity_runs(&self, out: &mut Vec<(u32, f32)>) {
        match self.kind {
            Kind::Screen(s, _) => {
                out.clear();
                for prim in 0..s.prims.len() as u32 {
                    push_opacity(out, prim + 1, s.material(prim).opacity.clamp(0.0, 1.0));
                }
            }
            Kind::Lean(_, scene, _) => scene_opacity_runs(scene, out),
        }
    }

    /// The material index of `prim` (merging requires equal ones).
    pub(crate) fn material(&self, prim: u32) -> u32 {
        match self.kind {
            Kind::Screen(s, _) => s.prims[prim as usize].material,
            Kind::Lean(lean, scene, _) => lean.material_index(scene, prim),
        }
    }

    /// The colour and opacity of `prim` at window point `(x, y)` when the
    /// frame is shaded per point (textures, vertex normals or colours),
    /// from `prepare`'s per-primitive data ([`palette::at_point`]) or, for
    /// the lean front end, the same data assembled from its vertices
    /// ([`LeanScene::surface_rgb`]): the same colour, bit for bit; `rgba`
    /// (the primitive's flat colour, [`Self::prim_rgba`]) otherwise. The
    /// primitive's shading setup comes from `setups` (built there on first
    /// use).
    #[inline(always)]
    pub(crate) fn at_point(
        &self,
        setups: &mut SetupCache,
        prim: u32,
        rgba: [f32; 4],
        (x, y): (f64, f64),
    ) -> [f32; 4] {
        match self.kind {
            Kind::Screen(_, None) | Kind::Lean(_, _, None) => rgba,
            Kind::Screen(s, sampler) => palette::at_point(s, sampler, setups, prim, rgba, x, y),
            Kind::Lean(lean, world, Some(sampler)) => {
                let setup = setups.get_or_insert_with(prim, || {
                    SurfaceSetup::new(sampler, &lean.prim_info(world, prim))
                });
                let base = [rgba[0], rgba[1], rgba[2]];
                let [r, g, b] = lean.surface_rgb(world, sampler, setup, base, (x, y));
                [r, g, b, rgba[3]]
            }
        }
    }

    /// Whether a primitive's colour is the same at every pixel (the frame
    /// is not textured): [`Self::at_point`] gives back its `rgba`.
    pub(crate) fn flat_colors(&self) -> bool {
        match self.kind {
            Kind::Screen(_, sampler) | Kind::Lean(_, _, sampler) => sampler.is_none(),
        }
    }
}

/// The front ends of a hider that draws a frame's triangles from a
/// [`Source`] and keeps nothing of them between frames (the supersampled
/// baselines): `prepare`'s output converted, or the lean front end's,
/// with their memory kept from frame to frame.
#[derive(Clone, Debug, Default)]
pub(crate) struct FrontEnds {
    lean: LeanScene,
    tris: Vec<LeanTri>,
}

impl FrontEnds {
    /// `draw` of `scene`'s triangles, coloured under `mode`
    /// ([`Hider::render`](hider_scene::Hider::render)).
    pub(crate) fn screen<T>(
        &mut self,
        scene: &ScreenScene,
        mode: ShadeMode,
        draw: impl FnOnce(&Source<'_>) -> T,
    ) -> T {
        self.tris.clear();
        self.tris.extend(scene.tris.iter().map(LeanTri::from));
        let sampler = palette::sampler(scene, mode);
        draw(&Source::screen(scene, &self.tris, sampler.as_ref()))
    }

    /// `draw` of world-space `scene`'s triangles for `view`, coloured
    /// under `mode`, through the lean front end (`prepare`'s triangles,
    /// in its order, with the same colours, bit for bit), shaded per point
    /// from its vertices when the scene varies per point; a scene with
    /// cut-outs (alpha-tested per sample from `prepare`'s primitives) is
    /// prepared into `screen` instead
    /// ([`Hider::render_scene`](hider_scene::Hider::render_scene)).
    /// `name` names the hider when `frame` is not `view`'s size (checked
    /// before any front end runs).
    pub(crate) fn scene<T>(
        &mut self,
        name: &str,
        (scene, view, options): (&Scene, &View, &PrepareOptions),
        screen: &mut ScreenScene,
        (mode, frame): (ShadeMode, &mut Frame),
        draw: impl FnOnce(&Source<'_>, &mut Frame) -> Result<T>,
    ) -> Result<T> {
        if hider_scene::shade::cutout::scene_has_cutouts(scene) {
            prepare_into(scene, view, options, screen)?;
            check_frame(name, screen, frame)?;
            return self.screen(screen, mode, |s| draw(s, frame));
        }
        check_frame_size(name, view.viewport, frame)?;
        self.lean.set_point_shading(mode == ShadeMode::Lambert);
        prepare_lean_into(scene, view, options, &mut self.lean)?;
        let sampler = lean_sampler(&self.lean, view);
        draw(&Source::lean(&self.lean, scene, sampler.as_ref()), frame)
    }
}

/// The sampler of a frame the lean front end prepared into `lean` for
/// `view`: `Some` when it kept what shading per point reads
/// ([`LeanScene::shades_per_point`], asked for in Lambert mode only, as
/// [`palette::sampler`] decides for `prepare`'s output), with the same
/// options and rays as [`palette::sampler`]'s.
pub(crate) fn lean_sampler(lean: &LeanScene, view: &View) -> Option<TextureSampler> {
    lean.shades_per_point()
        .then(|| TextureSampler::for_view(view, TextureOptions::default()))
}

/// The flat colour and opacity of each primitive of a frame, computed on
/// first use ([`Source::prim_rgba`]): a primitive is shaded only when a
/// fragment of it is merged, pruned or resolved (the opacity the culling
/// needs comes from the materials alone), so primitives culled whole are
/// never shaded. A stamp per primitive says which frame shaded it, so
/// starting a frame writes nothing (marking every entry stale was 8 MB of
/// writes a frame per thread on the 500 sphere's 499,000 primitives).
#[derive(Clone, Debug, Default)]
pub(crate) struct ColorCache {
    colors: Vec<[f32; 4]>,
    /// The frame that computed each entry of `colors`.
    stamps: Vec<u32>,
    /// The current frame's stamp (never 0, the stamp of a new entry).
    frame: u32,
    /// The shading setups ([`SurfaceSetup`]: the data, barycentric
    /// planes, face normal and textures) of primitives shaded per point
    /// this frame, from `prepare`'s data or the lean front end's vertices.
    setups: SetupCache,
}

impl ColorCache {
    /// Starts a frame of `prims` primitives: every entry stale.
    pub(crate) fn begin(&mut self, prims: usize) {
        self.setups.clear();
        self.frame = self.frame.wrapping_add(1);
        if self.frame == 0 {
            // After 2^32 - 1 frames, stamps repeat: forget them all.
            self.stamps.fill(0);
            self.frame = 1;
        }
        if self.stamps.len() < prims {
            self.stamps.resize(prims, 0);
            self.colors.resize(prims, [0.0; 4]);
        }
    }

    /// The colour and opacity of `prim` in `scene` under `mode`, shaded on
    /// the frame's first use.
    #[inline]
    pub(crate) fn get(&mut self, scene: &Source<'_>, mode: ShadeMode, prim: u32) -> [f32; 4] {
        let k = prim as usize;
        if self.stamps[k] != self.frame {
            self.colors[k] = scene.prim_rgba(prim, mode);
            self.stamps[k] = self.frame;
        }
        self.colors[k]
    }

    /// The colour and opacity of `prim` in `scene` under `mode` at pixel
    /// `ij`: [`Self::get`], then, when the frame is shaded per point,
    /// shaded at the pixel centre ([`Source::at_point`]). The
    /// primitive's shading setup is built once per run of pixels. Inlined
    /// into the resolve loops (a call cost 2 % of the smooth-shaded
    /// spider's frame).
    #[inline(always)]
    pub(crate) fn at_pixel(
        &mut self,
        scene: &Source<'_>,
        mode: ShadeMode,
        prim: u32,
        ij: (u32, u32),
    ) -> [f32; 4] {
        let flat = self.get(scene, mode, prim);
        scene.at_point(&mut self.setups, prim, flat, palette::pixel_centre(ij))
    }
}

/// [`Source::opacity_runs`] of a scene the lean front end prepares, from
/// its meshes' materials alone (as [`LeanScene::prim_color`] finds a
/// primitive's material: the mesh's, or the default one), so that it can
/// be known before the front end has run.
pub(crate) fn scene_opacity_runs(scene: &Scene, out: &mut Vec<(u32, f32)>) {
    out.clear();
    let default = Material::default().opacity;
    let mut end = 0u32;
    let opacity = |m: Option<&Material>| m.map_or(default, |m| m.opacity).clamp(0.0, 1.0);
    for (m, mesh) in scene.meshes.iter().enumerate() {
        if mesh.indices.is_empty() {
            continue;
        }
        if mesh.triangle_materials.is_empty() {
            end += mesh.indices.len() as u32;
            push_opacity(out, end, opacity(scene.mesh_material(mesh)));
            continue;
        }
        for t in 0..mesh.indices.len() {
            end += 1;
            push_opacity(out, end, opacity(scene.triangle_material(m, t)));
        }
    }
}

/// Gives `alpha` to the primitives from the end of `out`'s last run up to
/// `end`: that run grows when its opacity is the same, so neighbouring
/// runs differ.
fn push_opacity(out: &mut Vec<(u32, f32)>, end: u32, alpha: f32) {
    match out.last_mut() {
        Some(last) if last.1 == alpha => last.0 = end,
        _ => out.push((end, alpha)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::procedural;

    /// Colours are shaded once a frame, and a new frame (also the one
    /// after the stamps wrap around) sees none of the last frame's.
    #[test]
    fn the_colour_cache_forgets_each_frame() {
        let screen = hider_testkit::screen(&procedural::random_soup(4, 1), 32, 32);
        let tris: Vec<LeanTri> = screen.tris.iter().map(LeanTri::from).collect();
        let source = Source::screen(&screen, &tris, None);
        let mut cache = ColorCache::default();
        cache.begin(source.prims());
        let shaded = cache.get(&source, ShadeMode::Lambert, 2);
        assert_eq!(shaded, source.prim_rgba(2, ShadeMode::Lambert));
        // A stale entry a frame keeps would show here.
        cache.colors[2] = [9.0; 4];
        assert_eq!(cache.get(&source, ShadeMode::Lambert, 2), [9.0; 4]);
        cache.begin(source.prims());
        assert_eq!(cache.get(&source, ShadeMode::Lambert, 2), shaded);
        cache.colors[2] = [9.0; 4];
        cache.frame = u32::MAX;
        cache.stamps[2] = 1;
        cache.begin(source.prims());
        assert_eq!(cache.frame, 1);
        assert_eq!(cache.get(&source, ShadeMode::Lambert, 2), shaded);
    }
}
