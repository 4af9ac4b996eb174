//! A hider that keeps one surface per sample draws translucent surfaces
//! opaque; `hider render` says so, naming the hider that composites them,
//! instead of writing a wrong picture without a word.

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
        let warned = stderr.contains("draws them opaque; --algo abuffer composites them");
        assert_eq!(warned, warns, "{algo}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
