//! The shared front end: world-space [`Scene`] to screen-space
//! [`ScreenScene`].
//!
//! `prepare` transforms, clips (near, far, guard band), divides, maps to the
//! viewport, snaps to 1/256 pixel and sets up each triangle once. Every hider
//! consumes the result and none re-projects, which is what makes
//! cross-validation between hiders exact rather than approximate.

use glam::{DMat4, DVec3, DVec4, Vec2, Vec3, Vec4};
use hider_geom::clip::{ClipOutcome, ClipVertex, ClipVolume, clip_triangle};
use hider_geom::fixed::{FixedPt, GUARD_BAND_PIXELS};
use hider_geom::{Camera, PlaneEq, Viewport, orient2d};
use rayon::prelude::*;

use crate::error::Result;
use crate::model::{Light, Material, Scene};
use crate::view::{View, check_image_size};

/// Arithmetic used for the model-view-projection transform.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TransformPrecision {
    /// Transform, divide and map in `f64` (the accurate default; keeps huge
    /// coordinates with small triangles apart).
    #[default]
    F64,
    /// Round the view-projection matrix and the vertices to `f32` and
    /// transform, divide and map in `f32`, as a GL implementation does.
    /// Reproduces the GL reference renders' snapped vertices.
    F32,
}

/// Options of [`prepare`]. `Default` is the accurate choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrepareOptions {
    /// Transform arithmetic.
    pub precision: TransformPrecision,
    /// Guard band beyond each image side, in pixels; triangles reaching
    /// further are clipped. At most [`GUARD_BAND_PIXELS`].
    pub guard_band_pixels: u32,
    /// Drop triangles facing away from the camera (GL's `GL_CULL_FACE` with
    /// counter-clockwise front faces). Off by default: the GL reference
    /// renders cull nothing.
    pub cull_back_faces: bool,
    /// Process large scenes (over 32k triangles) in chunks on the current
    /// rayon thread pool. The result is identical; whether it is faster
    /// depends on free cores, so it is off by default and the CLI turns it
    /// on with `--threads` above 1.
    pub parallel: bool,
}

impl Default for PrepareOptions {
    fn default() -> Self {
        Self {
            precision: TransformPrecision::F64,
            guard_band_pixels: GUARD_BAND_PIXELS,
            cull_back_faces: false,
            parallel: false,
        }
    }
}

impl PrepareOptions {
    /// The options that reproduce a GL pipeline (f32 transform).
    pub fn gl_compatible() -> Self {
        Self::default().with_precision(TransformPrecision::F32)
    }

    /// Sets [`Self::precision`].
    pub fn with_precision(mut self, precision: TransformPrecision) -> Self {
        self.precision = precision;
        self
    }

    /// Sets [`Self::cull_back_faces`].
    pub fn with_cull_back_faces(mut self, cull: bool) -> Self {
        self.cull_back_faces = cull;
        self
    }

    /// Sets [`Self::parallel`].
    pub fn with_parallel(mut self, parallel: bool) -> Self {
        self.parallel = parallel;
        self
    }

    /// Sets [`Self::guard_band_pixels`] (clamped to [`GUARD_BAND_PIXELS`]).
    pub fn with_guard_band_pixels(mut self, pixels: u32) -> Self {
        self.guard_band_pixels = pixels.min(GUARD_BAND_PIXELS);
        self
    }
}

/// A triangle ready for rasterisation: snapped, positively oriented, with
/// its depth and 1/w planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenTri {
    /// Vertices in 1/256 pixel, ordered so that
    /// `orient2d(v[0], v[1], v[2]) > 0` (edge functions positive inside).
    pub v: [FixedPt; 3],
    /// Window depth `z/w` in [0, 1] at each vertex.
    pub z: [f64; 3],
    /// Clip-space `w` at each vertex (camera-space distance along the view
    /// axis for a perspective camera, 1 for an orthographic one).
    pub w: [f64; 3],
    /// Window depth as an affine function of window position.
    pub depth: PlaneEq,
    /// `1/w` as an affine function of window position, for
    /// perspective-correct attributes.
    pub inv_w: PlaneEq,
    /// Primitive id: index of the source triangle in the scene.
    pub prim: u32,
    /// Whether the source triangle faces the camera (counter-clockwise on
    /// screen, GL's default front face).
    pub front_facing: bool,
}

