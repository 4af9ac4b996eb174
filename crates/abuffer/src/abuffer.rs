//! The A-buffer hider: fragment generation, insertion, merging, culling
//! and the overflow policy. Resolving the lists is in [`crate::resolve`].
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
//! 1. **Bins.** Triangles are binned to 64 x 64 pixel tiles ([`TILE`]); a
//!    bin item carries what rasterising needs (pixel range, depth plane,
//!    vertices).
//! 2. **Tiles, front to back.** Each tile sorts its triangles by nearest
//!    vertex depth (the order changes no sample: lists are sorted by depth
//!    at resolve) and renders them into its pixels' lists; then the tile is
//!    resolved at once, while its lists are in cache.
//! 3. **Culling, three levels, all exact.** Per pixel an *opaque bound*:
//!    a depth such that every sample and the centre is covered by opaque
//!    fragments of the list no farther than it (a full opaque fragment's
//!    `zmax`, or the farthest `zmax` of partial opaque fragments gathered
//!    until their masks cover everything). A fragment whose `zmin` is
//!    beyond it is strictly behind at every sample and the centre: culled
//!    on arrival, or pruned when the bound drops. Per 8 x 8 block, the
//!    farthest bound of its pixels: a triangle whose plane is beyond it
//!    over the block (one evaluation, the plane being monotonic) makes no
//!    fragment there, and a triangle with no live block is not even set
//!    up. Per partial pixel, the plane at the hull corner bounds `zmin`
//!    from below before the mask is computed.
//! 4. **Fragments** are 40 bytes: depth bounds from at most 4 plane
//!    evaluations each, equal to the extremes over the samples
//!    ([`DepthBounds`]); sample depths are recomputed at resolve where
//!    needed; shading is computed for the primitives with a triangle that
//!    survives the block test only.

use hider_geom::{FixedPt, PlaneEq};
use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, ShadeMode, Stats, check_frame};

use crate::coverage::{Class, Coverage, DepthBounds, TriCoverage, pixel_range, plane_depth};
use crate::fragment::{Fragment, FragmentPool, MERGED_BASE, NIL};
use crate::options::{ABufferOptions, DepthMode, MergePolicy, OverflowPolicy};
use crate::palette::prim_rgba;
use crate::pattern::{CENTRE, MAX_SAMPLES};
use crate::resolve::{Resolver, Shaded, hidden_in_every_sample};
use crate::stats::ABufferStats;

/// Two colour channels closer than this count as equal for
/// [`MergePolicy::SameColor`]: far below one step of an 8-bit output
/// (1/255), so a merge never changes the image.
pub const MERGE_COLOR_TOLERANCE: f32 = 1e-5;

/// How many fragments at the front of a list are tried as merge partners.
/// The partner is the fragment of the neighbouring triangle, inserted
/// recently (a mesh's triangles arrive together), so a short search finds
/// it without making insertion cost grow with the list.
pub const MERGE_SEARCH: usize = 8;

/// Side of the square screen tiles, in pixels. Triangles are binned to
/// tiles; each tile is rendered and resolved before the next, so its
/// pixel entries and fragments stay in cache from insertion to resolve.
pub const TILE: u32 = 64;

/// Side of the blocks of the hierarchical occlusion test, in pixels.
const BLOCK: u32 = 8;
/// Blocks per tile side.
const BLOCKS: usize = (TILE / BLOCK) as usize;
// A tile's blocks are the bits of a `u64`.
const _: () = assert!(BLOCKS * BLOCKS <= 64 && TILE % BLOCK == 0);

/// Per 8 x 8 block of the current tile: an upper bound of the opaque
/// bounds of its pixels. While some pixel of the block has no bound yet
/// (`open > 0`) it is infinite; after that it is their maximum, recomputed
/// only when a test needs it and a bound dropped since (`stale`). Bounds
/// only decrease, so a stale value is still an upper bound.
#[derive(Clone, Debug)]
struct BlockFar {
    far: [f32; BLOCKS * BLOCKS],
    open: [u8; BLOCKS * BLOCKS],
    stale: u64,
}

