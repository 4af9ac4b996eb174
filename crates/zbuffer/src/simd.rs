//! The crate's AVX2 code in one place, and with it every `unsafe` of the
//! crate: the workspace denies `unsafe_code`, and only items of this module
//! allow it, each for an instruction the CPU might lack.
//!
//! The tile kernel ([`crate::tiled`]) and the depth front end's triangle
//! pass are each compiled twice, for baseline x86-64 and for AVX2 and FMA:
//! [`with_avx2`] runs a [`Kernel`] in the second copy, the crate's one call
//! into a `target_feature` function. The intrinsics ([`block`]: a full 8x8
//! block of the tile kernel; [`small`]: a small triangle's box, row by
//! row; [`classify`]: the classification of eight
//! triangles; [`plane`]: their depth planes; [`emit`]: the
//! triangles they keep, written into the run; [`fragments`]: the pixels
//! of the small ones; [`resolve`]: the read-back of eight pixels) are `#[inline(always)]` into that copy (a `target_feature`
//! function of their own would be a call per block, and the call spills
//! the kernel's registers), so their soundness is carried by a type: an
//! [`Avx2`] value, which only [`Avx2::detect`] makes, is passed down the
//! hot loops ([`Portable`](hider_geom::isa::Portable) in the baseline
//! copy), and each copy picks its code at compile time.
//!
//! Both copies give the same bits: integer arithmetic is exact, and the
//! floating-point operations are IEEE operations Rust never fuses into an
//! FMA. The tiled z-buffer's `both_kernels_agree` test compares the two
//! kernels, and the tests of [`block`] and [`classify`] the intrinsics
//! with the portable code.

pub(crate) mod block;
pub(crate) mod classify;
pub(crate) mod emit;
pub(crate) mod fragments;
pub(crate) mod gather;
pub(crate) mod plane;
pub(crate) mod resolve;
pub(crate) mod small;

#[cfg(target_arch = "x86_64")]
use hider_geom::isa::{Avx2, Isa};

/// Work compiled once per instruction set: [`Self::run`] is
/// `#[inline(always)]`, and so is everything it calls, so that all of it
/// lands in the copy of its caller (the baseline one, or [`with_avx2`]'s).
#[cfg(target_arch = "x86_64")]
pub(crate) trait Kernel {
    /// What the work returns.
    type Output;

    /// Does the work with the instructions of `isa`.
    fn run<I: Isa>(self, isa: I) -> Self::Output;
}

/// Runs `kernel` in a copy compiled for AVX2 and FMA.
///
/// `unsafe` only because calling a `target_feature` function on a CPU
/// without the features would be undefined; the [`Avx2`] value proves it
/// has them.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call, proven sound by the Avx2 token"
)]
pub(crate) fn with_avx2<K: Kernel>(kernel: K, avx2: Avx2) -> K::Output {
    #[target_feature(enable = "avx2,fma")]
    fn wide<K: Kernel>(kernel: K, avx2: Avx2) -> K::Output {
        kernel.run(avx2)
    }
    // SAFETY: an `Avx2` value exists only where AVX2 and FMA were
    // detected.
    unsafe { wide(kernel, avx2) }
}
