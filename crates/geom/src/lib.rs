//! Exact screen-space geometry shared by every hider.
//!
//! `hider-geom` is the pure-math floor of the hider workspace: cameras
//! ([`camera`]), homogeneous clipping with a guard band ([`clip`]), the
//! viewport transform and snapping to 1/256 pixel the way a GL rasterizer
//! does ([`viewport`], [`fixed`]),
//! exact `i64` edge functions with GL's fill rule ([`edge`]), affine
//! depth and 1/w planes ([`plane`]) and the lecture's point-in-polygon tests
//! ([`polygon`]), plus the instruction-set token the hot loops of the other
//! crates pass down ([`isa`]). Everything that decides *whether a sample is covered* lives
//! here, so that all hidden-surface algorithms agree on coverage bit for bit.
//!
//! # Example
//!
//! Project a triangle, snap it, and count the pixel centres it covers in a
//! 16 x 16 window:
//!
//! ```
//! use hider_geom::{edge, fixed::{FixedPt, pixel_center}, viewport::Viewport};
//! use glam::DVec3;
//!
//! let vp = Viewport::new(16, 16);
//! let ndc = [DVec3::new(-1.0, 1.0, 0.0), DVec3::new(1.0, 1.0, 0.0), DVec3::new(-1.0, -1.0, 0.0)];
//! let mut v = ndc.map(|p| vp.snap_ndc(p.x, p.y).unwrap());
//! if edge::orient2d(v[0], v[1], v[2]) < 0 {
//!     v.swap(1, 2); // the edge functions expect positive orientation
//! }
//! let mut covered = 0;
//! for j in 0..16 {
//!     for i in 0..16 {
//!         if edge::triangle_covers(&v, pixel_center(i).into(), pixel_center(j).into()) {
//!             covered += 1;
//!         }
//!     }
//! }
//! // 120 centres lie strictly above the diagonal. The 16 centres exactly on
//! // it are on this triangle's bottom-right edge, so the fill rule leaves
//! // them to the mirrored triangle that would complete the square.
//! assert_eq!(covered, 120);
//! ```

pub mod camera;
pub mod clip;
pub mod edge;
pub mod fixed;
pub mod isa;
pub mod lens;
pub mod plane;
pub mod polygon;
pub mod star;
pub mod viewport;

pub use camera::{Camera, Projection};
pub use edge::{EdgeFunction, orient2d, triangle_covers};
pub use fixed::FixedPt;
pub use lens::{Intrinsics, Lens};
pub use plane::PlaneEq;
pub use viewport::{Centres, FEW_CENTRES, Viewport};

/// The `glam` version this crate is built against, re-exported so users
/// name the same types.
pub use glam;
