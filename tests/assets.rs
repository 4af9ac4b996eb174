//! The bundled scenes in `assets/` are the project's own generators written
//! out as OBJ; this test keeps the two in step. Run with `HIDER_BLESS=1` to
//! rewrite the files after changing a generator.

use std::path::PathBuf;

use hider::scene::{Scene, load_obj, obj_write::to_obj_text, procedural};

fn assets() -> Vec<(&'static str, Scene)> {
    vec![
        ("cube", procedural::cube()),
        ("intersecting", procedural::intersecting_pair()),
        ("cyclic", procedural::cyclic_triple()),
        ("coplanar", procedural::coplanar_pair()),
        ("sphere", procedural::uv_sphere(24)),
    ]
}

#[test]
fn assets_match_their_generators() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets");
    let bless = std::env::var_os("HIDER_BLESS").is_some();
    for (name, scene) in assets() {
        let obj_path = dir.join(format!("{name}.obj"));
        let mtl_name = format!("{name}.mtl");
        let (obj, mtl) = to_obj_text(&scene, &mtl_name);
        if bless {
            std::fs::write(&obj_path, &obj).unwrap();
            std::fs::write(dir.join(&mtl_name), &mtl).unwrap();
        }
        let on_disk = std::fs::read_to_string(&obj_path)
            .unwrap_or_else(|e| panic!("{}: {e} (run with HIDER_BLESS=1)", obj_path.display()));
        assert_eq!(on_disk, obj, "{name}.obj is stale: run with HIDER_BLESS=1");
        let loaded = load_obj(&obj_path).unwrap();
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        assert_eq!(loaded.triangle_count(), scene.triangle_count());
        assert_eq!(loaded.materials.len(), scene.materials.len());
    }
}

/// The spider (from assimp's test models, see `assets/spider/LICENSE`)
/// loads with its five textures found: the README's first example
/// renders it.
#[test]
fn the_bundled_spider_loads_with_its_textures() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/spider/spider.obj");
    let spider = load_obj(&path).unwrap();
    assert_eq!(spider.triangle_count(), 1368);
    assert_eq!(spider.materials.len(), 5);
    for m in &spider.materials {
        let texture = m
            .diffuse_texture
            .as_ref()
            .expect("every material is textured");
        assert!(texture.path().is_file(), "{}", texture.path().display());
    }
    // Its one warning: the degenerate triangles the exporter wrote.
    assert!(
        spider.warnings.iter().all(|w| w.contains("degenerate")),
        "{:?}",
        spider.warnings
    );
}
