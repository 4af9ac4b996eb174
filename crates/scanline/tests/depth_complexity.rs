//! Thousands of polygons on one span: a pile of tiny triangles all covering
//! one pixel centre. The active polygon list's upkeep (sorting by depth,
//! removing the polygons whose runs end) must stay near linear in the pile,
//! which the work counters show; the picture must stay the reference's.

mod common;

use common::{assert_matches, render};
use hider_scanline::ScanlineOptions;
use hider_scene::NO_ID;
use hider_testkit::{hard_cases, screen};

#[test]
fn a_pile_over_one_pixel_costs_near_linear_list_work() {
    for n in [2_000u32, 16_000] {
        let s = screen(&hard_cases::one_pixel_pile(n, 5), 64, 64);
        assert_eq!(s.tris.len(), n as usize);
        let (frame, stats) = render(&s, ScanlineOptions::default());
        assert_matches(&s, &frame, "pile");
        assert_eq!(frame.ids.iter().filter(|&&id| id != NO_ID).count(), 1);
        assert_eq!(stats.span_polygons_max, u64::from(n));
        // Every run ends on the same column: one removal pass over the
        // list instead of one search per polygon (n^2 / 2 entries).
        let n64 = u64::from(n);
        assert!(
            stats.apl_removal_scanned <= 2 * n64,
            "n = {n}: {} entries scanned",
            stats.apl_removal_scanned
        );
        // Sorting n random depths: n log2 n comparisons, not the n^2 / 4
        // moves of an insertion sort.
        let log = f64::from(n).log2().ceil() as u64;
        assert!(
            stats.sort_comparisons <= 2 * n64 * log,
            "n = {n}: {} comparisons",
            stats.sort_comparisons
        );
    }
}