impl ScreenTri {
    /// The edge functions of this triangle (top-left rule applied).
    #[inline]
    pub fn edges(&self) -> [hider_geom::EdgeFunction; 3] {
        hider_geom::edge::triangle_edges(&self.v)
    }

    /// The inclusive pixel rectangle `(x0, y0, x1, y1)` whose centres may be
    /// covered, clamped to the viewport, or `None` if it is empty.
    pub fn pixel_bounds(&self, viewport: Viewport) -> Option<(u32, u32, u32, u32)> {
        viewport.pixel_bounds(&self.v)
    }
}

/// Per-primitive data kept for shading and for the exact oracle, indexed by
/// primitive id.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimInfo {
    /// Corners in camera space (`f64`, before any clipping).
    pub camera: [DVec3; 3],
    /// Index into [`ScreenScene::materials`].
    pub material: u32,
    /// Per-corner normals in camera space, when the mesh has normals.
    pub normals: Option<[Vec3; 3]>,
    /// Per-corner texture coordinates, when the mesh has them.
    pub uvs: Option<[Vec2; 3]>,
}

/// What the front end did, for statistics and warnings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PrepareStats {
    /// Triangles in the scene.
    pub input: u64,
    /// Triangles dropped entirely (behind the eye, outside the view, beyond
    /// near or far).
    pub culled: u64,
    /// Triangles cut by the near, far or guard-band planes.
    pub clipped: u64,
    /// Triangles (or clipped pieces) dropped because their snapped area is
    /// zero: they cover no sample.
    pub degenerate: u64,
    /// Back-facing triangles dropped by [`PrepareOptions::cull_back_faces`].
    pub back_faces: u64,
    /// Screen triangles produced.
    pub output: u64,
    /// Triangles dropped by a depth-only front end of a hider's own (the
    /// tiled z-buffer's) because they certainly cover no pixel centre;
    /// always 0 from [`prepare`], which keeps them.
    pub empty: u64,
    /// Triangles a depth-only front end of a hider's own handed over as
    /// the pixels they cover rather than as triangles, because their box
    /// holds at most four pixel centres; not counted in [`Self::output`].
    /// Always 0 from [`prepare`].
    pub fragmented: u64,
}

impl PrepareStats {
    /// Adds the per-triangle counters of another run of triangles (all but
    /// [`Self::input`] and [`Self::output`], which describe a whole frame).
    pub fn add(&mut self, other: &Self) {
        self.empty += other.empty;
        self.fragmented += other.fragmented;
        self.culled += other.culled;
        self.clipped += other.clipped;
        self.degenerate += other.degenerate;
        self.back_faces += other.back_faces;
    }
}

/// A scene in screen space: what every hider consumes.
#[derive(Clone, Debug, PartialEq)]
pub struct ScreenScene {
    /// The image size.
    pub viewport: Viewport,
    /// The camera used.
    pub camera: Camera,
    /// World to camera space.
    pub view_matrix: DMat4,
    /// Camera space to clip space.
    pub projection_matrix: DMat4,
    /// The triangles, in primitive-id order (pieces of one clipped triangle
    /// are adjacent).
    pub tris: Vec<ScreenTri>,
    /// Per-primitive data, indexed by primitive id.
    pub prims: Vec<PrimInfo>,
    /// Materials; the scene's, plus the default material at the end.
    pub materials: Vec<Material>,
    /// Lights in camera space.
    pub lights: Vec<Light>,
    /// What the front end did.
    pub stats: PrepareStats,
}

impl ScreenScene {
    /// The material of a primitive.
    pub fn material(&self, prim: u32) -> &Material {
        &self.materials[self.prims[prim as usize].material as usize]
    }

    /// Whether the camera is a perspective one.
    pub fn is_perspective(&self) -> bool {
        matches!(
            self.camera.projection,
            hider_geom::Projection::Perspective { .. }
        )
    }

    /// The camera-space ray through window position `(x, y)` (pixels):
    /// `(origin, direction)`, direction not normalised. For a perspective
    /// camera the origin is the eye; for an orthographic one it lies on the
    /// near plane.
    pub fn camera_ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let vp = self.viewport;
        let ndc_x = 2.0 * x / f64::from(vp.width) - 1.0;
        let ndc_y = 1.0 - 2.0 * y / f64::from(vp.height);
        let inv = self.projection_matrix.inverse();
        let near = inv * DVec4::new(ndc_x, ndc_y, -1.0, 1.0);
        let far = inv * DVec4::new(ndc_x, ndc_y, 1.0, 1.0);
        let near = near.truncate() / near.w;
        let far = far.truncate() / far.w;
        if self.is_perspective() {
            (DVec3::ZERO, near)
        } else {
            (near, far - near)
        }
    }
}

