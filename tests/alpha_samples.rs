//! Alpha at the anti-aliasing hiders' own samples (issue 36): a leaf card
//! (an opaque disc, alpha 0 around it) alpha-tested per sample by the
//! A-buffer (its 8 x 4 masks), the supersampled z-buffers and the
//! anti-aliased Warnock, against a brute-force reference at the same
//! sample positions; `map_d` (a greyscale dissolve texture) cutting as an
//! RGBA `map_Kd` does; partial alpha composited by the A-buffer as by hand,
//! and planned as transparency; scenes without cut-outs on the paths they
//! took before.

use std::path::{Path, PathBuf};
use std::process::Command;

use hider::abuffer::SamplePattern;
use hider::registry;
use hider::scene::shade::texture::srgb_to_linear;
use hider::scene::shade::{Stages, render_frame, to_srgb8};
use hider::scene::{
    Frame, PrepareOptions, ScreenScene, ShadeMode, StatsTable, TextureOptions, TextureSampler,
    View, load_obj, prepare,
};

const SIZE: u32 = 48;

/// The card's textures.
#[derive(Clone, Copy, PartialEq)]
enum Card {
    /// An RGBA `map_Kd`: a green disc of radius 20 texels (of 64), white
    /// with alpha 0 around it.
    Rgba,
    /// An RGB `map_Kd` (green everywhere) and a greyscale `map_d`: the
    /// same disc, 255 inside, 0 outside.
    MapD,
    /// The RGBA texture's green with alpha 128 everywhere.
    Half,
    /// The same green, RGB (no alpha).
    Opaque,
}

fn inside(x: u32, y: u32) -> bool {
    (f64::from(x) + 0.5 - 32.0).hypot(f64::from(y) + 0.5 - 32.0) < 20.0
}

const GREEN: [u8; 3] = [30, 200, 40];

/// Writes the card (2 x 2, tilted a little so its depth varies), over a
/// red wall (4 x 4, 1 behind) when `wall`, to `dir`; the OBJ file.
fn scene(dir: &Path, card: Card, wall: bool) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let map = match card {
        Card::Rgba => {
            image::RgbaImage::from_fn(64, 64, |x, y| {
                let [r, g, b] = GREEN;
                if inside(x, y) {
                    image::Rgba([r, g, b, 255])
                } else {
                    image::Rgba([255, 255, 255, 0])
                }
            })
            .save(dir.join("leaf.png"))
            .unwrap();
            "map_Kd leaf.png"
        }
        Card::MapD => {
            image::RgbImage::from_pixel(64, 64, image::Rgb(GREEN))
                .save(dir.join("green.png"))
                .unwrap();
            image::GrayImage::from_fn(64, 64, |x, y| {
                image::Luma([if inside(x, y) { 255 } else { 0 }])
            })
            .save(dir.join("disc.png"))
            .unwrap();
            "map_Kd green.png\nmap_d disc.png"
        }
        Card::Half => {
            let [r, g, b] = GREEN;
            image::RgbaImage::from_pixel(8, 8, image::Rgba([r, g, b, 128]))
                .save(dir.join("half.png"))
                .unwrap();
            "map_Kd half.png"
        }
        Card::Opaque => {
            image::RgbImage::from_pixel(8, 8, image::Rgb(GREEN))
                .save(dir.join("green.png"))
                .unwrap();
            "map_Kd green.png"
        }
    };
    std::fs::write(
        dir.join("card.mtl"),
        format!("newmtl leaf\nKd 1 1 1\n{map}\nnewmtl wall\nKd 1 0 0\n"),
    )
    .unwrap();
    let mut obj = "mtllib card.mtl\n\
         o card\nusemtl leaf\n\
         v -1 -1 0.1\nv 1 -1 0.1\nv 1 1 -0.1\nv -1 1 -0.1\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
        .to_owned();
    if wall {
        obj.push_str(
            "o wall\nusemtl wall\n\
             v -2 -2 -1\nv 2 -2 -1\nv 2 2 -1\nv -2 2 -1\n\
             f 5 6 7\nf 5 7 8\n",
        );
    }
    let path = dir.join("card.obj");
    std::fs::write(&path, obj).unwrap();
    path
}

fn view(scene: &hider::scene::Scene) -> View {
    View::for_scene(scene, SIZE, SIZE).unwrap()
}

