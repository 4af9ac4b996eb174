//! How the exact regions and lines grow with the input on scenes whose
//! drawing is bounded by the image: the random soup of `gen:soup:N` and
//! `N` large random triangles piled in a cube (the testkit's
//! `heavy_overdraw`), at 256 x 256, `N` doubling from a start until one
//! drawing takes longer than a cap (or a largest `N`). Prints one
//! markdown table with the work counters and the thread CPU time of
//! `visible_regions` + `regions_svg` and of `line_pairs` +
//! `hidden_lines_in` + `lines_svg` (what `hider render --svg` runs), and
//! the growth exponent of each time between successive sizes.
//!
//!
//! Two more families hold one big face group each, whose union is one
//! boolean over all its regions: a flat sheet of `N` triangles (a square
//! grid of cells) under a directional light, and a cube whose six faces
//! are each such a grid, one material (three faces seen, each a group);
//! and the sheet pierced by a random soup of `N / 8` triangles, so that
//! its group's union is over many cut pieces with holes.
//! Two more are the triangulations CAD files make of a disc or a
//! cylinder's cap and of a sphere's pole: a flat fan of `N` triangles
//! around one centre vertex, and the same fan with its centre raised
//! towards the camera (a cone seen from its apex). Every spoke meets the
//! centre, so anything that pairs edges or triangles by shared bins (or
//! boxes) costs the square of `N` there while nothing crosses.
//! Two more are where a segment's or a triangle's neighbours in square
//! bins are not the ones it can meet: `N` long thin parallel slivers in
//! seven planes (`sheets::slivers`, seen head-on: each plane's slivers
//! are one face group of separate pieces, and square bins hold a row of
//! them each), and two fans of `N / 2` triangles on one centre, one
//! tilted so that their triangles overlap there (`sheets::two_fans`),
//! and the slivers turned 45 degrees (square boxes, long diagonal
//! triangles).
//! The peak resident memory of each drawing is the process's (`VmHWM`,
//! reset before it; the scene is resident already, so it counts, and so
//! does heap the allocator kept from the family's smaller sizes); each
//! family runs in a process of its own.
//!
//! `cargo run --release -p hider-bench --bin vector_scaling -- [cap seconds] [largest N] [soup|pile|sheet|mesh|pierced|fan|cone|slivers|twofans|diagonal]`
//! (defaults: 20 s, 1,024,000 triangles, all ten families).

use std::time::Instant;

use glam::DVec3;
use hider_bench::machine;
use hider_bench::programs::thread_cpu_seconds;
use hider_scene::{PrepareOptions, Scene, ScreenScene, ShadeMode, View, prepare, procedural};
use hider_testkit::hard_cases::heavy_overdraw;
use hider_testkit::sheets::{self, grid, lit};
use hider_vector::{
    ObjectGroups, VectorOptions, hidden_lines_in, line_pairs, lines_svg, regions_svg,
    visible_regions,
};

/// Image side in pixels (the outsider's report measured at 256).
const SIZE: u32 = 256;

/// Seconds of CPU time (wall time where the platform gives none) of `f`.
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let wall = Instant::now();
    let cpu = thread_cpu_seconds();
    let out = f();
    let seconds = thread_cpu_seconds()
        .zip(cpu)
        .map_or(wall.elapsed().as_secs_f64(), |(b, a)| b - a);
    (out, seconds)
}

/// The peak resident memory since the last
/// [`machine::reset_peak_resident`], in MB (`-` where the platform gives
/// none).
fn peak_mb() -> String {
    machine::peak_resident_bytes().map_or("-".into(), |b| format!("{:.0}", b as f64 / 1048576.0))
}

/// A flat sheet of about `n` triangles.
fn sheet(n: u32) -> Scene {
    let cells = (f64::from(n) / 2.0).sqrt().round().max(1.0) as u32;
    lit(vec![grid(cells, |p| p)])
}

/// The sheet of `n` triangles pierced by the random soup of `n / 8`
/// (`gen:soup`): the sheet's group is cut into many pieces with holes.
fn pierced(n: u32) -> Scene {
    let mut scene = sheet(n);
    let soup = procedural::random_soup(n / 8, 1);
    let material = soup.materials.into_iter().next();
    for mut mesh in soup.meshes {
        mesh.material = None;
        scene.push_mesh(mesh, material.clone());
    }
    scene
}

/// A cube of about `n` triangles, each face a grid, turned so that three
/// faces are seen.
fn mesh(n: u32) -> Scene {
    let cells = (f64::from(n) / 12.0).sqrt().round().max(1.0) as u32;
    let turn = glam::DMat3::from_rotation_y(0.6) * glam::DMat3::from_rotation_x(0.5);
    // The grid's plane flattened to z = 0, then moved onto a face: the
    // axes of each face chosen so that it faces outward.
    let faces: [(DVec3, DVec3, DVec3); 6] = [
        (DVec3::X, DVec3::Y, DVec3::Z),
        (DVec3::Y, DVec3::X, -DVec3::Z),
        (DVec3::Y, DVec3::Z, DVec3::X),
        (DVec3::Z, DVec3::Y, -DVec3::X),
        (DVec3::Z, DVec3::X, DVec3::Y),
        (DVec3::X, DVec3::Z, -DVec3::Y),
    ];
    let meshes = faces
        .iter()
        .map(|&(u, v, w)| grid(cells, move |p| turn * (p.x * u + p.y * v + w)))
        .collect();
    lit(meshes)
}

