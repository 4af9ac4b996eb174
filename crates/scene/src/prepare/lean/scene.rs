//! [`LeanScene`]: `prepare`'s triangles without `prepare`'s per-primitive
//! data, and the colour of a primitive computed when a hider asks for it.

use glam::DVec3;
use hider_geom::{EdgeFunction, FixedPt, PlaneEq, Viewport};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::error::Result;
use crate::model::{Light, Material, Scene};
use crate::prepare::{FrontEnd, PrepareOptions, PrepareStats, PrimInfo};
use crate::shade::{ShadeMode, SurfaceSetup, TextureSampler, flat_color, id_color};
use crate::view::View;

use super::attributes::PointAttributes;
use super::triangles::triangles;
use super::{CachedVertex, lean_passes};

/// A screen triangle as a hider that samples inside pixels needs it:
/// [`ScreenTri`](crate::ScreenTri) without the per-vertex clip `w` and the
/// `1/w` plane (which only texturing reads).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LeanTri {
    /// Snapped vertices, ordered so that the edge functions are positive
    /// inside (as [`ScreenTri::v`](crate::ScreenTri::v)).
    pub v: [FixedPt; 3],
    /// Window depth `z/w` in [0, 1] at each vertex (as
    /// [`ScreenTri::z`](crate::ScreenTri::z)).
    pub z: [f64; 3],
    /// Window depth as an affine function of window position.
    pub depth: PlaneEq,
    /// Primitive id: index of the source triangle in the scene.
    pub prim: u32,
    /// Whether the source triangle faces the camera (as
    /// [`ScreenTri::front_facing`](crate::ScreenTri::front_facing)).
    pub front_facing: bool,
}

impl LeanTri {
    /// The edge functions of this triangle (GL's fill rule applied,
    /// `hider_geom::edge`).
    #[inline]
    pub fn edges(&self) -> [EdgeFunction; 3] {
        hider_geom::edge::triangle_edges(&self.v)
    }
}

/// What [`prepare_lean_into`] makes: `prepare`'s triangles, in the same
/// order, as [`LeanTri`]s, and what it takes to colour a primitive. Keeps
/// its memory between frames.
#[derive(Clone, Debug, Default)]
pub struct LeanScene {
    /// The image size.
    pub viewport: Viewport,
    /// What the front end did: the same counts as `prepare`'s.
    pub stats: PrepareStats,
    tris: Vec<LeanTri>,
    /// The output of each worker but the first (which writes into `tris`
    /// itself: its slot holds the buffer `tris` lends it), before it is
    /// appended to `tris`.
    runs: Vec<Vec<LeanTri>>,
    /// Per vertex of every mesh (meshes one after the other).
    vertices: Vec<CachedVertex>,
    /// The first primitive id of each mesh.
    mesh_starts: Vec<usize>,
    /// The lights in camera space, as `prepare` transforms them.
    lights: Vec<Light>,
    /// The frame's transforms (`None` before the first frame).
    front: Option<FrontEnd>,
    /// The material of meshes without one (made once, not per colour).
    default_material: Material,
    /// Whether the caller shades per point ([`Self::set_point_shading`]).
    point_shading: bool,
    /// What shading per point reads of the vertices, when it is on and
    /// the scene needs it.
    attributes: PointAttributes,
}

impl LeanScene {
    /// An empty scene (the buffers grow on first use).
    pub fn new() -> Self {
        Self::default()
    }

    /// The triangles, exactly `prepare`'s (the same pieces of clipped
    /// triangles included), in the same order.
    pub fn tris(&self) -> &[LeanTri] {
        &self.tris
    }

    /// Bytes of memory held.
    pub fn bytes(&self) -> usize {
        (self.tris.capacity() + self.runs.iter().map(Vec::capacity).sum::<usize>())
            * std::mem::size_of::<LeanTri>()
            + self.vertices.capacity() * std::mem::size_of::<CachedVertex>()
            + self.attributes.bytes()
    }

    /// Asks the next frames to keep what shading per point reads (the
    /// camera-space position and normal of each vertex) when the scene's
    /// colours vary per point ([`Scene::varies_per_point`]: textures,
    /// vertex normals or colours, highlights), for
    /// [`Self::surface_rgb`]. Off by default: a hider that shades flat,
    /// or a scene that does not vary, pays nothing.
    pub fn set_point_shading(&mut self, on: bool) {
        self.point_shading = on;
    }

