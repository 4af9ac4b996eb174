//! Warnock's area-subdivision hidden-surface algorithm: a [`Warnock`]
//! hider that draws a prepared scene by cutting the image into quadrants
//! until each is simple enough to draw, exactly at pixel centres or
//! anti-aliased on a sub-pixel grid.
//!
//! Warnock (1969, "A hidden surface algorithm for computer generated
//! halftone pictures") divides and conquers the *image*: look at a window;
//! if what it holds is simple enough to draw, draw it; otherwise cut it into
//! four quadrants and look again. The lecture on image-space hidden-surface
//! algorithms lists it with the z-buffer and the scanline algorithm.
//!
//! This crate runs that loop (iterative, with an explicit stack) over the shared [`ScreenScene`](hider_scene::ScreenScene):
//! - each polygon is classified against a region as surrounding,
//!   intersecting, contained or disjoint with the shared
//!   exact integer edge functions, evaluated at the region's extreme
//!   *samples* (a region is a rectangle of pixels, and what matters is which
//!   of their centres a triangle covers);
//! - a region is decided when it is empty, holds one polygon, or holds a
//!   surrounding polygon in front of all others at every sample (certified
//!   at the four corners on the affine depth planes; if planes cross inside
//!   the region it is subdivided further);
//! - at pixel size the pixel is resolved at its centre exactly as the
//!   z-buffer does (`LESS`, ties to the earlier primitive), so the picture
//!   equals the oracle's on every non-tie pixel, with identical coverage;
//! - candidate lists pass down the recursion in one reusable arena: a
//!   region's children see only its survivors, a list every candidate of
//!   which survives is handed on uncopied, and quadrants the survivors'
//!   bounding box misses are settled empty without a look (a pile of `N`
//!   triangles over one pixel costs `2N` classifications, not `N` per
//!   level);
//! - optionally ([`WarnockOptions::samples_per_side`]) the subdivision goes
//!   on inside pixels to an `n x n` sample grid for anti-aliased coverage;
//! - a debug record of the final regions
//!   ([`WarnockOptions::record_regions`], [`Warnock::leaf_regions`],
//!   [`LeafRegion`]) draws the picture in the docs
//!   ([`draw_region_outlines`]).
//!
//! # Example
//!
//! ```
//! use hider_scene::{prepare, procedural, Frame, Hider, PrepareOptions, View};
//! use hider_warnock::{Rule, Warnock, WarnockOptions};
//!
//! let scene = procedural::intersecting_pair();
//! let view = View::for_scene(&scene, 64, 64)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let mut frame = Frame::new(64, 64)?;
//! let mut warnock = Warnock::new(WarnockOptions::default());
//! let stats = warnock.render(&screen, &mut frame)?;
//! // The two triangles pierce each other: both are visible somewhere.
//! assert!(frame.ids.contains(&0) && frame.ids.contains(&1));
//! // Big regions were settled whole (empty, or one triangle in front of the
//! // other); only the silhouettes and the piercing line were subdivided
//! // down to single pixels.
//! assert!(stats.decided_by(Rule::Empty) > 0);
//! assert!(stats.decided_by(Rule::SurrounderInFront) > 0);
//! assert_eq!(stats.max_level(), 6); // 64 = 2^6: level 6 is one pixel
//! assert!(stats.regions < 64 * 64 / 8);
//! # Ok::<(), hider_scene::Error>(())
//! ```

mod classify;
mod coverage;
mod debug;
mod grid;
mod options;
mod pixel;
mod stats;
mod subdivide;
mod trace;
mod warnock;

pub use classify::Class;
pub use debug::{CutRegion, LeafRegion, draw_region_outlines};
pub use options::WarnockOptions;
pub use stats::{Rule, WarnockStats};
pub use trace::{Look, MAX_CLASS_RECORDS, Outcome, PolygonClass, WindowClasses, WindowRecord};
pub use warnock::Warnock;

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;