/// A fan of `n` triangles around the origin in the plane `z = 0`, its
/// centre raised to `z = apex` (0: flat).
fn fan(n: u32, apex: f64) -> Scene {
    lit(vec![sheets::fan(n, apex)])
}

/// `n` long thin parallel slivers in seven planes.
fn slivers(n: u32) -> Scene {
    lit(vec![sheets::slivers(n)])
}

/// The slivers turned 45 degrees in their planes: their boxes are
/// square, so bins shaped like the boxes stay square.
fn diagonal_slivers(n: u32) -> Scene {
    let mut mesh = sheets::slivers(n);
    let turn = glam::DMat3::from_rotation_z(std::f64::consts::FRAC_PI_4);
    for p in &mut mesh.positions {
        *p = turn * *p;
    }
    lit(vec![mesh])
}

/// Two fans of `n / 2` triangles on one centre, one tilted.
fn two_fans(n: u32) -> Scene {
    lit(vec![sheets::two_fans(n / 2, 0.3)])
}

fn exponent(last: Option<(f64, f64)>, n: f64, t: f64) -> String {
    last.map_or("-".into(), |(n0, t0)| {
        format!("{:.2}", (t / t0.max(1e-4)).ln() / (n / n0).ln())
    })
}

fn main() -> Result<(), hider_scene::Error> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let cap = args.first().copied().unwrap_or(20.0);
    let largest = args.get(1).copied().unwrap_or(1_024_000.0) as u32;
    let only = std::env::args().nth(3);
    let options = VectorOptions::default();
    println!(
        "| scene | N | culled | candidate pairs | overlapping pairs | differences | outline triangles | region points | snap segments | sweep tests | snap nodes | largest group | regions s | exponent | regions MB | line features | culled features | occluder tests | lines s | exponent | lines MB |"
    );
    println!(
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    type Family = (&'static str, &'static str, u32, fn(u32) -> Scene);
    let families: [Family; 10] = [
        ("`gen:soup:N`", "soup", 2_000, |n| {
            procedural::random_soup(n, 1)
        }),
        ("`heavy_overdraw(N, 1)`", "pile", 250, |n| {
            heavy_overdraw(n, 1)
        }),
        ("flat sheet", "sheet", 2_000, sheet),
        ("cube of grids", "mesh", 2_000, mesh),
        ("sheet pierced by `gen:soup:N/8`", "pierced", 2_000, pierced),
        ("flat fan", "fan", 2_000, |n| fan(n, 0.0)),
        ("cone from its apex", "cone", 2_000, |n| fan(n, 0.5)),
        ("parallel slivers", "slivers", 2_000, slivers),
        ("two fans on one centre", "twofans", 2_000, two_fans),
        ("diagonal slivers", "diagonal", 2_000, diagonal_slivers),
    ];
    for (name, key, start, make) in families {
        let Some(only) = only.as_deref() else {
            // Each family in a process of its own, so that no heap kept
            // from an earlier family counts in a later one's peak.
            let exe = std::env::current_exe().expect("this program's path");
            let out = std::process::Command::new(exe)
                .args([cap.to_string(), largest.to_string(), key.to_string()])
                .output()
                .expect("run one family");
            let text = String::from_utf8_lossy(&out.stdout);
            text.lines().skip(2).for_each(|l| println!("{l}"));
            if !out.status.success() {
                println!("| {name} | stopped: {} |", out.status);
            }
            continue;
        };
        if only != key {
            continue;
        }
        let mut n = start;
        let (mut last_r, mut last_l) = (None, None);
        while n <= largest {
            let scene = make(n);
            let view = View::for_scene(&scene, SIZE, SIZE)?;
            let s: ScreenScene = prepare(&scene, &view, &PrepareOptions::default())?;
            machine::reset_peak_resident();
            let (map, tr) = timed(|| {
                let map = visible_regions(&s, &options, ShadeMode::Lambert)?;
                let svg = regions_svg(&s, &map, &options);
                Ok::<_, hider_scene::Error>((map, svg.len()))
            });
            let (map, _) = map?;
            let mr = peak_mb();
            let largest_group = map.groups.iter().map(|g| g.prims.len()).max().unwrap_or(0);
            machine::reset_peak_resident();
            let (lines, tl) = timed(|| {
                let pairs = line_pairs(&s, &options)?;
                let lines = hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default())?;
                let svg = lines_svg(&s, &lines, &options);
                Ok::<_, hider_scene::Error>((lines, svg.len()))
            });
            let (lines, _) = lines?;
            let ml = peak_mb();
            let (r, l) = (map.stats, lines.stats);
            let x = f64::from(n);
            println!(
                "| {name} | {n} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {largest_group} | {tr:.2} | {} | {mr} | {} | {} | {} | {tl:.2} | {} | {ml} |",
                r.culled,
                r.candidate_pairs,
                r.overlapping_pairs,
                r.differences,
                r.outline_triangles,
                r.region_points,
                r.snap_segments,
                r.sweep_tests,
                r.snap_nodes,
                exponent(last_r, x, tr),
                l.feature_edges,
                l.culled_features,
                l.occluder_tests,
                exponent(last_l, x, tl),
            );
            last_r = Some((x, tr));
            last_l = Some((x, tl));
            if tr.max(tl) > cap {
                break;
            }
            n *= 2;
        }
    }
    Ok(())
}