/// The frame and counters of hider `name` (the registry's defaults) on
/// `obj`, through the library's one-frame pipeline.
fn render(obj: &Path, name: &str) -> (Frame, StatsTable) {
    let scene = load_obj(obj).unwrap();
    let view = view(&scene);
    let mut hider = registry::by_name(name).unwrap().make();
    let stages = Stages::for_scene(&scene, true);
    let mut screen = ScreenScene::empty(&view);
    let mut frame = Frame::new(SIZE, SIZE).unwrap();
    let stats = render_frame(
        hider.as_mut(),
        &scene,
        &view,
        &PrepareOptions::default(),
        &stages,
        ShadeMode::Lambert,
        &mut screen,
        &mut frame,
    )
    .unwrap();
    (frame, stats)
}

/// The multi-sample hiders and their sample positions (1/256 pixel inside
/// the pixel).
fn hiders() -> Vec<(&'static str, Vec<(i32, i32)>)> {
    let warnock: Vec<(i32, i32)> = (0..4)
        .flat_map(|b| (0..4).map(move |a| (32 + 64 * a, 32 + 64 * b)))
        .collect();
    vec![
        ("abuffer", SamplePattern::Grid32.positions().to_vec()),
        (
            "abuffer-carpenter",
            SamplePattern::Grid32.positions().to_vec(),
        ),
        ("ssaa-4", SamplePattern::Grid4.positions().to_vec()),
        ("ssaa-8", SamplePattern::Grid8.positions().to_vec()),
        ("ssaa-sorted", SamplePattern::Grid32.positions().to_vec()),
        ("warnock-4x4", warnock),
    ]
}

/// Brute force: per pixel, the samples at `positions` where some screen
/// triangle covers the sample (the exact edge functions) and passes the
/// alpha test at the sample's own position, over the sample count; and
/// the share of samples where the nearest such triangle is the card
/// (primitives 0 and 1); and whether the card's square (its triangles,
/// whatever the alpha) covers each pixel's every sample.
fn reference(obj: &Path, positions: &[(i32, i32)]) -> (Vec<f32>, Vec<f32>, Vec<bool>) {
    let scene = load_obj(obj).unwrap();
    let screen = prepare(&scene, &view(&scene), &PrepareOptions::default()).unwrap();
    let sampler = TextureSampler::new(&screen, TextureOptions::default());
    let passes = |prim: u32, x: f64, y: f64| {
        let info = &screen.prims[prim as usize];
        sampler.alpha_at(info, &screen.materials[info.material as usize], x, y) >= 0.5
    };
    let n = positions.len() as f32;
    let (mut covered, mut card, mut square) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..SIZE {
        for i in 0..SIZE {
            let (mut c, mut k) = (0.0, 0.0);
            let mut in_square = true;
            for &(ox, oy) in positions {
                let (px, py) = (
                    i64::from(i) * 256 + i64::from(ox),
                    i64::from(j) * 256 + i64::from(oy),
                );
                let (x, y) = (px as f64 / 256.0, py as f64 / 256.0);
                let mut best: Option<(f64, u32)> = None;
                in_square &= screen
                    .tris
                    .iter()
                    .any(|t| t.prim < 2 && t.edges().iter().all(|e| e.contains(px, py)));
                for t in &screen.tris {
                    if !t.edges().iter().all(|e| e.contains(px, py)) || !passes(t.prim, x, y) {
                        continue;
                    }
                    let z = t.depth.eval(x, y);
                    if best.is_none_or(|(bz, b)| z < bz || (z == bz && t.prim < b)) {
                        best = Some((z, t.prim));
                    }
                }
                if let Some((_, prim)) = best {
                    c += 1.0;
                    k += f32::from(u8::from(prim < 2));
                }
            }
            covered.push(c / n);
            card.push(k / n);
            square.push(in_square);
        }
    }
    (covered, card, square)
}

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("hider-alpha-{name}-{}", std::process::id()))
}

