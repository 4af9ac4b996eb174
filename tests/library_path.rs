//! What a library user writes gives what the command line gives: for every
//! registered hider, `render_frame` (`render_scene`, the one path every
//! frame takes, then, unless the hider resolved colour itself, the colour
//! pass reading the world-space scene) equals the PNG of
//! `hider render --algo NAME`, pixel for pixel, on the textured spider and
//! on a translucent scene. No hider leaves the colour pass a black frame.

mod library_support;
use library_support::library_frame;

use std::path::PathBuf;
use std::process::Command;

use hider::plan::registry;
use hider::scene::load_obj;

const SIZE: u32 = 48;

fn cli_pixels(name: &str, model: &str, out: &std::path::Path) -> Vec<[u8; 4]> {
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(["render", model, "--size", &SIZE.to_string(), "--algo", name])
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    image::open(out)
        .unwrap()
        .to_rgba8()
        .pixels()
        .map(|p| p.0)
        .collect()
}

#[test]
fn every_hider_through_the_library_equals_the_cli() {
    let dir = std::env::temp_dir().join(format!("hider-library-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let spider = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/spider/spider.obj");
    let glass = dir.join("glass.obj");
    std::fs::write(
        dir.join("glass.mtl"),
        "newmtl glass\nKd 0.2 0.6 0.9\nd 0.5\n",
    )
    .unwrap();
    std::fs::write(
        &glass,
        "mtllib glass.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nv -1 0 -1\nv 1 0 -1\nv 0 -1 -1\n\
         f 4 5 6\nusemtl glass\nf 1 2 3\n",
    )
    .unwrap();
    let out = dir.join("out.png");
    for model in [spider, glass] {
        let scene = load_obj(&model).unwrap();
        for name in registry::names() {
            let library = library_frame(name, &scene, SIZE);
            assert!(library.covered_count() > 0, "{name}");
            let lit = library.color.iter().filter(|c| c[..3] != [0, 0, 0]).count();
            assert!(lit > 0, "{name}: a black frame");
            let cli = cli_pixels(name, model.to_str().unwrap(), &out);
            assert_eq!(library.color, cli, "{name} on {}", model.display());
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