/// Runs the front end. See the module documentation.
pub fn prepare(scene: &Scene, view: &View, options: &PrepareOptions) -> Result<ScreenScene> {
    let mut out = ScreenScene {
        viewport: view.viewport,
        camera: view.camera,
        view_matrix: DMat4::IDENTITY,
        projection_matrix: DMat4::IDENTITY,
        tris: Vec::new(),
        prims: Vec::new(),
        materials: Vec::new(),
        lights: Vec::new(),
        stats: PrepareStats::default(),
    };
    prepare_into(scene, view, options, &mut out)?;
    Ok(out)
}

/// [`prepare`] into an existing [`ScreenScene`], reusing its memory: for
/// repeated frames this avoids allocating (and the kernel zeroing) hundreds
/// of megabytes for large scenes. Every field of `out` is overwritten.
pub fn prepare_into(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    out: &mut ScreenScene,
) -> Result<()> {
    let vp = view.viewport;
    let front = FrontEnd::new(scene, view, options)?;
    let (view_matrix, projection_matrix) = (front.view_matrix, front.projection_matrix);

    let mut materials = std::mem::take(&mut out.materials);
    materials.clear();
    materials.extend_from_slice(&scene.materials);
    materials.push(Material::default());

    let mut prims = std::mem::take(&mut out.prims);
    prims.clear();
    prims.reserve(scene.triangle_count());
    let mut tris = std::mem::take(&mut out.tris);
    tris.clear();
    tris.reserve(scene.triangle_count());
    let mut stats = PrepareStats {
        input: scene.triangle_count() as u64,
        ..PrepareStats::default()
    };
    // Below this many triangles the fork-join overhead is not worth it.
    const PARALLEL_CHUNK: usize = 16 * 1024;
    if options.parallel
        && rayon::current_num_threads() > 1
        && scene.triangle_count() > 2 * PARALLEL_CHUNK
    {
        let mut segments = Vec::new();
        let mut first_prim = 0u32;
        for (m, mesh) in scene.meshes.iter().enumerate() {
            for start in (0..mesh.indices.len()).step_by(PARALLEL_CHUNK) {
                let end = (start + PARALLEL_CHUNK).min(mesh.indices.len());
                segments.push((m, start..end, first_prim));
                first_prim += (end - start) as u32;
            }
        }
        let parts: Vec<Part> = segments
            .into_par_iter()
            .map(|(m, range, first)| {
                let mut part = Part::default();
                let mut scratch = ClipScratch::default();
                for (k, t) in range.enumerate() {
                    front.triangle(scene, (m, t, first + k as u32), &mut part, &mut scratch);
                }
                part
            })
            .collect();
        for part in parts {
            prims.extend_from_slice(&part.prims);
            tris.extend_from_slice(&part.tris);
            stats.add(&part.stats);
        }
    } else {
        let mut scratch = ClipScratch::default();
        let mut part = Part { prims, tris, stats };
        for (prim, m, t) in scene.triangles() {
            front.triangle(scene, (m, t, prim), &mut part, &mut scratch);
        }
        (prims, tris, stats) = (part.prims, part.tris, part.stats);
    }
    stats.output = tris.len() as u64;
    let lights = scene
        .lights
        .iter()
        .map(|l| match *l {
            Light::Directional { direction, color } => Light::Directional {
                direction: view_matrix.transform_vector3(direction),
                color,
            },
            Light::Point { position, color } => Light::Point {
                position: view_matrix.transform_point3(position),
                color,
            },
        })
        .collect();
    *out = ScreenScene {
        viewport: vp,
        camera: view.camera,
        view_matrix,
        projection_matrix,
        tris,
        prims,
        materials,
        lights,
        stats,
    };
    Ok(())
}

/// The output of the front end for a run of triangles
/// ([`FrontEnd::triangle`] appends to it).
#[derive(Clone, Debug, Default)]
pub struct Part {
    /// Per-primitive data, one per triangle visited.
    pub prims: Vec<PrimInfo>,
    /// The screen triangles (clipped pieces adjacent).
    pub tris: Vec<ScreenTri>,
    /// What was dropped or clipped.
    pub stats: PrepareStats,
}

