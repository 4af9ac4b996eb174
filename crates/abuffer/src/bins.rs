//! Binning: the triangles of a frame sorted into the screen tiles they
//! touch, each tile then taken front to back.
//!
//! A bin item carries what rasterising needs (pixel range, depth plane,
//! vertices, opacity): once a tile sorts its bin front to back, triangles
//! are visited out of index order, and reading them from the scene would
//! cost a cache miss each. For the same reason the sorted tile's items are
//! gathered into one array in processing order ([`TileQueue::item`]): one
//! tight gather pass, whose independent loads overlap, and then the tile
//! loop reads a stream instead of chasing the sort's permutation through
//! the bins (on a pile of 10^6 triangles over one pixel the permutation is
//! random over 100 MB).

use crate::source::Source;
use hider_geom::{FixedPt, PlaneEq};
use hider_scene::prepare::lean::LeanTri;
use rayon::prelude::*;

use crate::coverage::pixel_range_of;
use crate::depth::{depth_key, nearest_over};
use crate::pattern::SamplePattern;

mod queue;
mod runs;

pub(crate) use queue::{LEADER, SOLE, TileQueue};
pub(crate) use runs::BinRun;

/// Side of the square screen tiles, in pixels. Triangles are binned to
/// tiles; each tile is rendered and resolved before the next, so its
/// pixel entries and fragments stay in cache from insertion to resolve.
pub(crate) const TILE: u32 = 64;

/// The pixels of tile `(tx, ty)` of a `width x height` frame: top-left
/// and bottom-right, inclusive (the last row and column of tiles may be
/// partial).
pub(crate) fn tile_rect(tx: u32, ty: u32, (width, height): (u32, u32)) -> (u32, u32, u32, u32) {
    let (x0, y0) = (tx * TILE, ty * TILE);
    (
        x0,
        y0,
        (x0 + TILE).min(width) - 1,
        (y0 + TILE).min(height) - 1,
    )
}

/// One triangle of a bin, with what rasterising it needs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BinItem {
    /// Its primitive.
    pub(crate) prim: u32,
    /// Its pixel range `(x0, y0, x1, y1)` (see [`crate::coverage::pixel_range`]).
    pub(crate) range: (u32, u32, u32, u32),
    /// Its depth plane.
    pub(crate) plane: PlaneEq,
    /// Its vertices.
    pub(crate) v: [FixedPt; 3],
    /// The opacity of its primitive ([`Source::opacity_runs`]), read in
    /// triangle order at binning: the culling bookkeeping needs it for
    /// every fragment, the colour only fragments that are resolved.
    pub(crate) alpha: f32,
    /// Its depth plane at the near corner of its whole pixel range, as
    /// [`nearest_over`] computes it, rounded to `f32`: a lower bound of
    /// its depth at every sample and centre it covers, in any part of
    /// that range (the plane is monotonic). The culling tests try it
    /// before the tighter bound of the part a pass or a block holds:
    /// computed at binning, in triangle order, it is not a chain of
    /// dependent `f64` operations that a branch waits for (the profile
    /// put 5 % of the soup's frame on that evaluation; the 500 sphere
    /// measured 1 to 2.7 % faster with this bound, the others the same).
    pub(crate) near: f32,
    /// Whether its source triangle faces the camera (merging needs equal
    /// facings). Its index in the frame's triangles is its place in
    /// [`Bins::items`], which the tile refs carry.
    pub(crate) front_facing: bool,
}

/// An unsigned key ordered like `f32::total_cmp`: the signed
/// [`depth_key`] with its sign bit flipped.
#[inline]
fn order_key(x: f32) -> u32 {
    (depth_key(x) as u32) ^ (1 << 31)
}

/// Triangles binned by tile: the triangles (in submission order) whose
/// pixel range meets tile `t` are, chunk after chunk, `items[refs[b]]`
/// for `b` in `start[t]..start[t + 1]` of each [`Chunk`]. Read by every
/// thread once binned.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bins {
    /// One item per triangle of the scene, in submission order (written
    /// once: a triangle over several tiles is not copied into each; the
    /// vector keeps its length from frame to frame, so no slot is written
    /// twice either). Triangles that meet no pixel have an empty range.
    items: Vec<BinItem>,
    /// The triangles in contiguous chunks, one per thread, each binned
    /// on its own (in parallel).
    chunks: Vec<Chunk>,
    /// Tiles of the frame binned last (0 before the first).
    tiles: usize,
    /// [`Source::opacity_runs`] of the frame.
    opacity: Vec<(u32, f32)>,
}

