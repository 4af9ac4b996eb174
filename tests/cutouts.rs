//! Alpha cut-outs (issue 36): a leaf card (an RGBA `map_Kd`, an opaque
//! disc with alpha 0 around it) in front of a red wall shows the wall
//! through its transparent texels in every single-sample hider, equal to a
//! brute-force per-pixel reference; the stage runs only when a scene has
//! cut-outs. The hiders that resolve colour from several samples alpha-test
//! their own samples: see `alpha_samples.rs`.

use std::path::{Path, PathBuf};
use std::process::Command;

use hider::scene::shade::cutout::AlphaTest;
use hider::scene::{NO_ID, PrepareOptions, TextureOptions, View, load_obj, prepare};

const SIZE: u32 = 96;

/// The leaf card's texture: 64 x 64, an opaque green disc of radius 20 in
/// texels, white with alpha 0 elsewhere (white, so that a card drawn
/// opaque shows white, not red).
fn leaf_png(path: &Path) {
    let img = image::RgbaImage::from_fn(64, 64, |x, y| {
        let (dx, dy) = (f64::from(x) + 0.5 - 32.0, f64::from(y) + 0.5 - 32.0);
        if dx.hypot(dy) < 20.0 {
            image::Rgba([30, 200, 40, 255])
        } else {
            image::Rgba([255, 255, 255, 0])
        }
    });
    img.save(path).unwrap();
}

/// The card (2 x 2 at z = 0, tilted a little so its depth varies) in front
/// of a red wall (4 x 4 at z = -1), written to `dir`.
fn scene(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    leaf_png(&dir.join("leaf.png"));
    std::fs::write(
        dir.join("leaf.mtl"),
        "newmtl leaf\nKd 1 1 1\nmap_Kd leaf.png\nnewmtl wall\nKd 1 0 0\n",
    )
    .unwrap();
    let obj = dir.join("leaf.obj");
    std::fs::write(
        &obj,
        "mtllib leaf.mtl\n\
         o card\nusemtl leaf\n\
         v -1 -1 0.1\nv 1 -1 0.1\nv 1 1 -0.1\nv -1 1 -0.1\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n\
         o wall\nusemtl wall\n\
         v -2 -2 -1\nv 2 -2 -1\nv 2 2 -1\nv -2 2 -1\n\
         f 5 6 7\nf 5 7 8\n",
    )
    .unwrap();
    obj
}

fn render(obj: &Path, algo: &str, dir: &Path) -> (Vec<[u8; 4]>, Vec<u32>, String) {
    let (png, ids) = (dir.join("out.png"), dir.join("out.ids"));
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(["render", "--size", &SIZE.to_string(), "--algo", algo])
        .arg(obj)
        .arg("-o")
        .arg(&png)
        .arg("--ids-out")
        .arg(&ids)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{algo}: {stderr}");
    let pixels = image::open(&png)
        .unwrap()
        .to_rgba8()
        .pixels()
        .map(|p| p.0)
        .collect();
    let ids = std::fs::read(&ids)
        .unwrap()
        .chunks_exact(4)
        .map(|b| i32::from_le_bytes(b.try_into().unwrap()) as u32)
        .collect();
    (pixels, ids, stderr)
}

/// Brute force: at each pixel centre, every screen triangle covering it
/// whose primitive passes the alpha test, the nearest by window depth in
/// `f64`, the lower id at an exact tie.
fn reference(obj: &Path) -> (Vec<u32>, Vec<bool>) {
    let scene = load_obj(obj).unwrap();
    let view = View::for_scene(&scene, SIZE, SIZE).unwrap();
    let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
    let test = AlphaTest::new(&screen, TextureOptions::default()).expect("a cut-out");
    let mut ids = vec![NO_ID; (SIZE * SIZE) as usize];
    let mut card = vec![false; ids.len()];
    for j in 0..SIZE {
        for i in 0..SIZE {
            let mut best: Option<(f64, u32)> = None;
            for t in &screen.tris {
                let mut covered = false;
                t.for_each_centre(screen.viewport, |x, y, inside| {
                    covered |= inside && (x, y) == (i, j);
                });
                card[(j * SIZE + i) as usize] |= covered && t.prim < 2;
                if !covered || !test.passes(t.prim, i, j) {
                    continue;
                }
                let z = t.depth.at_pixel(i, j);
                if best.is_none_or(|(bz, b)| z < bz || (z == bz && t.prim < b)) {
                    best = Some((z, t.prim));
                }
            }
            ids[(j * SIZE + i) as usize] = best.map_or(NO_ID, |b| b.1);
        }
    }
    (ids, card)
}

