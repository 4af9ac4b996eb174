//! The per-triangle path of the front end: transform, clip, divide, map to
//! the window, snap and set up; shared with the z-buffer's lean front end.

use glam::{DMat4, DVec3, DVec4, Vec3, Vec4};
use hider_geom::clip::{ClipOutcome, ClipVertex, ClipVolume, clip_triangle};
use hider_geom::fixed::{FixedPt, GUARD_BAND_PIXELS};
use hider_geom::{PlaneEq, Viewport, orient2d};

use crate::error::Result;
use crate::model::{Light, Scene};
use crate::view::{View, check_image_size};

use super::options::{PrepareOptions, TransformPrecision};
use super::screen::{PrepareStats, PrimInfo, ScreenTri};

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
/// building blocks of [`prepare`](crate::prepare()), public so that a hider with a front end
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
    /// [`Self::mvp`] rounded to `f32`, for [`TransformPrecision::F32`]: what
    /// a GL program hands to GL, applied to positions rounded to `f32`.
    pub mvp32: glam::Mat4,
    /// The camera's eye in world space: [`TransformPrecision::F64`]
    /// subtracts it from a position before anything else.
    pub eye: DVec3,
    /// Eye-relative world to clip space: `projection_matrix` times the
    /// view matrix's rotation (no translation), for
    /// [`TransformPrecision::F64`]. Subtracting the eye first keeps a scene
    /// far from the origin as exact as one at it: `p - eye` is exact for
    /// nearby points (Sterbenz's lemma), where the view matrix's
    /// translation would cancel two huge products.
    pub eye_to_clip: DMat4,
    /// Eye-relative world to camera space: the view matrix's rotation.
    pub eye_to_camera: DMat4,
    /// The clip volume: near, far and the guard band.
    pub volume: ClipVolume,
    /// The image size.
    pub viewport: Viewport,
    /// The options of the frame.
    pub options: PrepareOptions,
    /// Index of the default material (after the scene's).
    pub default_material: u32,
    /// Whether the camera is a perspective one (shading's view direction).
    pub perspective: bool,
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
        let mut eye_to_camera = view_matrix;
        eye_to_camera.w_axis = glam::DVec4::W;
        Ok(Self {
            view_matrix,
            projection_matrix,
            normal_matrix: eye_to_camera.inverse().transpose(),
            mvp,
            mvp32: mvp.as_mat4(),
            eye: view.camera.eye,
            eye_to_clip: projection_matrix * eye_to_camera,
            eye_to_camera,
            volume: ClipVolume::for_viewport(
                vp.width,
                vp.height,
                options.guard_band_pixels.min(GUARD_BAND_PIXELS),
            ),
            viewport: vp,
            options: *options,
            default_material: scene.materials.len() as u32,
            perspective: matches!(
                view.camera.projection,
                hider_geom::Projection::Perspective { .. }
            ),
        })
    }

    /// The clip-space position of a world-space point in the configured
    /// precision.
    #[inline]
    pub(crate) fn clip(&self, p: DVec3) -> DVec4 {
        match self.options.precision {
            TransformPrecision::F64 => self.eye_to_clip * (p - self.eye).extend(1.0),
            TransformPrecision::F32 => (self.mvp32 * Vec4::from((p.as_vec3(), 1.0))).as_dvec4(),
        }
    }

    /// The camera-space position of a world-space point, relative to the
    /// eye first (see [`Self::eye_to_clip`]).
    #[inline]
    pub fn to_camera(&self, p: DVec3) -> DVec3 {
        self.eye_to_camera.transform_vector3(p - self.eye)
    }

    /// A world-space light in camera space, where shading works: a
    /// direction rotated, a position moved relative to the eye first.
    pub fn light_to_camera(&self, light: &Light) -> Light {
        match *light {
            Light::Directional { direction, color } => Light::Directional {
                direction: self.eye_to_camera.transform_vector3(direction),
                color,
            },
            Light::Point { position, color } => Light::Point {
                position: self.to_camera(position),
                color,
            },
        }
    }

    /// The per-primitive data of triangle `t` of mesh `m`: what shading
    /// reads (camera-space corners, material, normals, uvs).
    pub fn prim_info(&self, scene: &Scene, m: usize, t: usize) -> PrimInfo {
        let mesh = &scene.meshes[m];
        self.prim_info_from(
            scene,
            (m, t),
            |i| self.to_camera(mesh.positions[i]),
            |i| self.normal_to_camera(mesh.normals[i]),
        )
    }

    /// [`Self::prim_info`] with the camera-space position and normal of
    /// vertex `i` of the mesh given by `camera` and `normal` (which must
    /// give [`Self::to_camera`] and [`Self::normal_to_camera`] of the
    /// mesh's: a front end that transformed each vertex once reads them
    /// from its cache, and the data is the same, bit for bit).
    #[inline]
    pub fn prim_info_from(
        &self,
        scene: &Scene,
        (m, t): (usize, usize),
        camera: impl Fn(usize) -> DVec3,
        normal: impl Fn(usize) -> Vec3,
    ) -> PrimInfo {
        let mesh = &scene.meshes[m];
        let idx = mesh.indices[t];
        PrimInfo {
            camera: idx.map(|i| camera(i as usize)),
            material: mesh
                .triangle_material(t)
                .map_or(self.default_material, |k| k as u32),
            normals: (!mesh.normals.is_empty()).then(|| idx.map(|i| normal(i as usize))),
            uvs: (!mesh.uvs.is_empty()).then(|| idx.map(|i| mesh.uvs[i as usize])),
            colors: (!mesh.colors.is_empty()).then(|| idx.map(|i| mesh.colors[i as usize])),
        }
    }

    /// A world-space vertex normal in camera space, as shading reads it
    /// (transformed in `f64`, kept as `f32`).
    #[inline]
    pub fn normal_to_camera(&self, n: Vec3) -> Vec3 {
        self.normal_matrix.transform_vector3(n.as_dvec3()).as_vec3()
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
        let world = mesh.indices[t].map(|i| mesh.positions[i as usize]);
        prims.push(self.prim_info(scene, m, t));
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

/// The divide, the viewport transform and the snap of a clipped vertex,
/// as Mesa's llvmpipe computes them (its `draw_llvm.c`, `generate_viewport`,
/// and `lp_setup_tri.c`, `calc_fixed_position`): the reciprocal of `w`
/// first, `ndc = clip * (1/w)`, then [`Viewport::snap_ndc_f32`] (GL's own
/// frame, ties to even, the flip in integers) and window depth
/// `ndc_z * 0.5 + 0.5`; in `f32` for [`TransformPrecision::F32`], the same
/// steps in `f64` for [`TransformPrecision::F64`]. The lean front end of the
/// tiled z-buffer repeats these steps lane by lane and must stay bit for bit
/// equal.
#[inline]
pub(crate) fn to_window(
    v: &ClipVertex,
    vp: Viewport,
    precision: TransformPrecision,
) -> Option<WindowVertex> {
    let (p, z) = match precision {
        TransformPrecision::F64 => {
            let r = 1.0 / v.pos.w;
            let p = vp.snap_ndc(v.pos.x * r, v.pos.y * r)?;
            (p, v.pos.z * r * 0.5 + 0.5)
        }
        TransformPrecision::F32 => {
            let c = v.pos.as_vec4();
            let r = 1.0 / c.w;
            let p = vp.snap_ndc_f32(c.x * r, c.y * r)?;
            (p, f64::from(c.z * r * 0.5 + 0.5))
        }
    };
    Some(WindowVertex {
        p,
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
