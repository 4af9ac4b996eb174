//! Times both painters on soups and spheres of about 1k, 10k and 100k
//! triangles and reports the splits and wrong pixels (against a z-buffer
//! on the same window-depth planes).
//!
//! `cargo run --release -p hider-painter --example bench [sizes...]`
//! (default sizes: 1000 10000 100000; image 512 x 512). A `soup` or
//! `sphere` argument runs only that scene. `PAINTER_MAX_MIB` raises the
//! painter's piece-memory budget (default 1 GiB).

use std::time::Instant;

use hider_geom::fixed::pixel_center;
use hider_painter::{NaivePainter, Painter, PainterOptions, PainterStats};
use hider_scene::{
    Frame, Hider, NO_ID, PrepareOptions, Scene, ScreenScene, View, prepare, procedural,
};

fn main() -> Result<(), hider_scene::Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let only = args.iter().find(|a| a.parse::<u32>().is_err()).cloned();
    let sizes: Vec<u32> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() {
        vec![1000, 10_000, 100_000]
    } else {
        sizes
    };
    println!(
        "| scene | triangles | naive ms | naive wrong px | painter ms | splits | pieces | comparisons | painter wrong px |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in &sizes {
        // uv_sphere(k) has 2k(k-1) triangles.
        let k = ((f64::from(n) / 2.0).sqrt().round() as u32).max(3);
        for (name, scene) in [
            ("soup", procedural::random_soup(n, 1)),
            ("sphere", procedural::uv_sphere(k)),
        ] {
            if only.as_deref().is_some_and(|o| o != name) {
                continue;
            }
            run(name, &scene)?;
        }
    }
    Ok(())
}

fn run(name: &str, scene: &Scene) -> Result<(), hider_scene::Error> {
    let view = View::for_scene(scene, 512, 512)?;
    let s = prepare(scene, &view, &PrepareOptions::default())?;
    let reference = zbuffer(&s);
    let mut frame = Frame::new(512, 512)?;
    // Best of three below 50k triangles (warm caches), one run above.
    let runs = if s.tris.len() < 50_000 { 3 } else { 1 };
    let mut naive = NaivePainter::default();
    let mut naive_ms = f64::INFINITY;
    for _ in 0..runs {
        let t = Instant::now();
        naive.render(&s, &mut frame)?;
        naive_ms = naive_ms.min(t.elapsed().as_secs_f64() * 1e3);
    }
    let naive_wrong = wrong(&frame, &reference);
    // PAINTER_MAX_MIB raises the piece-memory budget (default 1 GiB).
    let mut options = PainterOptions::default();
    if let Some(mib) = std::env::var("PAINTER_MAX_MIB")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
    {
        options = options.with_max_bytes(mib << 20);
    }
    let mut painter = Painter::new(options);
    let mut ms = f64::INFINITY;
    let mut st = PainterStats::default();
    for _ in 0..runs {
        let t = Instant::now();
        st = painter.render(&s, &mut frame)?;
        ms = ms.min(t.elapsed().as_secs_f64() * 1e3);
    }
    println!(
        "| {name} | {} | {naive_ms:.1} | {naive_wrong} | {ms:.1} | {} | {} | {} | {} |",
        s.tris.len(),
        st.splits,
        st.pieces_out,
        st.comparisons,
        wrong(&frame, &reference)
    );
    eprintln!(
        "{name} {}: peak {} MiB, moves {}, plane splits {}, line splits {}",
        s.tris.len(),
        st.peak_bytes >> 20,
        st.moves,
        st.plane_splits,
        st.line_splits
    );
    Ok(())
}

/// Ids of a z-buffer on the same window-depth planes, and a tie flag for
/// pixels whose two nearest primitives are within 1e-8 in window depth.
fn zbuffer(s: &ScreenScene) -> Vec<(u32, f64, f64)> {
    let vp = s.viewport;
    let mut buf = vec![(NO_ID, f64::INFINITY, f64::INFINITY); (vp.width * vp.height) as usize];
    for t in &s.tris {
        let Some((x0, y0, x1, y1)) = t.pixel_bounds(vp) else {
            continue;
        };
        let edges = t.edges();
        for j in y0..=y1 {
            for i in x0..=x1 {
                let (x, y) = (
                    i64::from(pixel_center(i as i32)),
                    i64::from(pixel_center(j as i32)),
                );
                if !edges.iter().all(|e| e.contains(x, y)) {
                    continue;
                }
                let d = t.depth.at_pixel(i, j);
                let c = &mut buf[(j * vp.width + i) as usize];
                if c.0 == t.prim {
                    c.1 = c.1.min(d);
                } else if d < c.1 {
                    *c = (t.prim, d, c.1);
                } else {
                    c.2 = c.2.min(d);
                }
            }
        }
    }
    buf
}

fn wrong(frame: &Frame, reference: &[(u32, f64, f64)]) -> usize {
    frame
        .ids
        .iter()
        .zip(reference)
        .filter(|&(&id, &(want, d1, d2))| id != want && d2 - d1 >= 1e-8)
        .count()
}
