//! Opaque tiles through a sample buffer: what their fragment lists would
//! resolve to, sample for sample, without the lists.
//!
//! Carpenter's pixel holds a plain depth when one opaque surface covers it
//! and a fragment list only where surfaces share it; his argument is that
//! most pixels need no list. In a tile whose triangles are all opaque the
//! lists only ever decide, per sample, which surface is in front (the
//! nearest by the sample's own depth, the lower primitive id on ties), and
//! per pixel which one is in front at the centre: a depth and a primitive
//! per sample answer exactly that. So such a tile keeps, per pixel, the
//! 32 samples' depths (the triangle's plane at the sample, the very `f32`
//! the lists compare, [`crate::depth::plane_depth`]) and primitives, and
//! the centre's `f64` depth and primitive, in a buffer the size of half a
//! tile that stays in the core's cache; triangles are taken front to back
//! and a pixel's farthest depth rejects what lies behind it before its
//! mask is computed. A triangle is walked 8 x 8 block by block (blocks
//! rejected or accepted whole from the edge functions at their corners,
//! the rows of the others classified and culled 8 pixels at once). A
//! pixel covered entirely by a triangle in front of everything there is
//! Carpenter's plain pixel: it is held *whole*, as that one primitive,
//! and its 32 depths are computed only if a later fragment shares it; an
//! unwritten 8 x 8 block a triangle covers whole is held so a row of 8
//! at a time.
//! The resolve counts, per pixel, the samples each
//! primitive shows in and sums colours in the one canonical order the
//! lists use too ([`crate::composite::opaque_sum`]): the image, coverage
//! and ids are those of the lists, bit for bit (property-tested against
//! them), at a fraction of the cost: no fragment is allocated, linked,
//! merged, pruned or sorted.
//!
//! Tiles with a translucent triangle keep the lists (the samples would
//! need every layer); so do [`crate::DepthMode::MinMax`] and
//! [`crate::DepthMode::ZminOrder`], which are about the fragments' depth
//! ranges, and [`crate::MergePolicy::SameSurface`], whose averaged colours
//! show in the image ([`crate::ABufferOptions::sample_tiles`]).

use hider_geom::PlaneEq;
use hider_geom::isa::Avx2;
use hider_scene::NO_ID;

use crate::bins::{BinItem, TILE};
use crate::centre::in_front;
use crate::composite::Shown;
use crate::coverage::{Class, Coverage, TriCoverage};
// Blocks of pixels whose farthest key is kept: the lists' culling blocks.
use crate::culling::{BLOCK, block_part};
use crate::depth::{depth_key, far_corner, near_corner, plane_depth};
use crate::pattern::{CENTRE, MAX_SAMPLES, SamplePattern};
use crate::select::{pick, pick_f64};
#[cfg(target_arch = "x86_64")]
use crate::simd::samples as avx2;
use crate::stats::ABufferStats;

mod culling;
mod resolve;
mod whole;

pub(crate) use whole::Held;

/// Rows of a tile taken in one pass: 64 x 32 pixels of 32 samples of 8
/// bytes are 512 KiB, which stays in a 1 MiB level-2 cache.
pub(crate) const PASS_ROWS: u32 = 32;
/// Pixels of one pass.
const PASS_PIXELS: usize = (TILE * PASS_ROWS) as usize;

/// The key of an empty sample: beyond the key of every depth.
const EMPTY: i32 = i32::MAX;

/// Rows of a block at least this long are classified and depth-tested
/// 8 pixels at once ([`SampleBuffer::row_culled`]); shorter ones pixel by
/// pixel.
const RUN_MIN: u32 = 4;

/// Blocks per row of a pass.
const BLOCKS_X: u32 = TILE / BLOCK;
/// Blocks of a pass.
const BLOCKS: usize = (BLOCKS_X * PASS_ROWS / BLOCK) as usize;

