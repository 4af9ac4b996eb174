//! Writes the scenes of the llvmpipe comparison
//! ([`programs::llvmpipe_scenes`]: the spider, the UV spheres of 200 and
//! 500 segments, the soup of 100k triangles) as OBJ files into a folder,
//! for the programs outside Rust that time the same scenes (the Python
//! package's `benchmarks/frames.py`).
//!
//! Each scene goes through [`hider_scene::obj_write::save_obj`], the
//! spider included (its loaded scene, not a copy of its file), so all four
//! take one path: `v x y z` in Rust's shortest round-trip form, `f a b c`
//! 1-based, one mesh after the other with its vertex offset, triangles in
//! primitive-id order, so that a reader that numbers the `f` lines from 0
//! gets the ids hider reports. A file is named after the scene with its
//! spaces made underscores (`sphere_200.obj`). Every file is loaded back
//! and its triangles' corners compared with the scene's before the next
//! is written; the fit camera, which depends on those corners only, is
//! then the same on both sides (a scene with a camera of its own is
//! refused).
//!
//! `cargo run --release -p hider-bench --bin export_scenes -- FOLDER`

use std::path::{Path, PathBuf};

use hider_bench::programs;
use hider_scene::{Scene, glam::DVec3, load_obj, obj_write::save_obj};

/// The file a scene called `name` is written to in `folder`.
fn scene_path(folder: &Path, name: &str) -> PathBuf {
    folder.join(format!("{}.obj", name.replace(' ', "_")))
}

/// The corners of every triangle of `scene`, in primitive-id order: what
/// a renderer sees of it, whatever the vertex numbering.
fn corners(scene: &Scene) -> Vec<[DVec3; 3]> {
    scene
        .meshes
        .iter()
        .flat_map(|m| m.indices.iter().map(|t| t.map(|i| m.positions[i as usize])))
        .collect()
}

/// Writes `scene` to `path` and loads it back: an error when the file's
/// triangles are not the scene's, corner for corner, in the same order.
fn export(scene: &Scene, path: &Path) -> Result<usize, String> {
    // An OBJ file has no camera: a scene with one would be seen through
    // another (the fit camera) by whoever reads the file.
    if scene.camera.is_some() {
        return Err(format!(
            "{}: the scene has a camera of its own, which OBJ cannot carry",
            path.display()
        ));
    }
    save_obj(scene, path).map_err(|e| e.to_string())?;
    let back = load_obj(path).map_err(|e| e.to_string())?;
    let (want, got) = (corners(scene), corners(&back));
    if want.len() != got.len() {
        return Err(format!(
            "{}: {} triangles read back, {} written",
            path.display(),
            got.len(),
            want.len()
        ));
    }
    if let Some(id) = want.iter().zip(&got).position(|(a, b)| a != b) {
        return Err(format!(
            "{}: triangle {id} reads back as {:?}, written as {:?}",
            path.display(),
            got[id],
            want[id]
        ));
    }
    Ok(want.len())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [folder] = args.as_slice() else {
        return Err("usage: export_scenes FOLDER".into());
    };
    let folder = Path::new(folder);
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    for (name, scene) in programs::llvmpipe_scenes() {
        let path = scene_path(folder, name);
        let triangles = export(&scene, &path)?;
        println!("{name}: {triangles} triangles -> {}", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::procedural;

    #[test]
    fn exported_scenes_read_back_triangle_for_triangle() {
        let folder = std::env::temp_dir().join(format!("hider-export-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        // Two meshes in one scene: the second's indices need the offset.
        let mut scene = procedural::uv_sphere(6);
        for m in procedural::random_soup(40, 3).meshes {
            scene.push_mesh(m, None);
        }
        let path = scene_path(&folder, "sphere and soup");
        assert_eq!(path.file_name().unwrap(), "sphere_and_soup.obj");
        assert_eq!(export(&scene, &path), Ok(scene.triangle_count()));
        let back = load_obj(&path).unwrap();
        assert_eq!(corners(&back), corners(&scene));
        // Compared exactly: the positions went through the text in
        // round-trip form (the loader numbers the vertices in the order
        // of first use, so the corners are compared, not the arrays).
        assert_eq!(back.triangle_count(), scene.triangle_count());
        // A camera would be lost on the way.
        scene.camera = Some(hider_scene::fit_camera(&scene));
        assert!(export(&scene, &path).is_err());
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
