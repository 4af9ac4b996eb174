//! `hider render MODEL -o OUT.png` with no `--algo`: the planner picks the
//! hider and the colour stages the model calls for, so a textured model
//! comes out textured, a flat face in one shade, and a textured
//! translucent model textured and translucent.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

mod cli_support;
use cli_support::{assert_success, render, temp_dir};

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets")
}

/// A rendered image: RGB per pixel and the visible id per pixel (`None`
/// for background), with what the tool printed.
struct Rendered {
    rgb: Vec<[u8; 3]>,
    ids: Vec<Option<u32>>,
    stderr: String,
}

impl Rendered {
    /// The distinct colours of each visible id.
    fn colours_per_id(&self) -> HashMap<u32, HashSet<[u8; 3]>> {
        let mut map: HashMap<u32, HashSet<[u8; 3]>> = HashMap::new();
        for (id, rgb) in self.ids.iter().zip(&self.rgb) {
            if let Some(id) = id {
                map.entry(*id).or_default().insert(*rgb);
            }
        }
        map
    }
}

/// Renders `model` at `size` with the default hider choice.
fn render_default(dir: &Path, model: &Path, size: u32) -> Rendered {
    render_with(dir, model.to_str().unwrap(), size, &[])
}

/// Renders `model` at `size` with `extra` flags (the camera, say) but no
/// hider named.
fn render_with(dir: &Path, model: &str, size: u32, extra: &[&str]) -> Rendered {
    let png = dir.join("out.png");
    let ids = dir.join("out.i32");
    let size_s = size.to_string();
    let mut args = vec!["--size", &size_s];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--ids-out", ids.to_str().unwrap()]);
    let out = render(model, &png, &args);
    let stderr = assert_success(&out);
    let image = image::open(&png).unwrap().to_rgb8();
    let rgb = image.pixels().map(|p| p.0).collect();
    let ids = hider::scene::frame::read_ids(&ids, size, size)
        .unwrap()
        .into_iter()
        .map(|id| (id != hider::scene::NO_ID).then_some(id))
        .collect();
    Rendered { rgb, ids, stderr }
}

/// An sRGB channel as linear light.
fn linear(c: u8) -> f64 {
    let c = f64::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn a_textured_model_comes_out_textured() {
    let dir = temp_dir("spider");
    let image = render_default(&dir, &assets().join("spider/spider.obj"), 256);
    assert!(image.stderr.contains("auto, asked for"), "{}", image.stderr);
    assert!(image.stderr.contains("texture"), "{}", image.stderr);
    // One flat-shaded triangle has one colour; a textured one many.
    let textured = image
        .colours_per_id()
        .values()
        .filter(|c| c.len() >= 4)
        .count();
    assert!(
        textured >= 20,
        "only {textured} triangles show texture detail"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_flat_face_comes_out_in_one_shade() {
    let dir = temp_dir("flat");
    // The cube: six quads, each two triangles; seen from above and aside
    // so that three faces show.
    let image = render_with(&dir, "gen:cube", 96, &["--eye", "3,4,5"]);
    let mut per_face: HashMap<u32, HashSet<[u8; 3]>> = HashMap::new();
    for (id, rgb) in image.ids.iter().zip(&image.rgb) {
        if let Some(id) = id {
            per_face.entry(id / 2).or_default().insert(*rgb);
        }
    }
    assert_eq!(per_face.len(), 3, "three faces in view");
    for (face, colours) in &per_face {
        assert_eq!(colours.len(), 1, "face {face}: {colours:?}");
    }
    let shades: HashSet<[u8; 3]> = per_face.values().flatten().copied().collect();
    assert_eq!(
        shades.len(),
        3,
        "faces turned differently differ: {shades:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_textured_translucent_model_comes_out_textured_and_translucent() {
    let dir = temp_dir("glass");
    for file in ["checker_plane.obj", "checker.png"] {
        std::fs::copy(assets().join(file), dir.join(file)).unwrap();
    }
    let mtl = std::fs::read_to_string(assets().join("checker_plane.mtl")).unwrap();
    let with_opacity = |d: &str| {
        let text: String = mtl
            .lines()
            .map(|l| {
                if l.starts_with("d ") {
                    format!("d {d}\n")
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        assert!(text.contains(&format!("d {d}\n")), "{mtl}");
        std::fs::write(dir.join("checker_plane.mtl"), text).unwrap();
    };
    let model = dir.join("checker_plane.obj");
    with_opacity("1");
    let opaque = render_default(&dir, &model, 128);
    with_opacity("0.6");
    let glass = render_default(&dir, &model, 128);
    assert!(glass.stderr.contains("transparency"), "{}", glass.stderr);
    assert_eq!(opaque.ids, glass.ids, "the same pixels are covered");
    // Textured: light and dark squares.
    let covered: Vec<usize> = (0..glass.ids.len())
        .filter(|&i| glass.ids[i].is_some())
        .collect();
    assert!(covered.len() > 500);
    let lum = |img: &Rendered, i: usize| linear(img.rgb[i][1]);
    let (dark, light) = covered.iter().fold((0, 0), |(d, l), &i| {
        let v = lum(&opaque, i);
        (d + usize::from(v < 0.05), l + usize::from(v > 0.15))
    });
    assert!(dark > 100 && light > 100, "dark {dark}, light {light}");
    // Translucent over the black background: 60% of the opaque light,
    // blended in linear light.
    let off = covered
        .iter()
        .filter(|&&i| (lum(&glass, i) - 0.6 * lum(&opaque, i)).abs() > 0.02)
        .count();
    assert!(
        off * 20 <= covered.len(),
        "{off} of {} pixels are not 60% of the opaque colour",
        covered.len()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