impl BlockFar {
    /// The blocks of a tile whose pixels `x0..=x1`, `y0..=y1` (tile-local)
    /// exist: every one open.
    fn reset(&mut self, x1: u32, y1: u32) {
        self.far = [f32::INFINITY; BLOCKS * BLOCKS];
        self.stale = 0;
        for (b, open) in self.open.iter_mut().enumerate() {
            let (bx, by) = ((b % BLOCKS) as u32 * BLOCK, (b / BLOCKS) as u32 * BLOCK);
            let w = (x1 + 1).saturating_sub(bx).min(BLOCK);
            let h = (y1 + 1).saturating_sub(by).min(BLOCK);
            *open = (w * h) as u8;
        }
    }
}

impl Default for BlockFar {
    fn default() -> Self {
        Self {
            far: [f32::INFINITY; BLOCKS * BLOCKS],
            open: [(BLOCK * BLOCK) as u8; BLOCKS * BLOCKS],
            stale: 0,
        }
    }
}

/// The opaque fragments gathered towards a new opaque bound of one pixel:
/// the samples (and centre) they cover and their farthest `zmax`.
#[derive(Clone, Copy, Debug)]
struct Gather {
    mask: u32,
    centre: bool,
    far: f32,
}

impl Gather {
    const EMPTY: Gather = Gather {
        mask: 0,
        centre: false,
        far: f32::NEG_INFINITY,
    };
}

/// One triangle of a bin, with what rasterising it needs: once a tile
/// sorts its bin front to back, triangles are visited out of index order,
/// and reading them from the scene would cost a cache miss each.
#[derive(Clone, Copy, Debug, Default)]
struct BinItem {
    /// Sort key: nearest vertex depth (total order), then triangle index.
    key: u64,
    tri: u32,
    prim: u32,
    range: (u32, u32, u32, u32),
    plane: PlaneEq,
    v: [FixedPt; 3],
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
struct Bins {
    start: Vec<u32>,
    /// The items, tile by tile.
    items: Vec<BinItem>,
    /// Per tile: sort keys and positions in the tile's bin.
    order: Vec<(u64, u32)>,
    ranges: Vec<(u32, u32, u32, u32)>,
    /// Tiles whose pixel entries may hold lists of the last frame.
    dirty: Vec<bool>,
    /// Frame size the dirty flags refer to.
    dims: (u32, u32),
}

/// Carpenter's A-buffer. See the crate documentation.
#[derive(Clone, Debug, Default)]
pub struct ABuffer {
    options: ABufferOptions,
    pool: FragmentPool,
    colors: Vec<[f32; 4]>,
    planes: Vec<PlaneEq>,
    bins: Bins,
    gather: Vec<Gather>,
    blocks: BlockFar,
    /// The triangle set-up, reused.
    setup: Option<Box<TriCoverage>>,
    scratch: Vec<Shaded>,
    resolver: Resolver,
    width: u32,
    height: u32,
    last: ABufferStats,
    /// Occlusion culling switched off (the reference path of the tests).
    no_cull: bool,
    /// Triangles taken in submission order instead of front to back.
    no_sort: bool,
}

/// What the insertion of one fragment needs besides the fragment.
struct Ctx<'a> {
    scene: &'a ScreenScene,
    p: usize,
    ij: (u32, u32),
    /// Index of the pixel in the tile's gather table.
    g: usize,
    alpha: f32,
}

