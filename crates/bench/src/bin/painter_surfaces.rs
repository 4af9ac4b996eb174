//! Two intersecting height fields, the scene of the Python binding's
//! matplotlib benchmark: `z = x y` and `z = 0.5 sin(3x) + 0.3 y` on a
//! 100 x 100 grid over [-1, 1]^2 (39,204 triangles), seen from above at
//! matplotlib's default angle (30 degrees up) at 600 x 600. Most pairs of
//! triangles never meet on screen; the ones along the curve where the
//! surfaces cross must be split. Times the front end and the painter's
//! `render` and its ordering alone (median and min over several runs),
//! prints its counters and
//! checks the raster against the window-depth z-buffer.
//!
//! `cargo run --release -p hider-bench --bin painter_surfaces -- [grid] [runs]`
//! (default grid 100, runs 9).

use glam::DVec3;
use hider_geom::Camera;
use hider_painter::{Painter, PainterOptions};
use hider_scene::{Frame, Hider, Mesh, PrepareOptions, Scene, View, prepare};
use hider_testkit::reference;
use hider_testkit::score::score;
use hider_testkit::timer::Timer;

/// A `grid x grid` height field of `f` over [-1, 1]^2, height along +Y.
fn surface(grid: usize, f: impl Fn(f64, f64) -> f64) -> Mesh {
    let at = |k: usize| -1.0 + 2.0 * k as f64 / (grid - 1) as f64;
    let mut positions = Vec::with_capacity(grid * grid);
    for j in 0..grid {
        for i in 0..grid {
            let (x, y) = (at(i), at(j));
            positions.push(DVec3::new(x, f(x, y), -y));
        }
    }
    let mut indices = Vec::with_capacity(2 * (grid - 1) * (grid - 1));
    let id = |i: usize, j: usize| (j * grid + i) as u32;
    for j in 0..grid - 1 {
        for i in 0..grid - 1 {
            indices.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            indices.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh {
        name: "surface".into(),
        positions,
        indices,
        ..Mesh::default()
    }
}

fn main() -> Result<(), hider_scene::Error> {
    let mut args = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse::<usize>().ok());
    let grid = args.next().unwrap_or(100).max(2);
    let runs = args.next().unwrap_or(9).clamp(1, 1000) as u32;
    let mut scene = Scene::default();
    scene.push_mesh(surface(grid, |x, y| x * y), None);
    scene.push_mesh(surface(grid, |x, y| 0.5 * (3.0 * x).sin() + 0.3 * y), None);
    // matplotlib's default view: 30 degrees above the plane, azimuth -60.
    let (elev, azim) = (30f64.to_radians(), (-60f64).to_radians());
    let dir = DVec3::new(
        elev.cos() * azim.cos(),
        elev.sin(),
        -elev.cos() * azim.sin(),
    );
    let camera = Camera::perspective(dir * 4.0, DVec3::ZERO, 0.5, 10.0);
    let view = View::new(camera, 600, 600)?;
    let options = PrepareOptions::default();
    let timer = Timer::new(runs);
    let mut screen = prepare(&scene, &view, &options)?;
    let front = timer.time(|| screen = prepare(&scene, &view, &options).expect("prepared once"));
    let mut painter = Painter::new(PainterOptions::default());
    let mut frame = Frame::new(600, 600)?;
    let mut stats = painter.render(&screen, &mut frame)?;
    let order = timer.time(|| {
        stats = painter.render(&screen, &mut frame).expect("rendered once");
    });
    println!("painter counters: {stats:?}");
    // Ordering alone, as a caller that draws the pieces itself runs it.
    let ordered = timer.time(|| {
        painter.order(&screen).expect("ordered once");
    });
    let truth = reference::pixel_centre(&screen);
    // Pixels where another triangle is within 1e-8 of the nearest are
    // ties, which any order may show.
    let result = score(&truth, &frame, 1e-8);
    let wrong = result.coverage_mismatches + result.wrong_ids;
    println!(
        "{} triangles: front end {front}; painter render {order}, order only {ordered}; {} comparisons, {} moves, \
         {} splits, {} pieces, {wrong} pixels differ from the z-buffer",
        screen.tris.len(),
        stats.comparisons,
        stats.moves,
        stats.splits,
        stats.pieces_out
    );
    Ok(())
}
