//! The one way this crate builds a polygon boolean: `i_overlay` on `i32`
//! coordinates, its segment splitter chosen by the input's size.
//!
//! `i_overlay` splits segments at their crossings with a sweep list below
//! 2,000 segments, a tree above, and a fragment grid past 32,000. The list
//! compares each segment with those after it in x order until one starts
//! beyond its end, so its cost is the segments times those spanning one
//! x: a face group of `N` long parallel slivers (every segment spans the
//! whole x range) made it quadratic, 72% of the regions' time at 32,000
//! slivers. The tree's cost follows the segments and crossings.
//!
//! Up to `i_overlay` 4.5.2 the crate used the list splitter alone: on the
//! snapped regions of `gen:soup:64000` at 256 px (17,717 contours,
//! 173,694 points, crossing-free) 4.5.2's tree and fragment splitters
//! built a graph whose contour walk never returned to its start, and one
//! contour grew until memory ran out (7.6 GB asked for). 9.1 gives the
//! same shapes with every splitter on that input
//! (`tests/scaling.rs`, `the_64000_triangle_soup_has_its_regions`, holds
//! its areas).

/// Polygon sets on the crate's integer grid: shapes, each an outer
/// contour (counter-clockwise) followed by its holes (clockwise).
pub type IntShapes = i_overlay::i_shape::int::shape::IntShapes<i32>;

/// A polygon boolean on the crate's integer grid.
pub type Overlay = i_overlay::core::overlay::Overlay<i32>;

/// An overlay with room for about `points` points, its splitter chosen
/// by `i_overlay` (`Solver::AUTO`) from the segments it is given.
pub fn new_overlay(points: usize) -> Overlay {
    Overlay::new(points)
}