/// What the pixels of one triangle share while it is rendered.
struct Tri {
    /// Its depth plane.
    plane: PlaneEq,
    /// Its primitive.
    prim: u32,
    /// The corners of the sample hull where its plane is lowest and
    /// highest ([`near_corner`], [`far_corner`]).
    near_corner: (i32, i32),
    far_corner: (i32, i32),
    /// The coverage of a fully covered pixel.
    full: Coverage,
    /// Its index in [`SampleBuffer::planes`], once it holds a pixel whole.
    own_plane: Option<u32>,
    /// The sample pattern.
    pattern: SamplePattern,
    /// The AVX2 depth test of the 8 x 4 grid, when taken.
    grid: Option<Avx2>,
}

/// One pass's pixels: per sample a depth key and a primitive, per pixel
/// the centre and the farthest key.
#[derive(Clone, Debug)]
pub(crate) struct SampleBuffer {
    /// Depth key per sample ([`depth_key`]; [`EMPTY`] when uncovered).
    keys: Vec<[i32; MAX_SAMPLES]>,
    /// Front primitive per sample ([`NO_ID`] when uncovered).
    prims: Vec<[u32; MAX_SAMPLES]>,
    /// Per pixel the largest of its sample keys and its centre's key
    /// ([`EMPTY`] while any is uncovered): a triangle whose nearest depth
    /// over the pixel has a larger key is behind everywhere.
    far: Vec<i32>,
    /// Depth at the centre (`f64`, as the lists keep it).
    centre_z: Vec<f64>,
    /// Front primitive at the centre.
    centre_prim: Vec<u32>,
    /// Per row of the pass, the pixels written this pass (bit = column).
    touched: [u64; PASS_ROWS as usize],
    /// Per row of the pass, the written pixels held whole (bit = column):
    /// one primitive, `centre_prim`, in front at every sample and the
    /// centre, its sample depths not computed (`keys` and `prims` are
    /// stale there) until a fragment that shares the pixel needs them.
    whole: [u64; PASS_ROWS as usize],
    /// Per whole pixel, the smallest key of its samples and centre (its
    /// plane at the near corner of the sample hull): a fully covering
    /// triangle farther than that nowhere wins every sample outright.
    near: Vec<i32>,
    /// Per whole pixel, its plane, an index into `planes`.
    plane_of: Vec<u32>,
    /// The planes of the triangles that made whole pixels this pass.
    planes: Vec<PlaneEq>,
    /// Whether hidden triangles are rejected per block and per pixel
    /// before their samples are tested
    /// ([`crate::ABufferOptions::occlusion_culling`]; the answer is the
    /// same either way).
    cull: bool,
    /// Per 8 x 8 block, an upper bound of its pixels' farthest keys
    /// ([`EMPTY`] while one of them is unwritten): exact when its bit of
    /// `stale` is clear, recomputed when a test needs it. Pixels' keys only
    /// fall, so a stale bound stays an upper bound and culls only what the
    /// exact one would.
    block_far: [i32; BLOCKS],
    /// Blocks written since their bound was last computed.
    stale: u32,
    /// Per block, its pixels whose farthest key is still [`EMPTY`]
    /// (unwritten, or a sample or the centre uncovered): while any is,
    /// the block hides nothing and its bound is not computed.
    open: [u8; BLOCKS],
    /// The AVX2 depth test, when the CPU has it.
    #[cfg_attr(
        not(target_arch = "x86_64"),
        expect(dead_code, reason = "only the x86_64 build has the AVX2 path")
    )]
    avx2: Option<Avx2>,
    /// The pass's pixels: top-left `(x0, y0)`, bottom-right `(x1, y1)`.
    rect: (u32, u32, u32, u32),
    /// The triangle set-up, reused (taken while a triangle is rendered).
    setup: Option<Box<TriCoverage>>,
    /// Resolve scratch: samples shown per primitive.
    shown: Vec<Shown>,
}

