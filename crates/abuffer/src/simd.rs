//! The crate's AVX2 code in one place, and with it every `unsafe` of the
//! crate: the workspace denies `unsafe_code`, and only items of this module
//! allow it, each for an instruction the CPU might lack.
//!
//! The coverage masks and the sample buffer choose at run time: each holds
//! an `Option<Avx2>` ([`Avx2::detect`](hider_geom::isa::Avx2::detect)) and
//! calls here when it has one. Every function here takes the
//! [`Avx2`](hider_geom::isa::Avx2) value, the proof that the CPU has AVX2,
//! and calls a `#[target_feature(enable = "avx2")]` copy of its work:
//! - [`coverage`]: the 8 x 4 grid mask of the 32-bit path and its
//!   per-triangle offsets, and the classification of a run of 8 pixels;
//! - [`samples`]: the sample buffer's loops compiled for AVX2 (a triangle
//!   on the 8 x 4 grid, a whole block, the resolve), and the intrinsics
//!   they inline (the depth test of a pixel's 32 samples, a row's keys at
//!   a corner, key comparisons, per-primitive sample masks).
//!
//! Each is the same integer and IEEE arithmetic as the portable code, in
//! the same order and never fused, so it gives the same bits (the tests
//! of `coverage` and `samples` compare the two).

pub(crate) mod coverage;
pub(crate) mod samples;
