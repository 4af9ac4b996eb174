//! What a ray caster reports per pixel, from an id buffer: the distance
//! along the pixel-centre ray, view depth, the barycentric coordinates of
//! the hit, the geometric normal and the interpolated vertex normal.
//!
//! A pixel-centre hider decides *which* primitive each pixel centre sees
//! ([`crate::Frame::ids`]); a ray caster such as open3d's
//! `RaycastingScene.cast_rays` also says *where*. Both meet here: the ray
//! through the centre of pixel `(i, j)` (window `(i + 0.5, j + 0.5)`) is
//! intersected, in `f64` and in camera space, with the world-space
//! triangle of the primitive that won the pixel (Möller and Trumbore's
//! ray-triangle solution, "Fast, minimum storage ray/triangle
//! intersection", 1997, whose `(t, u, v)` are the quantities wanted). No
//! interpolated window depth is used, so the values are as exact as the
//! triangle's `f64` corners allow, whatever depth format the hider kept.
//!
//! The rays come from the view's own matrices ([`hider_geom::Camera`]'s
//! view and projection, a [`hider_geom::Lens`] included), so they pass
//! through the pixel centres the front end sampled.
//!
//! Conventions, as open3d's `cast_rays` where it has the same output:
//! - `distance` is the Euclidean distance from the eye to the hit (for an
//!   orthographic camera: from the plane through the eye across the view
//!   axis, which equals `view_z`), `inf` where no primitive is seen;
//! - `view_z` is the hit's depth along the view axis, positive in front
//!   of the eye (OpenCV's and a depth camera's z; OpenGL's camera-space z
//!   is its negative), `inf` where no primitive is seen;
//! - `barycentrics` are `(u, v)` with the hit at
//!   `(1 - u - v) p0 + u p1 + v p2` for the triangle's corners in index
//!   order (open3d's and Embree's `primitive_uvs`), `(0, 0)` where no
//!   primitive is seen. At a triangle's edges they may leave `[0, 1]` by
//!   the front end's snapping (1/256 pixel), which can give a pixel centre
//!   just outside the exact triangle to it;
//! - `normals` are the unit geometric normals `(p1 - p0) x (p2 - p0)`
//!   normalised, in world space, not turned toward the viewer (front faces
//!   are counter-clockwise), `(0, 0, 0)` where no primitive is seen;
//! - `vertex_normals` are the mesh's vertex normals interpolated with the
//!   barycentrics and normalised, `(0, 0, 0)` where no primitive is seen
//!   or its mesh has no normals.

use glam::{DMat4, DVec3};

use crate::frame::NO_ID;
use crate::model::Scene;
use crate::view::View;
use crate::{Error, Result};

/// Which per-pixel attributes [`surface_at_pixels`] computes; each costs
/// only when asked. `Default` asks for none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceOutputs {
    /// Distance along the pixel-centre ray.
    pub distance: bool,
    /// View depth, positive in front of the eye.
    pub view_z: bool,
    /// Barycentric `(u, v)` of the hit.
    pub barycentrics: bool,
    /// Unit geometric normals, world space.
    pub normals: bool,
    /// Interpolated unit vertex normals, world space.
    pub vertex_normals: bool,
    /// Whether bands of rows are solved in parallel, in the caller's rayon
    /// pool (as `par_iter` would run them: wrap the call in a pool's
    /// `install` to choose the threads). The values do not change. Without
    /// the crate's `parallel` feature the calling thread solves them all.
    pub parallel: bool,
}

impl SurfaceOutputs {
    /// Whether any attribute is asked for.
    pub fn any(&self) -> bool {
        self.distance || self.view_z || self.barycentrics || self.normals || self.vertex_normals
    }
}

/// The attributes of a frame's visible surface, row-major with row 0 at
/// the top, each empty unless asked for (see the module docs for the
/// conventions).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PixelSurface {
    /// Distance from the eye along the pixel-centre ray, `inf` for none.
    pub distance: Vec<f32>,
    /// View depth, positive in front of the eye, `inf` for none.
    pub view_z: Vec<f32>,
    /// `(u, v)` with the hit at `(1 - u - v) p0 + u p1 + v p2`.
    pub barycentrics: Vec<[f32; 2]>,
    /// Unit geometric normals, world space.
    pub normals: Vec<[f32; 3]>,
    /// Interpolated unit vertex normals, world space.
    pub vertex_normals: Vec<[f32; 3]>,
    /// What the pass did.
    pub stats: SurfaceStats,
}

