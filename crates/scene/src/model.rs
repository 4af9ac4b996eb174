//! The scene model: meshes, materials, lights and an optional camera.

use glam::{DVec3, Vec2, Vec3};
use hider_geom::Camera;

use crate::error::{Error, Result};
use crate::shade::TextureRef;

/// A surface material: what the MTL format says of a surface that the
/// hiders simulate (see `docs/analysis.md` for every MTL key and what is
/// done with it). Colours are linear RGB in [0, 1].
///
/// The lighting model (`hider_scene::shade::shade_point`) is the MTL
/// specification's: `illum 0` shows `Kd` unlit, `illum 1` adds the
/// ambient term `Ka` and Lambert diffuse `Kd`, `illum 2` adds Blinn-Phong
/// highlights `Ks` with exponent `Ns`; the emission `Ke` is added in every
/// model.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name from the MTL file, or a generated one.
    pub name: String,
    /// Diffuse colour `Kd`.
    pub diffuse: [f32; 3],
    /// Ambient colour `Ka`, lit by the ambient term; `None` when the file
    /// gives none: the diffuse colour then takes the ambient light too (as
    /// most viewers do).
    pub ambient: Option<[f32; 3]>,
    /// Specular colour `Ks` (highlights under `illum 2`).
    pub specular: [f32; 3],
    /// Specular exponent `Ns` (0 to 1000).
    pub shininess: f32,
    /// Emitted colour `Ke`, added whatever the light.
    pub emission: [f32; 3],
    /// The illumination model `illum`.
    pub illumination: Illumination,
    /// Opacity in [0, 1]: MTL `d`, or `1 - Tr`. 1 is opaque.
    pub opacity: f32,
    /// Diffuse texture `map_Kd`, resolved against the MTL file's folder
    /// (Windows separators turned into `/`), decoded on first use, with
    /// its statement's options (`-s`, `-o`, `-clamp`).
    pub diffuse_texture: Option<TextureRef>,
    /// Specular texture `map_Ks`, multiplying `Ks`.
    pub specular_texture: Option<TextureRef>,
    /// Dissolve texture `map_d`, read as a mask ([`TextureRef::as_mask`]):
    /// its value multiplies the alpha of `map_Kd` (cut-outs and partial
    /// alpha, [`crate::shade::cutout`]).
    pub alpha_texture: Option<TextureRef>,
}

/// The MTL illumination model (`illum`), as far as the hiders simulate it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Illumination {
    /// `illum 0`: the diffuse colour, no lighting ("color on, ambient
    /// off").
    Color,
    /// `illum 1`: ambient and Lambert diffuse.
    Diffuse,
    /// `illum 2` (and the models above it, whose reflection, refraction
    /// and Fresnel terms are named in a warning): ambient, diffuse and
    /// Blinn-Phong highlights. The default: without `Ks` the highlights are
    /// black, so a file without `illum` looks as under `illum 1`.
    #[default]
    Highlight,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            diffuse: [0.8, 0.8, 0.8],
            ambient: None,
            specular: [0.0; 3],
            shininess: 0.0,
            emission: [0.0; 3],
            illumination: Illumination::default(),
            opacity: 1.0,
            diffuse_texture: None,
            specular_texture: None,
            alpha_texture: None,
        }
    }
}

impl Material {
    /// Whether highlights can show: `illum 2` with a specular colour or
    /// texture.
    pub fn has_highlights(&self) -> bool {
        self.illumination == Illumination::Highlight
            && (self.specular.iter().any(|&c| c > 0.0) && self.shininess.is_finite())
    }
}

/// A light source, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Light from a direction (the direction the light travels).
    Directional {
        /// Direction of travel, need not be normalised.
        direction: DVec3,
        /// Linear RGB intensity.
        color: [f32; 3],
    },
    /// Light from a point, without fall-off.
    Point {
        /// Position in world space.
        position: DVec3,
        /// Linear RGB intensity.
        color: [f32; 3],
    },
}

/// A triangle mesh: one material, or one per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Name (OBJ object or group, or generator name).
    pub name: String,
    /// Vertex positions, world space. `f64` so that huge coordinates with
    /// small triangles survive until the camera transform.
    pub positions: Vec<DVec3>,
    /// Optional per-vertex normals (same length as `positions` when present).
    pub normals: Vec<Vec3>,
    /// Optional per-vertex texture coordinates (same length as `positions`
    /// when present).
    pub uvs: Vec<Vec2>,
    /// Optional per-vertex colours, linear RGB in [0, 1] (OBJ's `v x y z r
    /// g b`; same length as `positions` when present): the diffuse colour,
    /// interpolated across each triangle, in place of the material's `Kd`.
    pub colors: Vec<[f32; 3]>,
    /// Triangles as indices into `positions`.
    pub indices: Vec<[u32; 3]>,
    /// Index into [`Scene::materials`], or `None` for the default material.
    pub material: Option<usize>,
    /// Optional per-triangle materials (same length as `indices` when
    /// present): the index into [`Scene::materials`] of each triangle, in
    /// place of [`Self::material`], so that one mesh can hold faces of
    /// several materials (a material per face, as a CAD export or a
    /// per-face colour array gives). For the default look on some faces,
    /// push [`Material::default`] and name it. Empty: every triangle has
    /// [`Self::material`].
    pub triangle_materials: Vec<u32>,
}

