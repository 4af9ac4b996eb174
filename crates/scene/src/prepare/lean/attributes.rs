//! What shading per point reads of a lean scene's vertices: camera-space
//! positions and normals, transformed once per vertex.
//!
//! `prepare` keeps a [`PrimInfo`] per triangle (its corners and normals
//! transformed per corner); a colour-resolving hider that shades textured
//! or smooth surfaces reads it for every fragment. The lean front end
//! keeps no per-triangle data; when the frame is shaded per point it
//! transforms each vertex's position and normal once (the same
//! [`FrontEnd::to_camera`] and [`FrontEnd::normal_to_camera`], so the
//! same bits) and assembles a primitive's [`PrimInfo`] from them when a
//! fragment asks ([`FrontEnd::prim_info_from`]). Texture coordinates and
//! vertex colours are read from the mesh as they are. A scene whose
//! colours do not vary per point ([`Scene::varies_per_point`]) transforms
//! nothing here.

use glam::{DVec3, Vec3};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::model::Scene;
use crate::prepare::{FrontEnd, PrimInfo};

/// Vertices below which the attribute pass stays on one thread.
const PARALLEL_MIN: usize = 32 * 1024;

/// Camera-space positions and normals of every vertex of a scene (meshes
/// one after the other), kept between frames.
#[derive(Clone, Debug, Default)]
pub(super) struct PointAttributes {
    /// Whether the last frame filled them.
    filled: bool,
    /// Camera-space position of each vertex.
    camera: Vec<DVec3>,
    /// Camera-space normal of each vertex of the meshes that have normals.
    normals: Vec<Vec3>,
    /// Per mesh, its first entry in `camera` and in `normals`.
    starts: Vec<(usize, usize)>,
}

impl PointAttributes {
    /// Fills the attributes of `scene` seen through `front` when `wanted`
    /// and the scene's colours vary per point; forgets them otherwise (so
    /// a flat scene pays nothing).
    pub(super) fn fill(&mut self, scene: &Scene, front: &FrontEnd, wanted: bool, parallel: bool) {
        self.camera.clear();
        self.normals.clear();
        self.starts.clear();
        self.filled = wanted && scene.varies_per_point();
        if !self.filled {
            return;
        }
        #[cfg(not(feature = "parallel"))]
        let _ = parallel;
        for mesh in &scene.meshes {
            self.starts.push((self.camera.len(), self.normals.len()));
            let to_camera = |p: &DVec3| front.to_camera(*p);
            let to_normal = |n: &Vec3| front.normal_to_camera(*n);
            #[cfg(feature = "parallel")]
            if parallel && mesh.positions.len() >= PARALLEL_MIN {
                self.camera
                    .par_extend(mesh.positions.par_iter().map(to_camera));
                self.normals
                    .par_extend(mesh.normals.par_iter().map(to_normal));
                continue;
            }
            self.camera.extend(mesh.positions.iter().map(to_camera));
            self.normals.extend(mesh.normals.iter().map(to_normal));
        }
    }

    /// Whether the last frame filled them.
    pub(super) fn filled(&self) -> bool {
        self.filled
    }

    /// Triangle `t` of mesh `m`'s [`PrimInfo`] from the attributes (which
    /// must be filled): bit for bit [`FrontEnd::prim_info`].
    #[inline]
    pub(super) fn prim_info(
        &self,
        scene: &Scene,
        front: &FrontEnd,
        m: usize,
        t: usize,
    ) -> PrimInfo {
        let (c, n) = self.starts[m];
        front.prim_info_from(
            scene,
            (m, t),
            |i| self.camera[c + i],
            |i| self.normals[n + i],
        )
    }

    /// Bytes of memory held.
    pub(super) fn bytes(&self) -> usize {
        self.camera.capacity() * std::mem::size_of::<DVec3>()
            + self.normals.capacity() * std::mem::size_of::<Vec3>()
    }
}
