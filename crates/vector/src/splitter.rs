//! The one way this crate builds a polygon boolean: `i_overlay` on `i32`
//! coordinates, with the sweep-list segment splitter for now.
//!
//! (Being switched to `i_overlay` 9.1's automatic choice; see below.)

use i_overlay::core::solver::Solver;

/// Polygon sets on the crate's integer grid: shapes, each an outer
/// contour (counter-clockwise) followed by its holes.
pub type IntShapes = i_overlay::i_shape::int::shape::IntShapes<i32>;

/// A polygon boolean on the crate's integer grid.
pub type Overlay = i_overlay::core::overlay::Overlay<i32>;

/// An overlay with room for about `points` points that splits segments
/// with the sweep list only.
pub fn list_overlay(points: usize) -> Overlay {
    Overlay::new_custom(points, Default::default(), Solver::LIST)
}