impl Default for SampleBuffer {
    fn default() -> Self {
        Self {
            keys: vec![[EMPTY; MAX_SAMPLES]; PASS_PIXELS],
            prims: vec![[NO_ID; MAX_SAMPLES]; PASS_PIXELS],
            // Padded by a block row: the culling tests read 8 pixels from
            // any pixel of the pass on (the ones past its end are masked).
            far: vec![EMPTY; PASS_PIXELS + BLOCK as usize],
            centre_z: vec![f64::INFINITY; PASS_PIXELS],
            centre_prim: vec![NO_ID; PASS_PIXELS],
            touched: [0; PASS_ROWS as usize],
            whole: [0; PASS_ROWS as usize],
            near: vec![EMPTY; PASS_PIXELS],
            plane_of: vec![0; PASS_PIXELS],
            planes: Vec::new(),
            cull: true,
            block_far: [EMPTY; BLOCKS],
            stale: 0,
            open: [0; BLOCKS],
            avx2: Avx2::detect(),
            rect: (1, 1, 0, 0),
            setup: None,
            shown: Vec::new(),
        }
    }
}

/// Bytes of one thread's sample buffer.
pub(crate) const SAMPLE_BUFFER_BYTES: u64 =
    PASS_PIXELS as u64 * (MAX_SAMPLES as u64 * 8 + 4 + 8 + 4 + 4 + 4);

/// The passes of the tile `(x0, y0)` to `(x1, y1)`: its rows,
/// [`PASS_ROWS`] at a time, top first.
pub(crate) fn passes(
    (x0, y0, x1, y1): (u32, u32, u32, u32),
) -> impl Iterator<Item = (u32, u32, u32, u32)> {
    (y0..=y1)
        .step_by(PASS_ROWS as usize)
        .map(move |py0| (x0, py0, x1, (py0 + PASS_ROWS - 1).min(y1)))
}

impl SampleBuffer {
    /// Starts a pass over the pixels `(x0, y0)` to `(x1, y1)` (inside one
    /// tile, at most [`PASS_ROWS`] rows): every pixel empty. Pixels are
    /// cleared when first written, so an empty pass costs nothing.
    pub(crate) fn begin(&mut self, rect: (u32, u32, u32, u32), cull: bool) {
        self.rect = rect;
        self.cull = cull;
        self.touched = [0; PASS_ROWS as usize];
        self.whole = [0; PASS_ROWS as usize];
        self.planes.clear();
        self.block_far = [EMPTY; BLOCKS];
        self.stale = 0;
        let (x0, y0, x1, y1) = rect;
        for (b, open) in self.open.iter_mut().enumerate() {
            let (bx, by) = (b as u32 % BLOCKS_X, b as u32 / BLOCKS_X);
            let (i0, j0) = (x0 + bx * BLOCK, y0 + by * BLOCK);
            let w = (i0 + BLOCK).min(x1 + 1).saturating_sub(i0);
            let h = (j0 + BLOCK).min(y1 + 1).saturating_sub(j0);
            *open = (w * h) as u8;
        }
    }

    /// Index of pixel `(i, j)` of the pass.
    #[inline]
    fn index(&self, i: u32, j: u32) -> usize {
        ((j - self.rect.1) * TILE + (i - self.rect.0)) as usize
    }

    /// Renders the part of `item`'s triangle inside the pass.
    pub(crate) fn triangle(
        &mut self,
        item: &BinItem,
        pattern: SamplePattern,
        stats: &mut ABufferStats,
    ) {
        #[cfg(target_arch = "x86_64")]
        if let Some(isa) = self.avx2.filter(|_| pattern == SamplePattern::Grid32) {
            // The whole loop compiled for AVX2, so that the mask and the
            // depth test inline into it.
            avx2::triangle(isa, self, item, stats);
            return;
        }
        self.triangle_with(item, pattern, stats, None);
    }

