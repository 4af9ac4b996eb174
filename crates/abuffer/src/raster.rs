//! Rasterising a tile's triangles into fragments: the hierarchical block
//! test, then per pixel the coverage mask, the cull test against the
//! pixel's opaque bound, the exact depth bounds, and insertion into the
//! pixel's list.
//!
//! Fragments are 40 bytes: depth bounds from at most 4 plane evaluations
//! each, equal to the extremes over the samples ([`DepthBounds`]); sample
//! depths are recomputed at resolve where needed; the opacity comes with
//! the bin item, and shading waits for the fragments that need a colour.

use hider_geom::PlaneEq;
use hider_scene::{NO_ID, Result};

use crate::bins::{BinItem, TILE};
use crate::coverage::{Class, Coverage, TriCoverage};
use crate::culling::{BLOCK, BLOCKS, block_part};
use crate::cutout::{Cutouts, PrimCutout};
use crate::depth::{DepthBounds, near_corner, nearest_over, plane_depth};
use crate::fragment::{Fragment, NIL};
use crate::lists::{Ctx, Lists};
use crate::options::{ABufferOptions, DepthMode};
use crate::pattern::CENTRE;
use crate::source::Source;
use crate::stats::ABufferStats;

/// What rasterising one triangle needs at every pixel.
struct TriRaster<'a> {
    scene: &'a Source<'a>,
    tri: u32,
    prim: u32,
    plane: PlaneEq,
    bounds: DepthBounds,
    /// Opacity of the primitive.
    alpha: f32,
    /// The mask of every sample.
    full_mask: u32,
    /// The corner of the sample hull where the plane is nearest.
    near_corner: (i32, i32),
    /// Top-left pixel of the tile.
    tile: (u32, u32),
    /// The alpha test, when the primitive may cut out, set up once for
    /// the triangle's fragments.
    cutout: Option<PrimCutout<'a, 'a>>,
}

/// Turns triangles into fragments of the lists of a frame.
#[derive(Clone, Debug, Default)]
pub(crate) struct Rasterizer {
    /// The fragment lists being filled.
    pub(crate) lists: Lists,
    /// The triangle set-up, reused (it is half a kilobyte).
    setup: Option<Box<TriCoverage>>,
    /// Frame size.
    dims: (u32, u32),
}

impl Rasterizer {
    /// Starts a frame of `scene` with `options` (see [`Lists::begin_frame`]).
    pub(crate) fn begin_frame(
        &mut self,
        scene: &Source<'_>,
        options: &ABufferOptions,
    ) -> Result<bool> {
        self.dims = (scene.viewport.width, scene.viewport.height);
        self.lists.begin_frame(scene, options)
    }

