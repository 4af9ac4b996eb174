//! Painter's algorithm hiders: paint polygons back to front, and get the
//! visible surfaces as an ordered polygon list (SVG) as well as a raster.
//!
//! Object-space hidden-surface removal by painting polygons back to front,
//! in two forms:
//!
//! - [`NaivePainter`] (`"painter-naive"`): sort the triangles by one depth
//!   each (farthest vertex, or centroid) and paint. Wrong where triangles
//!   intersect or overlap cyclically, as the software-renderer tutorial
//!   (chapter 8) and scratchapixel's depth-buffer lesson describe; kept to
//!   show that.
//! - [`Painter`] (`"painter"`): Newell, Newell & Sancha (1972). After the
//!   sort, each candidate is checked against the polygons it overlaps in
//!   depth with Newell's six tests (depth, x and y extents, the two
//!   plane-side tests, exact projected overlap); polygons that must go
//!   first are moved ahead, and where no order exists one polygon is split
//!   by the other's plane and the pieces ([`Piece`]) re-inserted. Pieces
//!   keep their primitive id, and a split budget bounds the work. Plane
//!   sides are decided by Shewchuk's adaptive `orient3d` on the front
//!   end's own coordinates, without a depth tolerance, so the order does
//!   not depend on scale, near plane or symmetry; a pair where one piece
//!   covers at most one pixel centre is decided by the depths on that
//!   centre, which keeps a pile of sub-pixel triangles at O(n log n). Pieces
//!   hidden at every point of their polygon behind opaque triangles are
//!   culled before they are ordered ([`PainterOptions::cull_hidden`]), so
//!   deep overlapping scenes cost what they show; an opt-in
//!   [`PainterTrace`] records every step.
//!
//! Both paint through the shared coverage rules: a piece covers a pixel
//! centre iff its source triangle does under the exact edge
//! functions and its cuts keep it ([`Cut`]), so split pieces never crack or
//! double-cover, and on every pixel that is not a depth tie [`Painter`]
//! gives the z-buffer's (and the oracle's) primitive. Both keep the ordered
//! pieces of their last frame and write them as SVG through
//! [`Hider::ordered_polygons`](hider_scene::Hider::ordered_polygons).
//!
//! # Example
//!
//! Two triangles that pierce each other: the naive sort gets part of the
//! picture wrong, the Newell–Newell–Sancha painter splits and gets it
//! right, and writes the split pieces as SVG.
//!
//! ```
//! use hider_painter::{NaivePainter, Painter, PainterOptions};
//! use hider_scene::{prepare, procedural, Frame, Hider, PrepareOptions, ShadeMode, View};
//!
//! let scene = procedural::intersecting_pair();
//! let view = View::for_scene(&scene, 48, 48)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//!
//! let mut painter = Painter::new(PainterOptions::default());
//! let mut frame = Frame::new(48, 48)?;
//! let stats = painter.render(&screen, &mut frame)?;
//! assert!(stats.splits >= 1, "an intersection needs a split");
//! assert_eq!(painter.name(), "painter");
//!
//! // The naive painter covers the same pixels but shows the wrong
//! // triangle on one side of the intersection line.
//! let mut naive_frame = Frame::new(48, 48)?;
//! NaivePainter::default().render(&screen, &mut naive_frame)?;
//! assert_eq!(naive_frame.covered_count(), frame.covered_count());
//! assert_ne!(naive_frame.ids, frame.ids);
//!
//! // The pieces of the frame just rendered, as SVG.
//! let path = std::env::temp_dir().join("hider-painter-doc-example.svg");
//! painter
//!     .ordered_polygons()
//!     .expect("painters have vector output")
//!     .write_svg(&screen, &path, ShadeMode::Lambert)?;
//! assert!(std::fs::read_to_string(&path)?.contains("<path"));
//! # std::fs::remove_file(&path).ok();
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod bins;
mod blocker;
mod centres;
mod cull;
mod naive;
mod newell;
mod options;
mod order;
mod painter;
mod piece;
mod raster;
mod resolve;
mod sides;
mod split;
#[cfg(test)]
mod star_tests;
mod stats;
mod svg;
mod trace;

pub use naive::NaivePainter;
pub use options::{NaivePainterOptions, PainterOptions, SPLIT_BUDGET, SortKey};
pub use painter::Painter;
pub use piece::{Cut, Piece};
pub use stats::PainterStats;
pub use trace::{PainterTrace, TraceEvent, TraceTest};

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;
