//! The texture memory budget (issue 37, item 5): decoded texture bytes are
//! counted before a texture is decoded; a texture over the budget is
//! refused with a warning naming the file, its size and the limit, and is
//! drawn with its material's colour; the bytes in use never exceed the
//! budget. Textures are decoded down to the mip level the screen needs, so
//! a large texture on a small triangle costs a small level.
//!
//! One test in this binary: the budget is the process's.

mod library_support;
use library_support::library_frame;

use std::path::Path;

use hider::scene::shade::{set_texture_budget, texture_budget, texture_bytes_in_use};
use hider::scene::{Scene, load_obj};

const SIZE: u32 = 64;

/// Six 256 x 256 RGB textures on six quads side by side, each seen at
/// about 8 pixels across (so their level 5 is what a pixel needs), and one
/// more quad filling the lower half of the view with a fiftieth of a seventh
/// texture, under a texel per pixel (level 0).
fn scene(dir: &Path) -> Scene {
    std::fs::create_dir_all(dir).unwrap();
    // uvs 1-4 span a texture once; 5-8 a fiftieth of it, so the large quad
    // samples under a texel per pixel.
    let mut obj = String::from(
        "mtllib m.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0 0\nvt 0.02 0\nvt 0.02 0.02\nvt 0 0.02\n",
    );
    let mut mtl = String::new();
    for k in 0..7 {
        let shade = 40 + 30 * k as u8;
        image::RgbImage::from_pixel(256, 256, image::Rgb([shade, 255 - shade, 90]))
            .save(dir.join(format!("t{k}.png")))
            .unwrap();
        mtl.push_str(&format!("newmtl m{k}\nKd 1 1 1\nmap_Kd t{k}.png\n"));
        let (x0, x1, y0, y1) = if k < 6 {
            let x = -3.0 + k as f64;
            (x, x + 0.9, 0.2, 1.1)
        } else {
            (-3.0, 3.0, -3.0, -0.1)
        };
        let v = 4 * k + 1;
        let t = if k < 6 { 1 } else { 5 };
        obj.push_str(&format!(
            "usemtl m{k}\nv {x0} {y0} 0\nv {x1} {y0} 0\nv {x1} {y1} 0\nv {x0} {y1} 0\n\
             f {}/{} {}/{} {}/{}\nf {}/{} {}/{} {}/{}\n",
            v,
            t,
            v + 1,
            t + 1,
            v + 2,
            t + 2,
            v,
            t,
            v + 2,
            t + 2,
            v + 3,
            t + 3
        ));
    }
    std::fs::write(dir.join("m.mtl"), mtl).unwrap();
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    load_obj(dir.join("m.obj")).unwrap()
}

#[test]
fn textures_stay_within_the_budget() {
    let dir = std::env::temp_dir().join(format!("hider-texture-budget-{}", std::process::id()));
    let default = texture_budget();
    assert_eq!(default, hider::scene::shade::DEFAULT_TEXTURE_BUDGET);

    // Unbounded: each small quad holds only the coarse levels it needs,
    // far less than its full chain (256^2 x 3 x 4/3 = 262,144 bytes).
    let scene_a = scene(&dir.join("a"));
    library_frame("zbuffer", &scene_a, SIZE);
    let small: Vec<usize> = scene_a.materials[..6]
        .iter()
        .map(|m| m.diffuse_texture.as_ref().unwrap().bytes())
        .collect();
    assert!(
        small.iter().all(|&b| b > 0 && b < 262_144 / 16),
        "{small:?}"
    );
    let big = scene_a.materials[6]
        .diffuse_texture
        .as_ref()
        .unwrap()
        .bytes();
    assert!(big >= 262_144 / 4, "{big}");
    let needed = texture_bytes_in_use();
    drop(scene_a);
    assert_eq!(texture_bytes_in_use(), 0, "the bytes are returned");

    // A budget below what the frame needs: the bytes in use never exceed
    // it, and the textures refused are named with their size and the
    // limit, and drawn with the material's colour (white).
    let limit = (needed as u64) / 2;
    set_texture_budget(limit);
    let scene_b = scene(&dir.join("b"));
    let frame = library_frame("zbuffer", &scene_b, SIZE);
    assert!(texture_bytes_in_use() <= limit);
    let refused: Vec<String> = scene_b
        .materials
        .iter()
        .filter_map(|m| m.diffuse_texture.as_ref()?.problem())
        .collect();
    assert!(!refused.is_empty());
    for why in &refused {
        assert!(why.contains(".png"), "{why}");
        assert!(why.contains("256x256"), "{why}");
        assert!(why.contains("over the texture budget"), "{why}");
        assert!(why.contains("--texture-budget"), "{why}");
    }
    assert!(
        frame
            .color
            .iter()
            .any(|c| c[0] == c[1] && c[1] == c[2] && c[0] > 100),
        "a refused texture shows its (white, lit) material colour"
    );
    drop(scene_b);
    set_texture_budget(default);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The command line's `--texture-budget`: a budget under one texture's
/// size draws it in the material's colour and says so, naming the file,
/// its size and the limit; a bad value is refused naming the flag.
#[test]
fn the_command_line_sets_the_budget() {
    let dir = std::env::temp_dir().join(format!("hider-texture-flag-{}", std::process::id()));
    let _ = scene(&dir);
    let run = |budget: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_hider"))
            .args(["render", "--size", "32", "--texture-budget", budget])
            .arg(dir.join("m.obj"))
            .arg("-o")
            .arg(dir.join("out.png"))
            .output()
            .unwrap()
    };
    let tight = run("1K");
    let stderr = String::from_utf8_lossy(&tight.stderr);
    assert!(tight.status.success(), "{stderr}");
    assert!(
        stderr.contains("over the texture budget of 1.0 KiB"),
        "{stderr}"
    );
    assert!(stderr.contains("t6.png: 256x256 texture needs"), "{stderr}");
    let roomy = run("1G");
    assert!(roomy.status.success());
    assert!(!String::from_utf8_lossy(&roomy.stderr).contains("texture budget"));
    let bad = run("lots");
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--texture-budget"));
    std::fs::remove_dir_all(&dir).unwrap();
}
