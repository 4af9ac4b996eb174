//! Test set-up shared by the hider workspace, so that every crate's tests
//! and examples build scenes, cameras and references the same way.
//!
//! - [`hard_cases`]: deterministic scenes built to break hidden-surface
//!   algorithms (intersections, ties, precision, degenerate triangles...);
//! - [`screen()`] / [`screen_with`]: a world-space scene prepared with the
//!   default front end, and [`render()`] into a fresh frame;
//! - [`cameras`]: the 60-degree look-at camera and random cameras;
//! - [`reference`](mod@reference): the pixel-centre references from `hider-oracle` (the
//!   brute-force window-depth z-buffer and the ray cast);
//! - [`score`]: counting wrong pixels and ties against a reference, and
//!   tallies for property tests;
//! - [`sheets`]: big flat faces, grids of many coplanar triangles of one
//!   colour;
//! - [`timer`]: warm-up, repeated runs, median and minimum, for examples;
//! - `lean_reference` (feature `lean`): the brute-force definition of the
//!   z-buffer's lean depth-only front end;
//! - `hostile` (feature `hostile`): arbitrary bytes decoded as scenes and
//!   the invariants every registered hider keeps on them, shared with the
//!   fuzz targets;
//! - `differential` (feature `hostile`): bytes decoded into the hard-case
//!   families at extreme scales, offsets and near planes, and the check
//!   that every exact hider equals the oracle off ties on them.
//!
//! A dev-dependency only (`publish = false`); test code panics on errors
//! rather than returning them.
//!
//! # Example
//!
//! Render a hard case with the oracle and score it against the brute-force
//! pixel-centre z-buffer:
//!
//! ```
//! use hider_oracle::RayCastOracle;
//! use hider_testkit::{hard_cases, reference, render, score, screen};
//!
//! let scene = hard_cases::interpenetrating_boxes(3, 1);
//! let s = screen(&scene, 32, 32);
//! let (frame, stats) = render(&mut RayCastOracle::default(), &s);
//! let result = score::score(&reference::pixel_centre(&s), &frame, 1e-8);
//! assert_eq!(result.coverage_mismatches, 0, "{result}");
//! assert!(stats.hits > 0);
//! ```

pub mod cameras;
pub mod crossing;
#[cfg(feature = "hostile")]
pub mod differential;
pub mod front_end_input;
pub mod hard_cases;
#[cfg(feature = "hostile")]
pub mod hostile;
#[cfg(feature = "lean")]
pub mod lean_reference;
pub mod reference;
pub mod score;
pub mod screen;
pub mod sheets;
pub mod timer;

#[cfg(feature = "lean")]
pub use lean_reference::lean_reference;
pub use screen::{frame_for, render, screen, screen_with};
