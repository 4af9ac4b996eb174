//! The benchmark of issue 12: the scenes of the llvmpipe comparison
//! (spider, UV sphere 200 and 500, random soup of 100,000 triangles) with
//! the fit camera at 512, 1024 and 2048, timed over the span a GL draw call
//! plus `glFinish` covers: everything after loading (transform, clip,
//! set-up; clear; rasterise), with the GL-compatible f32 front end.
//!
//! - `zbuffer`: the reference pipeline, [`prepare`] then [`ZBuffer`].
//! - `tiled 1T` / `tiled 2T`: the fast pipeline, [`prepare_depth_into`]
//!   then [`TiledZBuffer::draw_depth_scene`], on 1 thread (no pool) and on
//!   a 2-thread pool (front end and tiles in parallel, in that one pool:
//!   the hider uses the pool it is called from when it has the right
//!   number of threads). The image stays in
//!   the hider's tiles, as GL's stays in its framebuffer; the read-back is
//!   not timed, but it is checked equal to the reference, pixel for pixel,
//!   for every scene and size.
//!
//! Rounds are interleaved so that machine noise hits all three alike; in
//! each round a pipeline renders [`FRAMES`] frames in a row and the last
//! ones are timed (a frame loop's steady state: caches hold the pipeline's
//! own data and the pool's threads are awake). The table gives median
//! (minimum) ms over all timed frames, Mtri/s from the median, and at 1024
//! the ratios to llvmpipe's and euc's figures from the issue (above 1 =
//! faster than them).
//!
//! With `--peers FILE`, the JSON the `peers` package wrote
//! (`cargo run --release --manifest-path peers/Cargo.toml -- --json FILE`,
//! run right before on the same machine) adds the ratios to the peers
//! measured here and now, every size.
//!
//! `cargo run --release -p hider-zbuffer --example fast_zbuffer_bench [K] [SIZES...] [--peers FILE]`
//! (default K = 9 rounds, sizes 512 1024 2048).

use std::path::PathBuf;
use std::time::Instant;

use hider_scene::{
    DepthScene, Frame, Hider, PrepareOptions, Scene, View, load_obj, prepare, prepare_depth_into,
    procedural,
};
use hider_zbuffer::{TiledZBuffer, TiledZBufferOptions, ZBuffer};

/// Issue 12's figures at 1024: (scene, llvmpipe 1 thread, 2 threads, euc).
const FIGURES: [(&str, f64, f64, f64); 4] = [
    ("spider", 2.6, 1.8, 5.7),
    ("sphere 200", 20.0, 22.0, 13.6),
    ("sphere 500", 100.0, 59.0, 29.0),
    ("soup 100k", 117.0, 72.0, 298.0),
];

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn stats(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0])
}

/// Frames each pipeline renders in a row per round; all but the first are
/// timed.
const FRAMES: usize = 3;

/// A peer's figure measured on this machine: (scene, size, peer, threads)
/// to median ms.
type Peers = Vec<((String, u32, String, u32), f64)>;

