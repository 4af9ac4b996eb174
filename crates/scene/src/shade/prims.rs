//! What shading reads of a primitive, from the world-space scene and the
//! view alone: for colour passes after a hider whose front end keeps no
//! per-primitive data (the lean front ends), so that colour never depends
//! on which front end a hider ran.

use super::surface::{TextureOptions, TextureSampler};
use super::texture::TextureRef;
use crate::error::Result;
use crate::model::{Light, Material, Scene};
use crate::prepare::{FrontEnd, PrepareOptions, PrimInfo, ScreenScene};
use crate::view::View;

/// The per-primitive data of a scene seen through a view, computed per
/// primitive on demand with the shared front end's transforms: for any
/// primitive id, the same [`PrimInfo`] [`prepare`](crate::prepare()) keeps.
///
/// ```
/// use hider_scene::shade::ScenePrims;
/// use hider_scene::{PrepareOptions, View, prepare, procedural};
///
/// let scene = procedural::cube();
/// let view = View::for_scene(&scene, 32, 32)?;
/// let prims = ScenePrims::new(&scene, &view)?;
/// let screen = prepare(&scene, &view, &PrepareOptions::default())?;
/// assert_eq!(prims.len(), 12);
/// assert_eq!(prims.info(5), screen.prims[5]);
/// assert_eq!(prims.lights(), &screen.lights[..]);
/// # Ok::<(), hider_scene::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ScenePrims<'a> {
    scene: &'a Scene,
    front: FrontEnd,
    /// First primitive id of each mesh, then the total.
    starts: Vec<u32>,
    lights: Vec<Light>,
    default_material: Material,
    view: View,
}

impl<'a> ScenePrims<'a> {
    /// The primitives of `scene` seen through `view`.
    ///
    /// # Errors
    ///
    /// An invalid camera or image size, or a scene `prepare` refuses
    /// (checked without reading every vertex).
    pub fn new(scene: &'a Scene, view: &View) -> Result<Self> {
        let front = FrontEnd::checked(scene, view, &PrepareOptions::default(), false)?;
        let mut starts = Vec::with_capacity(scene.meshes.len() + 1);
        let mut next = 0u32;
        for mesh in &scene.meshes {
            starts.push(next);
            next += mesh.indices.len() as u32;
        }
        starts.push(next);
        let lights = scene
            .lights
            .iter()
            .map(|l| front.light_to_camera(l))
            .collect();
        Ok(Self {
            scene,
            front,
            starts,
            lights,
            default_material: Material::default(),
            view: *view,
        })
    }

    /// Number of primitives (triangles of the scene).
    pub fn len(&self) -> usize {
        *self.starts.last().unwrap_or(&0) as usize
    }

    /// Whether the scene has no triangles.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The data of primitive `prim` (`prim < self.len()`).
    pub fn info(&self, prim: u32) -> PrimInfo {
        // The last mesh starting at or before `prim` (empty meshes share
        // their start with the next one, and hold no primitive).
        let m = self.starts.partition_point(|&s| s <= prim) - 1;
        self.front
            .prim_info(self.scene, m, (prim - self.starts[m]) as usize)
    }

    /// The material at `index` of [`PrimInfo::material`]: the scene's, or
    /// the default one after them.
    pub fn material(&self, index: u32) -> &Material {
        self.scene
            .materials
            .get(index as usize)
            .unwrap_or(&self.default_material)
    }

    /// The scene's lights in camera space.
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// The view the primitives are seen through.
    pub fn view(&self) -> &View {
        &self.view
    }
}

/// Where a colour pass reads its primitives: a prepared scene's table, or
/// the world-space scene on demand. Both give the same data.
#[derive(Clone, Copy, Debug)]
pub enum Prims<'s, 'a> {
    /// [`ScreenScene::prims`] of a prepared scene.
    Screen(&'s ScreenScene),
    /// [`ScenePrims`] of the world-space scene.
    Scene(&'s ScenePrims<'a>),
}

impl Prims<'_, '_> {
    /// Number of primitives.
    pub fn len(&self) -> usize {
        match self {
            Prims::Screen(s) => s.prims.len(),
            Prims::Scene(s) => s.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The data of primitive `prim`.
    pub fn info(&self, prim: u32) -> PrimInfo {
        match self {
            Prims::Screen(s) => s.prims[prim as usize],
            Prims::Scene(s) => s.info(prim),
        }
    }

    /// The material of [`PrimInfo::material`] `index`.
    pub fn material(&self, index: u32) -> &Material {
        match self {
            Prims::Screen(s) => &s.materials[index as usize],
            Prims::Scene(s) => s.material(index),
        }
    }

    /// Lights in camera space.
    pub fn lights(&self) -> &[Light] {
        match self {
            Prims::Screen(s) => &s.lights,
            Prims::Scene(s) => s.lights(),
        }
    }

    /// The diffuse textures of the materials (each file once per
    /// material that names it).
    pub fn textures(&self) -> Vec<&TextureRef> {
        let materials: &[Material] = match self {
            Prims::Screen(s) => &s.materials,
            Prims::Scene(s) => &s.scene.materials,
        };
        materials
            .iter()
            .filter_map(|m| m.diffuse_texture.as_ref())
            .collect()
    }

    /// Whether the camera is a perspective one.
    pub fn perspective(&self) -> bool {
        match self {
            Prims::Screen(s) => s.is_perspective(),
            Prims::Scene(s) => s.front.perspective,
        }
    }

    /// A texture sampler for the frame these primitives are seen in.
    pub fn sampler(&self, options: TextureOptions) -> TextureSampler {
        match self {
            Prims::Screen(s) => TextureSampler::new(s, options),
            Prims::Scene(s) => TextureSampler::for_view(s.view(), options),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Mesh, prepare, procedural};

    /// Every primitive of a scene with several meshes (one empty), normals
    /// and uvs equals what `prepare` keeps.
    #[test]
    fn every_primitive_equals_the_prepared_one() {
        let mut scene = procedural::uv_sphere(6);
        scene.meshes.insert(0, Mesh::default());
        scene.meshes.push(procedural::cube().meshes.remove(0));
        let view = View::for_scene(&scene, 24, 16).unwrap();
        let prims = ScenePrims::new(&scene, &view).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        assert_eq!(prims.len(), screen.prims.len());
        for prim in 0..prims.len() as u32 {
            assert_eq!(prims.info(prim), screen.prims[prim as usize], "{prim}");
            let info = prims.info(prim);
            assert_eq!(
                prims.material(info.material),
                &screen.materials[info.material as usize]
            );
        }
    }
}
