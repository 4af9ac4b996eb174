//! Output files are never damaged: a replaced file keeps its permissions,
//! an output that is an input or another output is refused before any
//! work, and an output that cannot be written stops the run before any
//! other output is written.

use std::os::unix::fs::PermissionsExt;
use std::path::PathBuf;
use std::process::{Command, Output};

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-outputs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn hider(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn a_replaced_file_keeps_its_permissions() {
    let dir = folder("perms");
    let png = dir.join("out.png");
    let ids = dir.join("out.i32");
    for p in [&png, &ids] {
        std::fs::write(p, "old").unwrap();
        std::fs::set_permissions(p, std::fs::Permissions::from_mode(0o600)).unwrap();
    }
    let out = hider(&[
        "render",
        "gen:cube",
        "--size",
        "16",
        "-o",
        png.to_str().unwrap(),
        "--ids-out",
        ids.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    for p in [&png, &ids] {
        let mode = std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o600, "{}", p.display());
        assert_ne!(std::fs::read(p).unwrap(), b"old");
    }
}

#[test]
fn an_output_that_is_an_input_or_another_output_is_refused() {
    let dir = folder("clobber");
    let model = dir.join("model.obj");
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::fs::write(&model, text).unwrap();
    let m = model.to_str().unwrap();
    let out = hider(&["render", m, "-o", m]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("is an input"), "{}", stderr(&out));
    assert_eq!(
        std::fs::read_to_string(&model).unwrap(),
        text,
        "the model was replaced"
    );
    let same = dir.join("same.bin");
    let s = same.to_str().unwrap();
    let out = hider(&["render", m, "-o", s, "--ids-out", s, "--depth-out", s]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("the same file as -o"),
        "{}",
        stderr(&out)
    );
    assert!(!same.exists());
}

#[test]
fn every_file_the_scene_was_read_from_is_an_input() {
    // The MTL file, each texture (`map_Kd`, `map_d`), and any other name
    // for them (a symbolic or a hard link) are inputs as much as the OBJ.
    let dir = folder("sources");
    let png = |w: u32| {
        let mut bytes = Vec::new();
        image::RgbaImage::from_pixel(w, w, image::Rgba([200, 100, 50, 255]))
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
            .unwrap();
        bytes
    };
    std::fs::write(dir.join("colour.png"), png(4)).unwrap();
    std::fs::write(dir.join("mask.png"), png(2)).unwrap();
    let mtl = "newmtl m\nKd 1 1 1\nmap_Kd colour.png\nmap_d mask.png\n";
    std::fs::write(dir.join("m.mtl"), mtl).unwrap();
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n";
    let model = dir.join("model.obj");
    std::fs::write(&model, obj).unwrap();
    std::os::unix::fs::symlink(dir.join("colour.png"), dir.join("soft.png")).unwrap();
    std::fs::hard_link(dir.join("m.mtl"), dir.join("hard.mtl")).unwrap();
    let before: Vec<Vec<u8>> = ["m.mtl", "colour.png", "mask.png"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect();
    for (flag, target) in [
        ("-o", "m.mtl"),
        ("-o", "colour.png"),
        ("--ids-out", "mask.png"),
        ("-o", "soft.png"),
        ("--depth-out", "hard.mtl"),
    ] {
        let (path, png) = (dir.join(target), dir.join("x.png"));
        let mut args = vec!["render", model.to_str().unwrap(), "--size", "16"];
        if flag != "-o" {
            args.extend(["-o", png.to_str().unwrap()]);
        }
        args.extend([flag, path.to_str().unwrap()]);
        let out = hider(&args);
        assert_eq!(out.status.code(), Some(2), "{target}: {}", stderr(&out));
        assert!(
            stderr(&out).contains("is an input"),
            "{target}: {}",
            stderr(&out)
        );
    }
    let after: Vec<Vec<u8>> = ["m.mtl", "colour.png", "mask.png"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect();
    assert_eq!(before, after, "an input was replaced");
    // A new file beside them is fine.
    let fine = dir.join("out.png");
    let out = hider(&[
        "render",
        model.to_str().unwrap(),
        "--size",
        "16",
        "-o",
        fine.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn an_unwritable_output_stops_the_run_before_any_output() {
    let dir = folder("nodir");
    let png = dir.join("a.png");
    let ids = dir.join("nodir").join("a.i32");
    let out = hider(&[
        "render",
        "gen:cube",
        "--size",
        "16",
        "-o",
        png.to_str().unwrap(),
        "--ids-out",
        ids.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("does not exist"), "{}", stderr(&out));
    assert!(!png.exists(), "a.png was written");
    let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// The hider is asked only for the buffers the outputs need (the ids
/// for `--ids-out` and the colour pass, the depth for `--depth-out`), and
/// the files do not change: the tiled z-buffer, which writes only what is
/// asked, gives the PNG and ids of the plain z-buffer, which writes
/// everything, with and without `--depth-out`, on a textured model and a
/// generated one; the depth files agree too.
#[test]
fn outputs_do_not_depend_on_the_buffers_asked_for() {
    let dir = folder("buffers");
    let checker = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/checker_plane.obj");
    for model in [checker, "gen:sphere:12"] {
        let mut runs = Vec::new();
        for algo in ["zbuffer-tiled", "zbuffer"] {
            for depth in [false, true] {
                let tag = format!("{algo}-{depth}");
                let png = dir.join(format!("{tag}.png"));
                let ids = dir.join(format!("{tag}.i32"));
                let z = dir.join(format!("{tag}.f32"));
                let (png_s, ids_s, z_s) = (
                    png.to_str().unwrap(),
                    ids.to_str().unwrap(),
                    z.to_str().unwrap(),
                );
                let mut args = vec!["render", model, "--size", "48", "--algo", algo];
                args.extend(["-o", png_s, "--ids-out", ids_s]);
                if depth {
                    args.extend(["--depth-out", z_s]);
                }
                let out = hider(&args);
                assert!(out.status.success(), "{args:?}: {}", stderr(&out));
                let read = |p: &PathBuf| std::fs::read(p).unwrap();
                runs.push((tag, read(&png), read(&ids), depth.then(|| read(&z))));
            }
        }
        let (first, png, ids, _) = &runs[0];
        for (tag, p, i, _) in &runs[1..] {
            assert!(p == png, "{model}: the PNG of {tag} differs from {first}'s");
            assert!(i == ids, "{model}: the ids of {tag} differ from {first}'s");
        }
        assert!(runs[1].3 == runs[3].3, "{model}: the depth files differ");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
