//! The instruction set a hot loop is compiled for, as a type.
//!
//! The front end and the tile kernel are each compiled twice: for baseline
//! x86-64 and, inside a `#[target_feature(enable = "avx2,fma")]` function,
//! for AVX2. Code written with AVX2 intrinsics can only run in the second
//! copy. Passing an [`Isa`] down the call chain makes that choice at
//! compile time (each copy is monomorphised with its own type) and makes
//! it sound: an [`Avx2`] value exists only where the CPU was found to have
//! AVX2 and FMA, so code holding one may call the intrinsics.
//!
//! Keep intrinsics in the body of the `#[target_feature]` function or in
//! `#[inline(always)]` functions it calls directly, never in a closure
//! handed to a generic combinator (`Option::and_then`, an iterator
//! adaptor): the combinator is compiled without the feature, so the
//! closure cannot be inlined into the AVX2 copy and each intrinsic in it
//! becomes a function call. A z-buffer helper written that way measured
//! 2.5x slower. `valgrind --tool=callgrind` shows it: the intrinsics
//! appear as functions of their own.
//!
//! ```
//! use hider_geom::isa::{Avx2, Isa, Portable};
//!
//! fn lanes<I: Isa>(isa: I) -> usize {
//!     if isa.avx2().is_some() { 8 } else { 4 }
//! }
//! assert_eq!(lanes(Portable), 4);
//! if let Some(avx2) = Avx2::detect() {
//!     assert_eq!(lanes(avx2), 8);
//! }
//! ```

/// An instruction set, chosen at compile time by the type.
pub trait Isa: Copy + Send + Sync {
    /// The proof of AVX2, for the copy compiled for it.
    fn avx2(self) -> Option<Avx2>;
}

/// Baseline code, on any target: no intrinsics.
#[derive(Clone, Copy, Debug, Default)]
pub struct Portable;

impl Isa for Portable {
    #[inline(always)]
    fn avx2(self) -> Option<Avx2> {
        None
    }
}

/// Proof that the CPU has AVX2 and FMA: only [`Avx2::detect`] makes one.
#[derive(Clone, Copy, Debug)]
pub struct Avx2(());

impl Avx2 {
    /// `Some` when the CPU reports AVX2 and FMA.
    pub fn detect() -> Option<Self> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            return Some(Avx2(()));
        }
        None
    }
}

impl Isa for Avx2 {
    #[inline(always)]
    fn avx2(self) -> Option<Avx2> {
        Some(self)
    }
}

/// Asks the CPU to start loading `value` into cache: the cache lines of
/// its first and last byte (every line of a value of up to two lines).
/// For gathers a hardware prefetcher cannot predict: a tile's
/// triangles are scattered through the triangle list, and without it
/// every one is a cache miss.
///
/// ```
/// let items = vec![[0u64; 12]; 100];
/// hider_geom::isa::prefetch(&items[42]);
/// ```
///
/// One of the workspace's `unsafe` sites (listed in `docs/zbuffer.md`):
/// `_mm_prefetch` is marked unsafe only because it is a `target_feature`
/// intrinsic; SSE is part of every x86-64 CPU, and a prefetch is a hint
/// that never faults nor changes memory, whatever the address.
#[inline(always)]
#[allow(unsafe_code, reason = "a prefetch hint, which never faults nor writes")]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let first = std::ptr::from_ref(value).cast::<i8>();
        let last = first.wrapping_add(size_of::<T>().saturating_sub(1));
        // SAFETY: see above; the pointers come from a reference.
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(first);
            _mm_prefetch::<_MM_HINT_T0>(last);
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