    /// [`Self::triangle`], with the AVX2 depth test of the 8 x 4 grid
    /// when `grid` is given.
    #[inline(always)]
    pub(crate) fn triangle_with(
        &mut self,
        item: &BinItem,
        pattern: SamplePattern,
        stats: &mut ABufferStats,
        grid: Option<Avx2>,
    ) {
        let (x0, y0, x1, y1) = self.rect;
        let (rx0, ry0, rx1, ry1) = item.range;
        let (x0, y0, x1, y1) = (rx0.max(x0), ry0.max(y0), rx1.min(x1), ry1.min(y1));
        if x0 > x1 || y0 > y1 {
            return;
        }
        let plane = item.plane;
        let live = if self.cull {
            self.live_blocks(item, (x0, y0, x1, y1), pattern.hull(), stats)
        } else {
            u32::MAX
        };
        if live == 0 {
            return;
        }
        let mut setup = self
            .setup
            .take()
            .unwrap_or_else(|| Box::new(TriCoverage::from_vertices(&item.v, pattern)));
        setup.reset_vertices(&item.v, pattern);
        let mut tri = Tri {
            plane,
            prim: item.prim,
            // The plane there is a lower bound of every sample's and the
            // centre's depth in a pixel, and at the far corner an upper
            // bound.
            near_corner: near_corner(&plane, pattern.hull()),
            far_corner: far_corner(&plane, pattern.hull()),
            full: Coverage {
                mask: pattern.full_mask(),
                centre: true,
                full: true,
            },
            own_plane: None,
            pattern,
            grid,
        };
        let step = setup.step_x();
        let (px0, py0) = (self.rect.0, self.rect.1);
        // Block by block, as the tiled z-buffer: the edge functions at a
        // block's extreme corners reject it whole (no pixel of it touches
        // the triangle) or accept it whole (every pixel covered: no pixel
        // is classified, no mask computed).
        let mut blocks = live & self.blocks_over((x0, y0, x1, y1));
        while blocks != 0 {
            let b = blocks.trailing_zeros();
            blocks &= blocks - 1;
            let block = (b % BLOCKS_X, b / BLOCKS_X);
            let (i0, j0, i1, j1) = block_part((px0, py0), block, (x0, y0, x1, y1));
            let class = setup.classify_rect((i0, j0, i1, j1));
            if class == Class::Empty {
                continue;
            }
            let n = i1 - i0 + 1;
            let all = (1u32 << n) - 1;
            if n < RUN_MIN {
                self.short_rows(&mut tri, (i0, j0, i1, j1), (class, &setup), stats);
                continue;
            }
            if n == BLOCK && j1 - j0 + 1 == BLOCK && class == Class::Full && self.unwritten(i0, j0)
            {
                let held = Held {
                    plane: tri.plane,
                    prim: tri.prim,
                    corners: (tri.near_corner, tri.far_corner),
                    index: self.own_plane(&mut tri),
                };
                self.whole_block(held, (i0, j0), stats);
                continue;
            }
            for j in j0..=j1 {
                // The row's pixels as bits: which it touches, which it
                // covers whole, which it loses to the pixel's farthest
                // depth. Branch-free over the row, then a branch per
                // pixel left (the tests one by one mispredicted).
                let base = setup.corner_values(i0, j);
                let (full, touched) = if class == Class::Full {
                    (all, all)
                } else {
                    let (full, touched) = setup.classify_run(base);
                    (full & all, touched & all)
                };
                if touched == 0 {
                    continue;
                }
                let mut left = touched;
                let mut near = None;
                if self.cull {
                    let keys = self.row_near_keys(&tri, (i0, j));
                    let culled = self.row_culled(&keys, (i0, j)) & touched;
                    stats.fragments += u64::from(culled.count_ones());
                    stats.culled += u64::from(culled.count_ones());
                    left &= !culled;
                    near = Some(keys);
                }
                while left != 0 {
                    let k = left.trailing_zeros();
                    left &= left - 1;
                    let here = [0, 1, 2].map(|e| base[e] + i64::from(k) * step[e]);
                    let class = if full >> k & 1 == 1 {
                        Class::Full
                    } else {
                        Class::Partial
                    };
                    let near = near.map(|keys| keys[k as usize]);
                    self.pixel(&mut tri, (i0 + k, j), (class, &setup, here), near, stats);
                }
            }
        }
        self.setup = Some(setup);
    }