    /// Renders the fragments of `item`'s triangle inside the pixel
    /// rectangle `(x0, y0, x1, y1)` of the tile at `tile`, alpha-tested
    /// per sample by `cutouts` when it is given (the primitive may cut
    /// out: [`Cutouts::coverage`]).
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
    pub(crate) fn triangle(
        &mut self,
        scene: &Source<'_>,
        (item, index, cutouts): (&BinItem, u32, Option<&Cutouts<'_>>),
        rect: (u32, u32, u32, u32),
        tile: (u32, u32),
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let live = self.live_blocks(item, rect, tile, stats);
        if live == 0 {
            return Ok(());
        }
        let options = *self.lists.options();
        let pattern = options.pattern;
        // Set up in place.
        let mut setup = self
            .setup
            .take()
            .unwrap_or_else(|| Box::new(TriCoverage::from_vertices(&item.v, pattern)));
        setup.reset_vertices(&item.v, pattern);
        let plane = item.plane;
        let mut tri = TriRaster {
            scene,
            tri: index,
            prim: item.prim,
            plane,
            bounds: DepthBounds::new(&plane, pattern, options.depth != DepthMode::PerSample),
            alpha: item.alpha,
            full_mask: pattern.full_mask(),
            near_corner: near_corner(&plane, pattern.hull()),
            tile,
            cutout: cutouts.map(|c| c.prim(item.prim)),
        };
        let result = self.live_pixels(&mut tri, &setup, live, rect, stats);
        self.setup = Some(setup);
        result
    }

    /// The blocks of the tile at `(tx0, ty0)` where `item` may leave a
    /// fragment inside `(x0, y0, x1, y1)`, as bits; counts the others in
    /// [`ABufferStats::culled_blocks`].
    fn live_blocks(
        &mut self,
        item: &BinItem,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        tile: (u32, u32),
        stats: &mut ABufferStats,
    ) -> u64 {
        let pattern = self.lists.options().pattern;
        let plane = item.plane;
        let (tx0, ty0) = tile;
        let hull = pattern.hull();
        let (bx0, bx1) = ((x0 - tx0) / BLOCK, (x1 - tx0) / BLOCK);
        let (by0, by1) = ((y0 - ty0) / BLOCK, (y1 - ty0) / BLOCK);
        // The tile first, for a triangle over several blocks (for one, the
        // block test is as cheap): the plane at the rectangle's near
        // corner is a lower bound of its value at every block's near
        // corner (the plane is monotonic), so when it is beyond the tile's
        // bound every block is hidden, as the loop below would find one by
        // one.
        let blocks = (bx1 - bx0 + 1) * (by1 - by0 + 1);
        if blocks > 1 {
            let tile_far = self.lists.culling.tile_far();
            // The item's bound over its whole range first (see
            // [`BinItem::near`]): weaker, so it hides only what the
            // rectangle's own bound would.
            if tile_far < f32::INFINITY
                && (item.near > tile_far
                    || nearest_over(&plane, (x0, y0, x1, y1), hull) as f32 > tile_far)
            {
                stats.culled_tiles += 1;
                stats.culled_blocks += u64::from(blocks);
                return 0;
            }
        }
        let mut live = 0u64;
        for by in by0..=by1 {
            for bx in bx0..=bx1 {
                let b = (by * BLOCKS as u32 + bx) as usize;
                let part = block_part(tile, (bx, by), (x0, y0, x1, y1));
                let near = nearest_over(&plane, part, hull) as f32;
                let lists = &mut self.lists;
                if lists
                    .culling
                    .block_hidden(&lists.pool, self.dims, b, near, tile)
                {
                    stats.culled_blocks += 1;
                } else {
                    live |= 1 << b;
                }
            }
        }
        live
    }

    /// The fragments of triangle `tri` in the blocks of `live` inside
    /// `(x0, y0, x1, y1)`: row by row, along each run of live blocks, the
    /// pixels the row's span may cover.
    fn live_pixels(
        &mut self,
        tri: &mut TriRaster<'_>,
        setup: &TriCoverage,
        live: u64,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let (tx0, ty0) = tri.tile;
        let (bx0, bx1) = ((x0 - tx0) / BLOCK, (x1 - tx0) / BLOCK);
        for j in y0..=y1 {
            let by = (j - ty0) / BLOCK;
            let bit = |bx: u32| live >> (by * BLOCKS as u32 + bx) & 1 == 1;
            let mut bx = bx0;
            while bx <= bx1 {
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
                    if class != Class::Empty {
                        self.pixel(tri, setup, (i, j), (here, class), stats)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The fragment of triangle `tri` in pixel `(i, j)`, whose corner edge
    /// values are `here` (classified `class`, not empty): culled, or
    /// inserted into the pixel's list.
    #[inline]
    fn pixel(
        &mut self,
        tri: &mut TriRaster<'_>,
        setup: &TriCoverage,
        (i, j): (u32, u32),
        (here, class): ([i64; 3], Class),
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let plane = &tri.plane;
        let p = j as usize * self.dims.0 as usize + i as usize;
        let occluder = self.lists.pool.pixel(p).occluder;
        let c = if class == Class::Full {
            Coverage {
                mask: tri.full_mask,
                centre: true,
                full: true,
            }
        } else {
            // A partial pixel is first tested with the plane at its hull
            // corner, a lower bound of any zmin it could have (monotonic
            // plane, see `DepthBounds`): hidden ones skip the per-sample
            // mask.
            if occluder < f32::INFINITY {
                let near = plane_depth(plane, i, j, tri.near_corner) as f32;
                if near > occluder {
                    stats.fragments += 1;
                    stats.culled += 1;
                    return Ok(());
                }
            }
            let c = setup.partial(here);
            if c.is_empty() {
                return Ok(());
            }
            c
        };
        let mut alpha = tri.alpha;
        let c = match &mut tri.cutout {
            None => c,
            Some(cut) => match cut.opacity((i, j)) {
                // Partial alpha: composited, with the fragment's own
                // opacity (the colour's, at the same centre).
                Some(a) => {
                    alpha = a;
                    c
                }
                None => {
                    let c = cut.coverage((i, j), c);
                    if c.is_empty() {
                        return Ok(());
                    }
                    c
                }
            },
        };
        stats.fragments += 1;
        stats.full_coverage += u64::from(c.full);
        let Some((zmin, zmax, centre_z)) = depth_range(tri, (i, j), c, occluder) else {
            stats.culled += 1;
            return Ok(());
        };
        let f = Fragment {
            next: NIL,
            mask: c.mask,
            prim: tri.prim,
            tri: tri.tri,
            centre_prim: if c.centre { tri.prim } else { NO_ID },
            shade: tri.prim,
            zmin,
            zmax,
            centre_z,
        };
        let (tx0, ty0) = tri.tile;
        let ctx = Ctx {
            scene: tri.scene,
            p,
            ij: (i, j),
            g: (j - ty0) as usize * TILE as usize + (i - tx0) as usize,
            alpha,
        };
        self.lists.insert(&ctx, f, c, stats)
    }
}

/// The depth bounds `(zmin, zmax)` and the centre depth of the fragment of
/// coverage `c` in pixel `(i, j)`, or `None` when it lies beyond the
/// pixel's opaque bound `occluder` (culled).
///
/// `as f32` rounds to nearest, which is monotonic: every sample depth and
/// the centre depth stay inside `[zmin, zmax]`, so the strict comparisons
/// of culling and pruning are exact.
#[inline]
fn depth_range(
    tri: &TriRaster<'_>,
    (i, j): (u32, u32),
    c: Coverage,
    occluder: f32,
) -> Option<(f32, f32, f64)> {
    let plane = &tri.plane;
    // A full mask's bounds do not need the centre: it is evaluated after
    // the cull test.
    let mut centre_z = f64::INFINITY;
    if c.centre && !c.full {
        centre_z = plane_depth(plane, i, j, CENTRE);
    }
    if c.full {
        let zmin = tri.bounds.bound(plane, (i, j), c, centre_z, false) as f32;
        if zmin > occluder {
            return None;
        }
        centre_z = plane_depth(plane, i, j, CENTRE);
        let zmax = tri.bounds.bound(plane, (i, j), c, centre_z, true) as f32;
        Some((zmin, zmax, centre_z))
    } else {
        // Partial pixels that reach here are rarely culled: both bounds in
        // one pass over the rows.
        let (lo, hi) = tri.bounds.range(plane, (i, j), c, centre_z);
        if lo as f32 > occluder {
            return None;
        }
        Some((lo as f32, hi as f32, centre_z))
    }
}
