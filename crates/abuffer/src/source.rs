//! What a frame is rendered from: the triangles, and how to colour a
//! primitive. Either the shared front end's [`ScreenScene`] (through
//! [`Hider::render`](hider_scene::Hider::render)) or the lean front end's
//! [`LeanScene`] with the world-space scene it came from (through
//! [`Hider::render_scene`](hider_scene::Hider::render_scene)); both give
//! the same triangles in the same order and the same colours, bit for bit,
//! so the frame does not depend on which one was used.

use hider_geom::Viewport;
use hider_scene::prepare::lean::{LeanScene, LeanTri};
use hider_scene::{Scene, ScreenScene, ShadeMode};

use crate::palette;

/// Where the colours come from.
#[derive(Clone, Copy, Debug)]
enum Kind<'a> {
    /// `prepare`'s output (textures included).
    Screen(&'a ScreenScene),
    /// The lean front end's output, and the scene it was prepared from.
    Lean(&'a LeanScene, &'a Scene),
}

/// The triangles of a frame and their colours.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Source<'a> {
    /// The image size.
    pub(crate) viewport: Viewport,
    /// The triangles, in `prepare`'s order.
    pub(crate) tris: &'a [LeanTri],
    kind: Kind<'a>,
}

impl<'a> Source<'a> {
    /// `scene`'s triangles as `tris` (converted by the caller).
    pub(crate) fn screen(scene: &'a ScreenScene, tris: &'a [LeanTri]) -> Self {
        Self {
            viewport: scene.viewport,
            tris,
            kind: Kind::Screen(scene),
        }
    }

    /// The lean front end's `lean`, prepared from `scene`.
    pub(crate) fn lean(lean: &'a LeanScene, scene: &'a Scene) -> Self {
        Self {
            viewport: lean.viewport,
            tris: lean.tris(),
            kind: Kind::Lean(lean, scene),
        }
    }

    /// The number of primitives (ids are below it).
    pub(crate) fn prims(&self) -> usize {
        match self.kind {
            Kind::Screen(s) => s.prims.len(),
            Kind::Lean(_, scene) => scene.triangle_count(),
        }
    }

    /// `[r, g, b, opacity]` (linear, opacity clamped to [0, 1]) of `prim`.
    pub(crate) fn prim_rgba(&self, prim: u32, mode: ShadeMode) -> [f32; 4] {
        match self.kind {
            Kind::Screen(s) => palette::prim_rgba(s, prim, mode),
            Kind::Lean(lean, scene) => {
                let (rgb, alpha) = lean.prim_color(scene, prim, mode);
                [rgb[0], rgb[1], rgb[2], alpha.clamp(0.0, 1.0)]
            }
        }
    }

    /// The opacity of every primitive, clamped to [0, 1] (the last
    /// channel of [`Self::prim_rgba`]), as runs: `out[k] = (end, alpha)`
    /// gives `alpha` to the primitives from the previous run's end up to
    /// `end` (exclusive); neighbouring runs differ. From the materials
    /// alone, no shading: a mesh's primitives share its material, so the
    /// lean front end's scene needs one look-up per mesh, not one per
    /// triangle.
    pub(crate) fn opacity_runs(&self, out: &mut Vec<(u32, f32)>) {
        out.clear();
        let mut push = |end: u32, alpha: f32| match out.last_mut() {
            Some(last) if last.1 == alpha => last.0 = end,
            _ => out.push((end, alpha)),
        };
        match self.kind {
            Kind::Screen(s) => {
                for prim in 0..s.prims.len() as u32 {
                    push(prim + 1, s.material(prim).opacity.clamp(0.0, 1.0));
                }
            }
            Kind::Lean(lean, scene) => {
                let mut first = 0u32;
                for mesh in &scene.meshes {
                    let end = first + mesh.indices.len() as u32;
                    if end > first {
                        // The identifier colour is a hash of the id: no
                        // vertex or normal is read.
                        let alpha = lean.prim_color(scene, first, ShadeMode::Ids).1;
                        push(end, alpha.clamp(0.0, 1.0));
                    }
                    first = end;
                }
            }
        }
    }

    /// The material index of `prim` (merging requires equal ones).
    pub(crate) fn material(&self, prim: u32) -> u32 {
        match self.kind {
            Kind::Screen(s) => s.prims[prim as usize].material,
            Kind::Lean(lean, scene) => lean.material_index(scene, prim),
        }
    }

    /// [`palette::at_pixel`]: `rgba` textured at the centre of pixel `ij`
    /// when the scene's textures are loaded (the lean front end is used
    /// only when they are not).
    #[inline]
    pub(crate) fn at_pixel(&self, prim: u32, rgba: [f32; 4], ij: (u32, u32)) -> [f32; 4] {
        match self.kind {
            Kind::Screen(s) => palette::at_pixel(s, prim, rgba, ij),
            Kind::Lean(..) => rgba,
        }
    }

    /// The colour and opacity of `prim` from `colors`, computed on first
    /// use (see [`palette::shade_of`]).
    #[inline]
    pub(crate) fn shade_of(&self, colors: &mut [[f32; 4]], mode: ShadeMode, prim: u32) -> [f32; 4] {
        let c = &mut colors[prim as usize];
        if c[3].is_nan() {
            *c = self.prim_rgba(prim, mode);
        }
        *c
    }
}
