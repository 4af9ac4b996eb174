//! Depth-buffer hidden-surface removal on the hider front end.
//!
//! [`ZBuffer`] is Catmull's (1974) z-buffer as scratchapixel's depth-buffer
//! lesson describes it:
//! for every triangle, for every pixel centre it covers, compare its depth
//! with the stored one and keep the nearer. Coverage is the shared exact
//! integer edge-function test with the top-left rule, traversed over the
//! triangle's bounding box with incremental edge functions; depth is the
//! window depth `z/w`, affine in screen space, stored in one of several
//! [`DepthFormat`]s. A [`DepthSource::LinearViewZ`] mode interpolates
//! camera depth linearly in screen space — the lesson's classic mistake —
//! so the benchmark can show what it costs.
//!
//! [`TiledZBuffer`] gives the same frame, pixel for pixel, from a binned,
//! tiled, parallel traversal with 8x8 block accept/reject and hierarchical
//! depth (see `docs/zbuffer.md`). It has a front end of its own: from a
//! world-space scene, [`Hider::render_scene`](hider_scene::Hider::render_scene)
//! runs the lean depth-only [`prepare_depth_into`] into a [`DepthScene`]
//! (snapped corners, depth plane and id; pixel [`DepthFragment`]s for the
//! smallest triangles) instead of the shared `prepare`, with the same
//! output bit for bit.
//!
//! # Example
//!
//! Load an OBJ, render it with the fit camera, write a PNG (the scene crate
//! is re-exported as [`scene`], so this crate alone is enough):
//!
//! ```
//! use hider_zbuffer::scene::{load_obj, prepare, shade_frame, Frame, Hider, PrepareOptions, ShadeMode, View};
//! use hider_zbuffer::{ZBuffer, ZBufferOptions};
//!
//! # let dir = std::env::temp_dir().join(format!("hider-zdoc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir)?;
//! # let obj = dir.join("quad.obj");
//! # std::fs::write(&obj, "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n")?;
//! let scene = load_obj(&obj)?;
//! let view = View::for_scene(&scene, 64, 64)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let mut frame = Frame::new(64, 64)?;
//! let mut zbuffer = ZBuffer::new(ZBufferOptions::default());
//! let stats = zbuffer.render(&screen, &mut frame)?;
//! shade_frame(&screen, &mut frame, ShadeMode::Lambert)?;
//! frame.write_png(&dir.join("quad.png"))?;
//! assert!(frame.covered_count() > 0);
//! assert_eq!(stats.depth_passes, frame.covered_count() as u64);
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The tiled z-buffer's own pipeline gives the same ids and depths:
//!
//! ```
//! use hider_scene::{procedural, Frame, Hider, PrepareOptions, View};
//! use hider_zbuffer::{TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions};
//!
//! let scene = procedural::uv_sphere(24);
//! let view = View::for_scene(&scene, 64, 48)?;
//! let options = PrepareOptions::default();
//! let mut screen = hider_scene::prepare(&scene, &view, &options)?;
//! let mut reference = Frame::new(64, 48)?;
//! ZBuffer::new(ZBufferOptions::default()).render(&screen, &mut reference)?;
//! let mut tiled = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
//! let mut frame = Frame::new(64, 48)?;
//! tiled.render_scene(&scene, &view, &options, &mut screen, &mut frame)?;
//! assert!(frame == reference);
//! # Ok::<(), hider_scene::Error>(())
//! ```

mod depth;
mod depth_scene;
mod options;
mod raster;
mod simd;
mod tiled;
pub mod trace;

pub use depth_scene::{DepthFragment, DepthScene, DepthTri, prepare_depth_into};
pub use options::{DepthFormat, DepthSource, DepthTest, ZBufferOptions};
pub use raster::{ZBuffer, ZBufferStats};
pub use tiled::{TiledZBuffer, TiledZBufferOptions, TiledZBufferStats};
pub use trace::ZBufferTrace;

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;

#[cfg(test)]
mod tests;
