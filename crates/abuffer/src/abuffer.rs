//! The A-buffer hider: how a frame runs, tile by tile.
//!
//! Carpenter (1984), "The A-buffer, an antialiased hidden surface method":
//! every primitive is scan-converted into *fragments*, one per pixel it
//! touches, each carrying a coverage mask (8 x 4 bits), its depth range,
//! colour and opacity. Nothing is decided while primitives arrive, except
//! what is provably invisible: a fragment entirely behind opaque fragments
//! that cover every sample and the centre of its pixel is dropped (the
//! paper's pixels hold a plain depth in that case). Once every primitive is
//! in, each pixel's list is sorted and composited front to back
//! ([`crate::resolve`]). The result does not depend on the order primitives
//! are submitted in, which is what makes its transparency correct where a
//! z-buffer's is not.
//!
//! How a frame runs:
//! 1. **Bins.** Triangles are binned to 64 x 64 pixel tiles
//!    ([`crate::bins`]).
//! 2. **Tiles, front to back.** Each tile sorts its triangles by nearest
//!    vertex depth (the order changes no sample: lists are sorted by depth
//!    at resolve) and renders them into its pixels' lists
//!    ([`crate::raster`], [`crate::lists`]); then the tile is resolved at
//!    once, while its lists are in cache.
//! 3. **Culling, three levels, all exact** ([`crate::culling`]): per pixel
//!    behind an opaque bound, per 8 x 8 block, per partial pixel before its
//!    mask is computed.

use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, check_frame};

use crate::bins::{Bins, LEADER, SOLE, TILE};
use crate::centre::in_front;
use crate::fragment::NIL;
use crate::options::{ABufferOptions, DepthMode};
use crate::raster::Rasterizer;
use crate::resolve::{Input, Resolver};
use crate::stats::ABufferStats;

/// Carpenter's A-buffer. See the crate documentation.
#[derive(Clone, Debug, Default)]
pub struct ABuffer {
    options: ABufferOptions,
    raster: Rasterizer,
    bins: Bins,
    resolver: Resolver,
    /// Per item of the current tile that leads coincident ones: the
    /// lowest id of an opaque one taken so far, `NO_ID` if none.
    shadow: Vec<u32>,
    width: u32,
    height: u32,
}

impl ABuffer {
    /// After a render: the primitive in front at every sample, pixel by
    /// pixel (`samples` entries per pixel, row-major), [`NO_ID`] where no
    /// fragment covers the sample. Ordered as the resolve orders samples:
    /// by per-sample depth in [`DepthMode::PerSample`], by `zmin` otherwise.
    /// A merged fragment reports its lowest primitive id, so compare with
    /// merging off ([`crate::MergePolicy::Off`]).
    pub fn sample_ids(&self) -> Vec<u32> {
        let pattern = self.options.pattern;
        let n = pattern.count();
        let pixels = self.width as usize * self.height as usize;
        let per_sample = self.options.depth == DepthMode::PerSample;
        let (pool, planes) = (&self.raster.lists.pool, &self.raster.lists.planes);
        let mut out = vec![NO_ID; pixels * n];
        let mut best = vec![f32::INFINITY; n];
        for p in 0..pixels {
            let ij = (
                (p % self.width as usize) as u32,
                (p / self.width as usize) as u32,
            );
            best.fill(f32::INFINITY);
            let ids = &mut out[p * n..(p + 1) * n];
            let mut cur = pool.head(p);
            while cur != NIL {
                let f = pool.get(cur);
                for k in (0..n).filter(|&k| f.mask >> k & 1 == 1) {
                    let z = if per_sample {
                        pool.sample_depth(planes, f, ij, pattern.positions(), k)
                    } else {
                        f.zmin
                    };
                    if in_front(z, f.prim, best[k], ids[k]) {
                        best[k] = z;
                        ids[k] = f.prim;
                    }
                }
                cur = f.next;
            }
        }
        out
    }

    fn check_options(&self) -> Result<()> {
        let o = &self.options;
        if o.max_list_len == 0 {
            return Err(Error::OutOfRange {
                what: "A-buffer max_list_len",
                expected: "at least 1",
                value: "0".into(),
            });
        }
        Ok(())
    }

