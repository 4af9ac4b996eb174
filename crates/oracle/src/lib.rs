//! The slow, exact references every hider is measured against.
//!
//! `hider-oracle` is the referee of the hider workspace:
//! - [`RayCastOracle`] answers, for every pixel centre, which primitive is
//!   visible. It is the "one depth variable" z-buffer of the lecture on
//!   image-space hidden-surface algorithms: loop over every triangle per
//!   pixel, decide coverage with the shared exact edge functions, compute
//!   depth in `f64` by intersecting the camera ray with the triangle's
//!   camera-space plane ([`DepthPlane`]), keep the nearest. It also reports
//!   how far the runner-up was ([`Reference::gap`]) so that ties can be told
//!   from errors ([`Reference::compare`], [`Agreement`]).
//! - [`window_depth_reference`] is the textbook pixel-centre z-buffer in
//!   `f64` on the window-depth planes the hiders interpolate: the plain
//!   brute force tests hold `f64` hiders to bit for bit.
//! - [`analytic_coverage`] answers, for every pixel *square*, the exact area
//!   each primitive shows in it, by `f64` polygon clipping — the ground truth
//!   anti-aliasing hiders (MSAA, A-buffer) converge to.
//!
//! All are slow on purpose: simple enough to be obviously right.
//!
//! # Example
//!
//! ```
//! use hider_oracle::{OracleOptions, RayCastOracle, DEFAULT_TIE_TOLERANCE};
//! use hider_scene::{prepare, procedural, Hider, PrepareOptions, View};
//!
//! let scene = procedural::intersecting_pair();
//! let view = View::for_scene(&scene, 32, 32)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let reference = RayCastOracle::new(OracleOptions::default()).evaluate(&screen);
//! // Both triangles are visible somewhere: they pierce each other.
//! assert!(reference.ids.contains(&0) && reference.ids.contains(&1));
//! // The reference agrees with itself, of course.
//! assert!(reference.compare(&reference.ids, DEFAULT_TIE_TOLERANCE).is_exact());
//! # Ok::<(), hider_scene::Error>(())
//! ```

pub mod agreement;
pub mod coverage;
mod depth;
#[cfg(test)]
mod dump_tests;
mod exact;
mod nearest;
pub mod options;
pub mod polygon;
pub mod raycast;
pub mod reference;
pub mod tolerance;
pub mod window_depth;

pub use agreement::Agreement;
pub use coverage::{CoverageReference, analytic_coverage};
pub use exact::plane_rounding_bound;
pub use options::{DEFAULT_MAX_BYTES, DepthPlane, OracleOptions};
pub use raycast::{OracleStats, RayCastOracle};
pub use reference::Reference;
pub use tolerance::{DEFAULT_TIE_TOLERANCE, WINDOW_TIE_TOLERANCE};
pub use window_depth::{WindowDepthReference, window_depth_reference};