/// What [`surface_at_pixels`] did: its cost is one ray-triangle solution
/// per covered pixel, and three corner transforms per change of primitive
/// along a row.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceStats {
    /// Pixels with a primitive (the rays solved).
    pub covered: u64,
    /// Times the primitive changed from one covered pixel to the next (the
    /// triangles fetched and transformed).
    pub triangle_fetches: u64,
    /// Covered pixels whose ray runs parallel to the primitive's plane (a
    /// triangle seen edge-on, or degenerate): their values are NaN.
    pub parallel: u64,
}

/// The camera-space ray through window point `(x, y)` of a frame: an
/// origin and a direction whose z is -1, so that the ray parameter of a
/// point is its view depth.
#[derive(Clone, Copy, Debug)]
struct Rays {
    projection: DMat4,
    width: f64,
    height: f64,
    perspective: bool,
}

impl Rays {
    fn ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let ndc_x = 2.0 * x / self.width - 1.0;
        let ndc_y = 1.0 - 2.0 * y / self.height;
        let m = &self.projection;
        if self.perspective {
            // Clip x = m00 x + m02 z and w = -z: at z = -1, NDC x is
            // m00 x - m02 (and the same in y), solved for x.
            let dx = (ndc_x + m.z_axis.x) / m.x_axis.x;
            let dy = (ndc_y + m.z_axis.y) / m.y_axis.y;
            (DVec3::ZERO, DVec3::new(dx, dy, -1.0))
        } else {
            // NDC x = m00 x + m03, w = 1.
            let ox = (ndc_x - m.w_axis.x) / m.x_axis.x;
            let oy = (ndc_y - m.w_axis.y) / m.y_axis.y;
            (DVec3::new(ox, oy, 0.0), DVec3::NEG_Z)
        }
    }
}

/// A primitive's corners in world and camera space, and its mesh.
struct Triangle {
    world: [DVec3; 3],
    camera: [DVec3; 3],
    mesh: usize,
    corners: [u32; 3],
}

/// What every band of rows reads: the scene, where its meshes' ids start,
/// the camera's rays and view matrix.
struct FrameRays<'a> {
    scene: &'a Scene,
    starts: Vec<usize>,
    count: usize,
    view_matrix: DMat4,
    eye: DVec3,
    rays: Rays,
    width: usize,
    wanted: SurfaceOutputs,
}

/// One band's share of the outputs (empty slices for those not asked).
struct Band<'a> {
    /// The band's first pixel.
    start: usize,
    ids: &'a [u32],
    distance: &'a mut [f32],
    view_z: &'a mut [f32],
    barycentrics: &'a mut [[f32; 2]],
    normals: &'a mut [[f32; 3]],
    vertex_normals: &'a mut [[f32; 3]],
}

/// Rows per band: enough for a band to cost far more than handing it to a
/// thread, few enough for two threads to share a small frame.
const BAND_ROWS: usize = 16;