/// Whether hider `name` resolves colour from several samples per pixel
/// (and alpha-tests them itself).
fn multi_sample(name: &str) -> bool {
    name.starts_with("abuffer") || name.starts_with("ssaa") || name.starts_with("warnock-")
}

fn hiders() -> Vec<String> {
    let list = Command::new(env!("CARGO_BIN_EXE_hider"))
        .arg("list")
        .output()
        .unwrap();
    String::from_utf8_lossy(&list.stdout)
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .collect()
}

#[test]
fn the_wall_shows_through_the_leaf_in_every_hider() {
    let dir = std::env::temp_dir().join(format!("hider-cutouts-{}", std::process::id()));
    let obj = scene(&dir);
    let (expected, card_square) = reference(&obj);
    // The card is primitives 0 and 1, the wall 2 and 3: the wall shows
    // inside the card's square (its corners) and the card in the middle.
    let centre = (SIZE / 2 * SIZE + SIZE / 2) as usize;
    assert!(expected[centre] < 2, "{:?}", expected[centre]);
    let wall = expected.iter().filter(|&&id| id == 2 || id == 3).count();
    let card = expected.iter().filter(|&&id| id < 2).count();
    assert!(card > 50 && wall > card, "card {card}, wall {wall}");
    let names = hiders();
    assert!(names.len() >= 20, "{names:?}");
    let mut single = 0;
    for name in &names {
        if multi_sample(name) {
            // Tested at its own samples in `alpha_samples.rs`.
            continue;
        }
        let (pixels, ids, stderr) = render(&obj, name, &dir);
        single += 1;
        let exact = !matches!(
            name.as_str(),
            "zbuffer-fixed16" | "zbuffer-fixed24" | "painter-naive" | "zbuffer-linear-z"
        );
        let differ = ids.iter().zip(&expected).filter(|(a, b)| a != b).count();
        if exact {
            assert_eq!(
                differ, 0,
                "{name}: {differ} pixels differ from the reference"
            );
        } else {
            // The approximate hiders may pick the other surface where the
            // two are close; the card and the wall are 1 apart.
            assert!(differ * 50 < ids.len(), "{name}: {differ} pixels differ");
        }
        // Where the wall shows through, it is red; in the disc, green.
        let k = (0..expected.len())
            .find(|&k| card_square[k] && expected[k] >= 2)
            .expect("the wall seen through the card");
        let [r, g, b, _] = pixels[k];
        assert!(
            r > 100 && g < 60 && b < 60,
            "{name}: wall pixel {:?}",
            pixels[k]
        );
        let [r, g, _, _] = pixels[centre];
        assert!(g > r, "{name}: leaf pixel {:?}", pixels[centre]);
        assert!(
            stderr.contains("cut-out pixels replaced"),
            "{name}: {stderr}"
        );
    }
    assert!(single >= 10, "{single} single-sample hiders");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A scene without cut-outs runs no cut-out stage (and pays nothing).
#[test]
fn the_stage_runs_only_for_cut_outs() {
    let dir = std::env::temp_dir().join(format!("hider-no-cutouts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args([
            "render", "gen:cube", "--size", "16", "--algo", "zbuffer", "-o",
        ])
        .arg(dir.join("cube.png"))
        .output()
        .unwrap();
    assert!(run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!stderr.contains("cut-out"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The plan line names the cut-out stage when the scene has cut-outs (it
/// lists the stages that run), and the planner's frame alpha-tests them.
#[test]
fn the_plan_line_names_the_cut_out_stage() {
    let dir = std::env::temp_dir().join(format!("hider-cutout-plan-{}", std::process::id()));
    let obj = scene(&dir);
    let run = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(["render", "--size", "32", "-o"])
        .arg(dir.join("auto.png"))
        .arg(&obj)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let plan = stderr.lines().next().unwrap_or_default();
    assert!(
        plan.starts_with("auto") && plan.contains("cutout"),
        "{plan}"
    );
    assert!(stderr.contains("cut-out pixels replaced"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}
