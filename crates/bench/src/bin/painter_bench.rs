//! Times both painters on soups and spheres of about 1k, 10k and 100k
//! triangles and reports the splits and wrong pixels (against a z-buffer
//! on the same window-depth planes).
//!
//! `cargo run --release -p hider-bench --bin painter_bench -- [sizes...]`
//! (default sizes: 1000 10000 100000; image 512 x 512). A `soup`,
//! `sphere`, `fan` or `cone` argument runs only that scene (`fan`: the
//! unit disk's fan of N triangles around its centre; `cone`: the same
//! with the centre lifted towards the camera, a UV sphere's pole). `PAINTER_MAX_MIB` raises the
//! painter's piece-memory budget (default 1 GiB).

use hider_bench::analysis::star_fan;
use hider_painter::{NaivePainter, Painter, PainterOptions, PainterStats};
use hider_scene::{Frame, Hider, PrepareOptions, Scene, ScreenScene, View, prepare, procedural};
use hider_testkit::reference::{self, Reference};
use hider_testkit::score::score;
use hider_testkit::timer::Timer;

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
            ("fan", star_fan(n, 0.0)),
            ("cone", star_fan(n, 0.5)),
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
    let reference = reference::pixel_centre(&s);
    let mut frame = Frame::new(512, 512)?;
    // Best of three below 50k triangles (warm caches), one run above.
    let runs = if s.tris.len() < 50_000 { 3 } else { 1 };
    let mut naive = NaivePainter::default();
    let (naive_ms, _) = time(&mut naive, &s, &mut frame, runs)?;
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
    let (ms, st) = time(&mut painter, &s, &mut frame, runs)?;
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

/// The fastest of `runs` frames (no warm-up) in milliseconds, and the
/// stats of the last.
fn time<H: Hider<Stats = PainterStats>>(
    hider: &mut H,
    s: &ScreenScene,
    frame: &mut Frame,
    runs: u32,
) -> Result<(f64, PainterStats), hider_scene::Error> {
    let mut stats = PainterStats::default();
    let timing = Timer::new(runs).with_warmup(0).try_time(&|| false, || {
        stats = hider.render(s, frame)?;
        Ok(())
    })?;
    Ok((timing.min_ms, stats))
}

/// Pixels whose id is not the window-depth z-buffer's, where its two
/// nearest primitives are at least 1e-8 apart in window depth.
fn wrong(frame: &Frame, reference: &Reference) -> u64 {
    let result = score(reference, frame, 1e-8);
    result.coverage_mismatches + result.wrong_ids
}