/// The card alone: every multi-sample hider's coverage is the reference's
/// at its own samples, pixel by pixel (within one sample; the samples and
/// the alpha are evaluated alike, so all but a few pixels match exactly),
/// and the corners of the card's square, where the texture is cut, are
/// empty. Before, the card was drawn opaque: coverage 1 over the square.
#[test]
fn coverage_is_alpha_tested_at_each_hiders_own_samples() {
    let dir = temp("coverage");
    let obj = scene(&dir, Card::Rgba, false);
    for (name, positions) in hiders() {
        let (expected, _, _) = reference(&obj, &positions);
        let (frame, stats) = render(&obj, name);
        let step = 1.0 / positions.len() as f32 + 1e-6;
        let mut differ = 0;
        for (k, (&got, &want)) in frame.coverage.iter().zip(&expected).enumerate() {
            assert!(
                (got - want).abs() <= step,
                "{name}: pixel {k} coverage {got}, reference {want}"
            );
            differ += usize::from(got != want);
        }
        assert!(
            differ * 100 <= expected.len(),
            "{name}: {differ} pixels differ"
        );
        let full = expected.iter().filter(|&&c| c == 1.0).count();
        let partial = expected.iter().filter(|&&c| c > 0.0 && c < 1.0).count();
        assert!(
            full > 100 && partial > 20,
            "{name}: {full} full, {partial} partial"
        );
        assert!(
            !stats.warnings.iter().any(|w| w.contains("opaque")),
            "{name}: {:?}",
            stats.warnings
        );
        if name == "warnock-4x4" {
            let resolved = stats.counters.iter().find(|c| c.0 == "cut-out pixels");
            assert!(resolved.is_some_and(|c| c.1 > 0), "{:?}", stats.counters);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// In front of the red wall: where every sample of a pixel inside the
/// card's square sees the wall through the cut, the pixel is red; the
/// middle of the disc is green.
#[test]
fn the_wall_shows_through_the_cut_at_every_sample() {
    let dir = temp("wall");
    let obj = scene(&dir, Card::Rgba, true);
    for (name, positions) in hiders() {
        let (_, card, square) = reference(&obj, &positions);
        let (frame, _) = render(&obj, name);
        let w = SIZE as usize;
        // The pixels of the square's corners, where the texture is cut at
        // every sample.
        let corners: Vec<usize> = (0..card.len())
            .filter(|&k| square[k] && card[k] == 0.0)
            .collect();
        assert!(
            corners.len() > 10,
            "{name}: {} corner pixels",
            corners.len()
        );
        for k in corners {
            let [r, g, b, _] = frame.color[k];
            assert!(
                r > 100 && g < 60 && b < 60,
                "{name}: corner {:?}",
                frame.color[k]
            );
        }
        let centre = w * w / 2 + w / 2;
        let [r, g, _, _] = frame.color[centre];
        assert!(g > r, "{name}: centre {:?}", frame.color[centre]);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A green RGB `map_Kd` with a greyscale `map_d` disc cuts exactly as the
/// RGBA texture does: the same coverage and ids in every multi-sample
/// hider and in the z-buffer (the cut-out stage). Before, `map_d` was read
/// and ignored (with a warning): the whole card was drawn.
#[test]
fn map_d_cuts_as_an_rgba_map_kd() {
    let (rgba_dir, map_d_dir) = (temp("rgba"), temp("mapd"));
    let rgba = scene(&rgba_dir, Card::Rgba, true);
    let map_d = scene(&map_d_dir, Card::MapD, true);
    for name in hiders().into_iter().map(|h| h.0).chain(["zbuffer"]) {
        let (a, _) = render(&rgba, name);
        let (b, stats) = render(&map_d, name);
        let ids = a.ids.iter().zip(&b.ids).filter(|(x, y)| x != y).count();
        let coverage = a
            .coverage
            .iter()
            .zip(&b.coverage)
            .filter(|(x, y)| x != y)
            .count();
        assert_eq!(
            (ids, coverage),
            (0, 0),
            "{name}: pixels whose id, coverage differ"
        );
        assert!(
            !stats.warnings.iter().any(|w| w.contains("map_d")),
            "{name}: {:?}",
            stats.warnings
        );
    }
    std::fs::remove_dir_all(&rgba_dir).unwrap();
    std::fs::remove_dir_all(&map_d_dir).unwrap();
}

/// A texture of alpha 128 everywhere over the red wall: inside the card,
/// the A-buffer's pixel is the card's colour (the same card with an RGB
/// texture, same geometry) over the wall's (flat, read off a pixel beside
/// the card) composited by hand with opacity 128/255 in linear light,
/// within the rounding of the sRGB bytes. Before, the card was drawn
/// opaque. The single-sample z-buffer cuts it at one half, with a warning.
#[test]
fn partial_alpha_is_composited_by_the_a_buffer() {
    let (half_dir, opaque_dir) = (temp("half"), temp("opaque"));
    let half = scene(&half_dir, Card::Half, true);
    let opaque = scene(&opaque_dir, Card::Opaque, true);
    let a = 128.0 / 255.0;
    let w = SIZE as usize;
    let middle = w * w / 2 + w / 2;
    for name in ["abuffer", "abuffer-carpenter"] {
        let (blend, stats) = render(&half, name);
        let (card, _) = render(&opaque, name);
        // Inside the wall, above the card.
        let beside = 15 * w + w / 2;
        let wall = blend.color[beside];
        assert!(wall[0] > 100 && wall[1] < 60, "{name}: wall {wall:?}");
        assert_eq!(card.color[beside], wall, "{name}");
        for k in [middle, middle - 3, middle + 3 * w] {
            let expected: Vec<u8> = (0..3)
                .map(|c| {
                    let over = srgb_to_linear(card.color[k][c]);
                    let under = srgb_to_linear(wall[c]);
                    to_srgb8(a * over + (1.0 - a) * under)
                })
                .collect();
            for (c, want) in expected.iter().enumerate() {
                let got = blend.color[k][c];
                assert!(
                    got.abs_diff(*want) <= 1,
                    "{name}: pixel {k} {:?}, by hand {expected:?}",
                    blend.color[k]
                );
            }
        }
        assert!(
            stats.warnings.iter().all(|w| !w.contains("partial alpha")),
            "{name}: {:?}",
            stats.warnings
        );
    }
    let (_, stats) = render(&half, "zbuffer");
    assert!(
        stats.warnings.iter().any(|w| w.contains("partial alpha")),
        "{:?}",
        stats.warnings
    );
    std::fs::remove_dir_all(&half_dir).unwrap();
    std::fs::remove_dir_all(&opaque_dir).unwrap();
}

/// The planner reports partial alpha as transparency (the texture and its
/// share of partial texels) and picks the A-buffer; a cut-out (alpha 0 or
/// 1 only) stays on the opaque path.
#[test]
fn the_plan_picks_a_transparency_hider_for_partial_alpha() {
    let (half_dir, cut_dir) = (temp("plan-half"), temp("plan-cut"));
    let plan = |obj: &Path, dir: &Path| {
        let run = Command::new(env!("CARGO_BIN_EXE_hider"))
            .args(["render", "--size", "32", "-o"])
            .arg(dir.join("auto.png"))
            .arg(obj)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
        assert!(run.status.success(), "{stderr}");
        stderr.lines().next().unwrap_or_default().to_owned()
    };
    let half = plan(&scene(&half_dir, Card::Half, true), &half_dir);
    assert!(half.contains("abuffer"), "{half}");
    let cut = plan(&scene(&cut_dir, Card::Rgba, true), &cut_dir);
    assert!(!cut.contains("abuffer"), "{cut}");
    let analyze = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(["analyze", "--size", "32"])
        .arg(half_dir.join("card.obj"))
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&analyze.stdout);
    assert!(
        out.contains("partial texture alpha") && out.contains("half.png: 100.0% of texels"),
        "{out}"
    );
    std::fs::remove_dir_all(&half_dir).unwrap();
    std::fs::remove_dir_all(&cut_dir).unwrap();
}

/// Scenes without cut-outs pay nothing: an RGB-textured card keeps the
/// A-buffer's sample-buffer tiles (cut-out triangles take the lists), and
/// no hider reports cut-out work.
#[test]
fn scenes_without_cut_outs_take_the_paths_they_took() {
    let dir = temp("plain");
    let obj = scene(&dir, Card::Opaque, true);
    for (name, _) in hiders() {
        let (_, stats) = render(&obj, name);
        for (counter, value) in &stats.counters {
            if counter.contains("cut-out") {
                assert_eq!(*value, 0, "{name}: {counter}");
            }
        }
        if name == "abuffer" {
            let tiles = stats
                .counters
                .iter()
                .find(|(c, _)| c.contains("sample tiles"))
                .map(|c| c.1);
            assert!(tiles.is_some_and(|t| t > 0), "{:?}", stats.counters);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