/// The bins of one contiguous run of triangles.
#[derive(Clone, Debug, Default)]
struct Chunk {
    /// Per tile, where its indices start in `refs` (and one past the end).
    start: Vec<u32>,
    /// Per tile, the chunk's triangles that meet it, in order, as sort
    /// keys: the nearest vertex depth's total order ([`order_key`]) in
    /// the high half, the index into [`Bins::items`] in the low half. A
    /// tile's order is sorted from these alone, without reading its items
    /// (gathering their keys was 5 % of the 500 sphere's frame).
    refs: Vec<u64>,
    /// Per triangle of the chunk, its sort key's depth half and the
    /// tiles its pixel range meets (`[tx0, ty0, tx1, ty1]`, empty ranges
    /// for none), between the counting and the filling pass: the filling
    /// pass reads these 12 bytes a triangle, not its 96-byte item (on the
    /// 500 sphere a third of binning's memory traffic).
    key_tiles: Vec<(u32, [u16; 4])>,
    /// The run of opacities the last triangle's primitive fell in
    /// (triangles come in primitive order: almost always the next one's).
    opacity_run: usize,
}

/// What binning one triangle needs besides the triangle: the sample
/// pattern, the frame's size and its tiles per row.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Grid {
    pub(crate) pattern: SamplePattern,
    pub(crate) dims: (u32, u32),
    pub(crate) tiles: (u32, u32),
}

impl Grid {
    /// The grid of a `dims` frame sampled with `pattern`.
    pub(crate) fn new(pattern: SamplePattern, (w, h): (u32, u32)) -> Self {
        Self {
            pattern,
            dims: (w, h),
            tiles: (w.div_ceil(TILE), h.div_ceil(TILE)),
        }
    }

    /// How many tiles the frame has.
    pub(crate) fn count(&self) -> usize {
        (self.tiles.0 * self.tiles.1) as usize
    }
}

/// A chunk's share of a frame's binning: its items to write, its
/// triangles, and its bins.
type ChunkWork<'a> = ((&'a mut [BinItem], &'a [LeanTri]), &'a mut Chunk);

/// The empty pixel range.
const NONE: (u32, u32, u32, u32) = (1, 1, 0, 0);

impl Bins {
    /// Bins the triangles of `scene` by tile (counting sort, submission
    /// order kept), on `grid`, in `threads` chunks of triangles binned in
    /// parallel on the current rayon pool (one chunk, in order, for one
    /// thread).
    pub(crate) fn bin(&mut self, scene: &Source<'_>, grid: Grid, threads: usize) {
        self.tiles = grid.count();
        scene.opacity_runs(&mut self.opacity);
        let n = scene.tris.len();
        if self.items.len() < n {
            self.items.resize(n, BinItem::default());
        }
        self.items.truncate(n);
        let len = n.div_ceil(threads.max(1)).max(1);
        self.chunks.resize_with(n.div_ceil(len), Chunk::default);
        let opacity = &self.opacity;
        let work = |(c, ((items, tris), chunk)): (usize, ChunkWork<'_>)| {
            chunk.on_stack(|local| {
                local.begin(grid.count());
                for (item, tri) in items.iter_mut().zip(tris) {
                    *item = local.add(tri, grid, opacity);
                }
                local.fill(c * len, grid.tiles.0);
            });
        };
        let parallel = self.chunks.len() > 1;
        let parts = self
            .items
            .chunks_mut(len)
            .zip(scene.tris.chunks(len))
            .zip(self.chunks.iter_mut());
        if parallel {
            let parts: Vec<_> = parts.collect();
            parts.into_par_iter().enumerate().for_each(work);
        } else {
            parts.enumerate().for_each(work);
        }
    }

    /// The sort keys of tile `t`'s triangles (see [`Chunk::refs`]; the
    /// low half is the index into `items`), in submission order.
    fn tile_refs(&self, t: usize) -> impl Iterator<Item = u64> + '_ {
        self.chunks
            .iter()
            .flat_map(move |c| c.refs[c.start[t] as usize..c.start[t + 1] as usize].iter())
            .copied()
    }

    /// The items of tile `t`, in submission order.
    pub(crate) fn tile_items(&self, t: usize) -> impl Iterator<Item = &BinItem> + '_ {
        self.tile_refs(t).map(|key| self.item(key))
    }

    /// The item a sort key (see [`Chunk::refs`]) names: its low half.
    #[inline]
    fn item(&self, key: u64) -> &BinItem {
        &self.items[key as u32 as usize]
    }

    /// The frame's binned triangles, in the frame's order (a tile ref's
    /// low half indexes them).
    pub(crate) fn items(&self) -> &[BinItem] {
        &self.items
    }

    /// Whether nothing was binned yet.
    pub(crate) fn is_empty(&self) -> bool {
        self.tiles == 0
    }

    /// How many triangles tile `t` has this frame.
    pub(crate) fn tile_len(&self, t: usize) -> usize {
        self.chunks
            .iter()
            .map(|c| (c.start[t + 1] - c.start[t]) as usize)
            .sum()
    }

    /// Whether tile `t` has triangles this frame.
    pub(crate) fn has_items(&self, t: usize) -> bool {
        self.chunks.iter().any(|c| c.start[t] != c.start[t + 1])
    }
}

