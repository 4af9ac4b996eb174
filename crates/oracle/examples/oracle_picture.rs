//! Makes the pictures and numbers of `docs/oracle.md` and
//! `docs/hard-cases.md`:
//! - `docs/images/oracle-hard-cases.png`: every hard case rendered by the
//!   ray-cast oracle (flat shading), exact ties in magenta, rounding ties
//!   in orange;
//! - `docs/images/oracle-coverage.png`: the exact box-filtered image of the
//!   interpenetrating boxes from analytic coverage, next to the pixel-centre one;
//! - timings of the oracle (with how many comparisons needed exact
//!   arithmetic) and of analytic coverage, and how often the source-plane
//!   oracle disagrees with the snapped-plane one.
//!
//! `cargo run --release -p hider-oracle --example oracle_picture`

use std::path::{Path, PathBuf};

use hider_oracle::{
    DEFAULT_TIE_TOLERANCE, DepthPlane, OracleOptions, RayCastOracle, analytic_coverage,
};
use hider_scene::shade::{prim_color, to_srgb8};
use hider_scene::{Frame, Hider, NO_ID, ScreenScene, ShadeMode, procedural};
use hider_testkit::timer::Timer;
use hider_testkit::{hard_cases, screen};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn colour(s: &ScreenScene, id: u32) -> [f32; 3] {
    prim_color(s, id, ShadeMode::Lambert).0
}

fn srgb(c: [f32; 3]) -> [u8; 4] {
    [to_srgb8(c[0]), to_srgb8(c[1]), to_srgb8(c[2]), 255]
}

/// Contact sheet of the hard cases, exact ties in magenta, rounding ties in
/// orange.
fn hard_case_sheet(images: &Path) -> Result<()> {
    let (tile, cols) = (84u32, 6u32);
    let cases = hard_cases::all(1);
    let rows = (cases.len() as u32).div_ceil(cols);
    let mut sheet = Frame::new(tile * cols, tile * rows)?;
    for (n, (name, scene)) in cases.iter().enumerate() {
        let s = screen(scene, tile, tile);
        let mut oracle = RayCastOracle::default();
        let r = oracle.evaluate(&s);
        let stats = oracle.render(&s, &mut Frame::new(tile, tile)?)?;
        let (ox, oy) = ((n as u32 % cols) * tile, (n as u32 / cols) * tile);
        for y in 0..tile {
            for x in 0..tile {
                let k = (y * tile + x) as usize;
                let c = match r.ids[k] {
                    NO_ID => [24, 24, 32, 255],
                    _ if r.is_exact_tie(k) => [255, 0, 255, 255],
                    _ if r.is_tie(k) => [255, 150, 0, 255],
                    id => srgb(colour(&s, id)),
                };
                let i = sheet.index(ox + x, oy + y);
                sheet.color[i] = c;
            }
        }
        println!(
            "{name:<24} {:>6} tris, {:>5} covered, {:>4} exact ties, {:>3} rounding ties, {:>4} below 1e-5, {:>5} exact comparisons",
            s.tris.len(),
            r.covered_count(),
            stats.ties,
            stats.rounding_ties,
            r.tie_count(DEFAULT_TIE_TOLERANCE),
            stats.exact,
        );
    }
    sheet.write_png(&images.join("oracle-hard-cases.png"))?;
    Ok(())
}

/// Exact box filter beside pixel centres, magnified.
fn coverage_picture(images: &Path) -> Result<()> {
    let (size, zoom) = (40u32, 6u32);
    let s = screen(&hard_cases::interpenetrating_boxes(3, 4), size, size);
    let r = RayCastOracle::default().evaluate(&s);
    let cov = analytic_coverage(&s);
    let mut pic = Frame::new(2 * size * zoom + zoom, size * zoom)?;
    for y in 0..size {
        for x in 0..size {
            let k = (y * size + x) as usize;
            let centre = if r.ids[k] == NO_ID {
                [0, 0, 0, 255]
            } else {
                srgb(colour(&s, r.ids[k]))
            };
            let mut acc = [0.0f32; 3];
            for (prim, a) in cov.pixel_fragments(x, y) {
                let c = colour(&s, prim);
                (0..3).for_each(|i| acc[i] += c[i] * a as f32);
            }
            let boxed = srgb(acc);
            for dy in 0..zoom {
                for dx in 0..zoom {
                    let i = pic.index(x * zoom + dx, y * zoom + dy);
                    pic.color[i] = centre;
                    let j = pic.index((size + 1 + x) * zoom + dx, y * zoom + dy);
                    pic.color[j] = boxed;
                }
            }
        }
    }
    pic.write_png(&images.join("oracle-coverage.png"))?;
    Ok(())
}

/// How long the oracle and analytic coverage take (one run each, as the
/// docs report: they are slow on purpose).
fn timings() {
    let once = Timer::new(1).with_warmup(0);
    for (count, size) in [(10_000u32, 128u32), (79_600, 128), (398, 128)] {
        let scene = match count {
            79_600 => procedural::uv_sphere(200),
            398 => hard_cases::repeated_polygon(100),
            _ => hard_cases::heavy_overdraw(count, 1),
        };
        let s = screen(&scene, size, size);
        let mut frame = Frame::new(size, size).expect("a valid size");
        let mut stats = Default::default();
        let t = once.time(|| {
            stats = RayCastOracle::default()
                .render(&s, &mut frame)
                .expect("within budget")
        });
        println!(
            "oracle: {count} triangles (heavy overdraw / uv sphere / repeated polygon) at {size}x{size}: {:.1} ms, {} pixel tests, {} hits, {} exact comparisons, {} exact ties, {} rounding ties",
            t.median_ms,
            stats.pixel_tests,
            stats.hits,
            stats.exact,
            stats.ties,
            stats.rounding_ties,
        );
    }
    for (name, scene, size) in [
        ("random_soup(200)", procedural::random_soup(200, 1), 64u32),
        ("random_soup(1000)", procedural::random_soup(1000, 1), 64),
        ("uv_sphere(24)", procedural::uv_sphere(24), 64),
    ] {
        let s = screen(&scene, size, size);
        let mut fragments = 0;
        let t = once.time(|| fragments = analytic_coverage(&s).fragments.len());
        println!(
            "analytic coverage: {name} at {size}x{size}: {:.1} ms, {fragments} fragments",
            t.median_ms
        );
    }
}

/// What snapping does: the source-plane oracle against the snapped-plane
/// one, off ties of the snapped one.
fn snapping_effect() {
    let source = OracleOptions::default().with_depth_plane(DepthPlane::Source);
    for (name, scene) in hard_cases::all(1) {
        let s = screen(&scene, 64, 64);
        let snapped = RayCastOracle::default().evaluate(&s);
        let source = RayCastOracle::new(source).evaluate(&s);
        let mut differ = 0;
        let mut worst: f64 = 0.0;
        for k in 0..snapped.ids.len() {
            if snapped.ids[k] != source.ids[k] && !snapped.is_tie(k) {
                differ += 1;
                worst = worst.max(source.gap[k].min(snapped.gap[k]));
            }
        }
        if differ > 0 {
            println!(
                "source vs snapped plane: {name}: {differ} non-tie pixels differ, largest gap {worst:.1e}"
            );
        }
    }
}

fn main() -> Result<()> {
    let images = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/images");
    std::fs::create_dir_all(&images)?;
    hard_case_sheet(&images)?;
    coverage_picture(&images)?;
    timings();
    snapping_effect();
    Ok(())
}