/// The attributes `wanted` of the surface seen at each pixel centre of
/// `ids` (a frame's id buffer: row-major, `view`'s size, [`NO_ID`] for
/// none), for `scene` rendered through `view`.
///
/// ```
/// use hider_scene::pixel_rays::{surface_at_pixels, SurfaceOutputs};
/// use hider_scene::{procedural, View};
///
/// let scene = procedural::cube();
/// let view = View::for_scene(&scene, 32, 32)?;
/// // Primitive 0 seen at the centre pixel only (a hider's frame.ids).
/// let ids: Vec<u32> = (0..32 * 32).map(|i| if i == 16 * 32 + 16 { 0 } else { u32::MAX }).collect();
/// let wanted = SurfaceOutputs { distance: true, ..Default::default() };
/// let s = surface_at_pixels(&scene, &view, &ids, wanted)?;
/// assert_eq!(s.distance.len(), 32 * 32);
/// assert!(s.distance[0].is_infinite());
/// assert!(s.view_z.is_empty());
/// # Ok::<(), hider_scene::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::InvalidScene`] when `ids` is not the view's size or names a
/// primitive the scene does not have.
pub fn surface_at_pixels(
    scene: &Scene,
    view: &View,
    ids: &[u32],
    wanted: SurfaceOutputs,
) -> Result<PixelSurface> {
    let (width, height) = (view.viewport.width, view.viewport.height);
    let pixels = width as usize * height as usize;
    if ids.len() != pixels {
        return Err(Error::InvalidScene(format!(
            "the id buffer has {} pixels, the view {width} x {height}",
            ids.len()
        )));
    }
    // The first primitive id of each mesh, for the id's mesh.
    let mut starts = Vec::with_capacity(scene.meshes.len());
    let mut next = 0usize;
    for mesh in &scene.meshes {
        starts.push(next);
        next += mesh.indices.len();
    }
    let camera = view.camera;
    let frame = FrameRays {
        scene,
        starts,
        count: next,
        view_matrix: camera.view_matrix(),
        eye: camera.eye,
        rays: Rays {
            projection: camera.projection_matrix(view.viewport.aspect()),
            width: f64::from(width),
            height: f64::from(height),
            perspective: matches!(
                camera.projection,
                hider_geom::Projection::Perspective { .. }
            ),
        },
        width: width as usize,
        wanted,
    };
    let mut out = PixelSurface {
        distance: filled(wanted.distance, pixels, f32::INFINITY),
        view_z: filled(wanted.view_z, pixels, f32::INFINITY),
        barycentrics: filled(wanted.barycentrics, pixels, [0.0; 2]),
        normals: filled(wanted.normals, pixels, [0.0; 3]),
        vertex_normals: filled(wanted.vertex_normals, pixels, [0.0; 3]),
        stats: SurfaceStats::default(),
    };
    // Outputs not asked for are empty: no chunks, and their bands take
    // empty slices.
    let band = (BAND_ROWS * frame.width).max(1);
    let mut distance = out.distance.chunks_mut(band);
    let mut view_z = out.view_z.chunks_mut(band);
    let mut barycentrics = out.barycentrics.chunks_mut(band);
    let mut normals = out.normals.chunks_mut(band);
    let mut vertex_normals = out.vertex_normals.chunks_mut(band);
    let jobs: Vec<Band<'_>> = ids
        .chunks(band)
        .enumerate()
        .map(|(b, ids)| Band {
            start: b * band,
            ids,
            distance: distance.next().unwrap_or_default(),
            view_z: view_z.next().unwrap_or_default(),
            barycentrics: barycentrics.next().unwrap_or_default(),
            normals: normals.next().unwrap_or_default(),
            vertex_normals: vertex_normals.next().unwrap_or_default(),
        })
        .collect();
    let add = |a: Result<SurfaceStats>, b: Result<SurfaceStats>| {
        let (a, b) = (a?, b?);
        Ok(SurfaceStats {
            covered: a.covered + b.covered,
            triangle_fetches: a.triangle_fetches + b.triangle_fetches,
            parallel: a.parallel + b.parallel,
        })
    };
    #[cfg(feature = "parallel")]
    let stats = if wanted.parallel {
        use rayon::prelude::*;
        jobs.into_par_iter()
            .map(|b| solve_band(&frame, b))
            .reduce(|| Ok(SurfaceStats::default()), add)
    } else {
        jobs.into_iter()
            .map(|b| solve_band(&frame, b))
            .fold(Ok(SurfaceStats::default()), add)
    };
    #[cfg(not(feature = "parallel"))]
    let stats = jobs
        .into_iter()
        .map(|b| solve_band(&frame, b))
        .fold(Ok(SurfaceStats::default()), add);
    out.stats = stats?;
    Ok(out)
}

/// `n` copies of `value` when asked for, else nothing.
fn filled<T: Clone>(on: bool, n: usize, value: T) -> Vec<T> {
    if on { vec![value; n] } else { Vec::new() }
}

