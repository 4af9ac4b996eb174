//! Renders one scene with one hider a few times, for profilers
//! (`perf record`, `valgrind --tool=callgrind`).
//!
//! `cargo run --release -p hider-bench --bin abuffer_profile -- SCENE HIDER [RUNS] [SIZE]`
//!
//! SCENE: `soup1k`, `soup10k`, `soup100k`, `sphere` (uv_sphere(200)),
//! `sphere500`, `sphere500-smooth` (with vertex normals), `spider` (the bundled
//! `assets/spider`, the GL reference's model, textured), `spider-flat`
//! (the spider without its textures), `spider-cutout` (the spider with
//! a cut-out checker texture: the alpha test per sample), `cube` (12 large
//! triangles: whole pixels), `one`
//! (a single triangle: the fixed cost of a frame);
//! HIDER: `ssaa1`, `ssaa32`, `sorted` (the sorted-transparency z-buffer,
//! 32 samples), `ssaa1-scene` / `ssaa32-scene` / `sorted-scene` (the
//! same from the world-space scene, through the lean front end; with
//! `-prep` after `-scene`, through `prepare` and `render` instead: what
//! `render_scene` ran before the baselines took the lean front end), `ps`
//! (A-buffer, per-sample), `ps-nomerge`
//! (merging off), `mm` (min/max),
//! `carpenter`, `ps2` (per-sample on 2 threads; the others take 1),
//! `cov` (mask generation alone), `ps-scene` / `carpenter-scene` /
//! `lists-scene` (the whole pipeline from the world-space scene: the lean
//! front end, then the render, GL-compatible front end; `lists-scene` with
//! every tile on fragment lists; `ids-scene` as `ps-scene` with identifier
//! colours, no Lambert shading; `ps2-scene` on 2 threads), `lean` (the lean front end
//! alone) or `prepare` (`prepare` alone). Prints the median and
//! fastest of the renders (the workspace's shared timer, no warm-up: a
//! profile sees the first frame too), the work counters and a digest of
//! the last frame (colour, coverage, ids and depth: two builds draw the
//! same frame bit for bit when their digests agree).

