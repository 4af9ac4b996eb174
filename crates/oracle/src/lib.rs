//! The slow, exact references every hider is measured against.
//!
//! `hider-oracle` is the referee of the hider workspace:
//! - [`RayCastOracle`] answers, for every pixel centre, which primitive is
//!   visible. It is the "one depth variable" z-buffer of the lecture on
//!   image-space hidden-surface algorithms: loop over every triangle per
//!   pixel, decide coverage with the shared exact edge functions, and keep
//!   the nearest, deciding "nearer" *exactly*: the window-depth planes of
//!   the snapped triangles (what every exact hider compares) are compared
//!   in exact arithmetic behind an `f64` filter. A tie is an exactly equal
//!   depth, and the lower primitive id wins it, the rule of every exact
//!   hider. It also reports how far the runner-up was ([`Reference::gap`],
//!   0 exactly at a tie), so that scoring can tell ties, `f32` resolution
//!   and `f64` rounding from errors ([`Reference::compare_exact`],
//!   [`Reference::compare`], [`Agreement`]).
//! - [`window_depth_reference`] is the textbook pixel-centre z-buffer in
//!   `f64` on the same window-depth planes, rounded as the hiders round:
//!   the brute force `f64` hiders match bit for bit.
//! - [`analytic_coverage`] answers, for every pixel *square*, the exact area
//!   each primitive shows in it, by `f64` polygon clipping — the ground truth
//!   anti-aliasing hiders (MSAA, A-buffer) converge to.
//!
//! All are slow on purpose: simple enough to be obviously right. See
//! `docs/oracle.md`.
//!
//! # Example
//!
//! Two parallel layers `1e-7` apart under an ordinary camera: the oracle
//! reports the nearer one everywhere (no tie), and an exact hider must
//! match it on every pixel.
//!
//! ```
//! use hider_oracle::{OracleOptions, RayCastOracle};
//! use hider_scene::{Hider, NO_ID, PrepareOptions, Scene, View, prepare};
//! use glam::DVec3;
//! use hider_geom::Camera;
//!
//! let layer = |z: f64| vec![
//!     DVec3::new(-4.0, -4.0, z), DVec3::new(4.0, -4.0, z), DVec3::new(0.0, 4.0, z),
//! ];
//! let mut scene = Scene::from_triangles([layer(0.0), layer(1e-7)].concat());
//! scene.camera = Some(
//!     Camera::perspective(DVec3::new(0.3, 0.2, 12.7), DVec3::ZERO, 6.35, 31.8)
//!         .with_fovy_degrees(45.0),
//! );
//! let view = View::for_scene(&scene, 16, 16)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let reference = RayCastOracle::new(OracleOptions::default()).evaluate(&screen);
//! assert!(reference.ids.iter().all(|&id| id == 1 || id == NO_ID));
//! assert!((0..256).all(|k| !reference.is_exact_tie(k)));
//! // The reference agrees with itself, ties included, of course.
//! assert!(reference.compare_exact(&reference.ids).is_exact());
//! # Ok::<(), hider_scene::Error>(())
//! ```

mod agreement;
mod coverage;
mod depth;
#[cfg(test)]
mod dump_tests;
mod exact;
mod nearest;
mod options;
mod polygon;
mod raycast;
mod reference;
mod tolerance;
mod window_depth;

pub use agreement::Agreement;
pub use coverage::{CoverageReference, analytic_coverage};
pub use exact::plane_rounding_bound;
pub use options::{DEFAULT_MAX_BYTES, DepthPlane, OracleOptions};
pub use raycast::{OracleStats, RayCastOracle};
pub use reference::Reference;
pub use tolerance::{DEFAULT_TIE_TOLERANCE, WINDOW_TIE_TOLERANCE};
pub use window_depth::{WindowDepthReference, window_depth_reference};

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;