impl Mesh {
    /// Whether every position is finite: one branch-free pass (it
    /// vectorises), which [`Scene::validate`] and the builders of scenes
    /// from arrays run on every frame before looking for a culprit.
    pub fn positions_finite(&self) -> bool {
        self.positions.iter().fold(true, |ok, p| {
            ok & p.x.is_finite() & p.y.is_finite() & p.z.is_finite()
        })
    }

    /// The material index of triangle `t`: its entry of
    /// [`Self::triangle_materials`] when there are any, else
    /// [`Self::material`] (`None` for the default material).
    pub fn triangle_material(&self, t: usize) -> Option<usize> {
        match self.triangle_materials.get(t) {
            Some(&k) => Some(k as usize),
            None => self.material,
        }
    }
}

/// A whole scene: what the front end turns into a [`crate::ScreenScene`].
///
/// Primitive ids are the positions of triangles in the concatenation of
/// all meshes' `indices`, in order; for an OBJ file that is the order of
/// its `f` lines after fan-splitting polygons.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The meshes, in primitive-id order.
    pub meshes: Vec<Mesh>,
    /// The materials meshes refer to.
    pub materials: Vec<Material>,
    /// Lights; empty means "head light" shading.
    pub lights: Vec<Light>,
    /// A camera the scene suggests (procedural scenes set one); the fit
    /// camera is used when absent.
    pub camera: Option<Camera>,
    /// Non-fatal problems found while loading (a missing MTL, dropped
    /// degenerate faces, ...), for the user to see.
    pub warnings: Vec<String>,
    /// The files the scene was read from besides its textures (which its
    /// materials name): the OBJ and each MTL file it loaded, for a caller
    /// that must not overwrite an input (`hider render` refuses such
    /// outputs). Empty for generated scenes and scenes built in memory.
    pub source_files: Vec<std::path::PathBuf>,
}