impl Chunk {
    /// Runs `work` on the chunk moved to this thread's stack, then puts it
    /// back: the chunks' headers sit side by side in [`Bins::chunks`], and
    /// lengths updated on every triangle shared a cache line with the
    /// other threads' (a 2-thread frame of the 500 sphere spent 2.7 to
    /// 7.9 ms binning).
    fn on_stack(&mut self, work: impl FnOnce(&mut Self)) {
        let mut local = std::mem::take(self);
        work(&mut local);
        *self = local;
    }

    /// Starts binning a run of triangles into `tiles` tiles.
    fn begin(&mut self, tiles: usize) {
        self.start.clear();
        self.start.resize(tiles + 1, 0);
        self.key_tiles.clear();
        self.opacity_run = 0;
    }

    /// Counts the next triangle of the run, `tri`, into the tiles of
    /// `grid` its pixel range meets, and returns its item; `opacity` is
    /// [`Source::opacity_runs`].
    #[inline(always)]
    fn add(&mut self, tri: &LeanTri, grid: Grid, opacity: &[(u32, f32)]) -> BinItem {
        let ((w, h), tiles_x, pattern) = (grid.dims, grid.tiles.0, grid.pattern);
        let range = pixel_range_of(&tri.v, pattern, w, h).unwrap_or(NONE);
        let (x0, y0, x1, y1) = range;
        // Tile coordinates fit 16 bits: a side is at most
        // `hider_geom::fixed::MAX_IMAGE_SIDE` (16,384) pixels.
        let tiles = if x0 <= x1 {
            for ty in y0 / TILE..=y1 / TILE {
                for tx in x0 / TILE..=x1 / TILE {
                    self.start[(ty * tiles_x + tx) as usize + 1] += 1;
                }
            }
            [x0 / TILE, y0 / TILE, x1 / TILE, y1 / TILE].map(|c| c as u16)
        } else {
            [1, 1, 0, 0]
        };
        let near = tri.z.iter().copied().fold(f64::INFINITY, f64::min) as f32;
        self.key_tiles.push((order_key(near), tiles));
        let prim = tri.prim;
        let run = self.opacity_run;
        let start = if run == 0 { 0 } else { opacity[run - 1].0 };
        if prim < start || prim >= opacity[run].0 {
            self.opacity_run = opacity.partition_point(|&(end, _)| end <= prim);
        }
        BinItem {
            prim,
            range,
            plane: tri.depth,
            v: tri.v,
            alpha: opacity[self.opacity_run].1,
            near: if x0 <= x1 {
                nearest_over(&tri.depth, range, pattern.hull()) as f32
            } else {
                f32::INFINITY
            },
            front_facing: tri.front_facing,
        }
    }

