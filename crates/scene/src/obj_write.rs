//! Writing scenes as OBJ + MTL, so generated scenes can be bundled as
//! assets and opened in other tools.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use crate::model::Scene;

/// The OBJ and MTL text of a scene. The OBJ refers to the MTL as
/// `mtl_name`; every mesh becomes an `o` block, its faces under `usemtl`
/// statements wherever their material changes. Numbers
/// are written in Rust's shortest round-trip form, so loading the text
/// gives back the same `f64` positions.
pub fn to_obj_text(scene: &Scene, mtl_name: &str) -> (String, String) {
    let mut obj = String::new();
    let mut mtl = String::new();
    let _ = writeln!(obj, "# written by hider");
    if !scene.materials.is_empty() {
        let _ = writeln!(obj, "mtllib {mtl_name}");
    }
    for m in &scene.materials {
        let [r, g, b] = m.diffuse;
        let _ = writeln!(
            mtl,
            "newmtl {}\nKd {r:?} {g:?} {b:?}\nd {:?}\n",
            m.name, m.opacity
        );
    }
    let mut base = 1usize;
    for mesh in &scene.meshes {
        let name = if mesh.name.is_empty() {
            "mesh"
        } else {
            &mesh.name
        };
        let _ = writeln!(obj, "o {name}");
        // A mesh of one material names it once, before its vertices; one
        // with per-triangle materials gets a `usemtl` at each change.
        let mut current = mesh
            .triangle_materials
            .is_empty()
            .then_some(mesh.material)
            .flatten();
        if let Some(k) = current {
            let _ = writeln!(obj, "usemtl {}", scene.materials[k].name);
        }
        for p in &mesh.positions {
            let _ = writeln!(obj, "v {:?} {:?} {:?}", p.x, p.y, p.z);
        }
        for (k, t) in mesh.indices.iter().enumerate() {
            let material = mesh.triangle_material(k);
            if material.is_some() && material != current {
                let name = &scene.materials[material.unwrap_or_default()].name;
                let _ = writeln!(obj, "usemtl {name}");
                current = material;
            }
            let _ = writeln!(
                obj,
                "f {} {} {}",
                base + t[0] as usize,
                base + t[1] as usize,
                base + t[2] as usize
            );
        }
        base += mesh.positions.len();
    }
    (obj, mtl)
}

/// Writes `path` (OBJ) and, if the scene has materials, an MTL of the same
/// stem beside it; both atomically.
pub fn save_obj(scene: &Scene, path: &Path) -> Result<()> {
    let mtl_path = path.with_extension("mtl");
    let mtl_name = mtl_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene.mtl".into());
    let (obj, mtl) = to_obj_text(scene, &mtl_name);
    let put = |p: &Path, text: &str| {
        write_atomic(p, |w| {
            w.write_all(text.as_bytes()).map_err(|source| Error::Io {
                path: p.to_path_buf(),
                source,
            })
        })
    };
    if !scene.materials.is_empty() {
        put(&mtl_path, &mtl)?;
    }
    put(path, &obj)
}

#[cfg(all(test, feature = "obj"))]
mod tests {
    use super::*;
    use crate::procedural;

    #[test]
    fn written_scenes_load_back_identically() {
        let dir = std::env::temp_dir().join(format!("hider-objw-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for scene in [
            procedural::cube(),
            procedural::cyclic_triple(),
            procedural::uv_sphere(5),
        ] {
            let path = dir.join("s.obj");
            save_obj(&scene, &path).unwrap();
            let back = crate::obj::load_obj(&path).unwrap();
            assert_eq!(back.triangle_count(), scene.triangle_count());
            let a: Vec<_> = scene
                .triangles()
                .map(|(_, m, t)| scene.triangle_positions(m, t))
                .collect();
            let b: Vec<_> = back
                .triangles()
                .map(|(_, m, t)| back.triangle_positions(m, t))
                .collect();
            assert_eq!(a, b);
            let mat = |s: &Scene, k: usize| s.materials[s.meshes[k].material.unwrap()].diffuse;
            assert_eq!(mat(&scene, 0), mat(&back, 0));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
