//! The scanline hidden-surface algorithm (Wylie, Romney, Evans and Erdahl
//! 1967; Watkins 1970): a [`Scanline`] hider that draws a prepared scene
//! one image row at a time, deciding visibility once per span of pixels
//! instead of once per pixel, with exactly the z-buffer's coverage and
//! answer.
//!
//! The lecture on image-space hidden-surface algorithms faults the
//! z-buffer for ignoring coherence: it decides every covered pixel of every
//! polygon on its own. The scanline
//! algorithm walks the image one row at a time and exploits two kinds of
//! coherence instead:
//! - *scan-line coherence*: an edge crosses row `j + 1` a constant step
//!   away from where it crossed row `j`, so edges are kept in an edge table
//!   bucketed by their starting row and stepped incrementally in an active
//!   edge list. The step is an exact integer walker on the shared edge
//!   functions, so each polygon's covered pixels on a row are exactly the
//!   z-buffer's (no float edge crossings);
//! - *span coherence*: between two consecutive edge crossings on a row the
//!   same polygons cover every pixel, so visibility is decided once per
//!   span with an active polygon list ordered by depth, splitting the span
//!   only where two polygons' depths cross (interpenetration).
//!
//! No per-pixel depth buffer is kept; a one-row buffer is the documented
//! fallback for spans that split too often
//! ([`ScanlineOptions::max_splits_per_span`], counted in
//! [`ScanlineStats::fallback_spans`]). Visibility per pixel is the
//! z-buffer's: window depth at the pixel centre, nearer wins, equal depths
//! go to the earlier primitive.
//!
//! # Example
//!
//! Two triangles that pierce each other: the spans crossing their
//! intersection line are split there.
//!
//! ```
//! use hider_scanline::{Scanline, ScanlineOptions};
//! use hider_scene::{prepare, procedural, Frame, Hider, PrepareOptions, View};
//!
//! let scene = procedural::intersecting_pair();
//! let view = View::for_scene(&scene, 64, 64)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let mut frame = Frame::new(64, 64)?;
//! let mut hider = Scanline::new(ScanlineOptions::default());
//! let stats = hider.render(&screen, &mut frame)?;
//! assert!(stats.split_spans > 0);
//! // Both triangles are visible somewhere.
//! assert!(frame.ids.contains(&0) && frame.ids.contains(&1));
//! // A second frame reuses the tables and does the same work.
//! let again = hider.render(&screen, &mut frame)?;
//! assert_eq!((again.spans, again.splits), (stats.spans, stats.splits));
//! # Ok::<(), hider_scene::Error>(())
//! ```

mod edge_table;
mod options;
mod scanline;
mod span;
mod stats;
mod trace;
mod walker;

pub use options::ScanlineOptions;
pub use scanline::Scanline;
pub use stats::ScanlineStats;
pub use trace::{ActiveEdge, EdgeRecord, Resolution, ScanlineTrace, Side, SpanRecord};

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;