    /// The blocks of the pass that meet the pixels `(x0, y0)` to
    /// `(x1, y1)`, as bits.
    fn blocks_over(&self, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> u32 {
        let (px0, py0) = (self.rect.0, self.rect.1);
        let (bx0, bx1) = ((x0 - px0) / BLOCK, (x1 - px0) / BLOCK);
        let (by0, by1) = ((y0 - py0) / BLOCK, (y1 - py0) / BLOCK);
        let row = ((1u32 << (bx1 + 1)) - 1) & !((1u32 << bx0) - 1);
        let mut bits = 0;
        for by in by0..=by1 {
            bits |= row << (by * BLOCKS_X);
        }
        bits
    }

    /// The rows `j0..=j1` of pixels `i0..=i1` (fewer than [`RUN_MIN`]) of
    /// a block of class `class`: pixel by pixel, each classified and
    /// depth-tested alone (for so few, cheaper than [`Self::row_culled`]).
    #[inline(always)]
    fn short_rows(
        &mut self,
        tri: &mut Tri,
        (i0, j0, i1, j1): (u32, u32, u32, u32),
        (class, setup): (Class, &TriCoverage),
        stats: &mut ABufferStats,
    ) {
        let step = setup.step_x();
        for j in j0..=j1 {
            let mut base = setup.corner_values(i0, j);
            for i in i0..=i1 {
                let here = base;
                base = [0, 1, 2].map(|e| base[e] + step[e]);
                let class = if class == Class::Full {
                    Class::Full
                } else {
                    setup.classify(here)
                };
                if class == Class::Empty {
                    continue;
                }
                let p = self.index(i, j);
                let live_px =
                    self.touched[(j - self.rect.1) as usize] >> (i - self.rect.0) & 1 == 1;
                let mut near = None;
                if self.cull && live_px && self.far[p] != EMPTY {
                    // Strictly behind the farthest of the pixel's samples
                    // and centre: loses every sample and the centre.
                    let key = depth_key(plane_depth(&tri.plane, i, j, tri.near_corner) as f32);
                    if key > self.far[p] {
                        stats.fragments += 1;
                        stats.culled += 1;
                        continue;
                    }
                    near = Some(key);
                }
                self.pixel(tri, (i, j), (class, setup, here), near, stats);
            }
        }
    }

    /// Renders triangle `tri` at pixel `(i, j)`, which it touches
    /// (`class` is not [`Class::Empty`]; `here` are its edge values there
    /// for `setup`) and which is not culled; `near` is its near key there
    /// if known.
    #[inline(always)]
    fn pixel(
        &mut self,
        tri: &mut Tri,
        (i, j): (u32, u32),
        (class, setup, here): (Class, &TriCoverage, [i64; 3]),
        near: Option<i32>,
        stats: &mut ABufferStats,
    ) {
        let (px0, py0) = (self.rect.0, self.rect.1);
        let plane = &tri.plane;
        let p = self.index(i, j);
        let row = (j - py0) as usize;
        let bit = 1u64 << (i - px0);
        let live_px = self.touched[row] & bit != 0;
        let whole_px = self.whole[row] & bit != 0;
        let b = ((j - py0) / BLOCK * BLOCKS_X + (i - px0) / BLOCK) as usize;
        if class == Class::Full && (!live_px || whole_px) {
            // Carpenter's common case: one opaque surface over the whole
            // pixel. Nearer than everything there at its farthest sample,
            // it wins every sample and the centre (the depths round
            // monotonically, so a strict order of the bounds orders every
            // sample), and the pixel is held as that one primitive: what
            // the samples would say, without computing them.
            let far = depth_key(plane_depth(plane, i, j, tri.far_corner) as f32);
            if !live_px || far < self.near[p] {
                let near = near
                    .unwrap_or_else(|| depth_key(plane_depth(plane, i, j, tri.near_corner) as f32));
                // `own_plane`'s work, spelled out: calling it needs the
                // triangle while its plane is borrowed, and the copy of the
                // plane that allows it cost 1 to 3 % more instructions.
                let index = *tri.own_plane.get_or_insert_with(|| {
                    self.planes.push(*plane);
                    self.planes.len() as u32 - 1
                });
                stats.fragments += 1;
                stats.full_coverage += 1;
                stats.whole_pixels += 1;
                if !live_px {
                    self.touched[row] |= bit;
                    self.whole[row] |= bit;
                    self.open[b] -= 1;
                }
                self.centre_z[p] = plane_depth(plane, i, j, CENTRE);
                self.centre_prim[p] = tri.prim;
                self.far[p] = far;
                self.near[p] = near;
                self.plane_of[p] = index;
                self.stale |= 1 << b;
                return;
            }
        }
        let c = if class == Class::Full {
            tri.full
        } else {
            let c = setup.partial(here);
            if c.is_empty() {
                return;
            }
            c
        };
        stats.fragments += 1;
        stats.full_coverage += u64::from(c.full);
        let how = (tri.pattern, tri.grid);
        if !live_px {
            self.keys[p] = [EMPTY; MAX_SAMPLES];
            self.prims[p] = [NO_ID; MAX_SAMPLES];
            self.centre_z[p] = f64::INFINITY;
            self.centre_prim[p] = NO_ID;
            self.touched[row] |= bit;
        } else if whole_px {
            self.expand(p, (i, j), how);
            self.whole[row] &= !bit;
        }
        let was_open = !live_px || self.far[p] == EMPTY;
        self.write(p, (i, j), plane, tri.prim, c, how);
        self.stale |= 1 << b;
        if was_open && self.far[p] != EMPTY {
            self.open[b] -= 1;
        }
    }

    /// Depth-tests the samples of `c` and its centre at pixel `p` (at
    /// `ij`) against what the pixel holds, keeping the nearer, then
    /// updates the pixel's farthest key.
    #[inline(always)]
    fn write(
        &mut self,
        p: usize,
        (i, j): (u32, u32),
        plane: &PlaneEq,
        prim: u32,
        c: Coverage,
        (pattern, grid): (SamplePattern, Option<Avx2>),
    ) {
        let keys = &mut self.keys[p];
        let prims = &mut self.prims[p];
        let positions = pattern.positions();
        let n = positions.len();
        #[cfg(target_arch = "x86_64")]
        let wide = grid.map(|isa| avx2::write_grid(isa, keys, prims, plane, (i, j), prim, c.mask));
        #[cfg(not(target_arch = "x86_64"))]
        let wide = grid.map(|_| 0);
        let samples_far = match wide {
            Some(far) => far,
            None => {
                let mut m = c.mask;
                while m != 0 {
                    let k = m.trailing_zeros() as usize;
                    m &= m - 1;
                    let key = depth_key(plane_depth(plane, i, j, positions[k]) as f32);
                    if key < keys[k] || (key == keys[k] && prim < prims[k]) {
                        keys[k] = key;
                        prims[k] = prim;
                    }
                }
                keys[..n].iter().copied().fold(i32::MIN, i32::max)
            }
        };
        // Branch-free (selects): whether a partial fragment covers the
        // centre, and wins it, is a coin toss; as branches they
        // mispredicted (callgrind's branch simulation).
        let z = plane_depth(plane, i, j, CENTRE);
        let (z0, prim0) = (self.centre_z[p], self.centre_prim[p]);
        let take = c.centre & in_front(z, prim, z0, prim0);
        let z = pick_f64(take, z, z0);
        let prim = pick(take, u64::from(prim), u64::from(prim0)) as u32;
        self.centre_z[p] = z;
        self.centre_prim[p] = prim;
        let far = samples_far.max(depth_key(z as f32));
        self.far[p] = pick(
            prim == NO_ID,
            u64::from(EMPTY as u32),
            u64::from(far as u32),
        ) as i32;
    }

    /// The front primitive of each sample of pixel `(i, j)` of the pass,
    /// `None` when nothing was written there.
    pub(crate) fn sample_prims(&self, i: u32, j: u32) -> Option<[u32; MAX_SAMPLES]> {
        let (row, bit) = ((j - self.rect.1) as usize, 1u64 << (i - self.rect.0));
        let p = self.index(i, j);
        if self.whole[row] & bit != 0 {
            Some([self.centre_prim[p]; MAX_SAMPLES])
        } else {
            (self.touched[row] & bit != 0).then(|| self.prims[p])
        }
    }
}
