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
//! 0. **Front end.** [`Hider::render`] takes `prepare`'s triangles;
//!    [`Hider::render_scene`] runs the lean front end
//!    ([`hider_scene::prepare::lean`]) for the same triangles without
//!    `prepare`'s per-primitive data; either fills a `Source` (triangles
//!    and colours), and everything after is the same.
//! 1. **Bins.** Triangles are binned to 64 x 64 pixel tiles
//!    ([`crate::bins`]): `prepare`'s after the front end, the lean front
//!    end's by each of its runs as it sets them up (no triangle is stored
//!    between the two).
//! 2. **Tiles, front to back.** Each tile sorts its triangles by nearest
//!    vertex depth (the order changes no sample: lists are sorted by depth
//!    at resolve) and renders them into its pixels' lists
//!    ([`crate::raster`], [`crate::lists`]); then the tile is resolved at
//!    once, while its lists are in cache.
//! 3. **Culling, four levels, all exact** ([`crate::culling`]): per pixel
//!    behind an opaque bound, per 8 x 8 block, per tile before the blocks,
//!    per partial pixel before its mask is computed.

use hider_geom::Viewport;
use hider_scene::pool::{OwnPool, thread_count};
use hider_scene::prepare::lean::{LeanScene, LeanTri, prepare_lean_sinks};
use hider_scene::{
    Error, Frame, Hider, NO_ID, PrepareOptions, Result, Scene, ScreenScene, ShadeMode, View,
    check_frame_size,
};
use std::sync::{Mutex, PoisonError};

use rayon::prelude::*;

use crate::bins::{BinItem, BinRun, Bins, Grid, TILE, tile_rect};
use crate::centre::in_front;
use crate::cutout::Cutouts;
use crate::fragment::{NIL, PIXEL_BYTES};
use crate::options::{ABufferOptions, DepthMode, MergePolicy};
use crate::palette;
use crate::pool::FragmentPool;
use crate::resolve::Band;
use crate::samples::{SAMPLE_BUFFER_BYTES, SampleBuffer, passes};
use crate::source::Source;
use crate::stats::ABufferStats;
use crate::worker::{Shared, Worker};

/// Carpenter's A-buffer. See the crate documentation.
///
/// Keeps its bins, per-thread lists and thread pool from one
/// frame to the next; a clone has the same options and none of that.
#[derive(Debug, Default)]
pub struct ABuffer {
    options: ABufferOptions,
    bins: Bins,
    /// One per thread (those of the last frame first).
    workers: Vec<Worker>,
    /// Per band (tile row) of the last frame: the worker that rendered
    /// it, whose pool holds its lists.
    owner: Vec<u32>,
    /// The hider's own pool, when the caller's does not have the threads
    /// asked for.
    pool: OwnPool,
    /// The lean front end's output, kept between frames
    /// ([`Hider::render_scene`]).
    lean: LeanScene,
    /// A prepared scene's triangles as the lean front end gives them
    /// ([`Hider::render`]).
    screen_tris: Vec<LeanTri>,
    /// The lean front end's runs, each binning its triangles as it sets
    /// them up ([`Hider::render_scene`]).
    bin_runs: Vec<BinRun>,
    width: u32,
    height: u32,
}

impl Clone for ABuffer {
    fn clone(&self) -> Self {
        Self::new(self.options)
    }
}

