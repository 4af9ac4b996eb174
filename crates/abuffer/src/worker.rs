//! One thread's share of a frame: bands of tiles, each tile rendered into
//! the thread's own lists and resolved at once.
//!
//! Tiles are independent: a tile's lists, its culling state and its
//! resolve touch only its own pixels, and the shading of a primitive is a
//! pure function of the scene. So a thread needs only scratch of its own
//! (pixel table, fragment pool, colour cache, tile order, resolve
//! scratch) and writes only the rows of its bands, and the frame, the
//! sample ids and the work counters do not depend on which thread took
//! which band.

use hider_scene::{NO_ID, Result};

use crate::source::Source;

use crate::bins::{Bins, LEADER, SOLE, TileQueue, tile_rect};
use crate::cutout::Cutouts;
use crate::options::ABufferOptions;
use crate::raster::Rasterizer;
use crate::resolve::{Band, Input, Resolver, Samples};
use crate::samples::{SampleBuffer, passes};
use crate::stats::ABufferStats;

/// What one thread keeps from frame to frame.
#[derive(Clone, Debug, Default)]
pub(crate) struct Worker {
    /// Its lists (pixel table, fragment pool) and rasteriser.
    pub(crate) raster: Rasterizer,
    /// Its resolve scratch.
    pub(crate) resolver: Resolver,
    /// Its tile order, coincident items and dirty tiles.
    queue: TileQueue,
    /// Per item of the current tile that leads coincident ones: the
    /// lowest id of an opaque one taken so far, `NO_ID` if none.
    shadow: Vec<u32>,
    /// Its sample buffer, made on first use.
    samples: Option<Box<SampleBuffer>>,
    /// The counters of its tiles this frame.
    pub(crate) stats: ABufferStats,
}

/// What every thread reads during a frame.
pub(crate) struct Shared<'a> {
    /// The scene.
    pub(crate) scene: &'a Source<'a>,
    /// The options (memory bound: this thread's share).
    pub(crate) options: &'a ABufferOptions,
    /// The binned triangles.
    pub(crate) bins: &'a Bins,
    /// Tiles per row.
    pub(crate) tiles_x: u32,
    /// Whether opaque tiles take the sample buffer this frame.
    pub(crate) sample_tiles: bool,
    /// The alpha test of cut-outs, when some material may cut out.
    pub(crate) cutouts: Option<Cutouts<'a>>,
}

impl Worker {
    /// Starts a frame: empty lists under `options.max_bytes`, counters at
    /// zero.
    pub(crate) fn begin_frame(
        &mut self,
        scene: &Source<'_>,
        options: &ABufferOptions,
        tiles: usize,
    ) -> Result<()> {
        let fresh = self.raster.begin_frame(scene, options)?;
        let dims = (scene.viewport.width, scene.viewport.height);
        self.queue.track(fresh, dims, tiles);
        self.resolver.begin();
        self.stats = ABufferStats::default();
        Ok(())
    }

    /// Renders and resolves the tiles of tile row `ty` into `band`.
    pub(crate) fn band(&mut self, shared: &Shared<'_>, ty: u32, band: &mut Band<'_>) -> Result<()> {
        let dims = (shared.scene.viewport.width, shared.scene.viewport.height);
        band.clear();
        for tx in 0..shared.tiles_x {
            shared.options.cancel.poll()?;
            let t = (ty * shared.tiles_x + tx) as usize;
            self.tile(shared, t, tile_rect(tx, ty, dims), band)?;
        }
        Ok(())
    }