use hider_abuffer::{
    ABuffer, ABufferOptions, DepthMode, SamplePattern, SortedTransparencyZBuffer, SsaaOptions,
    SupersampledZBuffer, TriCoverage, pixel_range,
};
use hider_scene::prepare::lean::{LeanScene, prepare_lean_into};
use hider_scene::{
    DynHider, Frame, Hider, PrepareOptions, ScreenScene, StatsTable, View, prepare_into, procedural,
};
use hider_testkit::screen;
use hider_testkit::timer::Timer;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene = match args.first().map_or("soup10k", String::as_str) {
        "soup1k" => procedural::random_soup(1_000, 1),
        "soup10k" => procedural::random_soup(10_000, 1),
        "soup100k" => procedural::random_soup(100_000, 1),
        "sphere" => procedural::uv_sphere(200),
        "sphere500" => procedural::uv_sphere(500),
        "sphere500-smooth" => {
            // Smooth shading: a normal per vertex, from the centre.
            let mut s = procedural::uv_sphere(500);
            for mesh in &mut s.meshes {
                mesh.normals = mesh
                    .positions
                    .iter()
                    .map(|p| p.normalize().as_vec3())
                    .collect();
            }
            s
        }
        "one" => procedural::random_soup(1, 1),
        "cube" => procedural::cube(),
        "spider" => hider_bench::programs::spider().expect("the bundled spider"),
        "spider-flat" => {
            // The spider with its texture statements removed: the same
            // triangles, coloured flat (what a textured frame is compared
            // with).
            let mut s = hider_bench::programs::spider().expect("the bundled spider");
            for m in &mut s.materials {
                m.diffuse_texture = None;
                m.specular_texture = None;
            }
            s
        }
        "spider-cutout" => {
            // The spider with a cut-out `map_Kd` (a checker of opaque and
            // fully transparent squares of 16 texels, 256 x 256) on every
            // material: the alpha test at every sample.
            let mut s = hider_bench::programs::spider().expect("the bundled spider");
            let side = 256;
            let texels: Vec<u8> = (0..side * side)
                .flat_map(|k| {
                    let (x, y) = (k % side / 16, k / side / 16);
                    let a = if (x + y) % 2 == 0 { 255 } else { 0 };
                    [(x * 16) as u8, (y * 16) as u8, 128, a]
                })
                .collect();
            let texture = hider_scene::shade::Texture::from_srgba8(side, side, &texels)
                .expect("a checker texture");
            for m in &mut s.materials {
                m.diffuse_texture = Some(hider_scene::TextureRef::from_texture(
                    "cutout-checker.png",
                    texture.clone(),
                ));
            }
            s
        }
        other => panic!("unknown scene {other}"),
    };
    // `NAME-prep`: NAME's hider, the scene prepared and rendered.
    let (name, prep) = match args.get(1).map(String::as_str) {
        Some(n) => n.strip_suffix("-prep").map_or((n, false), |n| (n, true)),
        None => ("ps", false),
    };
    let mut hider: Box<dyn DynHider> = match name {
        "ssaa1" => Box::new(SupersampledZBuffer::new(
            SsaaOptions::default().with_pattern(SamplePattern::Centre),
        )),
        "ssaa1-scene" => Box::new(SupersampledZBuffer::new(
            SsaaOptions::default().with_pattern(SamplePattern::Centre),
        )),
        "ssaa32" | "ssaa32-scene" => Box::new(SupersampledZBuffer::new(SsaaOptions::default())),
        "sorted" | "sorted-scene" => {
            Box::new(SortedTransparencyZBuffer::new(SsaaOptions::default()))
        }
        "ps" => Box::new(ABuffer::new(ABufferOptions::default().with_threads(1))),
        "ps2" => Box::new(ABuffer::new(ABufferOptions::default().with_threads(2))),
        "ps-nomerge" => Box::new(ABuffer::new(
            ABufferOptions::default()
                .with_merge(hider_abuffer::MergePolicy::Off)
                .with_threads(1),
        )),
        "mm" => Box::new(ABuffer::new(
            ABufferOptions::default()
                .with_depth(DepthMode::MinMax)
                .with_threads(1),
        )),
        "carpenter" => Box::new(ABuffer::new(ABufferOptions::carpenter().with_threads(1))),
        "cov" | "lean" | "prepare" => Box::new(ABuffer::default()),
        "ps-scene" => Box::new(ABuffer::new(ABufferOptions::default().with_threads(1))),
        "ps2-scene" => Box::new(ABuffer::new(ABufferOptions::default().with_threads(2))),
        "ids-scene" => Box::new(ABuffer::new(
            ABufferOptions::default()
                .with_shade(hider_scene::ShadeMode::Ids)
                .with_threads(1),
        )),
        "lists-scene" => Box::new(ABuffer::new(
            ABufferOptions::default()
                .with_sample_tiles(false)
                .with_threads(1),
        )),
        "carpenter-scene" => Box::new(ABuffer::new(ABufferOptions::carpenter().with_threads(1))),
        other => panic!("unknown hider {other}"),
    };
    let runs: u32 = args.get(2).map_or(3, |r| r.parse().expect("runs"));
    let size: u32 = args.get(3).map_or(1024, |r| r.parse().expect("size"));
    let s = screen(&scene, size, size);
    let timer = Timer::new(runs).with_warmup(0);
    if args.get(1).map(String::as_str) == Some("cov") {
        // Mask generation alone: the shared front of every hider here.
        let (mut hits, mut bits, mut visits) = (0u64, 0u64, 0u64);
        let summary = timer.time(|| {
            (hits, bits, visits) = (0, 0, 0);
            for tri in &s.tris {
                let pattern = SamplePattern::Grid32;
                let Some((x0, y0, x1, y1)) = pixel_range(tri, pattern, size, size) else {
                    continue;
                };
                let setup = TriCoverage::new(tri, pattern);
                visits += u64::from(x1 - x0 + 1) * u64::from(y1 - y0 + 1);
                for j in y0..=y1 {
                    for (_, c) in setup.row(x0, x1, j) {
                        hits += 1;
                        bits += u64::from(c.mask.count_ones());
                    }
                }
            }
        });
        println!("{summary}  visits {visits} hits {hits} bits {bits}");
        return;
    }
    let mut frame = Frame::new(size, size).expect("frame");
    let mut stats = StatsTable::default();
    let which = name;
    if matches!(
        which,
        "ps-scene"
            | "ssaa1-scene"
            | "ssaa32-scene"
            | "sorted-scene"
            | "ps2-scene"
            | "ids-scene"
            | "lists-scene"
            | "carpenter-scene"
            | "lean"
            | "prepare"
    ) {
        let view = View::for_scene(&scene, size, size).expect("view");
        // `ps2-scene`: the front end and the bands in parallel in one
        // 2-thread pool, as `abuffer_bench` runs them.
        let two = which == "ps2-scene";
        let options = PrepareOptions::gl_compatible().with_parallel(two);
        if two {
            rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build_global()
                .expect("a 2-thread pool");
        }
        let mut screen = ScreenScene::empty(&view);
        let mut lean = LeanScene::new();
        let summary = timer.time(|| match which {
            "lean" => prepare_lean_into(&scene, &view, &options, &mut lean).expect("lean"),
            "prepare" => prepare_into(&scene, &view, &options, &mut screen).expect("prepare"),
            _ if prep => {
                prepare_into(&scene, &view, &options, &mut screen).expect("prepare");
                stats = hider.render(&screen, &mut frame).expect("render");
            }
            _ => {
                stats = hider
                    .render_scene(&scene, &view, &options, &mut screen, &mut frame)
                    .expect("render")
            }
        });
        println!("{summary}  {stats}  frame {:016x}", digest(&frame));
        return;
    }
    let summary = timer.time(|| stats = hider.render(&s, &mut frame).expect("render"));
    println!("{summary}  {stats}  frame {:016x}", digest(&frame));
}

/// A hash of everything `frame` holds, the floats by their bits.
fn digest(frame: &Frame) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    frame.color.hash(&mut h);
    frame.ids.hash(&mut h);
    for v in frame.depth.iter().chain(&frame.coverage) {
        v.to_bits().hash(&mut h);
    }
    h.finish()
}
