//! The per-triangle path of the front end: transform, clip, divide, map to
//! the window, snap and set up; shared with the z-buffer's lean front end.

use glam::{DMat4, DVec3, DVec4, Vec4};
use hider_geom::clip::{ClipOutcome, ClipVertex, ClipVolume, clip_triangle};
use hider_geom::fixed::{FixedPt, GUARD_BAND_PIXELS};
use hider_geom::{PlaneEq, Viewport, orient2d};

use crate::error::Result;
use crate::model::Scene;
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