/// Reusable buffers of the clipper, for [`FrontEnd::triangle`].
#[derive(Clone, Debug, Default)]
pub struct ClipScratch {
    polygon: Vec<ClipVertex>,
    scratch: Vec<ClipVertex>,
    window: Vec<WindowVertex>,
}

/// Everything the per-triangle work needs, computed once per frame: the
/// building blocks of [`prepare`], public so that a hider with a front end
/// of its own (the tiled z-buffer's depth-only one) computes every number
/// exactly as `prepare` does.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct FrontEnd {
    /// World to camera space.
    pub view_matrix: DMat4,
    /// Camera space to clip space.
    pub projection_matrix: DMat4,
    /// World to camera space for normals.
    pub normal_matrix: DMat4,
    /// World to clip space, `projection_matrix * view_matrix`.
    pub mvp: DMat4,
    /// [`Self::mvp`] rounded to `f32`, for [`TransformPrecision::F32`].
    pub mvp32: glam::Mat4,
    /// The clip volume: near, far and the guard band.
    pub volume: ClipVolume,
    /// The image size.
    pub viewport: Viewport,
    /// The options of the frame.
    pub options: PrepareOptions,
    /// Index of the default material (after the scene's).
    pub default_material: u32,
}

impl FrontEnd {
    /// Checks the image size, the camera and the scene, and computes the
    /// per-frame transforms.
    pub(crate) fn new(scene: &Scene, view: &View, options: &PrepareOptions) -> Result<Self> {
        Self::checked(scene, view, options, true)
    }

    /// As `prepare` checks its input, with `geometry` false leaving the
    /// check of every position and index ([`Scene::validate`]'s costly
    /// part) to a caller that reads them all anyway.
    ///
    /// # Errors
    ///
    /// An absurd image size, an invalid camera or an invalid scene.
    pub fn checked(
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        geometry: bool,
    ) -> Result<Self> {
        let vp = view.viewport;
        check_image_size(vp.width, vp.height)?;
        view.camera
            .validate()
            .map_err(|e| crate::error::Error::Camera(e.0))?;
        if geometry {
            scene.validate()?;
        } else {
            scene.validate_structure()?;
        }
        let view_matrix = view.camera.view_matrix();
        let projection_matrix = view.camera.projection_matrix(vp.aspect());
        let mvp = projection_matrix * view_matrix;
        Ok(Self {
            view_matrix,
            projection_matrix,
            normal_matrix: view_matrix.inverse().transpose(),
            mvp,
            mvp32: mvp.as_mat4(),
            volume: ClipVolume::for_viewport(
                vp.width,
                vp.height,
                options.guard_band_pixels.min(GUARD_BAND_PIXELS),
            ),
            viewport: vp,
            options: *options,
            default_material: scene.materials.len() as u32,
        })
    }

    /// The clip-space position of a world-space point in the configured
    /// precision.
    #[inline]
    pub(crate) fn clip(&self, p: DVec3) -> DVec4 {
        match self.options.precision {
            TransformPrecision::F64 => self.mvp * p.extend(1.0),
            TransformPrecision::F32 => (self.mvp32 * Vec4::from((p.as_vec3(), 1.0))).as_dvec4(),
        }
    }

    /// Transforms, clips, projects, snaps and sets up triangle `t` of mesh
    /// `m` (primitive `prim`), appending its info and screen pieces.
    pub fn triangle(
        &self,
        scene: &Scene,
        (m, t, prim): (usize, usize, u32),
        out: &mut Part,
        buf: &mut ClipScratch,
    ) {
        let Part { prims, tris, stats } = out;
        let mesh = &scene.meshes[m];
        let idx = mesh.indices[t];
        let world = idx.map(|i| mesh.positions[i as usize]);
        prims.push(PrimInfo {
            camera: world.map(|p| self.view_matrix.transform_point3(p)),
            material: mesh.material.map_or(self.default_material, |k| k as u32),
            normals: (!mesh.normals.is_empty()).then(|| {
                idx.map(|i| {
                    self.normal_matrix
                        .transform_vector3(mesh.normals[i as usize].as_dvec3())
                        .as_vec3()
                })
            }),
            uvs: (!mesh.uvs.is_empty()).then(|| idx.map(|i| mesh.uvs[i as usize])),
        });
        let precision = self.options.precision;
        let clip: [DVec4; 3] = world.map(|p| self.clip(p));
        match clip_triangle(clip, &self.volume, &mut buf.polygon, &mut buf.scratch) {
            ClipOutcome::Culled => {
                stats.culled += 1;
                return;
            }
            ClipOutcome::Clipped => stats.clipped += 1,
            ClipOutcome::Inside => {}
        }
        buf.window.clear();
        for v in &buf.polygon {
            match to_window(v, self.viewport, precision) {
                Some(w) => buf.window.push(w),
                None => {
                    // Only reachable through numerical trouble at the guard
                    // band.
                    stats.culled += 1;
                    return;
                }
            }
        }
        let window = &buf.window;
        for k in 1..window.len() - 1 {
            match setup([window[0], window[k], window[k + 1]], prim) {
                Some(tri) if self.options.cull_back_faces && !tri.front_facing => {
                    stats.back_faces += 1;
                }
                Some(tri) => tris.push(tri),
                None => stats.degenerate += 1,
            }
        }
    }
}

