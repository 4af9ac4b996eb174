//! The tiles of the hider's framebuffer, kept between frames: one vector
//! of tile buffers per depth format, each holding its format's key type.

use super::key::{Fixed16, Fixed24, Reversed};
use super::tile::TileBuf;
use super::wide::{Avx2, WideBlock};

/// The tile buffers (one per tile), one vector per depth format so each
/// holds its format's own key type.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub(crate) f32: Vec<TileBuf<f32>>,
    pub(crate) f64: Vec<TileBuf<f64>>,
    pub(crate) fixed24: Vec<TileBuf<Fixed24>>,
    pub(crate) fixed16: Vec<TileBuf<Fixed16>>,
    pub(crate) reversed: Vec<TileBuf<Reversed>>,
}

/// A key type with its place in [`Scratch`].
pub(crate) trait TileKey: WideBlock {
    /// The tile buffers of this format.
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>>;

    /// Resolves eight pixels of a tile row (see [`TileBuf::resolve`])
    /// with AVX2 when the format has a wide resolve: whether it did.
    #[inline(always)]
    fn wide_resolve8<const IDS: bool, const DEPTH: bool>(
        proof: Avx2,
        keys: &[Self; 8],
        ids: &[u32; 8],
        clear: Self,
        out: (&mut [u32; 8], &mut [f32; 8]),
    ) -> bool {
        let _ = (proof, keys, ids, clear, out);
        false
    }
}

impl TileKey for f32 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.f32
    }

    #[inline(always)]
    fn wide_resolve8<const IDS: bool, const DEPTH: bool>(
        proof: Avx2,
        keys: &[Self; 8],
        ids: &[u32; 8],
        clear: Self,
        (out_ids, out_depth): (&mut [u32; 8], &mut [f32; 8]),
    ) -> bool {
        crate::simd::resolve::resolve8::<IDS, DEPTH>(proof, keys, ids, clear, out_ids, out_depth);
        true
    }
}

impl TileKey for f64 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.f64
    }
}

impl TileKey for Fixed24 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.fixed24
    }
}

impl TileKey for Fixed16 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.fixed16
    }
}

impl TileKey for Reversed {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.reversed
    }
}

impl Scratch {
    /// The id and decoded window depth of pixel `(x, y)` (image
    /// coordinates) of tile `t` in format `K`.
    pub(crate) fn pixel<K: TileKey>(&mut self, t: usize, x: u32, y: u32) -> (u32, f32) {
        K::bufs(self)[t].get(x, y)
    }
}
