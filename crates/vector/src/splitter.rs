//! The one way this crate builds a polygon boolean: `i_overlay` with its
//! sweep-list segment splitter, whatever the input's size.
//!
//! Past 4,000 segments `i_overlay`'s default (`Solver::AUTO`) switches to
//! its tree splitter, and past 16,000 to the fragment splitter. On the
//! snapped regions of `gen:soup:64000` at 256 px (17,717 contours,
//! 173,694 points, crossing-free) both build a graph whose contour walk
//! never returns to its start: 4.5.2 then grows one contour until memory
//! runs out (7.6 GB asked for). The list splitter gives the answer on the
//! same input at once. No small input that triggers it was found, so no
//! call may reach the other splitters: the face groups' unions (a flat
//! sheet of 128,000 triangles is one boolean of 768,000 points), the
//! ownership differences, the closing pass and the triangles' differences
//! all come here. Below 4,000 segments this is what `AUTO` chose anyway.
//!
//! The list splitter compares each segment with those after it in x order
//! until one starts beyond its end: linear times the segments spanning
//! one x, which on snapped or small inputs stays small (docs/vector.md,
//! the scaling table's sheet and cube rows).

use i_overlay::core::overlay::Overlay;
use i_overlay::core::solver::Solver;

/// An overlay with room for about `points` points that splits segments
/// with the sweep list only.
pub fn list_overlay(points: usize) -> Overlay {
    Overlay::new_custom(points, Default::default(), Solver::LIST)
}