/// Solves the rays of one band of pixels.
fn solve_band(frame: &FrameRays<'_>, out: Band<'_>) -> Result<SurfaceStats> {
    let FrameRays {
        scene,
        ref starts,
        count,
        view_matrix,
        eye,
        rays,
        width,
        wanted,
    } = *frame;
    let mut stats = SurfaceStats::default();
    let mut last: Option<(u32, Triangle)> = None;
    for (offset, &id) in out.ids.iter().enumerate() {
        if id == NO_ID {
            continue;
        }
        let k = out.start + offset;
        if id as usize >= count {
            return Err(Error::InvalidScene(format!(
                "pixel {k} shows primitive {id}, but the scene has {count} triangles"
            )));
        }
        stats.covered += 1;
        if last.as_ref().is_none_or(|(l, _)| *l != id) {
            stats.triangle_fetches += 1;
            let mesh = starts.partition_point(|&s| s <= id as usize) - 1;
            let corners = scene.meshes[mesh].indices[id as usize - starts[mesh]];
            let world = corners.map(|c| scene.meshes[mesh].positions[c as usize]);
            // Eye-relative, then rotated: a scene far from the origin
            // keeps the bits a translation after the rotation would
            // cancel (the front end's eye-relative transform).
            let camera = world.map(|p| view_matrix.transform_vector3(p - eye));
            last = Some((
                id,
                Triangle {
                    world,
                    camera,
                    mesh,
                    corners,
                },
            ));
        }
        let tri = &last.as_ref().expect("fetched above").1;
        let (x, y) = ((k % width) as f64 + 0.5, (k / width) as f64 + 0.5);
        let (origin, dir) = rays.ray(x, y);
        let Some((t, u, v)) = intersect(origin, dir, tri.camera) else {
            stats.parallel += 1;
            let nan = f32::NAN;
            set(out.distance, offset, nan);
            set(out.view_z, offset, nan);
            set(out.barycentrics, offset, [nan; 2]);
            set(out.normals, offset, [nan; 3]);
            set(out.vertex_normals, offset, [nan; 3]);
            continue;
        };
        // The direction's z is -1: t is the view depth.
        set(out.view_z, offset, t as f32);
        let distance = if rays.perspective {
            t * dir.length()
        } else {
            t
        };
        set(out.distance, offset, distance as f32);
        set(out.barycentrics, offset, [u as f32, v as f32]);
        if wanted.normals {
            let [p0, p1, p2] = tri.world;
            let n = (p1 - p0).cross(p2 - p0).normalize_or_zero();
            out.normals[offset] = n.as_vec3().to_array();
        }
        if wanted.vertex_normals {
            let normals = &scene.meshes[tri.mesh].normals;
            if !normals.is_empty() {
                let [n0, n1, n2] = tri.corners.map(|c| normals[c as usize].as_dvec3());
                let n = (n0 * (1.0 - u - v) + n1 * u + n2 * v).normalize_or_zero();
                out.vertex_normals[offset] = n.as_vec3().to_array();
            }
        }
    }
    Ok(stats)
}

/// `buffer[k] = value` when the buffer was asked for (is not empty).
fn set<T>(buffer: &mut [T], k: usize, value: T) {
    if let Some(slot) = buffer.get_mut(k) {
        *slot = value;
    }
}