/// Reads the `peers` package's JSON.
fn read_peers(path: &str) -> Result<Peers, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let rows: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))?;
    let rows = rows
        .as_array()
        .ok_or_else(|| format!("{path}: not an array of measurements"))?;
    let mut out = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let field = |k: &str| {
            row.get(k)
                .cloned()
                .ok_or_else(|| format!("{path}: entry {i} has no '{k}'"))
        };
        let text = |k: &str| -> Result<String, String> {
            field(k)?
                .as_str()
                .map(str::to_owned)
                .ok_or_else(|| format!("{path}: entry {i}: '{k}' is not text"))
        };
        let number = |k: &str| -> Result<f64, String> {
            field(k)?
                .as_f64()
                .ok_or_else(|| format!("{path}: entry {i}: '{k}' is not a number"))
        };
        out.push((
            (
                text("scene")?,
                number("size")? as u32,
                text("peer")?,
                number("threads")? as u32,
            ),
            number("median_ms")?,
        ));
    }
    Ok(out)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let peers = match args.iter().position(|a| a == "--peers") {
        Some(i) => {
            let path = args
                .get(i + 1)
                .cloned()
                .ok_or("--peers needs the path of the peers' JSON")?;
            args.drain(i..i + 2);
            read_peers(&path)?
        }
        None => Vec::new(),
    };
    let peer = |scene: &str, size: u32, name: &str, threads: u32| {
        peers
            .iter()
            .find(|((s, z, p, t), _)| s == scene && *z == size && p == name && *t == threads)
            .map(|(_, ms)| *ms)
    };
    let runs: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(9);
    let mut sizes: Vec<u32> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![512, 1024, 2048];
    }
    let spider = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/gl-reference/models/spider.obj");
    let mut scenes: Vec<(&str, Scene)> = Vec::new();
    if spider.exists() {
        scenes.push(("spider", load_obj(&spider)?));
    } else {
        eprintln!("skipped the spider: {} not found", spider.display());
    }
    scenes.push(("sphere 200", procedural::uv_sphere(200)));
    scenes.push(("sphere 500", procedural::uv_sphere(500)));
    scenes.push(("soup 100k", procedural::random_soup(100_000, 1)));

    let serial = PrepareOptions::gl_compatible();
    let parallel = serial.with_parallel(true);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    println!(
        "median (min) ms of {} frames ({runs} interleaved rounds) of prepare + clear + rasterise (f32 front end)\n",
        runs * (FRAMES - 1)
    );
    let same_run = if peers.is_empty() {
        ""
    } else {
        " same machine: vs llvmpipe 1T / 2T | vs euc 1T |"
    };
    println!(
        "| scene | triangles | size | zbuffer | tiled 1 thread | tiled 2 threads | Mtri/s 1T / 2T | speed-up 1T / 2T | vs llvmpipe 1T / 2T | vs euc 1T |{same_run}"
    );
    println!(
        "|---|---|---|---|---|---|---|---|---|---|{}",
        if peers.is_empty() { "" } else { "---|---|" }
    );
    for &size in &sizes {
        for (name, scene) in &scenes {
            let view = View::for_scene(scene, size, size)?;
            let mut screen = prepare(scene, &view, &serial)?;
            let mut reference = ZBuffer::default();
            let mut want = Frame::new(size, size)?;
            reference.render(&screen, &mut want)?;
            let mut one = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
            let mut two = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(2));
            let (mut lean1, mut lean2) = (DepthScene::new(), DepthScene::new());
            let mut got = Frame::new(size, size)?;
            // Warm-up, and the check that the fast pipeline's image is the
            // reference's.
            prepare_depth_into(scene, &view, &serial, &mut lean1)?;
            one.draw_depth_scene(&lean1)?;
            one.read_into(&mut got)?;
            assert!(got == want, "{name} at {size}: 1 thread differs");
            pool.install(|| {
                prepare_depth_into(scene, &view, &parallel, &mut lean2)?;
                two.draw_depth_scene(&lean2)
            })?;
            two.read_into(&mut got)?;
            assert!(got == want, "{name} at {size}: 2 threads differ");

            let (mut tz, mut t1, mut t2) = (Vec::new(), Vec::new(), Vec::new());
            for _ in 0..runs {
                // Each pipeline runs twice in a row and the second run is
                // timed: a frame loop's steady state, not the first frame
                // after another pipeline has filled the caches with its
                // own data (the rounds still interleave the three, so
                // machine noise hits them alike).
                for frame in 0..FRAMES {
                    let t = Instant::now();
                    hider_scene::prepare_into(scene, &view, &serial, &mut screen)?;
                    reference.render(&screen, &mut want)?;
                    if frame > 0 {
                        tz.push(ms(t));
                    }
                }
                for frame in 0..FRAMES {
                    let t = Instant::now();
                    prepare_depth_into(scene, &view, &serial, &mut lean1)?;
                    one.draw_depth_scene(&lean1)?;
                    if frame > 0 {
                        t1.push(ms(t));
                    }
                }
                for frame in 0..FRAMES {
                    let t = Instant::now();
                    pool.install(|| {
                        prepare_depth_into(scene, &view, &parallel, &mut lean2)?;
                        two.draw_depth_scene(&lean2)
                    })?;
                    if frame > 0 {
                        t2.push(ms(t));
                    }
                }
            }
            let ((mz, nz), (m1, n1), (m2, n2)) = (stats(tz), stats(t1), stats(t2));
            let tris = scene.triangle_count() as f64;
            let vs = FIGURES
                .iter()
                .find(|f| f.0 == *name && size == 1024)
                .map_or("- | -".to_owned(), |f| {
                    format!("{:.2}x / {:.2}x | {:.2}x", f.1 / m1, f.2 / m2, f.3 / m1)
                });
            let ratio = |peer: Option<f64>, ours: f64| {
                peer.map_or("-".to_owned(), |p| format!("{:.2}x", p / ours))
            };
            let here = if peers.is_empty() {
                String::new()
            } else {
                format!(
                    " {} / {} | {} |",
                    ratio(peer(name, size, "llvmpipe", 1), m1),
                    ratio(peer(name, size, "llvmpipe", 2), m2),
                    ratio(peer(name, size, "euc", 1), m1),
                )
            };
            println!(
                "| {name} | {} | {size} | {mz:.2} ({nz:.2}) | {m1:.2} ({n1:.2}) | {m2:.2} ({n2:.2}) | {:.0} / {:.0} | {:.1}x / {:.1}x | {vs} |{here}",
                scene.triangle_count(),
                tris / m1 / 1e3,
                tris / m2 / 1e3,
                mz / m1,
                mz / m2,
            );
        }
    }
    Ok(())
}
