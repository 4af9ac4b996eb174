//! Carpenter's A-buffer (1984): anti-aliased, order-independent hidden
//! surfaces from per-pixel lists of coverage-mask fragments.
//!
//! Loren Carpenter's "The A-buffer, an antialiased hidden surface method"
//! (SIGGRAPH 1984; scratchapixel's depth-buffer lesson describes it in its
//! section on the z-buffer's limitations and history) keeps, per pixel, a
//! list of *fragments*: the part of one surface inside the pixel, as an
//! 8 x 4 bit coverage mask with a depth range, a colour and an opacity.
//! When every primitive is in, each list is sorted and composited front to
//! back. Anti-aliasing costs one mask per (triangle, pixel) instead of one
//! depth test per sample, and transparency is correct whatever order
//! primitives arrive in.
//!
//! This crate holds three hiders, each built from its options with
//! [`Hider::new`](hider_scene::Hider::new) and run with
//! [`Hider::render`](hider_scene::Hider::render), which returns its typed
//! stats:
//! - [`ABuffer`] (`"abuffer"`, options [`ABufferOptions`], stats
//!   [`ABufferStats`]): masks from the shared exact edge functions at 32
//!   fixed-point sample positions ([`SamplePattern`], [`TriCoverage`])
//!   with a full-coverage fast path; exact depth bounds from a few plane
//!   evaluations; 40-byte fragments in a pooled arena with a memory bound
//!   ([`ABufferOptions::max_bytes`]); 64 x 64 tiles taken front to
//!   back and resolved in cache, exact occlusion culling per pixel and per
//!   8 x 8 block, merging of neighbouring fragments of one surface, an
//!   overflow policy; resolve with exact per-sample depth or the paper's
//!   `zmin`/`zmax` approximation; tiles whose triangles are all opaque
//!   resolved from a sample buffer instead of lists (a depth and a
//!   primitive per sample, [`ABufferOptions::sample_tiles`]), with the
//!   lists' image bit for bit;
//! - the baselines it is measured against, both with [`SsaaOptions`] and
//!   [`SsaaStats`]: [`SupersampledZBuffer`] (`"ssaa-N"`, N = 1 to 32
//!   samples at the same positions) and [`SortedTransparencyZBuffer`]
//!   (`"ssaa-sorted"`, opaque first, then translucent triangles sorted back
//!   to front).
//!
//! From a world-space scene, [`ABuffer`]'s
//! [`Hider::render_scene`](hider_scene::Hider::render_scene) runs the lean
//! front end ([`hider_scene::prepare::lean`], shared with the tiled
//! z-buffer: each vertex transformed and snapped once, no per-primitive
//! data but the colours asked for) instead of `prepare`, with the same
//! frame bit for bit.
//!
//! The mask set-up the three share, [`TriCoverage`] over the pixels of
//! [`pixel_range`], is public too, for the profiling bin's mask-only
//! mode (`abuffer_profile ... cov`).
//!
//! All three write `Frame::color` (composited in linear light, then sRGB),
//! `Frame::coverage` (covered fraction of the samples), and, in
//! `Frame::ids` / `Frame::depth`, the front-most surface covering the
//! *pixel centre* (any opacity, exact `f64` centre depth, lower id on
//! ties), exactly what a pixel-centre z-buffer reports, so ids and
//! coverage compare one to one with the other hiders (see
//! `docs/abuffer.md`).
//!
//! # Example
//!
//! Render the two triangles that pierce each other with 32 samples: the
//! A-buffer with per-sample depth equals a 32-sample supersampled
//! z-buffer, sample for sample.
//!
//! ```
//! use hider_abuffer::{ABuffer, ABufferOptions, MergePolicy, SupersampledZBuffer, SsaaOptions};
//! use hider_scene::{prepare, procedural, Frame, Hider, PrepareOptions, View};
//!
//! let scene = procedural::intersecting_pair();
//! let view = View::for_scene(&scene, 32, 32)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//!
//! let mut abuffer = ABuffer::new(ABufferOptions::default().with_merge(MergePolicy::Off));
//! let mut frame = Frame::new(32, 32)?;
//! let stats = abuffer.render(&screen, &mut frame)?;
//! assert!(stats.fragments > 0);
//!
//! let mut ssaa = SupersampledZBuffer::new(SsaaOptions::default());
//! let mut reference = Frame::new(32, 32)?;
//! ssaa.render(&screen, &mut reference)?;
//! assert_eq!(abuffer.sample_ids(), ssaa.sample_ids());
//! assert_eq!(frame.coverage, reference.coverage);
//! assert_eq!(frame.ids, reference.ids);
//! # Ok::<(), hider_scene::Error>(())
//! ```

mod abuffer;
mod bins;
mod centre;
mod composite;
mod coverage;
mod culling;
mod cutout;
mod depth;
mod fragment;
mod inspect;
mod lists;
mod options;
mod palette;
mod pattern;
mod pool;
mod raster;
mod resolve;
mod samples;
mod select;
#[cfg(target_arch = "x86_64")]
mod simd;
mod sorted;
mod source;
mod ssaa;
mod stats;
#[cfg(test)]
mod test_rng;
mod worker;

pub use abuffer::ABuffer;
pub use coverage::{Coverage, TriCoverage, pixel_range};
pub use inspect::{InspectedFragment, PixelInspection};
pub use options::{ABufferOptions, DepthMode, MergePolicy, OverflowPolicy, SsaaOptions};
pub use pattern::SamplePattern;
pub use sorted::SortedTransparencyZBuffer;
pub use ssaa::SupersampledZBuffer;
pub use stats::{ABufferStats, SsaaStats};

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;
