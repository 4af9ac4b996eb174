//! Warnings `hider render` owes its user instead of a wrong picture
//! without a word: a hider that keeps one surface per sample draws
//! translucent surfaces opaque, and says so, naming the hider that
//! composites them; fragments the A-buffer drops are counted in a warning.

use std::path::PathBuf;
use std::process::Command;

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets")
}

#[test]
fn hiders_that_cannot_composite_warn_on_translucent_scenes() {
    let dir = std::env::temp_dir().join(format!("hider-glass-warning-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for file in ["checker_plane.obj", "checker.png"] {
        std::fs::copy(assets().join(file), dir.join(file)).unwrap();
    }
    let mtl = std::fs::read_to_string(assets().join("checker_plane.mtl")).unwrap();
    assert!(mtl.contains("\nd 1"), "{mtl}");
    std::fs::write(
        dir.join("checker_plane.mtl"),
        mtl.replace("\nd 1", "\nd 0.6"),
    )
    .unwrap();
    let model = dir.join("checker_plane.obj");
    let out = dir.join("out.png");
    for (algo, warns) in [
        ("ssaa-8", true),
        ("warnock-4x4", true),
        ("zbuffer", true),
        ("abuffer", false),
        ("abuffer-carpenter", false),
        ("ssaa-sorted", false),
        ("auto", false),
    ] {
        let run = Command::new(env!("CARGO_BIN_EXE_hider"))
            .args([
                "render",
                model.to_str().unwrap(),
                "--size",
                "32",
                "--algo",
                algo,
            ])
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{algo}: {stderr}");
        let warned = stderr.contains("draws them opaque; the A-buffer (abuffer) composites them");
        assert_eq!(warned, warns, "{algo}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Fragments the A-buffer drops from full pixel lists are named in a
/// warning, not lost silently: 200 translucent copies of one face are more
/// layers than a list holds (128).
#[test]
fn dropped_fragments_are_a_warning() {
    let dir = std::env::temp_dir().join(format!("hider-dropped-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut obj =
        String::from("mtllib glass.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl glass\n");
    for _ in 0..200 {
        obj.push_str("f 1 2 3 4\n");
    }
    std::fs::write(dir.join("layers.obj"), obj).unwrap();
    std::fs::write(
        dir.join("glass.mtl"),
        "newmtl glass\nKd 0.5 0.7 0.9\nd 0.3\n",
    )
    .unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(["render", "--size", "16", "--algo", "abuffer"])
        .arg(dir.join("layers.obj"))
        .arg("-o")
        .arg(dir.join("out.png"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let line = stderr
        .lines()
        .find(|l| l.starts_with("hider: warning: abuffer dropped "))
        .unwrap_or_else(|| panic!("no dropped-fragment warning in: {stderr}"));
    assert!(line.contains("fragments"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A texture over the size limit is dropped with a warning naming the
/// file and its size (issue 37: a 30000-texel texture was dropped by
/// `render` without a word naming it). The header is read, never the
/// texels.
#[test]
fn an_oversized_texture_is_named() {
    let dir = std::env::temp_dir().join(format!("hider-huge-texture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    image::RgbImage::new(30_000, 1)
        .save(dir.join("huge.png"))
        .unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd huge.png\n").unwrap();
    let obj = dir.join("m.obj");
    std::fs::write(
        &obj,
        "mtllib m.mtl\nusemtl m\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0.5 1\n\
         f 1/1 2/2 3/3\n",
    )
    .unwrap();
    for algo in ["auto", "zbuffer", "abuffer"] {
        let run = Command::new(env!("CARGO_BIN_EXE_hider"))
            .args(["render", "--size", "16", "--algo", algo])
            .arg(&obj)
            .arg("-o")
            .arg(dir.join("out.png"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{algo}: {stderr}");
        assert!(
            stderr.contains("huge.png") && stderr.contains("30000") && stderr.contains("8192"),
            "{algo}: {stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