    /// Renders and resolves tile `t`, whose top-left pixel is `(x0, y0)`
    /// and bottom-right `(x1, y1)`.
    fn tile(
        &mut self,
        shared: &Shared<'_>,
        t: usize,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        band: &mut Band<'_>,
    ) -> Result<()> {
        let (scene, bins) = (shared.scene, shared.bins);
        let has_items = bins.has_items(t);
        let dirty = self.queue.is_dirty(t);
        if !has_items && !dirty {
            return Ok(());
        }
        // Front to back: the nearest surfaces first set the opaque bounds
        // (or the sample buffer's depths) that cull what lies behind them.
        // The order changes no sample (the lists are sorted by depth at
        // resolve), only how much work is culled.
        let n = if has_items {
            self.queue.order_tile(bins, t, shared.options.front_to_back)
        } else {
            0
        };
        // Items that may cut out take the lists, where their masks are
        // alpha-tested.
        let cut = |prim: u32| shared.cutouts.as_ref().is_some_and(|c| c.may_cut(prim));
        let sampled = has_items
            && shared.sample_tiles
            && (0..n).all(|k| self.queue.item(k).alpha >= 1.0 && !cut(self.queue.item(k).prim));
        let w = scene.viewport.width as usize;
        let lists = &mut self.raster.lists;
        if dirty || !sampled {
            for j in y0..=y1 {
                lists
                    .pool
                    .clear_pixels(j as usize * w + x0 as usize, (x1 - x0 + 1) as usize);
            }
        }
        self.queue.set_dirty(t, has_items && !sampled);
        if !has_items {
            return Ok(());
        }
        if sampled {
            self.sample_tile(shared, n, (x0, y0, x1, y1), band);
            return Ok(());
        }
        lists.culling.begin_tile(x1 - x0, y1 - y0);
        self.shadow.clear();
        self.shadow.resize(n, NO_ID);
        let stats = &mut self.stats;
        for k in 0..n {
            let item = self.queue.item(k);
            if shadowed(&self.queue, &mut self.shadow, k, stats) {
                continue;
            }
            let (rx0, ry0, rx1, ry1) = item.range;
            let rect = (rx0.max(x0), ry0.max(y0), rx1.min(x1), ry1.min(y1));
            let index = self.queue.index(k);
            let cutouts = shared.cutouts.as_ref().filter(|c| c.may_cut(item.prim));
            self.raster
                .triangle(scene, (item, index, cutouts), rect, (x0, y0), stats)?;
        }
        let lists = &mut self.raster.lists;
        let mut input = Input {
            scene,
            pool: &lists.pool,
            colors: &mut lists.colors,
            options: shared.options,
        };
        self.resolver
            .resolve_tile(&mut input, (x0, y0, x1, y1), band, &mut self.stats);
        Ok(())
    }

    /// Renders and resolves the `n` items of the current tile, all
    /// opaque, through the sample buffer, pass by pass ([`passes`]).
    fn sample_tile(
        &mut self,
        shared: &Shared<'_>,
        n: usize,
        rect: (u32, u32, u32, u32),
        band: &mut Band<'_>,
    ) {
        let pattern = shared.options.pattern;
        let k = Samples::new(pattern);
        let mut buffer = self.samples.take().unwrap_or_default();
        let mut stats = self.stats;
        for pass in passes(rect) {
            let (_, py0, _, py1) = pass;
            buffer.begin(pass, shared.options.occlusion_culling);
            self.shadow.clear();
            self.shadow.resize(n, NO_ID);
            for q in 0..n {
                let (_, ry0, _, ry1) = self.queue.item(q).range;
                if ry0 > py1 || ry1 < py0 || shadowed(&self.queue, &mut self.shadow, q, &mut stats)
                {
                    continue;
                }
                buffer.triangle(self.queue.item(q), pattern, &mut stats);
            }
            let mut input = Input {
                scene: shared.scene,
                pool: &self.raster.lists.pool,
                colors: &mut self.raster.lists.colors,
                options: shared.options,
            };
            buffer.resolve(&mut input, &mut self.resolver, &k, band);
        }
        stats.sample_tiles += 1;
        self.stats = stats;
        self.samples = Some(buffer);
    }
}

/// Whether item `k` of the current tile is a coincident copy that can
/// change nothing (counted in [`ABufferStats::coincident`]); notes it
/// as taken otherwise.
///
/// Coincident triangles (a face whose vertex list repeats itself): an
/// opaque one taken earlier, with a lower id, ties with this one at
/// every sample and centre and wins every tie. Without this the copies
/// fill the lists (equal depths are never strictly behind) and
/// overflow them.
#[inline]
fn shadowed(queue: &TileQueue, shadow: &mut [u32], k: usize, stats: &mut ABufferStats) -> bool {
    let twin = queue.twin(k);
    if twin == SOLE {
        return false;
    }
    let item = queue.item(k);
    let leader = if twin == LEADER { k } else { twin as usize };
    if shadow[leader] <= item.prim {
        stats.coincident += 1;
        return true;
    }
    if item.alpha >= 1.0 {
        shadow[leader] = item.prim;
    }
    false
}