    /// Renders and resolves tile `t`, whose top-left pixel is `(x0, y0)`
    /// and bottom-right `(x1, y1)`.
    fn render_tile(
        &mut self,
        scene: &ScreenScene,
        t: usize,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        frame: &mut Frame,
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let has_items = self.bins.has_items(t);
        if !has_items && !self.bins.is_dirty(t) {
            return Ok(());
        }
        let w = scene.viewport.width as usize;
        let lists = &mut self.raster.lists;
        for j in y0..=y1 {
            lists
                .pool
                .clear_pixels(j as usize * w + x0 as usize, (x1 - x0 + 1) as usize);
        }
        self.bins.set_dirty(t, has_items);
        if !has_items {
            return Ok(());
        }
        lists.culling.begin_tile(x1 - x0, y1 - y0);
        // Front to back: the nearest surfaces first set the opaque bounds
        // that cull what lies behind them. The order changes no sample
        // (the lists are sorted by depth at resolve), only how much work
        // is culled.
        let n = self.bins.order_tile(t, self.options.front_to_back);
        self.shadow.clear();
        self.shadow.resize(n, NO_ID);
        for k in 0..n {
            let item = self.bins.item(k);
            let twin = self.bins.twin(k);
            if twin != SOLE {
                // Coincident triangles (a face whose vertex list repeats
                // itself): an opaque one taken earlier, with a lower id,
                // ties with this one at every sample and centre and wins
                // every tie, so this one can change nothing. Without this
                // the copies fill the lists (equal depths are never
                // strictly behind) and overflow them.
                let leader = if twin == LEADER { k } else { twin as usize };
                if self.shadow[leader] <= item.prim {
                    stats.coincident += 1;
                    continue;
                }
                if self.raster.lists.prim_alpha(scene, item.prim) >= 1.0 {
                    self.shadow[leader] = item.prim;
                }
            }
            let (rx0, ry0, rx1, ry1) = item.range;
            let rect = (rx0.max(x0), ry0.max(y0), rx1.min(x1), ry1.min(y1));
            self.raster.triangle(scene, item, rect, (x0, y0), stats)?;
        }
        let lists = &mut self.raster.lists;
        let mut input = Input {
            scene,
            pool: &lists.pool,
            planes: &lists.planes,
            colors: &mut lists.colors,
            options: &self.options,
        };
        self.resolver
            .resolve_tile(&mut input, (x0, y0, x1, y1), frame, stats);
        Ok(())
    }
}

impl Hider for ABuffer {
    type Options = ABufferOptions;
    type Stats = ABufferStats;

    fn new(options: ABufferOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    fn options(&self) -> &ABufferOptions {
        &self.options
    }

    fn name(&self) -> &str {
        if self.options == ABufferOptions::carpenter() {
            "abuffer-carpenter"
        } else {
            "abuffer"
        }
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<ABufferStats> {
        check_frame("abuffer", scene, frame)?;
        self.check_options()?;
        frame.clear();
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        self.width = w;
        self.height = h;
        let fresh = self.raster.begin_frame(scene, &self.options)?;
        let (tiles_x, tiles_y) = (w.div_ceil(TILE), h.div_ceil(TILE));
        self.bins.bin(scene, self.options.pattern, tiles_x, tiles_y);
        self.bins.track(fresh, (w, h), (tiles_x * tiles_y) as usize);
        frame.coverage.clear();
        frame.coverage.resize(frame.len(), 0.0);
        self.resolver.begin();
        let mut stats = ABufferStats::default();
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let t = (ty * tiles_x + tx) as usize;
                let (x0, y0) = (tx * TILE, ty * TILE);
                let (x1, y1) = ((x0 + TILE).min(w) - 1, (y0 + TILE).min(h) - 1);
                self.render_tile(scene, t, (x0, y0, x1, y1), frame, &mut stats)?;
            }
        }
        self.resolver.finish(&mut stats);
        let pool = &self.raster.lists.pool;
        stats.pool_fragments = pool.peak_fragments() as u64;
        stats.bytes = pool.peak_bytes();
        Ok(stats)
    }

    fn resolves_color(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::{PrepareOptions, View, prepare, procedural};

    /// The resolve's shortcuts for lists of one or two opaque fragments give
    /// bit for bit what the general paths give, in every depth mode.
    #[test]
    fn resolve_shortcuts_change_no_bit() {
        let scenes = [
            procedural::uv_sphere(24),
            procedural::cube(),
            procedural::random_soup(400, 3),
            procedural::intersecting_pair(),
        ];
        for scene in &scenes {
            let view = View::for_scene(scene, 150, 90).unwrap();
            let s = prepare(scene, &view, &PrepareOptions::default()).unwrap();
            for depth in [
                DepthMode::PerSample,
                DepthMode::MinMax,
                DepthMode::ZminOrder,
            ] {
                let opts = ABufferOptions::default().with_depth(depth);
                let mut fast = ABuffer::new(opts);
                let mut slow = ABuffer::new(opts);
                slow.resolver.no_shortcuts = true;
                let (mut a, mut b) = (Frame::new(150, 90).unwrap(), Frame::new(150, 90).unwrap());
                fast.render(&s, &mut a).unwrap();
                slow.render(&s, &mut b).unwrap();
                assert_eq!(a, b, "{depth:?}");
            }
        }
    }
}
