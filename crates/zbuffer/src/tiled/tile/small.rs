//! Triangles whose box in the tile is a few pixels: a plain scan of the
//! box, for which block set-up would cost more than it saves.

use hider_geom::FixedPt;
use hider_geom::fixed::{SUBPIXEL_SCALE, pixel_center};

use super::super::raster_tri::RasterTri;
use super::super::wide::{Isa, SmallBox, WideBlock};
use super::{BLOCK, TileBuf};

impl<K: WideBlock> TileBuf<K> {
    /// A triangle whose box in the tile is a few pixels: with AVX2, the
    /// rows of the blocks the box meets as 8-lane registers (branch-free:
    /// the scalar scan's per-pixel branches are mispredicted about as
    /// often as they are taken on a sphere's triangles of a few pixels);
    /// otherwise a plain scalar scan of the box, evaluating the depth only
    /// where the edges pass. Both write the same bits and count the same.
    #[inline(always)]
    pub(super) fn small<T: RasterTri, I: Isa>(
        &mut self,
        isa: I,
        tri: &T,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        ready: Option<[i32; 3]>,
    ) {
        let unit = i64::from(SUBPIXEL_SCALE);
        let p = tri.depth();
        let (inside, passes) = match isa.avx2() {
            Some(avx2) => {
                let setup = match ready {
                    // Set up in the front end, eight triangles at a time
                    // (`SmallSetup`): the steps are the corners'
                    // differences, wrapping as the casts below wrap.
                    Some(e) => {
                        let v = tri.v();
                        let step = |k: usize, d: fn(FixedPt) -> i32| {
                            d(v[(k + 1) % 3])
                                .wrapping_sub(d(v[k]))
                                .wrapping_mul(SUBPIXEL_SCALE)
                        };
                        Some((
                            e,
                            std::array::from_fn(|k| step(k, |p| -p.y)),
                            std::array::from_fn(|k| step(k, |p| p.x)),
                        ))
                    }
                    None => self.small_setup(tri, (x0, y0, x1, y1)),
                };
                // A `match`, not a closure: a closure would be compiled
                // without the kernel's target features.
                match setup {
                    Some((e, sx, sy)) => {
                        let s = SmallBox {
                            per_row: (self.size / BLOCK) as usize,
                            tile_x0: self.x0,
                            tile_y0: self.y0,
                            lx0: x0 - self.x0,
                            ly0: y0 - self.y0,
                            lx1: x1 - self.x0,
                            ly1: y1 - self.y0,
                            plane: p,
                            e,
                            sx,
                            sy,
                            prim: tri.prim(),
                            mask_x: !self.w.is_multiple_of(BLOCK),
                        };
                        K::wide_small(avx2, &mut self.keys, &mut self.ids, &s)
                    }
                    None => None,
                }
            }
            None => None,
        }
        .unwrap_or_else(|| {
            let edges = hider_geom::edge::triangle_edges(tri.v());
            let sx = edges.map(|e| e.a * unit);
            self.small_scalar(tri, (x0, y0, x1, y1), &edges, sx)
        });
        self.stats.pixels_tested += u64::from((x1 - x0 + 1) * (y1 - y0 + 1));
        self.stats.depth_tests += u64::from(inside);
        self.stats.depth_passes += u64::from(passes);
        self.note_small_passes(x0, y0, passes);
    }

    /// The AVX2 kernel's set-up of a small triangle in this tile (what the
    /// front end's `SmallSetup` holds when the box lies in one tile): the
    /// biased edge values at the box's first block column and row, and
    /// their steps, as wrapping `i32`; `None` when a value over the box's
    /// block rows does not fit `i32`.
    #[inline(always)]
    fn small_setup<T: RasterTri>(
        &self,
        tri: &T,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
    ) -> Option<([i32; 3], [i32; 3], [i32; 3])> {
        let edges = hider_geom::edge::triangle_edges(tri.v());
        let unit = i64::from(SUBPIXEL_SCALE);
        let sx = edges.map(|e| e.a * unit);
        // The lanes span whole block rows: from the box's first block
        // column to its last one's eighth pixel.
        let xs = self.x0 + (x0 - self.x0) / BLOCK * BLOCK;
        let xe = self.x0 + (x1 - self.x0) / BLOCK * BLOCK + BLOCK - 1;
        let (px, py) = (
            i64::from(pixel_center(xs as i32)),
            i64::from(pixel_center(y0 as i32)),
        );
        let sy = edges.map(|e| e.b * unit);
        let e = edges.map(|e| e.eval(px, py) - 1);
        let (w, h) = (i64::from(xe - xs), i64::from(y1 - y0));
        // An edge function is affine: it fits i32 over the box when it
        // does at the four corners.
        let fits = (0..3).all(|k| {
            [0, w].iter().all(|&dx| {
                [0, h]
                    .iter()
                    .all(|&dy| i32::try_from(e[k] + sx[k] * dx + sy[k] * dy).is_ok())
            })
        });
        fits.then(|| {
            (
                e.map(|v| v as i32),
                sx.map(|v| v as i32),
                sy.map(|v| v as i32),
            )
        })
    }

    /// The scalar scan of a small triangle's box: returns (inside, passes).
    #[inline(always)]
    fn small_scalar<T: RasterTri>(
        &mut self,
        tri: &T,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        edges: &[hider_geom::EdgeFunction; 3],
        sx: [i64; 3],
    ) -> (u32, u32) {
        let px = i64::from(pixel_center(x0 as i32));
        let p = tri.depth();
        let (mut inside, mut passes) = (0u32, 0u32);
        // Half-open ranges: `a..=b` loops carry an extra exhausted flag
        // (a tenth of the sphere's small-triangle instructions).
        for y in y0..y1 + 1 {
            let py = i64::from(pixel_center(y as i32));
            // Biased by one: inside iff all three are >= 0, i.e. the OR of
            // the three has no sign bit (exact; |E| < 2^50).
            let [mut e0, mut e1, mut e2] = edges.map(|e| e.eval(px, py) - 1);
            let ty = p.dy * ((f64::from(y) + 0.5) - p.y0);
            for x in x0..x1 + 1 {
                if (e0 | e1 | e2) >= 0 {
                    inside += 1;
                    let key = K::encode(p.value + p.dx * ((f64::from(x) + 0.5) - p.x0) + ty);
                    let i = self.at(x, y);
                    if key < self.keys[i] {
                        self.keys[i] = key;
                        self.ids[i] = tri.prim();
                        passes += 1;
                    }
                }
                e0 += sx[0];
                e1 += sx[1];
                e2 += sx[2];
            }
        }
        (inside, passes)
    }
}
