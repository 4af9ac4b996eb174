//! A full 8x8 block in AVX2, one 8-lane register per row, for the depth
//! formats whose key is 32 bits (f32, reversed f32, 24-bit fixed point).
//!
//! The portable block ([`super::tile`]'s `block8`) writes each step as a
//! 64-lane pass and lets LLVM vectorise it. Inlined into the tile kernel,
//! LLVM lays those passes out across the whole block and spends most of
//! its instructions moving 64-lane arrays between registers and the stack
//! (about 700 instructions a block on the spider). Here a row is one
//! register from start to end: the depth of its eight pixels (two f64
//! registers added and rounded, as the reference computes it), the three
//! edge functions stepped by one addition each, the LESS test, the blends
//! and two counters, about 25 instructions a row.
//!
//! Every lane operation is the scalar one's exact counterpart (IEEE f64
//! addition and multiplication, f64 to f32 rounding to nearest even, the
//! same comparisons), so the block writes the same bits as the portable
//! one; `tests::both_kernels_agree` compares the two kernels.
//!
//! This module is the block's interface to the kernel (its inputs, the
//! keys that have one); the intrinsics are in [`crate::simd::block`], with
//! the crate's other AVX2 code.

pub(super) use hider_geom::isa::{Avx2, Isa, Portable};

use super::key::{DepthKey, Fixed16, Fixed24, Reversed};
use crate::simd::block::block8;
use crate::simd::small::small_box;

/// One full block's inputs.
pub(crate) struct Block8<'a> {
    /// The depth plane's column terms at the block's eight columns.
    pub(crate) col: &'a [f64; 8],
    /// The plane's `dy` and `y0`, and the block's first row: the row term
    /// is `dy * ((row + 0.5) - y0)`, as [`hider_geom::PlaneEq::eval`] has it.
    pub(crate) dy: f64,
    pub(crate) y0: f64,
    pub(crate) by: u32,
    /// Edge functions at the first centre, biased by -1 (inside iff the
    /// OR of the three is non-negative), the triangle's offsets along a
    /// row (per edge, used through `keep`) and their step per row; the
    /// value, step and `keep` are zero for an edge the block is inside of
    /// (all three edges for a block known to be inside).
    pub(crate) e: [i32; 3],
    pub(crate) lanes: &'a [[i32; 8]; 3],
    /// Per edge, all ones to use its lanes, zero for an edge the block is
    /// inside of (its lanes then count as 0).
    pub(crate) keep: [i32; 3],
    pub(crate) down: [i32; 3],
    pub(crate) prim: u32,
}

/// A small triangle's box in a tile (see [`super::tile`]'s `small`), as
/// the AVX2 small kernel reads it: tile-local pixel coordinates, edge
/// functions at the box's first block column and first row.
pub(crate) struct SmallBox<'a> {
    /// Blocks per row of the tile's block-linear storage.
    pub(crate) per_row: usize,
    /// The tile's origin in the image.
    pub(crate) tile_x0: u32,
    pub(crate) tile_y0: u32,
    /// The box, inclusive, in tile-local pixels.
    pub(crate) lx0: u32,
    pub(crate) ly0: u32,
    pub(crate) lx1: u32,
    pub(crate) ly1: u32,
    /// The window-depth plane.
    pub(crate) plane: &'a hider_geom::PlaneEq,
    /// Edge functions at the centre of (the box's first block column's
    /// first pixel, the box's first row), biased by -1 (inside iff the OR
    /// of the three is non-negative), and their steps per pixel in x and
    /// y, all as wrapping i32 (every value over the box fits i32).
    pub(crate) e: [i32; 3],
    pub(crate) sx: [i32; 3],
    pub(crate) sy: [i32; 3],
    pub(crate) prim: u32,
    /// Whether the lanes outside the box's columns must be masked: only
    /// where a block column runs past the tile's last column (a tile cut
    /// by the viewport's right edge). Elsewhere a lane outside the box is
    /// outside the triangle's bounding box, hence outside the triangle
    /// (its edge test fails exactly), and the row needs no column mask.
    pub(crate) mask_x: bool,
}

/// How a 32-bit key is encoded from a depth and compared.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Encoding {
    /// `depth as f32`, compared as f32.
    F32,
    /// `-((1 - depth) as f32)`, compared as f32.
    Reversed,
    /// `round(clamp(depth, 0, 1) * (2^24 - 1))`, compared as an integer.
    Fixed24,
}

/// A depth key that is 32 bits wide: its encoding and its bits.
pub(crate) trait WideKey: DepthKey {
    const ENCODING: Encoding;
    fn to_lane(self) -> u32;
    fn from_lane(bits: u32) -> Self;
}

/// A depth key as the tile kernel asks it for the AVX2 block: the 32-bit
/// keys have one, the others leave every block to the portable code.
pub(super) trait WideBlock: DepthKey {
    /// Draws a full 8x8 block with the AVX2 block when the format has one
    /// and the CPU can: `Some((inside, passes, the block's greatest
    /// key))`, or `None` to leave it to the portable block.
    #[inline(always)]
    fn wide_block8<const EDGES: bool>(
        proof: Avx2,
        keys: &mut [Self; 64],
        ids: &mut [u32; 64],
        b: &Block8<'_>,
    ) -> Option<(u32, u32, Self)> {
        let _ = (proof, keys, ids, b);
        None
    }

    /// Draws a small triangle's box with the AVX2 small kernel when the
    /// format has one: `Some((inside, passes))`, or `None` to leave it to
    /// the scalar scan.
    #[inline(always)]
    fn wide_small(
        proof: Avx2,
        keys: &mut [Self],
        ids: &mut [u32],
        s: &SmallBox<'_>,
    ) -> Option<(u32, u32)> {
        let _ = (proof, keys, ids, s);
        None
    }
}

impl WideBlock for f64 {}

impl WideBlock for Fixed16 {}

/// The 32-bit keys: their lanes, and [`block8`] (in [`crate::simd`]) as
/// their wide block.
macro_rules! wide_key {
    ($($t:ty: $encoding:ident, |$k:ident| $to:expr, |$bits:ident| $from:expr;)*) => {$(
        impl WideKey for $t {
            const ENCODING: Encoding = Encoding::$encoding;
            #[inline(always)]
            fn to_lane(self) -> u32 {
                let $k = self;
                $to
            }
            #[inline(always)]
            fn from_lane(bits: u32) -> Self {
                let $bits = bits;
                $from
            }
        }

        impl WideBlock for $t {
            #[inline(always)]
            fn wide_block8<const EDGES: bool>(
                proof: Avx2,
                keys: &mut [Self; 64],
                ids: &mut [u32; 64],
                b: &Block8<'_>,
            ) -> Option<(u32, u32, Self)> {
                Some(block8::<Self, EDGES>(proof, keys, ids, b))
            }

            #[inline(always)]
            fn wide_small(
                proof: Avx2,
                keys: &mut [Self],
                ids: &mut [u32],
                s: &SmallBox<'_>,
            ) -> Option<(u32, u32)> {
                Some(small_box::<Self>(proof, keys, ids, s))
            }
        }
    )*};
}

wide_key! {
    f32: F32, |k| k.to_bits(), |bits| f32::from_bits(bits);
    Fixed24: Fixed24, |k| k.0, |bits| Fixed24(bits);
    Reversed: Reversed, |k| k.0.to_bits(), |bits| Reversed(f32::from_bits(bits));
}