/// Möller and Trumbore's ray-triangle solution `(t, u, v)`: the ray point
/// `origin + t dir` is `(1 - u - v) c0 + u c1 + v c2` on the triangle's
/// plane (u and v not bounded: the pixel's id already chose the
/// triangle). `None` when the ray runs parallel to the plane.
fn intersect(origin: DVec3, dir: DVec3, c: [DVec3; 3]) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (c[1] - c[0], c[2] - c[0]);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let s = origin - c[0];
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    let t = e2.dot(q) / det;
    Some((t, u, v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mesh;
    use glam::{DVec2, Vec3};
    use hider_geom::{Camera, Lens};

    /// One triangle in the plane z = -2 (world), seen from the origin
    /// looking down -Z: every value is known in closed form.
    fn plane_scene(normals: bool) -> Scene {
        let mut s = Scene::default();
        s.push_mesh(
            Mesh {
                positions: vec![
                    DVec3::new(-4.0, -4.0, -2.0),
                    DVec3::new(4.0, -4.0, -2.0),
                    DVec3::new(0.0, 4.0, -2.0),
                ],
                normals: if normals {
                    vec![Vec3::X, Vec3::Y, Vec3::Z]
                } else {
                    Vec::new()
                },
                indices: vec![[0, 1, 2]],
                ..Mesh::default()
            },
            None,
        );
        s
    }

    fn all(on: bool) -> SurfaceOutputs {
        SurfaceOutputs {
            distance: on,
            view_z: on,
            barycentrics: on,
            normals: on,
            vertex_normals: on,
            parallel: false,
        }
    }

    #[test]
    fn values_at_pixel_centres_are_the_closed_forms() {
        let scene = plane_scene(true);
        let lens = Lens {
            centre: DVec2::new(0.2, -0.1),
            x_scale: 1.5,
        };
        for camera in [
            Camera::perspective(DVec3::ZERO, DVec3::NEG_Z, 0.5, 10.0).with_lens(lens),
            Camera::orthographic(DVec3::ZERO, DVec3::NEG_Z, 1.0, 0.5, 10.0).with_lens(lens),
        ] {
            let view = View::new(camera, 8, 6).unwrap();
            let ids = vec![0; 48];
            let s = surface_at_pixels(&scene, &view, &ids, all(true)).unwrap();
            assert_eq!(s.stats.covered, 48);
            assert_eq!(s.stats.triangle_fetches, 1);
            let clip = camera.projection_matrix(view.viewport.aspect());
            for k in 0..48 {
                assert!((s.view_z[k] - 2.0).abs() < 1e-6, "{}", s.view_z[k]);
                // The hit point, from distance and the pixel's ray: it must
                // project back to the pixel centre and lie on z = -2.
                let (x, y) = ((k % 8) as f64 + 0.5, (k / 8) as f64 + 0.5);
                let [u, v] = s.barycentrics[k].map(f64::from);
                let p = &scene.meshes[0].positions;
                let hit = p[0] * (1.0 - u - v) + p[1] * u + p[2] * v;
                let c = clip * hit.extend(1.0);
                let win = view.viewport.ndc_to_window(c.truncate() / c.w);
                assert!(
                    (win.x - x).abs() < 1e-5 && (win.y - y).abs() < 1e-5,
                    "{win} {x} {y}"
                );
                let expect = if matches!(
                    camera.projection,
                    hider_geom::Projection::Perspective { .. }
                ) {
                    hit.length()
                } else {
                    2.0
                };
                assert!((f64::from(s.distance[k]) - expect).abs() < 1e-5);
                assert_eq!(s.normals[k], [0.0, 0.0, 1.0]);
                let n = DVec3::new(1.0 - u - v, u, v)
                    .normalize()
                    .as_vec3()
                    .to_array();
                for (a, b) in s.vertex_normals[k].iter().zip(n) {
                    assert!((a - b).abs() < 1e-6);
                }
            }
        }
    }

    #[test]
    fn bands_in_parallel_give_the_same_values() {
        let scene = crate::procedural::cube();
        let view = View::new(
            Camera::perspective(DVec3::new(2.0, 1.5, 3.0), DVec3::ZERO, 0.5, 20.0),
            37,
            53,
        )
        .unwrap();
        // Every pixel shows the face its column picks: a made-up frame
        // whose rays still all meet their planes.
        let ids: Vec<u32> = (0..37 * 53).map(|k| (k % 37 / 4) as u32 % 12).collect();
        let one = surface_at_pixels(&scene, &view, &ids, all(true)).unwrap();
        let many = surface_at_pixels(
            &scene,
            &view,
            &ids,
            SurfaceOutputs {
                parallel: true,
                ..all(true)
            },
        )
        .unwrap();
        assert_eq!(one.stats.covered, 37 * 53);
        assert_eq!(one.stats, many.stats);
        for (a, b) in [(&one.distance, &many.distance), (&one.view_z, &many.view_z)] {
            assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()));
        }
        assert!(
            one.normals
                .iter()
                .zip(&many.normals)
                .all(|(x, y)| x.map(f32::to_bits) == y.map(f32::to_bits))
        );
    }

    #[test]
    fn background_and_unasked_outputs() {
        let scene = plane_scene(false);
        let view = View::new(
            Camera::perspective(DVec3::ZERO, DVec3::NEG_Z, 0.5, 10.0),
            4,
            4,
        )
        .unwrap();
        let ids = vec![NO_ID; 16];
        let s = surface_at_pixels(&scene, &view, &ids, all(true)).unwrap();
        assert!(s.distance.iter().chain(&s.view_z).all(|d| d.is_infinite()));
        assert!(s.normals.iter().all(|n| *n == [0.0; 3]));
        assert_eq!(s.stats, SurfaceStats::default());
        let none = surface_at_pixels(&scene, &view, &[0; 16], all(false)).unwrap();
        assert!(none.distance.is_empty() && none.normals.is_empty());
        // Without vertex normals the mesh's pixels keep (0, 0, 0).
        let s = surface_at_pixels(&scene, &view, &[0; 16], all(true)).unwrap();
        assert!(s.vertex_normals.iter().all(|n| *n == [0.0; 3]));
        let e = surface_at_pixels(&scene, &view, &[1; 16], all(true)).unwrap_err();
        assert!(e.to_string().contains("primitive 1"), "{e}");
        let e = surface_at_pixels(&scene, &view, &[0; 15], all(true)).unwrap_err();
        assert!(e.to_string().contains("15 pixels"), "{e}");
    }
}
