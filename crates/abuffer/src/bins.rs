//! Binning: the triangles of a frame sorted into the screen tiles they
//! touch, each tile then taken front to back.
//!
//! A bin item carries what rasterising needs (pixel range, depth plane,
//! vertices): once a tile sorts its bin front to back, triangles are
//! visited out of index order, and reading them from the scene would cost a
//! cache miss each.

use hider_geom::{FixedPt, PlaneEq};
use hider_scene::ScreenScene;

use crate::coverage::pixel_range;
use crate::pattern::SamplePattern;

/// Side of the square screen tiles, in pixels. Triangles are binned to
/// tiles; each tile is rendered and resolved before the next, so its
/// pixel entries and fragments stay in cache from insertion to resolve.
pub const TILE: u32 = 64;

/// One triangle of a bin, with what rasterising it needs.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct BinItem {
    /// Sort key: nearest vertex depth (total order), then triangle index.
    pub(crate) key: u64,
    /// Index of the triangle in the scene.
    pub(crate) tri: u32,
    /// Its primitive.
    pub(crate) prim: u32,
    /// Its pixel range `(x0, y0, x1, y1)` (see [`pixel_range`]).
    pub(crate) range: (u32, u32, u32, u32),
    /// Its depth plane.
    pub(crate) plane: PlaneEq,
    /// Its vertices.
    pub(crate) v: [FixedPt; 3],
}

/// An unsigned key ordered like `f32::total_cmp`.
#[inline]
fn order_key(x: f32) -> u32 {
    let b = x.to_bits();
    if b >> 31 == 1 { !b } else { b | 1 << 31 }
}

/// Triangles binned by tile: `items[start[t]..start[t + 1]]` are the
/// triangles (in submission order) whose pixel range meets tile `t`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bins {
    start: Vec<u32>,
    /// The items, tile by tile.
    items: Vec<BinItem>,
    /// The current tile's items in processing order: sort keys and
    /// positions in `items`.
    order: Vec<(u64, u32)>,
    ranges: Vec<(u32, u32, u32, u32)>,
    /// Tiles whose pixel entries may hold lists of the last frame.
    dirty: Vec<bool>,
    /// Frame size the dirty flags refer to.
    dims: (u32, u32),
}

impl Bins {
    /// Bins the triangles of `scene` by tile (counting sort, submission
    /// order kept), for a frame of `tiles_x x tiles_y` tiles.
    pub(crate) fn bin(
        &mut self,
        scene: &ScreenScene,
        pattern: SamplePattern,
        tiles_x: u32,
        tiles_y: u32,
    ) {
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        let tiles = (tiles_x * tiles_y) as usize;
        self.start.clear();
        self.start.resize(tiles + 1, 0);
        self.ranges.clear();
        const NONE: (u32, u32, u32, u32) = (1, 1, 0, 0);
        for tri in &scene.tris {
            let r = pixel_range(tri, pattern, w, h).unwrap_or(NONE);
            self.ranges.push(r);
            let (x0, y0, x1, y1) = r;
            if x0 > x1 {
                continue;
            }
            for ty in y0 / TILE..=y1 / TILE {
                for tx in x0 / TILE..=x1 / TILE {
                    self.start[(ty * tiles_x + tx) as usize + 1] += 1;
                }
            }
        }
        for t in 0..tiles {
            self.start[t + 1] += self.start[t];
        }
        self.items.clear();
        self.items
            .resize(self.start[tiles] as usize, BinItem::default());
        let mut fill = self.start.clone();
        for (t, (&(x0, y0, x1, y1), tri)) in self.ranges.iter().zip(&scene.tris).enumerate() {
            if x0 > x1 {
                continue;
            }
            let near = tri.z.iter().copied().fold(f64::INFINITY, f64::min) as f32;
            let item = BinItem {
                key: u64::from(order_key(near)) << 32 | t as u64,
                tri: t as u32,
                prim: tri.prim,
                range: (x0, y0, x1, y1),
                plane: tri.depth,
                v: tri.v,
            };
            for ty in y0 / TILE..=y1 / TILE {
                for tx in x0 / TILE..=x1 / TILE {
                    let slot = &mut fill[(ty * tiles_x + tx) as usize];
                    self.items[*slot as usize] = item;
                    *slot += 1;
                }
            }
        }
    }

    /// Starts tracking which tiles hold lists, for a frame of `dims` pixels
    /// and `tiles` tiles whose pixel table is `fresh` (just allocated,
    /// empty). A table kept from an earlier frame of another shape may
    /// hold lists anywhere: every tile is then taken as dirty.
    pub(crate) fn track(&mut self, fresh: bool, dims: (u32, u32), tiles: usize) {
        if fresh || self.dims != dims {
            self.dirty.clear();
            self.dirty.resize(tiles, !fresh);
            self.dims = dims;
        }
    }

    /// Whether tile `t` has triangles this frame.
    pub(crate) fn has_items(&self, t: usize) -> bool {
        self.start[t] != self.start[t + 1]
    }

    /// Whether tile `t`'s pixels may hold lists of an earlier frame.
    pub(crate) fn is_dirty(&self, t: usize) -> bool {
        self.dirty[t]
    }

    /// Records whether tile `t`'s pixels hold lists after this frame.
    pub(crate) fn set_dirty(&mut self, t: usize, dirty: bool) {
        self.dirty[t] = dirty;
    }

    /// The items of tile `t` in processing order: front to back (nearest
    /// vertex depth, then triangle index) or in submission order.
    pub(crate) fn tile_items(
        &mut self,
        t: usize,
        front_to_back: bool,
    ) -> impl Iterator<Item = &BinItem> {
        let (b0, b1) = (self.start[t] as usize, self.start[t + 1] as usize);
        self.order.clear();
        self.order
            .extend((b0..b1).map(|b| (self.items[b].key, b as u32)));
        if front_to_back {
            self.order.sort_unstable_by_key(|&(key, _)| key);
        }
        self.order.iter().map(|&(_, b)| &self.items[b as usize])
    }
}