    /// Fills the run's bins once every triangle is counted: its triangles
    /// are items `first..` of the frame, on `tiles_x` tiles per row.
    fn fill(&mut self, first: usize, tiles_x: u32) {
        let tiles = self.start.len() - 1;
        for t in 0..tiles {
            self.start[t + 1] += self.start[t];
        }
        self.refs.clear();
        self.refs.resize(self.start[tiles] as usize, 0);
        let mut fill = self.start.clone();
        for (k, &(key, [tx0, ty0, tx1, ty1])) in self.key_tiles.iter().enumerate() {
            let r = u64::from(key) << 32 | (first + k) as u64;
            for ty in u32::from(ty0)..=u32::from(ty1) {
                for tx in u32::from(tx0)..=u32::from(tx1) {
                    let slot = &mut fill[(ty * tiles_x + tx) as usize];
                    self.refs[*slot as usize] = r;
                    *slot += 1;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use hider_scene::prepare::lean::{LeanScene, LeanTri, prepare_lean_into};
    use hider_scene::{Material, PrepareOptions, Scene, ShadeMode, View, procedural};

    use super::{Bins, Grid, TILE, order_key};
    use crate::coverage::pixel_range_of;
    use crate::pattern::SamplePattern;
    use crate::source::Source;

    /// Every bin item carries its primitive's opacity, through both front
    /// ends, on meshes whose opacities repeat, differ, default and
    /// are empty (the runs of [`Source::opacity_runs`] merge and skip).
    #[test]
    fn bin_items_carry_the_opacity_of_their_primitive() {
        let mut scene = Scene::default();
        let opacities = [
            Some(1.0),
            Some(0.5),
            Some(0.5),
            None,
            Some(0.25),
            Some(1.0),
            Some(0.0),
        ];
        for (k, opacity) in opacities.into_iter().enumerate() {
            let mesh = procedural::random_soup(30, k as u64).meshes.remove(0);
            let material = opacity.map(|opacity| Material {
                opacity,
                ..Material::default()
            });
            scene.push_mesh(mesh, material);
            if k == 3 {
                // An empty mesh between two others.
                let empty = procedural::random_soup(0, 0).meshes.remove(0);
                scene.push_mesh(empty, Some(Material::default()));
            }
        }
        let (w, h) = (100, 70);
        let view = View::for_scene(&scene, w, h).expect("a camera");
        let options = PrepareOptions::default();
        let screen = hider_scene::prepare(&scene, &view, &options).expect("prepared");
        let tris: Vec<LeanTri> = screen.tris.iter().map(LeanTri::from).collect();
        let mut lean = LeanScene::new();
        prepare_lean_into(&scene, &view, &options, &mut lean).expect("prepared");
        for source in [
            Source::screen(&screen, &tris, None),
            Source::lean(&lean, &scene, None),
        ] {
            let mut bins = Bins::default();
            bins.bin(&source, Grid::new(SamplePattern::Grid32, (w, h)), 1);
            let mut seen: Vec<f32> = Vec::new();
            for item in &bins.items {
                let want = source.prim_rgba(item.prim, ShadeMode::Lambert)[3];
                assert_eq!(item.alpha, want, "primitive {}", item.prim);
                if !seen.contains(&want) {
                    seen.push(want);
                }
            }
            seen.sort_by(f32::total_cmp);
            assert_eq!(seen, [0.0, 0.25, 0.5, 1.0], "the opacities binned");
        }
    }

    /// Each tile holds exactly the triangles whose pixel range meets it, in
    /// submission order, whether binned in one chunk or in several (in
    /// parallel), on a frame that cuts through the scene (triangles off it
    /// meet no tile) and one whose size is not a multiple of the tile.
    #[test]
    fn tiles_hold_the_triangles_that_meet_them_in_any_number_of_chunks() {
        let scene = procedural::random_soup(3000, 7);
        let view = View::for_scene(&scene, 300, 200).expect("a camera");
        let options = PrepareOptions::default();
        let mut lean = LeanScene::new();
        prepare_lean_into(&scene, &view, &options, &mut lean).expect("prepared");
        // A frame smaller than the view: many triangles fall off it.
        let mut source = Source::lean(&lean, &scene, None);
        source.viewport.width = 150;
        source.viewport.height = 90;
        let (w, h) = (150u32, 90u32);
        let grid = (w.div_ceil(TILE), h.div_ceil(TILE));
        let tiles = (grid.0 * grid.1) as usize;
        let mut want: Vec<Vec<u32>> = vec![Vec::new(); tiles];
        for (t, tri) in source.tris.iter().enumerate() {
            if let Some((x0, y0, x1, y1)) = pixel_range_of(&tri.v, SamplePattern::Grid32, w, h) {
                for ty in y0 / TILE..=y1 / TILE {
                    for tx in x0 / TILE..=x1 / TILE {
                        want[(ty * grid.0 + tx) as usize].push(t as u32);
                    }
                }
            }
        }
        let on = source
            .tris
            .iter()
            .filter(|tri| pixel_range_of(&tri.v, SamplePattern::Grid32, w, h).is_some())
            .count();
        assert!(
            0 < on && on < source.tris.len(),
            "{on} of {} on the frame",
            source.tris.len()
        );
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .expect("a pool");
        let mut bins = Bins::default();
        for threads in [1, 3, 2, 7, 1] {
            let g = Grid::new(SamplePattern::Grid32, (w, h));
            pool.install(|| bins.bin(&source, g, threads));
            for (t, want) in want.iter().enumerate() {
                let got: Vec<u32> = bins.tile_refs(t).map(|key| key as u32).collect();
                assert_eq!(&got, want, "tile {t}, {threads} chunks");
                assert_eq!(bins.has_items(t), !want.is_empty());
                assert_eq!(bins.tile_len(t), want.len(), "tile {t}, {threads} chunks");
            }
        }
    }

    /// The key orders depths like `f32::total_cmp`, signed zeros,
    /// infinities and subnormals included, as the sort needs.
    #[test]
    fn order_key_is_total_order() {
        let values = [
            f32::NEG_INFINITY,
            -1e30,
            -1.0,
            -f32::MIN_POSITIVE,
            -1e-45,
            -0.0,
            0.0,
            1e-45,
            f32::MIN_POSITIVE,
            0.5,
            1.0,
            1e30,
            f32::INFINITY,
        ];
        for a in values {
            for b in values {
                assert_eq!(order_key(a).cmp(&order_key(b)), a.total_cmp(&b), "{a} {b}");
            }
        }
    }
}