    /// Whether the last frame kept what shading per point reads (asked
    /// for, and the scene varies per point).
    pub fn shades_per_point(&self) -> bool {
        self.attributes.filled()
    }

    /// The mesh of primitive `prim` and the triangle's index in it.
    #[inline]
    fn locate(&self, prim: u32) -> (usize, usize) {
        let k = prim as usize;
        let m = self.mesh_starts.partition_point(|&s| s <= k) - 1;
        (m, k - self.mesh_starts[m])
    }

    /// The per-primitive data `prepare` keeps for `prim` of `scene` (the
    /// scene this was prepared from), bit for bit: from the vertices'
    /// attributes when [`Self::shades_per_point`], transformed per corner
    /// otherwise.
    ///
    /// # Panics
    ///
    /// If `prim` is not a primitive id of the scene prepared last.
    pub fn prim_info(&self, scene: &Scene, prim: u32) -> PrimInfo {
        let (m, t) = self.locate(prim);
        let front = self.front.as_ref().expect("a prepared scene");
        if self.attributes.filled() {
            self.attributes.prim_info(scene, front, m, t)
        } else {
            front.prim_info(scene, m, t)
        }
    }

    /// The colour at window point `(x, y)` under `sampler` (built for the
    /// frame's view, [`TextureSampler::for_view`]) of the primitive of
    /// `scene` whose setup is `setup` (a [`SurfaceSetup`] of
    /// [`Self::prim_info`], which a caller shading several pixels of one
    /// primitive builds once), or `base`, its flat colour, when its colour
    /// does not vary: bit for bit
    /// [`ScreenScene::surface_rgb`](crate::ScreenScene::surface_rgb) on
    /// `prepare`'s output.
    #[inline]
    pub fn surface_rgb(
        &self,
        scene: &Scene,
        sampler: &TextureSampler,
        setup: &mut SurfaceSetup,
        base: [f32; 3],
        (x, y): (f64, f64),
    ) -> [f32; 3] {
        let material = scene
            .materials
            .get(setup.info().material as usize)
            .unwrap_or(&self.default_material);
        setup
            .color_at(sampler, material, &self.lights, x, y)
            .unwrap_or(base)
    }

    /// The linear RGB colour of primitive `prim` of `scene` (the scene
    /// this was prepared from) under `mode`, and its opacity: bit for bit
    /// [`prim_color`](crate::shade::prim_color) on `prepare`'s output,
    /// from the camera-space corners `prepare` would have stored.
    ///
    /// # Panics
    ///
    /// If `prim` is not a primitive id of the scene prepared last.
    pub fn prim_color(&self, scene: &Scene, prim: u32, mode: ShadeMode) -> ([f32; 3], f32) {
        let (m, t) = self.locate(prim);
        let mesh = &scene.meshes[m];
        let material = scene
            .triangle_material(m, t)
            .unwrap_or(&self.default_material);
        match mode {
            ShadeMode::Ids => (id_color(prim), material.opacity),
            ShadeMode::Lambert => {
                let front = self.front.as_ref().expect("a prepared scene");
                let idx = mesh.indices[t];
                let camera: [DVec3; 3] = idx.map(|i| front.to_camera(mesh.positions[i as usize]));
                (
                    flat_color(material, &camera, &self.lights, front.perspective),
                    material.opacity,
                )
            }
        }
    }

    /// The material index `prepare` gives primitive `prim` (an index into
    /// the scene's materials, or their count for the default material).
    pub fn material_index(&self, scene: &Scene, prim: u32) -> u32 {
        let (m, t) = self.locate(prim);
        scene.meshes[m]
            .triangle_material(t)
            .map_or(scene.materials.len() as u32, |i| i as u32)
    }
}