impl Scene {
    /// Number of triangles (primitive ids are `0..triangle_count()`).
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.indices.len()).sum()
    }

    /// Every triangle as `(primitive id, mesh index, triangle index in mesh)`,
    /// in primitive-id order.
    pub fn triangles(&self) -> impl Iterator<Item = (u32, usize, usize)> + '_ {
        self.meshes
            .iter()
            .enumerate()
            .flat_map(|(m, mesh)| (0..mesh.indices.len()).map(move |t| (m, t)))
            .enumerate()
            .map(|(id, (m, t))| (id as u32, m, t))
    }

    /// Whether a texture can show: a material names one (`map_Kd`) and a
    /// mesh that uses it has texture coordinates.
    pub fn is_textured(&self) -> bool {
        self.meshes.iter().any(|mesh| {
            !mesh.uvs.is_empty()
                && self
                    .mesh_materials(mesh)
                    .any(|m| m.is_some_and(|m| m.diffuse_texture.is_some()))
        })
    }

    /// Whether some primitive's colour can vary across it under Lambert
    /// shading: a texture ([`Self::is_textured`]), vertex colours, vertex
    /// normals on a lit material (smooth shading), or highlights. A colour-resolving hider
    /// then shades per point, from the per-primitive data of the shared
    /// front end.
    pub fn varies_per_point(&self) -> bool {
        self.is_textured()
            || self.meshes.iter().any(|mesh| !mesh.colors.is_empty())
            || self.materials.iter().any(Material::has_highlights)
            || self.meshes.iter().any(|mesh| {
                !mesh.normals.is_empty()
                    && self
                        .mesh_materials(mesh)
                        .any(|m| m.is_none_or(|m| m.illumination != Illumination::Color))
            })
    }

    /// The material `mesh` names, `None` for the default material (the
    /// front ends' [`Material::default`]; an index out of range, which
    /// [`Self::validate`] refuses, also gives `None`).
    pub fn mesh_material(&self, mesh: &Mesh) -> Option<&Material> {
        mesh.material.and_then(|i| self.materials.get(i))
    }

    /// Every material `mesh`'s triangles use, each once, in index order
    /// (`None` for the default material): [`Self::mesh_material`] alone,
    /// or those of [`Mesh::triangle_materials`].
    pub fn mesh_materials<'a>(
        &'a self,
        mesh: &Mesh,
    ) -> impl Iterator<Item = Option<&'a Material>> + 'a {
        let indices: Vec<Option<usize>> = if mesh.triangle_materials.is_empty() {
            vec![mesh.material]
        } else {
            let mut used: Vec<usize> = mesh
                .triangle_materials
                .iter()
                .map(|&k| k as usize)
                .collect();
            used.sort_unstable();
            used.dedup();
            used.into_iter().map(Some).collect()
        };
        indices
            .into_iter()
            .map(|k| k.and_then(|i| self.materials.get(i)))
    }

    /// The material of triangle `t` of mesh `m` ([`Mesh::triangle_material`]),
    /// `None` for the default material.
    pub fn triangle_material(&self, m: usize, t: usize) -> Option<&Material> {
        self.meshes[m]
            .triangle_material(t)
            .and_then(|i| self.materials.get(i))
    }

    /// The world-space corners of triangle `t` of mesh `m`.
    pub fn triangle_positions(&self, m: usize, t: usize) -> [DVec3; 3] {
        let mesh = &self.meshes[m];
        mesh.indices[t].map(|i| mesh.positions[i as usize])
    }

    /// The axis-aligned bounding box of all vertices used by triangles, or
    /// `None` for a scene without triangles.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        let mut any = false;
        for mesh in &self.meshes {
            any |= !mesh.indices.is_empty();
            if mesh.positions.len() * 2 < mesh.indices.len() * 3 {
                // Vertices shared by several triangles (a closed mesh has
                // about half as many as triangles): mark the ones used,
                // then take the extremes over the positions in order, a
                // third of the lookups and the min-max once per vertex.
                let mut used = vec![false; mesh.positions.len()];
                for &i in mesh.indices.as_flattened() {
                    used[i as usize] = true;
                }
                for (&p, &u) in mesh.positions.iter().zip(&used) {
                    if u {
                        lo = lo.min(p);
                        hi = hi.max(p);
                    }
                }
                continue;
            }
            for tri in &mesh.indices {
                for &i in tri {
                    let p = mesh.positions[i as usize];
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
        }
        any.then_some((lo, hi))
    }

    /// Checks that the scene is well formed: indices in range, finite
    /// positions, normals and uvs of matching length, valid material
    /// references and opacities. The loaders and generators produce valid
    /// scenes; call this on scenes built by hand.
    pub fn validate(&self) -> Result<()> {
        for (m, mesh) in self.meshes.iter().enumerate() {
            self.check_geometry(m, mesh)?;
            self.check_structure(m, mesh)?;
        }
        self.check_materials()
    }

    /// The part of [`Self::validate`] that does not read every vertex and
    /// index: attribute lengths, material references and opacities. The
    /// lean front end runs this, and finds non-finite positions and
    /// indices out of range in the passes it makes over them anyway (then
    /// [`Self::validate`] names the culprit).
    pub(crate) fn validate_structure(&self) -> Result<()> {
        for (m, mesh) in self.meshes.iter().enumerate() {
            self.check_structure(m, mesh)?;
        }
        self.check_materials()
    }

    /// Finite positions and indices in range.
    fn check_geometry(&self, m: usize, mesh: &Mesh) -> Result<()> {
        let n = mesh.positions.len();
        // Every frame's front end validates: branch-free passes (which
        // vectorise) first, the search for the culprit only on failure.
        let finite = mesh.positions_finite();
        let max_index = mesh.indices.as_flattened().iter().fold(0, |m, &i| m.max(i));
        if finite && ((max_index as usize) < n || mesh.indices.is_empty()) {
            return Ok(());
        }
        if let Some((v, p)) = mesh
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite())
        {
            return Err(Error::InvalidScene(format!(
                "mesh {m} ('{}') vertex {v} has a non-finite position {p}",
                mesh.name
            )));
        }
        for (t, tri) in mesh.indices.iter().enumerate() {
            if let Some(&i) = tri.iter().find(|&&i| i as usize >= n) {
                return Err(Error::InvalidScene(format!(
                    "mesh {m} ('{}') triangle {t} uses vertex {i}, but the mesh has {n} vertices",
                    mesh.name
                )));
            }
        }
        Ok(())
    }

    /// Attribute lengths and the material reference of one mesh.
    fn check_structure(&self, m: usize, mesh: &Mesh) -> Result<()> {
        let n = mesh.positions.len();
        for (what, len) in [
            ("normals", mesh.normals.len()),
            ("uvs", mesh.uvs.len()),
            ("colours", mesh.colors.len()),
        ] {
            if len != 0 && len != n {
                return Err(Error::InvalidScene(format!(
                    "mesh {m} ('{}') has {len} {what} for {n} vertices",
                    mesh.name
                )));
            }
        }
        if let Some(k) = mesh.material
            && k >= self.materials.len()
        {
            return Err(Error::InvalidScene(format!(
                "mesh {m} ('{}') uses material {k}, but there are {}",
                mesh.name,
                self.materials.len()
            )));
        }
        let per_triangle = mesh.triangle_materials.len();
        if per_triangle != 0 && per_triangle != mesh.indices.len() {
            return Err(Error::InvalidScene(format!(
                "mesh {m} ('{}') has {per_triangle} triangle materials for {} triangles",
                mesh.name,
                mesh.indices.len()
            )));
        }
        if let Some((t, k)) = mesh
            .triangle_materials
            .iter()
            .enumerate()
            .find(|&(_, &k)| k as usize >= self.materials.len())
        {
            return Err(Error::InvalidScene(format!(
                "mesh {m} ('{}') triangle {t} uses material {k}, but there are {}",
                mesh.name,
                self.materials.len()
            )));
        }
        Ok(())
    }

    /// Opacities in [0, 1].
    fn check_materials(&self) -> Result<()> {
        for mat in &self.materials {
            if !(0.0..=1.0).contains(&mat.opacity) {
                return Err(Error::InvalidScene(format!(
                    "material '{}' has opacity {} outside [0, 1]",
                    mat.name, mat.opacity
                )));
            }
        }
        Ok(())
    }

    /// A scene of one plain mesh (no material, normals or texture
    /// coordinates) with these positions and triangles.
    pub fn from_mesh(positions: Vec<DVec3>, indices: Vec<[u32; 3]>) -> Self {
        let mut scene = Self::default();
        scene.push_mesh(
            Mesh {
                positions,
                indices,
                ..Mesh::default()
            },
            None,
        );
        scene
    }

    /// A triangle soup: one plain mesh whose triangle `k` is positions
    /// `3k`, `3k + 1` and `3k + 2` (one or two positions left over at the
    /// end belong to no triangle).
    pub fn from_triangles(positions: Vec<DVec3>) -> Self {
        let indices = (0..(positions.len() / 3) as u32)
            .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
            .collect();
        Self::from_mesh(positions, indices)
    }

    /// Appends a mesh with its own material, returning the mesh index.
    pub fn push_mesh(&mut self, mut mesh: Mesh, material: Option<Material>) -> usize {
        if let Some(mat) = material {
            self.materials.push(mat);
            mesh.material = Some(self.materials.len() - 1);
        }
        self.meshes.push(mesh);
        self.meshes.len() - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri_scene() -> Scene {
        let mut s = Scene::default();
        s.push_mesh(
            Mesh {
                name: "t".into(),
                positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
                indices: vec![[0, 1, 2], [0, 2, 1]],
                ..Mesh::default()
            },
            None,
        );
        s
    }

    /// A mesh names its material by index, or none for the default.
    #[test]
    fn a_mesh_names_its_material_or_the_default() {
        let mut s = tri_scene();
        let glass = Material {
            name: "glass".into(),
            opacity: 0.5,
            ..Material::default()
        };
        s.push_mesh(s.meshes[0].clone(), Some(glass.clone()));
        assert_eq!(s.mesh_material(&s.meshes[0]), None);
        assert_eq!(s.mesh_material(&s.meshes[1]), Some(&glass));
        let mut stray = s.meshes[1].clone();
        stray.material = Some(7);
        assert_eq!(s.mesh_material(&stray), None);
    }

    #[test]
    fn ids_run_over_meshes_in_order() {
        let mut s = tri_scene();
        s.push_mesh(s.meshes[0].clone(), None);
        let ids: Vec<_> = s.triangles().collect();
        assert_eq!(ids.len(), 4);
        assert_eq!(ids[3], (3, 1, 1));
        assert_eq!(s.triangle_count(), 4);
    }

    #[test]
    fn validate_names_the_bad_item() {
        let mut s = tri_scene();
        assert!(s.validate().is_ok());
        s.meshes[0].indices[1][2] = 7;
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains("triangle 1") && e.contains("vertex 7"), "{e}");
        let mut s = tri_scene();
        s.meshes[0].positions[2].y = f64::NAN;
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains("vertex 2") && e.contains("NaN"), "{e}");
    }

    #[test]
    fn bounds_of_empty_scene_is_none() {
        assert!(Scene::default().bounds().is_none());
        assert_eq!(
            tri_scene().bounds(),
            Some((DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0)))
        );
    }
}