impl ABuffer {
    /// The number of threads rendering: [`ABufferOptions::threads`], or
    /// the machine's core count for 0.
    pub fn threads(&self) -> usize {
        thread_count(self.options.threads)
    }

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
        if self.options.depth == DepthMode::PerSample {
            return self.sample_ids_from_bins();
        }
        // The other modes order a fragment's samples by its zmin.
        let mut out = vec![NO_ID; pixels * n];
        let mut best = vec![f32::INFINITY; n];
        for p in 0..pixels {
            let ij = (
                (p % self.width as usize) as u32,
                (p / self.width as usize) as u32,
            );
            let band = (ij.1 / TILE) as usize;
            let pool = &self.workers[self.owner[band] as usize].raster.lists.pool;
            best.fill(f32::INFINITY);
            let ids = &mut out[p * n..(p + 1) * n];
            let mut cur = pool.head(p);
            while cur != NIL {
                let f = pool.get(cur);
                for k in (0..n).filter(|&k| f.mask >> k & 1 == 1) {
                    if in_front(f.zmin, f.prim, best[k], ids[k]) {
                        best[k] = f.zmin;
                        ids[k] = f.prim;
                    }
                }
                cur = f.next;
            }
        }
        out
    }

    /// [`Self::sample_ids`] in [`DepthMode::PerSample`]: the front
    /// primitive of every sample by its own depth, which is what the lists
    /// order each sample by and what the sample buffer keeps, found by
    /// running the last frame's binned triangles through a sample buffer
    /// (tiles resolved from samples keep no lists to read).
    fn sample_ids_from_bins(&self) -> Vec<u32> {
        let pattern = self.options.pattern;
        let n = pattern.count();
        let (w, h) = (self.width, self.height);
        let mut out = vec![NO_ID; w as usize * h as usize * n];
        if self.bins.is_empty() {
            return out;
        }
        let tiles_x = w.div_ceil(TILE);
        let mut buffer = SampleBuffer::default();
        let mut stats = ABufferStats::default();
        for ty in 0..h.div_ceil(TILE) {
            for tx in 0..tiles_x {
                let t = (ty * tiles_x + tx) as usize;
                if !self.bins.has_items(t) {
                    continue;
                }
                for pass in passes(tile_rect(tx, ty, (w, h))) {
                    let (x0, py0, x1, py1) = pass;
                    buffer.begin(pass, true);
                    for item in self.bins.tile_items(t) {
                        buffer.triangle(item, pattern, &mut stats);
                    }
                    for j in py0..=py1 {
                        for i in x0..=x1 {
                            if let Some(prims) = buffer.sample_prims(i, j) {
                                let p = j as usize * w as usize + i as usize;
                                out[p * n..(p + 1) * n].copy_from_slice(&prims[..n]);
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// The last frame's size, its binned triangles, and the pool that
    /// holds the lists of band (tile row) `band` ([`crate::inspect`]).
    pub(crate) fn last_lists(
        &self,
        band: usize,
    ) -> ((u32, u32), &[BinItem], Option<&FragmentPool>) {
        let worker = self
            .owner
            .get(band)
            .and_then(|&k| self.workers.get(k as usize));
        let pool = worker.map(|w| &w.raster.lists.pool);
        ((self.width, self.height), self.bins.items(), pool)
    }

    /// Refuses a frame that is not `viewport`'s size and options out of
    /// range, before anything is binned or drawn.
    fn check(&self, viewport: Viewport, frame: &Frame) -> Result<()> {
        check_frame_size("abuffer", viewport, frame)?;
        let o = &self.options;
        if o.max_list_len == 0 {
            return Err(Error::OutOfRange {
                what: "A-buffer max_list_len",
                expected: "at least 1",
                value: "0".into(),
            });
        }
        if o.threads > ABufferOptions::MAX_THREADS {
            return Err(Error::OutOfRange {
                what: "A-buffer threads",
                expected: "at most 256 (0: every core)",
                value: o.threads.to_string(),
            });
        }
        Ok(())
    }

    /// Renders the triangles of `scene` into `frame`; `binned` when the
    /// lean front end has binned them already ([`BinRun`]). The caller
    /// has checked the frame and the options ([`Self::check`]).
    fn run(&mut self, scene: &Source<'_>, binned: bool, frame: &mut Frame) -> Result<ABufferStats> {
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        self.width = w;
        self.height = h;
        let grid = Grid::new(self.options.pattern, (w, h));
        let (tiles_x, tiles_y) = grid.tiles;
        // No more threads than bands (tile rows), nor than `max_bytes`
        // holds with twice a pixel table each (each thread has a table
        // of the whole frame: many cores on a large frame would spend the
        // budget on tables and leave no room for fragments).
        let table = u64::from(w) * u64::from(h) * PIXEL_BYTES;
        let fit = (self.options.max_bytes / (2 * table).max(1)).max(1);
        let threads = self
            .threads()
            .min(tiles_y as usize)
            .min(usize::try_from(fit).unwrap_or(usize::MAX))
            .max(1);
        let mut options = self.options;
        options.max_bytes /= threads as u64;
        let tiles = grid.count();
        if self.workers.len() < threads {
            self.workers.resize_with(threads, Worker::default);
        }
        for worker in &mut self.workers[..threads] {
            worker.begin_frame(scene, &options, tiles)?;
        }
        self.pool.start(threads, "abuffer")?;
        let pool = self.pool.workers(threads);
        if !binned {
            let bins = &mut self.bins;
            pool.install(|| bins.bin(scene, grid, threads));
        }
        let scene = &scene.with_items(self.bins.items());
        // Each band is cleared by the thread that renders it, just before
        // (`Band::clear`): the frame's 16 bytes a pixel are written in
        // parallel, and not by a serial pass over the whole frame first
        // (at 2 threads the spider's frame at 1024 x 1024 took 5 to 11 %
        // less).
        frame.coverage.resize(frame.len(), 0.0);
        // A queue of bands: each thread takes the next one when it is done
        // with its last, so a thread the machine slows down takes fewer (a
        // fixed share would wait for the slowest). The bands with the most
        // triangles go first (longest processing time first): a costly
        // band taken last would leave the other threads idle while it
        // runs (a model in the middle of the frame fills a few of the
        // bands, unevenly).
        let bins = &self.bins;
        let cost = |ty: u32| -> usize {
            (0..tiles_x)
                .map(|tx| bins.tile_len((ty * tiles_x + tx) as usize))
                .sum()
        };
        let mut bands: Vec<(usize, u32, Band<'_>)> = Band::split(frame, TILE as usize)
            .into_iter()
            .enumerate()
            .map(|(ty, band)| (cost(ty as u32), ty as u32, band))
            .collect();
        // Ascending, popped from the end; ties top first.
        bands.sort_by_key(|&(cost, ty, _)| (cost, std::cmp::Reverse(ty)));
        let bands: Vec<(u32, Band<'_>)> =
            bands.into_iter().map(|(_, ty, band)| (ty, band)).collect();
        let queue = Mutex::new(bands);
        let shared = Shared {
            scene,
            options: &options,
            bins,
            tiles_x,
            sample_tiles: options.sample_tiles
                && options.depth == DepthMode::PerSample
                && options.merge != MergePolicy::SameSurface
                && options.max_bytes >= table + SAMPLE_BUFFER_BYTES,
            cutouts: Cutouts::new(scene.screen_scene(), options.pattern),
        };
        let run = |worker: &mut Worker| -> Result<Vec<u32>> {
            let mut done = Vec::new();
            loop {
                let next = queue.lock().unwrap_or_else(PoisonError::into_inner).pop();
                let Some((ty, mut band)) = next else {
                    return Ok(done);
                };
                worker.band(&shared, ty, &mut band)?;
                done.push(ty);
            }
        };
        let mut workers = std::mem::take(&mut self.workers);
        let result = if threads == 1 {
            run(&mut workers[0]).map(|done| vec![done])
        } else {
            let (mine, run) = (&mut workers[..threads], &run);
            pool.install(move || mine.par_iter_mut().map(run).collect())
        };
        self.workers = workers;
        let done: Vec<Vec<u32>> = match result {
            Ok(done) => done,
            Err(e) => {
                // Bands a failed frame never reached still hold the last
                // frame: clear them all rather than leave a mixed image.
                frame.clear();
                frame.coverage.resize(frame.len(), 0.0);
                return Err(e);
            }
        };
        self.owner.clear();
        self.owner.resize(tiles_y as usize, 0);
        for (k, bands) in done.iter().enumerate() {
            for &ty in bands {
                self.owner[ty as usize] = k as u32;
            }
        }
        Ok(total_stats(&self.workers[..threads]))
    }
}

/// The counters of the workers' tiles, added up (the longest list is the
/// longest of all; the mean list length comes from the resolvers' counts;
/// memory is the sum of the workers' peaks).
fn total_stats(workers: &[Worker]) -> ABufferStats {
    let mut s = ABufferStats::default();
    let (mut lists, mut total) = (0, 0);
    for w in workers {
        let t = &w.stats;
        s.fragments += t.fragments;
        s.full_coverage += t.full_coverage;
        s.merged += t.merged;
        s.culled += t.culled;
        s.culled_blocks += t.culled_blocks;
        s.culled_tiles += t.culled_tiles;
        s.pruned += t.pruned;
        s.dropped += t.dropped;
        s.coincident += t.coincident;
        s.max_list_len = s.max_list_len.max(t.max_list_len);
        s.per_sample_pixels += t.per_sample_pixels;
        s.sample_tiles += t.sample_tiles;
        s.whole_pixels += t.whole_pixels;
        let pool = &w.raster.lists.pool;
        s.pool_fragments += pool.peak_fragments() as u64;
        s.bytes += pool.peak_bytes();
        if t.sample_tiles > 0 {
            s.bytes += SAMPLE_BUFFER_BYTES;
        }
        let (l, n) = w.resolver.list_counts();
        lists += l;
        total += n;
    }
    s.mean_list_len = if lists == 0 {
        0.0
    } else {
        total as f64 / lists as f64
    };
    s.mean_list_len_x1000 = (s.mean_list_len * 1000.0).round() as u64;
    s
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
        if self.options.is_carpenter() {
            "abuffer-carpenter"
        } else {
            "abuffer"
        }
    }

    fn check_size(&self, width: u32, height: u32) -> Result<()> {
        crate::pool::check_table(width as usize * height as usize, self.options.max_bytes)
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<ABufferStats> {
        self.check(scene.viewport, frame)?;
        let mut tris = std::mem::take(&mut self.screen_tris);
        tris.clear();
        tris.extend(scene.tris.iter().map(LeanTri::from));
        let sampler = palette::sampler(scene, self.options.shade);
        let result = self.run(
            &Source::screen(scene, &tris, sampler.as_ref()),
            false,
            frame,
        );
        self.screen_tris = tris;
        result
    }

    /// The lean front end ([`prepare_lean_sinks`]: `prepare`'s triangles,
    /// transformed per vertex, without its per-primitive data, each run of
    /// its triangle pass binning its triangles as it sets them up), then
    /// the same rendering as [`Hider::render`]: the same frame, bit for
    /// bit. A scene whose colours vary across primitives (textures, vertex
    /// normals or colours, highlights: [`Scene::varies_per_point`]) drawn
    /// in Lambert mode is shaded per point from the camera-space positions
    /// and normals the lean front end then keeps per vertex
    /// ([`LeanScene::set_point_shading`]). `screen` is left as it was.
    fn render_scene(
        &mut self,
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        screen: &mut ScreenScene,
        frame: &mut Frame,
    ) -> Result<ABufferStats> {
        // Cut-outs are alpha-tested per sample from the prepared scene's
        // primitives (texture coordinates), in any shade mode; every other
        // scene, textured and smooth-shaded ones included, takes the lean
        // front end.
        if hider_scene::shade::cutout::scene_has_cutouts(scene) {
            hider_scene::prepare_into(scene, view, options, screen)?;
            return self.render(screen, frame);
        }
        // Checked before the front end bins anything.
        self.check(view.viewport, frame)?;
        let grid = Grid::new(self.options.pattern, (frame.width(), frame.height()));
        let mut lean = std::mem::take(&mut self.lean);
        lean.set_point_shading(self.options.shade == ShadeMode::Lambert);
        let mut runs = std::mem::take(&mut self.bin_runs);
        self.bins.lend(&mut runs);
        let opacity = self.bins.scene_opacity(scene);
        let prepared = prepare_lean_sinks(scene, view, options, &mut lean, &mut runs, |_, run| {
            run.begin(grid, opacity)
        });
        let result = match prepared {
            Ok(()) => {
                self.bins.adopt(&mut runs, grid);
                let sampler = crate::source::lean_sampler(&lean, view);
                self.run(&Source::lean(&lean, scene, sampler.as_ref()), true, frame)
            }
            Err(e) => {
                // The runs stopped part way: no bins of this frame.
                self.bins.abandon(&mut runs);
                Err(e)
            }
        };
        self.bin_runs = runs;
        self.lean = lean;
        result
    }

    fn resolves_color(&self) -> bool {
        true
    }

    fn composites_transparency(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::{PrepareOptions, ScreenScene, View, prepare, procedural};

    /// Both entry points refuse a frame of another size and options out of
    /// range with a one-line error, and leave the frame as it was.
    #[test]
    fn both_entry_points_refuse_bad_frames_and_options() {
        let scene = procedural::cube();
        let view = View::for_scene(&scene, 64, 48).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let mut unused = ScreenScene::empty(&view);
        let bad_list = ABufferOptions {
            max_list_len: 0,
            ..ABufferOptions::default()
        };
        let cases = [
            (ABufferOptions::default(), (48, 64), "48x64"),
            (bad_list, (64, 48), "max_list_len"),
            (
                ABufferOptions::default().with_threads(257),
                (64, 48),
                "threads",
            ),
        ];
        for (options, (w, h), says) in cases {
            let mut hider = ABuffer::new(options);
            let mut frame = Frame::new(w, h).unwrap();
            let before = frame.clone();
            let e = hider.render(&screen, &mut frame).unwrap_err();
            assert!(e.to_string().contains(says), "render: {e}");
            let e = hider
                .render_scene(
                    &scene,
                    &view,
                    &PrepareOptions::default(),
                    &mut unused,
                    &mut frame,
                )
                .unwrap_err();
            assert!(e.to_string().contains(says), "render_scene: {e}");
            assert_eq!(frame, before, "{says}");
        }
    }

    /// The resolve's shortcuts for lists of one or two opaque fragments give
    /// bit for bit what the general paths give, in every depth mode, with
    /// and without merging, on lists (the sample buffer has no shortcuts);
    /// the hard cases include triangles the near plane cuts into pieces of
    /// one primitive, which meet in a pixel as two fragments of it.
    #[test]
    fn resolve_shortcuts_change_no_bit() {
        let mut scenes = vec![
            procedural::uv_sphere(24),
            procedural::cube(),
            procedural::random_soup(400, 3),
            procedural::intersecting_pair(),
        ];
        scenes.extend(
            hider_testkit::hard_cases::all(5)
                .into_iter()
                .map(|(_, s)| s),
        );
        for scene in &scenes {
            let view = View::for_scene(scene, 150, 90).unwrap();
            let s = prepare(scene, &view, &PrepareOptions::default()).unwrap();
            for depth in [
                DepthMode::PerSample,
                DepthMode::MinMax,
                DepthMode::ZminOrder,
            ] {
                for merge in [MergePolicy::SameColor, MergePolicy::Off] {
                    let opts = ABufferOptions::default()
                        .with_depth(depth)
                        .with_merge(merge)
                        .with_sample_tiles(false);
                    let mut fast = ABuffer::new(opts);
                    let mut slow = ABuffer::new(opts.with_threads(1));
                    slow.workers.resize_with(1, Worker::default);
                    slow.workers[0].resolver.no_shortcuts = true;
                    let mut a = Frame::new(150, 90).unwrap();
                    let mut b = Frame::new(150, 90).unwrap();
                    fast.render(&s, &mut a).unwrap();
                    slow.render(&s, &mut b).unwrap();
                    assert_eq!(a, b, "{depth:?} {merge:?}");
                }
            }
        }
    }
}