/// Runs the lean front end into `out`, reusing its memory: the vertex pass
/// and the triangle pass, in parallel on the current rayon pool when
/// [`PrepareOptions::parallel`] is set and the scene is large.
///
/// # Errors
///
/// As [`prepare`](crate::prepare()): an absurd image size, an invalid
/// camera or an invalid scene.
pub fn prepare_lean_into(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    out: &mut LeanScene,
) -> Result<()> {
    out.tris.clear();
    // The first run writes into the output's own buffer, which holds the
    // whole frame's triangles (the runs' buffers are swapped back after
    // the passes); the other runs' triangles are then appended. Copying
    // every run into the output, serially, made the parallel front end
    // slower than the serial one on the 500 sphere at 2 threads (7.6 to
    // 8.1 ms against 6.0 to 6.2; 6.4 to 6.7 with only the second run
    // copied), and alternating the output with the first run's buffer
    // kept two buffers of the frame's size.
    if let Some(first) = out.runs.first_mut() {
        std::mem::swap(&mut out.tris, first);
    }
    let (front, mut stats) = lean_passes(
        scene,
        view,
        options,
        &mut out.vertices,
        &mut out.runs,
        |front, cache, range, run| triangles(scene, front, cache, range, run),
    )?;
    std::mem::swap(&mut out.tris, &mut out.runs[0]);
    // Appended in parallel (the runs were made in parallel): a serial copy
    // of the second half of the 500 sphere took 1.3 ms at 2 threads, this
    // 0.7.
    for r in &out.runs[1..] {
        #[cfg(feature = "parallel")]
        out.tris.par_extend(r.par_iter().copied());
        #[cfg(not(feature = "parallel"))]
        out.tris.extend_from_slice(r);
    }
    stats.output = out.tris.len() as u64;
    out.finish(scene, front, options, stats);
    Ok(())
}

/// Where the triangle pass of [`prepare_lean_sinks`] puts a run's
/// triangles, in order: a hider's own per-triangle records, made as each
/// triangle is set up (no [`LeanTri`] is stored and read back).
pub trait LeanSink: Default + Send {
    /// Forgets the triangles of the last frame (keeping the memory).
    fn clear(&mut self);
    /// Takes the run's next triangle.
    fn push(&mut self, tri: LeanTri);
    /// How many triangles the run has taken since [`Self::clear`].
    fn len(&self) -> usize;
    /// Whether the run has taken no triangle since [`Self::clear`].
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl LeanSink for Vec<LeanTri> {
    fn clear(&mut self) {
        Vec::clear(self);
    }

    fn push(&mut self, tri: LeanTri) {
        Vec::push(self, tri);
    }

    fn len(&self) -> usize {
        Vec::len(self)
    }
}

/// [`prepare_lean_into`] with the triangles handed to `runs` instead of
/// stored: one sink per contiguous run of primitive ids (as many as the
/// pass has runs; run `k`'s triangles all come before run `k + 1`'s, each
/// run's in `prepare`'s order), each first given the frame's transforms
/// through `begin`. `out` keeps what colouring a primitive needs and the
/// counters; its [`LeanScene::tris`] is left empty.
///
/// # Errors
///
/// As [`prepare_lean_into`].
pub fn prepare_lean_sinks<S: LeanSink>(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    out: &mut LeanScene,
    runs: &mut Vec<S>,
    begin: impl Fn(&FrontEnd, &mut S) + Sync,
) -> Result<()> {
    out.tris.clear();
    let (front, mut stats) = lean_passes(
        scene,
        view,
        options,
        &mut out.vertices,
        runs,
        |front, cache, range, run| {
            begin(front, run);
            triangles(scene, front, cache, range, run)
        },
    )?;
    stats.output = runs.iter().map(|r| r.len() as u64).sum();
    out.finish(scene, front, options, stats);
    Ok(())
}

impl LeanScene {
    /// What both front ends keep after the passes: the counters, the
    /// image size, and what colouring a primitive needs.
    fn finish(
        &mut self,
        scene: &Scene,
        front: FrontEnd,
        options: &PrepareOptions,
        stats: PrepareStats,
    ) {
        self.stats = stats;
        self.viewport = front.viewport;
        self.mesh_starts.clear();
        let mut first = 0;
        for mesh in &scene.meshes {
            self.mesh_starts.push(first);
            first += mesh.indices.len();
        }
        // `prepare`'s transform of the lights.
        self.lights.clear();
        self.lights
            .extend(scene.lights.iter().map(|l| front.light_to_camera(l)));
        self.attributes
            .fill(scene, &front, self.point_shading, options.parallel);
        self.front = Some(front);
    }
}
