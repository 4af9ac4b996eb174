//! The tiles of the hider's framebuffer, kept between frames: one vector
//! of tile buffers per depth format, each holding its format's key type.

use super::key::{Fixed16, Fixed24, Reversed};
use super::tile::TileBuf;
use super::wide::WideBlock;

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
}

impl TileKey for f32 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.f32
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