/// A vertex in window space: snapped position, window depth, clip w.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WindowVertex {
    /// Snapped window position.
    pub p: FixedPt,
    /// Window depth in [0, 1].
    pub z: f64,
    /// Clip-space `w`.
    pub w: f64,
}

#[inline]
pub(crate) fn to_window(
    v: &ClipVertex,
    vp: Viewport,
    precision: TransformPrecision,
) -> Option<WindowVertex> {
    let (x, y, z) = match precision {
        TransformPrecision::F64 => {
            let ndc = v.pos.truncate() / v.pos.w;
            let win = vp.ndc_to_window(ndc);
            (win.x, win.y, win.z)
        }
        TransformPrecision::F32 => {
            let c = v.pos.as_vec4();
            let ndc = [c.x / c.w, c.y / c.w, c.z / c.w];
            let win = vp.ndc_to_window_f32(ndc);
            (f64::from(win[0]), f64::from(win[1]), f64::from(win[2]))
        }
    };
    Some(WindowVertex {
        p: FixedPt::snap(x, y)?,
        // Clipping puts every vertex inside -w <= z <= w, so window depth is
        // in [0, 1] exactly; rounding of the divide (in f32, or with w near
        // the smallest normal numbers) can leave it far outside, which the
        // fuzzer found (-9007 at w = 1e-20). Clamp to what is exact.
        z: z.clamp(0.0, 1.0),
        w: v.pos.w,
    })
}

/// The part of set-up every hider needs: the vertices ordered positively,
/// the facing and the depth plane, given `area = orient2d(c)` (the caller
/// has it: it decides degenerate triangles and facing before this). `None`
/// when the snapped triangle has no area (it covers no sample).
#[inline]
pub fn setup_depth(
    mut c: [WindowVertex; 3],
    area: i64,
) -> Option<([WindowVertex; 3], bool, PlaneEq)> {
    if area == 0 {
        return None;
    }
    // Positive orient2d is clockwise on the y-down screen, i.e. clockwise as
    // seen by the viewer: a back face under GL's counter-clockwise rule.
    let front_facing = area < 0;
    if area < 0 {
        c.swap(1, 2);
    }
    let depth = PlaneEq::from_points(&c.map(|k| k.p), c.map(|k| k.z))?;
    Some((c, front_facing, depth))
}

