//! Work on random triangles overlapping in a cube must follow what the
//! picture can show, not the square of the input (issue 37, item 3).
//!
//! N triangles with corners anywhere in a cube pierce each other in about
//! N^2 segments, so a painter that orders every piece needs about N^2
//! splits and, since every piece overlaps nearly every other in depth and
//! on screen, about N^4 comparisons: 15,173 splits and 21 M comparisons
//! at 125 triangles, 84,409 and 444 M at 250 (release `painter_cube`
//! before the culling; 500 ran out of split budget after 105 s). At a
//! fixed image size the picture is bounded, and pieces hidden at every
//! point are culled as they are made (`cull.rs`), so once the scene is
//! many layers deep the work grows far slower than N^2. The bound checked
//! here: doubling N less than triples each counter (growth below
//! N^1.58; quadratic growth quadruples it). Counters, never seconds.

use hider_painter::{Painter, PainterOptions, PainterStats};
use hider_scene::Hider;
use hider_testkit::crossing::cube_triangles;
use hider_testkit::{render, screen};

/// The painter's counters on `n` cube triangles at `size` x `size`, with
/// the raster checked against the z-buffer on the same planes.
fn stats(n: u32, size: u32) -> PainterStats {
    let s = screen(&cube_triangles(n, 1), size, size);
    let (frame, stats) = render(&mut Painter::new(PainterOptions::default()), &s);
    let reference = hider_testkit::reference::pixel_centre(&s);
    let wrong = reference
        .ids
        .iter()
        .zip(&frame.ids)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(wrong, 0, "{n} triangles at {size} px");
    stats
}

#[test]
fn doubling_the_triangles_in_a_cube_less_than_triples_the_work() {
    let size = 64;
    let runs: Vec<(u32, PainterStats)> = [500, 1000, 2000]
        .into_iter()
        .map(|n| (n, stats(n, size)))
        .collect();
    for pair in runs.windows(2) {
        let ((n0, a), (n1, b)) = (pair[0], pair[1]);
        for (what, before, after) in [
            ("comparisons", a.comparisons, b.comparisons),
            ("splits", a.splits, b.splits),
            ("moves", a.moves, b.moves),
            ("pieces out", a.pieces_out, b.pieces_out),
        ] {
            assert!(
                after < 3 * before,
                "{what}: {before} at {n0} triangles, {after} at {n1}"
            );
        }
    }
    // The default split budget holds them with room to spare.
    let (n, last) = runs[runs.len() - 1];
    assert!(last.splits < 64 * u64::from(n) / 4, "{last:?}");
    assert!(last.culled > 0, "{last:?}");
}

/// The size: 500 random intersecting triangles at 512 x 512 are
/// ordered within the default budget, exactly.
#[test]
fn five_hundred_triangles_in_a_cube_fit_the_default_budget() {
    let st = stats(500, 512);
    assert!(st.splits < 20_000, "{st:?}");
    assert!(st.culled > st.pieces_out / 2, "{st:?}");
}