impl ABuffer {
    /// An A-buffer with the given options.
    pub fn new(options: ABufferOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// Switches occlusion culling on (the default) or off. Off, no pixel
    /// gets an opaque bound, so nothing is culled on arrival, no block is
    /// skipped and nothing is pruned behind a bound: every fragment reaches
    /// its list (the overflow policy still applies). The image, coverage,
    /// ids and sample ids are the same either way (culling only drops
    /// fragments that lose every sample and the centre; colours may differ
    /// in the last bit of rounding, within one 8-bit step); only the work
    /// counters and the time differ. Kept as the reference the culling is
    /// tested against, and to measure what it saves.
    pub fn with_occlusion_culling(mut self, on: bool) -> Self {
        self.no_cull = !on;
        self
    }

    /// Whether each tile takes its triangles front to back (the default:
    /// sorted by nearest vertex depth) or in submission order. The exact
    /// answer (samples, coverage, ids) is the same either way, since lists
    /// are ordered by depth at resolve; front to back, the nearest surfaces
    /// set the opaque bounds first, so far more of what lies behind is
    /// culled (per pixel or per block) instead of inserted and pruned.
    /// Merging decisions, which look at the latest fragments of a list,
    /// and colour rounding may differ.
    pub fn with_front_to_back(mut self, on: bool) -> Self {
        self.no_sort = !on;
        self
    }

    /// The options.
    pub fn options(&self) -> &ABufferOptions {
        &self.options
    }

    /// The counters of the last frame.
    pub fn stats(&self) -> ABufferStats {
        self.last
    }

    /// After a render: the primitive in front at every sample, pixel by
    /// pixel (`samples` entries per pixel, row-major), [`NO_ID`] where no
    /// fragment covers the sample. Ordered as the resolve orders samples:
    /// by per-sample depth in [`DepthMode::PerSample`], by `zmin` otherwise.
    /// A merged fragment reports its lowest primitive id, so compare with
    /// merging off ([`MergePolicy::Off`]).
    pub fn sample_ids(&self) -> Vec<u32> {
        let pattern = self.options.pattern;
        let n = pattern.count();
        let pixels = self.width as usize * self.height as usize;
        let per_sample = self.options.depth == DepthMode::PerSample;
        let mut out = vec![NO_ID; pixels * n];
        let mut best = vec![f32::INFINITY; n];
        for p in 0..pixels {
            let ij = (
                (p % self.width as usize) as u32,
                (p / self.width as usize) as u32,
            );
            best.fill(f32::INFINITY);
            let ids = &mut out[p * n..(p + 1) * n];
            let mut cur = self.pool.head(p);
            while cur != NIL {
                let f = self.pool.get(cur);
                for k in (0..n).filter(|&k| f.mask >> k & 1 == 1) {
                    let z = if per_sample {
                        sample_depth_of(&self.pool, &self.planes, f, ij, pattern.positions(), k)
                    } else {
                        f.zmin
                    };
                    if crate::centre::in_front(z, f.prim, best[k], ids[k]) {
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

    /// The colour and opacity of shading index `shade` (a primitive's
    /// computed on first use).
    #[inline]
    fn rgba(&mut self, scene: &ScreenScene, shade: u32) -> [f32; 4] {
        if shade >= MERGED_BASE {
            self.pool.merged(shade).rgba
        } else {
            shade_of(&mut self.colors, scene, self.options.shade, shade)
        }
    }

    /// Bins the triangles by tile (counting sort, submission order kept).
    fn bin(&mut self, scene: &ScreenScene, tiles_x: u32, tiles_y: u32) {
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        let pattern = self.options.pattern;
        let bins = &mut self.bins;
        let tiles = (tiles_x * tiles_y) as usize;
        bins.start.clear();
        bins.start.resize(tiles + 1, 0);
        bins.ranges.clear();
        const NONE: (u32, u32, u32, u32) = (1, 1, 0, 0);
        for tri in &scene.tris {
            let r = pixel_range(tri, pattern, w, h).unwrap_or(NONE);
            bins.ranges.push(r);
            let (x0, y0, x1, y1) = r;
            if x0 > x1 {
                continue;
            }
            for ty in y0 / TILE..=y1 / TILE {
                for tx in x0 / TILE..=x1 / TILE {
                    bins.start[(ty * tiles_x + tx) as usize + 1] += 1;
                }
            }
        }
        for t in 0..tiles {
            bins.start[t + 1] += bins.start[t];
        }
        bins.items.clear();
        bins.items
            .resize(bins.start[tiles] as usize, BinItem::default());
        let mut fill = bins.start.clone();
        for (t, (&(x0, y0, x1, y1), tri)) in bins.ranges.iter().zip(&scene.tris).enumerate() {
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
                    bins.items[*slot as usize] = item;
                    *slot += 1;
                }
            }
        }
    }

    /// Whether every fragment that a triangle could make in block `b` of
    /// the tile at `(tx0, ty0)`, all with `zmin >= near`, would be culled:
    /// `near` is beyond the opaque bound of every pixel of the block.
    #[inline]
    fn block_hidden(&mut self, b: usize, near: f32, (tx0, ty0): (u32, u32)) -> bool {
        let blocks = &mut self.blocks;
        if near > blocks.far[b] {
            return true;
        }
        if blocks.stale >> b & 1 == 0 || blocks.open[b] > 0 {
            return false;
        }
        // Tighten the stale bound to the current maximum and test again.
        blocks.stale &= !(1u64 << b);
        let (w, h) = (self.width, self.height);
        let x0 = tx0 + (b % BLOCKS) as u32 * BLOCK;
        let y0 = ty0 + (b / BLOCKS) as u32 * BLOCK;
        let (x1, y1) = ((x0 + BLOCK).min(w), (y0 + BLOCK).min(h));
        let mut far = f32::NEG_INFINITY;
        for j in y0..y1 {
            let row = j as usize * w as usize;
            for p in row + x0 as usize..row + x1 as usize {
                let z = self.pool.pixel(p).occluder;
                if z > far {
                    far = z;
                }
            }
        }
        blocks.far[b] = far;
        near > far
    }

    /// Renders the fragments of triangle `t` inside the pixel rectangle
    /// `(x0, y0, x1, y1)` of the tile at `(tx0, ty0)`.
    ///
    /// First the hierarchical test: for each 8 x 8 block of the tile that
    /// the rectangle meets, the plane's nearest value over the block's part
    /// of the rectangle (one evaluation, at the corner the plane's slopes
    /// point away from: the plane is monotonic, see [`DepthBounds`]) is a
    /// lower bound of the `zmin` of every fragment the triangle could make
    /// there. If it is beyond the farthest opaque bound of the block's
    /// pixels, each of those fragments would be culled anyway: the block is
    /// skipped without computing a mask, and the triangle without even its
    /// set-up when every block is.
    fn raster(
        &mut self,
        scene: &ScreenScene,
        item: &BinItem,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        tile: (u32, u32),
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let pattern = self.options.pattern;
        let plane = item.plane;
        let (tx0, ty0) = tile;
        let (hx0, hy0, hx1, hy1) = pattern.hull();
        let (up_x, up_y) = (plane.dx >= 0.0, plane.dy >= 0.0);
        let (bx0, bx1) = ((x0 - tx0) / BLOCK, (x1 - tx0) / BLOCK);
        let (by0, by1) = ((y0 - ty0) / BLOCK, (y1 - ty0) / BLOCK);
        let mut live = 0u64;
        for by in by0..=by1 {
            let (py0, py1) = (
                (ty0 + by * BLOCK).max(y0),
                (ty0 + by * BLOCK + BLOCK - 1).min(y1),
            );
            let (j, sy) = if up_y { (py0, hy0) } else { (py1, hy1) };
            for bx in bx0..=bx1 {
                let b = (by * BLOCKS as u32 + bx) as usize;
                let (px0, px1) = (
                    (tx0 + bx * BLOCK).max(x0),
                    (tx0 + bx * BLOCK + BLOCK - 1).min(x1),
                );
                let (i, sx) = if up_x { (px0, hx0) } else { (px1, hx1) };
                let near = plane_depth(&plane, i, j, (sx, sy)) as f32;
                if self.block_hidden(b, near, tile) {
                    stats.culled_blocks += 1;
                } else {
                    live |= 1 << b;
                }
            }
        }
        if live == 0 {
            return Ok(());
        }
        // Set up in place (the set-up is half a kilobyte).
        let mut setup = self
            .setup
            .take()
            .unwrap_or_else(|| Box::new(TriCoverage::new(&scene.tris[item.tri as usize], pattern)));
        setup.reset_vertices(&item.v, pattern);
        let result = self.raster_live(scene, item, &setup, live, (x0, y0, x1, y1), tile, stats);
        self.setup = Some(setup);
        result
    }

    /// The fragments of triangle `t` in the live blocks of `live`.
    #[allow(clippy::too_many_arguments)]
    fn raster_live(
        &mut self,
        scene: &ScreenScene,
        item: &BinItem,
        setup: &TriCoverage,
        live: u64,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        tile: (u32, u32),
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let (tx0, ty0) = tile;
        let (t, prim) = (item.tri, item.prim);
        let pattern = self.options.pattern;
        let plane = item.plane;
        let (hx0, hy0, hx1, hy1) = pattern.hull();
        let (up_x, up_y) = (plane.dx >= 0.0, plane.dy >= 0.0);
        let (bx0, bx1) = ((x0 - tx0) / BLOCK, (x1 - tx0) / BLOCK);
        let bounds = DepthBounds::new(&plane, pattern, self.options.depth != DepthMode::PerSample);
        // Shading (and opacity) is computed for the primitives that reach
        // this point, not for those culled whole.
        let alpha = shade_of(&mut self.colors, scene, self.options.shade, prim)[3];
        let w = self.width as usize;
        let full_mask = pattern.full_mask();
        let hull_x = if up_x { hx0 } else { hx1 };
        let hull_y = if up_y { hy0 } else { hy1 };
        for j in y0..=y1 {
            let row = j as usize * w;
            let grow = (j - ty0) as usize * TILE as usize;
            let by = (j - ty0) / BLOCK;
            // Runs of live blocks along this block row.
            let mut bx = bx0;
            while bx <= bx1 {
                let bit = |bx: u32| live >> (by * BLOCKS as u32 + bx) & 1 == 1;
                if !bit(bx) {
                    bx += 1;
                    continue;
                }
                let start = bx;
                while bx <= bx1 && bit(bx) {
                    bx += 1;
                }
                let rx0 = (tx0 + start * BLOCK).max(x0);
                let rx1 = (tx0 + bx * BLOCK - 1).min(x1);
                let (rx0, rx1) = setup.row_span(rx0, rx1, j);
                let step = setup.step_x();
                let mut base = setup.corner_values(rx0, j);
                for i in rx0..=rx1 {
                    let here = base;
                    base = [0, 1, 2].map(|e| base[e] + step[e]);
                    let class = setup.classify(here);
                    if class == Class::Empty {
                        continue;
                    }
                    let p = row + i as usize;
                    let occluder = self.pool.pixel(p).occluder;
                    let c = if class == Class::Full {
                        Coverage {
                            mask: full_mask,
                            centre: true,
                            full: true,
                        }
                    } else {
                        // A partial pixel is first tested with the plane at
                        // its hull corner, a lower bound of any zmin it
                        // could have (monotonic plane, see `DepthBounds`):
                        // hidden ones skip the per-sample mask.
                        if occluder < f32::INFINITY {
                            let near = plane_depth(&plane, i, j, (hull_x, hull_y)) as f32;
                            if near > occluder {
                                stats.fragments += 1;
                                stats.culled += 1;
                                continue;
                            }
                        }
                        let c = setup.partial(here);
                        if c.is_empty() {
                            continue;
                        }
                        c
                    };
                    stats.fragments += 1;
                    stats.full_coverage += u64::from(c.full);
                    // A full mask's bounds do not need the centre: it is
                    // evaluated after the cull test.
                    let mut centre_z = f64::INFINITY;
                    if c.centre && !c.full {
                        centre_z = plane_depth(&plane, i, j, CENTRE);
                    }
                    // `as f32` rounds to nearest, which is monotonic: every
                    // sample depth and the centre depth stay inside
                    // [zmin, zmax], so the strict comparisons of culling and
                    // pruning are exact.
                    let (zmin, zmax) = if c.full {
                        let zmin = bounds.bound(&plane, (i, j), c, centre_z, false) as f32;
                        if zmin > occluder {
                            stats.culled += 1;
                            continue;
                        }
                        centre_z = plane_depth(&plane, i, j, CENTRE);
                        (zmin, bounds.bound(&plane, (i, j), c, centre_z, true) as f32)
                    } else {
                        // Partial pixels that reach here are rarely culled:
                        // both bounds in one pass over the rows.
                        let (lo, hi) = bounds.range(&plane, (i, j), c, centre_z);
                        if lo as f32 > occluder {
                            stats.culled += 1;
                            continue;
                        }
                        (lo as f32, hi as f32)
                    };
                    let f = Fragment {
                        next: NIL,
                        mask: c.mask,
                        prim,
                        tri: t,
                        centre_prim: if c.centre { prim } else { NO_ID },
                        shade: prim,
                        zmin,
                        zmax,
                        centre_z,
                    };
                    let ctx = Ctx {
                        scene,
                        p,
                        ij: (i, j),
                        g: grow + (i - tx0) as usize,
                        alpha,
                    };
                    self.insert(&ctx, f, c, stats)?;
                }
            }
        }
        Ok(())
    }

    /// Adds fragment `f` (which survived culling) to pixel `ctx.p`.
    fn insert(
        &mut self,
        ctx: &Ctx<'_>,
        f: Fragment,
        c: Coverage,
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let full = self.options.pattern.full_mask();
        let p = ctx.p;
        // A full mask has no disjoint partner: interior pixels skip the
        // search entirely.
        if self.options.merge != MergePolicy::Off
            && !c.full
            && f.mask != full
            && let Some(idx) = self.try_merge(ctx, &f)?
        {
            stats.merged += 1;
            let merged = *self.pool.get(idx);
            self.note_opaque(ctx, &f, &merged, stats);
            return Ok(());
        }
        if self.pool.len(p) >= self.options.max_list_len {
            stats.pruned += self.prune_hidden(ctx.scene, p, full);
        }
        if self.pool.len(p) >= self.options.max_list_len {
            match self.options.overflow {
                OverflowPolicy::Error => {
                    return Err(Error::Render {
                        hider: "abuffer".into(),
                        message: format!(
                            "pixel ({}, {}) needs more than {} fragments (max_list_len); \
                             raise it or use OverflowPolicy::DropFarthest",
                            ctx.ij.0, ctx.ij.1, self.options.max_list_len
                        ),
                    });
                }
                OverflowPolicy::DropFarthest => {
                    stats.dropped += 1;
                    let mut far = f;
                    let mut cur = self.pool.head(p);
                    while cur != NIL {
                        let g = self.pool.get(cur);
                        if g.order(&far).is_gt() {
                            far = *g;
                        }
                        cur = g.next;
                    }
                    if far == f {
                        return Ok(());
                    }
                    let mut once = true;
                    self.pool.remove_where(p, |g| {
                        let hit = once && *g == far;
                        once &= !hit;
                        hit
                    });
                    // What was gathered may have included it.
                    self.gather[ctx.g] = Gather::EMPTY;
                }
            }
        }
        let idx = self.pool.alloc(f)?;
        self.pool.push_front(p, idx);
        self.note_opaque(ctx, &f, &f, stats);
        Ok(())
    }

    /// After opaque fragment `f` entered pixel `ctx.p` (as itself or merged
    /// into `m`): lowers the pixel's opaque bound when `m` covers every
    /// sample and the centre, or when the opaque fragments gathered since
    /// the last bound now do, and prunes the fragments entirely behind the
    /// new bound.
    ///
    /// The bound `B` means: every sample and the centre is covered by an
    /// opaque fragment of the list whose depth there is at most `B`. A
    /// fragment with `zmin > B` is then strictly behind an opaque surface
    /// at each of its samples and its centre, so it changes no sample, no
    /// coverage and no id: culling and pruning it is exact. Fragments
    /// supporting `B` have `zmin <= zmax <= B`, so pruning never removes
    /// them; a merge keeps every sample's depth.
    fn note_opaque(&mut self, ctx: &Ctx<'_>, f: &Fragment, m: &Fragment, stats: &mut ABufferStats) {
        if ctx.alpha < 1.0 || self.no_cull {
            return;
        }
        let full = self.options.pattern.full_mask();
        let e = *self.pool.pixel(ctx.p);
        let mut bound = e.occluder;
        if m.mask == full && m.covers_centre() && m.zmax < bound {
            bound = m.zmax;
        }
        if f.zmax < e.occluder {
            let g = &mut self.gather[ctx.g];
            g.mask |= f.mask;
            g.centre |= f.covers_centre();
            g.far = g.far.max(f.zmax);
            if g.mask == full && g.centre {
                bound = bound.min(g.far);
            }
        }
        if bound < e.occluder {
            self.pool.set_occluder(ctx.p, bound);
            let (gi, gj) = (ctx.g % TILE as usize, ctx.g / TILE as usize);
            let b = gj / BLOCK as usize * BLOCKS + gi / BLOCK as usize;
            self.blocks.stale |= 1 << b;
            if e.occluder == f32::INFINITY {
                self.blocks.open[b] -= 1;
            }
            self.gather[ctx.g] = Gather::EMPTY;
            if e.far > bound {
                stats.pruned += self.pool.remove_where(ctx.p, |g| g.zmin > bound);
            }
        }
    }

    /// Removes the fragments of pixel `p` hidden in every sample and at the
    /// centre by nearer opaque fragments; returns how many.
    fn prune_hidden(&mut self, scene: &ScreenScene, p: usize, full: u32) -> u64 {
        let mut list = std::mem::take(&mut self.scratch);
        list.clear();
        let mut cur = self.pool.head(p);
        while cur != NIL {
            let f = *self.pool.get(cur);
            list.push(Shaded::new(f, self.rgba(scene, f.shade), cur));
            cur = f.next;
        }
        let mut k = 0;
        let removed = self.pool.remove_where(p, |_| {
            let hit = hidden_in_every_sample(&list[k], &list, full);
            k += 1;
            hit
        });
        self.scratch = list;
        removed
    }

    /// Looks for a merge partner of `f` among the first fragments of pixel
    /// `ctx.p`'s list and merges into it, returning its index.
    fn try_merge(&mut self, ctx: &Ctx<'_>, f: &Fragment) -> Result<Option<u32>> {
        let scene = ctx.scene;
        let f_rgba = self.rgba(scene, f.shade);
        let mut cur = self.pool.head(ctx.p);
        for _ in 0..MERGE_SEARCH {
            if cur == NIL {
                return Ok(None);
            }
            let g = *self.pool.get(cur);
            let g_rgba = self.rgba(scene, g.shade);
            // Fields of the fragment first; the scene lookups last.
            let mergeable = g.mask & f.mask == 0
                && !(g.covers_centre() && f.covers_centre())
                && g_rgba[3] == f_rgba[3]
                && (self.options.merge == MergePolicy::SameSurface
                    || (0..3).all(|c| (g_rgba[c] - f_rgba[c]).abs() <= MERGE_COLOR_TOLERANCE))
                && {
                    // Scene lookups (cache misses) only for candidates.
                    let (tri, other) = (&scene.tris[f.tri as usize], &scene.tris[g.tri as usize]);
                    other.front_facing == tri.front_facing
                        && scene.prims[g.prim as usize].material
                            == scene.prims[f.prim as usize].material
                        && tri.v.iter().any(|v| other.v.contains(v))
                };
            if mergeable {
                self.merge_into(ctx, cur, g, g_rgba, f, f_rgba)?;
                return Ok(Some(cur));
            }
            cur = g.next;
        }
        Ok(None)
    }

    /// Merges `f` into fragment `g` at index `idx`.
    fn merge_into(
        &mut self,
        ctx: &Ctx<'_>,
        idx: u32,
        g: Fragment,
        g_rgba: [f32; 4],
        f: &Fragment,
        f_rgba: [f32; 4],
    ) -> Result<()> {
        let (wg, wf) = (g.mask.count_ones() as f32, f.mask.count_ones() as f32);
        let mut rgba = g_rgba;
        if wg + wf > 0.0 {
            for c in 0..3 {
                rgba[c] = (g_rgba[c] * wg + f_rgba[c] * wf) / (wg + wf);
            }
        }
        let keep_depths = self.options.depth == DepthMode::PerSample;
        let positions = self.options.pattern.positions();
        let (i, j) = ctx.ij;
        let shade = if g.is_merged() {
            self.pool.merged_mut(g.shade).rgba = rgba;
            g.shade
        } else {
            // The first merge into `g`: its shading and (per-sample mode)
            // its sample depths move to a merged entry.
            let mut depths = [f32::INFINITY; MAX_SAMPLES];
            if keep_depths {
                let plane = &self.planes[g.tri as usize];
                for (k, &pos) in positions.iter().enumerate() {
                    if g.mask >> k & 1 == 1 {
                        depths[k] = plane_depth(plane, i, j, pos) as f32;
                    }
                }
            }
            self.pool.add_merged(rgba, &depths)?
        };
        if keep_depths {
            let plane = self.planes[f.tri as usize];
            let stored = self.pool.merged_depths_mut(shade);
            for (k, &pos) in positions.iter().enumerate() {
                if f.mask >> k & 1 == 1 {
                    stored[k] = plane_depth(&plane, i, j, pos) as f32;
                }
            }
        }
        let m = self.pool.get_mut(idx);
        m.shade = shade;
        m.mask |= f.mask;
        m.zmin = g.zmin.min(f.zmin);
        m.zmax = g.zmax.max(f.zmax);
        m.prim = g.prim.min(f.prim);
        m.tri = f.tri;
        if f.covers_centre() {
            m.centre_z = f.centre_z;
            m.centre_prim = f.centre_prim;
        }
        // The pixel's `far` stays an upper bound: the merged zmin is at
        // most g's.
        Ok(())
    }
}

/// The colour and opacity of primitive `prim`, computed on first use (when
/// one of its triangles survives the block test): primitives culled whole
/// are never shaded (NaN marks "not yet").
#[inline]
pub(crate) fn shade_of(
    colors: &mut [[f32; 4]],
    scene: &ScreenScene,
    mode: ShadeMode,
    prim: u32,
) -> [f32; 4] {
    let c = &mut colors[prim as usize];
    if c[3].is_nan() {
        *c = prim_rgba(scene, prim, mode);
    }
    *c
}

/// The depth of fragment `f` at sample `k` (per-sample mode): from its
/// merged entry, or its triangle's plane, with the expression that the
/// supersampled z-buffer uses.
#[inline]
pub(crate) fn sample_depth_of(
    pool: &FragmentPool,
    planes: &[PlaneEq],
    f: &Fragment,
    (i, j): (u32, u32),
    positions: &[(i32, i32)],
    k: usize,
) -> f32 {
    if f.is_merged() {
        pool.merged_depths(f.shade)[k]
    } else {
        plane_depth(&planes[f.tri as usize], i, j, positions[k]) as f32
    }
}

impl Hider for ABuffer {
    fn name(&self) -> &str {
        if self.options == ABufferOptions::carpenter() {
            "abuffer-carpenter"
        } else {
            "abuffer"
        }
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        check_frame("abuffer", scene, frame)?;
        self.check_options()?;
        frame.clear();
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        self.width = w;
        self.height = h;
        let per_sample = self.options.depth == DepthMode::PerSample;
        let fresh = self
            .pool
            .reset(w as usize * h as usize, per_sample, self.options.max_bytes)?;
        self.colors.clear();
        self.colors.resize(scene.prims.len(), [f32::NAN; 4]);
        self.planes.clear();
        self.planes.extend(scene.tris.iter().map(|t| t.depth));
        let (tiles_x, tiles_y) = (w.div_ceil(TILE), h.div_ceil(TILE));
        self.bin(scene, tiles_x, tiles_y);
        let tiles = (tiles_x * tiles_y) as usize;
        if fresh || self.bins.dims != (w, h) {
            // A fresh table is empty; otherwise assume every tile dirty.
            self.bins.dirty.clear();
            self.bins.dirty.resize(tiles, !fresh);
            self.bins.dims = (w, h);
        }
        self.gather.resize((TILE * TILE) as usize, Gather::EMPTY);
        frame.coverage.clear();
        frame.coverage.resize(frame.len(), 0.0);
        self.resolver.begin();
        let mut stats = ABufferStats::default();
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let t = (ty * tiles_x + tx) as usize;
                let (x0, y0) = (tx * TILE, ty * TILE);
                let (x1, y1) = ((x0 + TILE).min(w) - 1, (y0 + TILE).min(h) - 1);
                let (b0, b1) = (self.bins.start[t] as usize, self.bins.start[t + 1] as usize);
                if b0 == b1 && !self.bins.dirty[t] {
                    continue;
                }
                for j in y0..=y1 {
                    self.pool.clear_pixels(
                        j as usize * w as usize + x0 as usize,
                        (x1 - x0 + 1) as usize,
                    );
                }
                self.bins.dirty[t] = b0 != b1;
                if b0 == b1 {
                    continue;
                }
                self.gather.fill(Gather::EMPTY);
                self.blocks.reset(x1 - x0, y1 - y0);
                // Front to back: the nearest surfaces first set the opaque
                // bounds that cull what lies behind them. The order changes
                // no sample (the lists are sorted by depth at resolve),
                // only how much work is culled.
                let mut order = std::mem::take(&mut self.bins.order);
                order.clear();
                order.extend((b0..b1).map(|b| (self.bins.items[b].key, b as u32)));
                if !self.no_sort {
                    order.sort_unstable_by_key(|&(key, _)| key);
                }
                let items = std::mem::take(&mut self.bins.items);
                let mut result = Ok(());
                for &(_, b) in &order {
                    let item = &items[b as usize];
                    let (rx0, ry0, rx1, ry1) = item.range;
                    let rect = (rx0.max(x0), ry0.max(y0), rx1.min(x1), ry1.min(y1));
                    result = self.raster(scene, item, rect, (x0, y0), &mut stats);
                    if result.is_err() {
                        break;
                    }
                }
                self.bins.items = items;
                self.bins.order = order;
                result?;
                self.resolver.resolve_tile(
                    scene,
                    &self.pool,
                    &self.planes,
                    &mut self.colors,
                    &self.options,
                    (x0, y0, x1, y1),
                    frame,
                    &mut stats,
                );
            }
        }
        self.resolver.finish(&mut stats);
        stats.pool_fragments = self.pool.peak_fragments() as u64;
        stats.bytes = self.pool.peak_bytes();
        self.last = stats;
        Ok(stats.into())
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