fn setup(c: [WindowVertex; 3], prim: u32) -> Option<ScreenTri> {
    let area = orient2d(c[0].p, c[1].p, c[2].p);
    let (c, front_facing, depth) = setup_depth(c, area)?;
    let v = c.map(|k| k.p);
    let z = c.map(|k| k.z);
    let w = c.map(|k| k.w);
    let inv_w = PlaneEq::from_points(&v, w.map(|w| 1.0 / w))?;
    Some(ScreenTri {
        v,
        z,
        w,
        depth,
        inv_w,
        prim,
        front_facing,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mesh;
    use hider_geom::Projection;
    use hider_geom::fixed::pixel_center;

    fn camera() -> Camera {
        Camera {
            eye: DVec3::new(0.0, 0.0, 5.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            projection: Projection::Perspective {
                fovy_degrees: 60.0,
                near: 1.0,
                far: 100.0,
            },
        }
    }

    fn one(positions: [DVec3; 3]) -> Scene {
        let mut s = Scene::default();
        s.push_mesh(
            Mesh {
                positions: positions.to_vec(),
                indices: vec![[0, 1, 2]],
                ..Mesh::default()
            },
            None,
        );
        s
    }

    fn run(s: &Scene) -> ScreenScene {
        let view = View::new(camera(), 64, 64).unwrap();
        prepare(s, &view, &PrepareOptions::default()).unwrap()
    }

    #[test]
    fn counter_clockwise_triangle_is_front_facing_and_reoriented() {
        let s = one([
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ]);
        let ss = run(&s);
        assert_eq!(ss.tris.len(), 1);
        let t = ss.tris[0];
        assert!(t.front_facing);
        assert!(orient2d(t.v[0], t.v[1], t.v[2]) > 0);
        // At distance 5 all three corners have w = 5 and the same depth.
        assert!(t.w.iter().all(|w| (w - 5.0).abs() < 1e-12));
        assert!((t.depth.dx).abs() < 1e-15 && t.depth.dy.abs() < 1e-15);
        let culled = prepare(
            &one([
                DVec3::new(-1.0, -1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(1.0, -1.0, 0.0),
            ]),
            &View::new(camera(), 64, 64).unwrap(),
            &PrepareOptions::default().with_cull_back_faces(true),
        )
        .unwrap();
        assert_eq!(culled.tris.len(), 0);
        assert_eq!(culled.stats.back_faces, 1);
    }

    #[test]
    fn triangle_crossing_near_plane_is_clipped_and_depth_stays_in_range() {
        // From z = 0 (5 in front of the eye) to z = 10 (5 behind it).
        let s = one([
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, -0.5, 10.0),
        ]);
        let ss = run(&s);
        assert_eq!(ss.stats.clipped, 1);
        assert!(!ss.tris.is_empty());
        for t in &ss.tris {
            assert!(
                t.z.iter().all(|z| (-1e-9..=1.0 + 1e-9).contains(z)),
                "{:?}",
                t.z
            );
            assert!(t.w.iter().all(|w| *w > 0.0));
        }
    }

    #[test]
    fn triangle_behind_the_eye_disappears() {
        let s = one([
            DVec3::new(-1.0, 0.0, 6.0),
            DVec3::new(1.0, 0.0, 6.0),
            DVec3::new(0.0, 1.0, 7.0),
        ]);
        let ss = run(&s);
        assert!(ss.tris.is_empty());
        assert_eq!(ss.stats.culled, 1);
        assert_eq!(ss.prims.len(), 1, "prim info is kept for every id");
    }

    #[test]
    fn camera_ray_hits_the_pixel_it_came_from() {
        let s = one([
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ]);
        let ss = run(&s);
        let (o, d) = ss.camera_ray(40.5, 20.5);
        let p = o + d * 3.0;
        let clip = ss.projection_matrix * p.extend(1.0);
        let win = ss.viewport.ndc_to_window(clip.truncate() / clip.w);
        assert!((win.x - 40.5).abs() < 1e-9 && (win.y - 20.5).abs() < 1e-9);
    }

    #[test]
    fn parallel_front_end_equals_sequential() {
        // Enough triangles (in two meshes) to take the parallel path.
        let mut scene = crate::procedural::random_soup(40_000, 3);
        let second = crate::procedural::uv_sphere(40);
        scene.push_mesh(second.meshes[0].clone(), Some(second.materials[0].clone()));
        let view = View::new(camera(), 96, 64).unwrap();
        let options = PrepareOptions::default().with_parallel(true);
        let run_with = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| prepare(&scene, &view, &options).unwrap())
        };
        let one = run_with(1);
        let two = run_with(2);
        assert!(one.tris.len() > 10_000);
        assert_eq!(one, two);
        // Reusing an output gives the same result too.
        let mut reused = run_with(2);
        prepare_into(
            &crate::procedural::cube(),
            &view,
            &PrepareOptions::default(),
            &mut reused,
        )
        .unwrap();
        prepare_into(&scene, &view, &options, &mut reused).unwrap();
        assert_eq!(one, reused);
    }

    #[test]
    fn pixel_bounds_cover_exactly_the_candidate_centres() {
        let s = one([
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ]);
        let ss = run(&s);
        let t = ss.tris[0];
        let (x0, y0, x1, y1) = t.pixel_bounds(ss.viewport).unwrap();
        let edges = t.edges();
        let mut inside = 0;
        for j in 0..64 {
            for i in 0..64 {
                let (px, py) = (
                    i64::from(pixel_center(i as i32)),
                    i64::from(pixel_center(j as i32)),
                );
                if edges.iter().all(|e| e.contains(px, py)) {
                    inside += 1;
                    assert!((x0..=x1).contains(&i) && (y0..=y1).contains(&j));
                }
            }
        }
        assert!(inside > 0);
    }
}
