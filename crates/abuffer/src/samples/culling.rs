//! The sample buffer's occlusion culling: the bounds that reject a hidden
//! triangle before its masks are computed, per pass rectangle, per 8 x 8
//! block and per row of a block. Every bound is a lower bound of the
//! triangle's computed depth (its plane at the near corner of the sample
//! hull, [`crate::depth::near_corner`]) against an upper bound of what the
//! pixels hold, compared strictly, so culling removes only what would
//! lose every sample and the centre: it changes no sample (tested).

use hider_geom::PlaneEq;

use super::{BLOCK, BLOCKS_X, EMPTY, SampleBuffer, Tri};
use crate::bins::BinItem;
use crate::culling::block_part;
use crate::depth::{depth_key, nearest_over, plane_depth};
use crate::stats::ABufferStats;

#[cfg(target_arch = "x86_64")]
use super::avx2;

impl SampleBuffer {
    /// The farthest key of the written pixels of block `b`, [`EMPTY`] if
    /// one is unwritten.
    pub(super) fn block_bound(&self, b: usize) -> i32 {
        let (x0, y0, _, _) = self.rect;
        let block = (b as u32 % BLOCKS_X, b as u32 / BLOCKS_X);
        let (i0, j0, i1, j1) = block_part((x0, y0), block, self.rect);
        let bits = (1u64 << (i1 - i0 + 1)) - 1;
        let mut far = i32::MIN;
        for j in j0..=j1 {
            if (self.touched[(j - y0) as usize] >> (i0 - x0)) & bits != bits {
                return EMPTY;
            }
            let p = self.index(i0, j);
            for &f in &self.far[p..=p + (i1 - i0) as usize] {
                far = far.max(f);
            }
        }
        far
    }

    /// The blocks of the pass where `item`'s triangle may win a sample or
    /// the centre inside `(x0, y0, x1, y1)`, as bits; counts the others in
    /// [`ABufferStats::culled_blocks`]. The plane at the block's near
    /// corner (of the sample hull `hull`) is a lower bound of the
    /// triangle's depth at every sample and centre of the block; the
    /// item's own bound ([`BinItem::near`], over its whole range) is a
    /// lower one, tried first: when it is beyond, so is the tighter one,
    /// so the decisions are those of the tighter bound alone.
    // Inlined into the AVX2 triangle loop: called out of line it made the
    // soup 6 % slower.
    #[inline(always)]
    pub(super) fn live_blocks(
        &mut self,
        item: &BinItem,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        hull: (i32, i32, i32, i32),
        stats: &mut ABufferStats,
    ) -> u32 {
        let plane = &item.plane;
        let item_near = depth_key(item.near);
        let (px0, py0) = (self.rect.0, self.rect.1);
        let (bx0, bx1) = ((x0 - px0) / BLOCK, (x1 - px0) / BLOCK);
        let (by0, by1) = ((y0 - py0) / BLOCK, (y1 - py0) / BLOCK);
        let blocks = (bx1 - bx0 + 1) * (by1 - by0 + 1);
        if blocks > 1 {
            // The whole rectangle first, with one evaluation: the plane at
            // its near corner is a lower bound of its value at every
            // block's near corner (the plane is monotonic), and the
            // largest of the blocks' bounds (upper bounds, stale or not)
            // bounds every pixel. The evaluations per block are a chain of
            // dependent `f64` operations each: on large hidden triangles
            // they were a tenth of the frame.
            let mut far = i32::MIN;
            'blocks: for by in by0..=by1 {
                for bx in bx0..=bx1 {
                    let b = (by * BLOCKS_X + bx) as usize;
                    far = far.max(if self.open[b] > 0 {
                        EMPTY
                    } else {
                        self.block_far[b]
                    });
                    if far == EMPTY {
                        break 'blocks;
                    }
                }
            }
            if far != EMPTY {
                let hidden = item_near > far
                    || depth_key(nearest_over(plane, (x0, y0, x1, y1), hull) as f32) > far;
                if hidden {
                    stats.culled_blocks += u64::from(blocks);
                    stats.culled_tiles += 1;
                    return 0;
                }
            }
        }
        let mut live = 0u32;
        for by in by0..=by1 {
            for bx in bx0..=bx1 {
                let b = (by * BLOCKS_X + bx) as usize;
                if self.open[b] > 0 || (self.block_far[b] == EMPTY && self.stale >> b & 1 == 0) {
                    live |= 1 << b;
                    continue;
                }
                if item_near > self.block_far[b] {
                    stats.culled_blocks += 1;
                    continue;
                }
                let part = block_part((px0, py0), (bx, by), (x0, y0, x1, y1));
                let near = depth_key(nearest_over(plane, part, hull) as f32);
                if near <= self.block_far[b] && self.stale >> b & 1 == 1 {
                    self.block_far[b] = self.block_bound(b);
                    self.stale &= !(1 << b);
                }
                if near > self.block_far[b] {
                    stats.culled_blocks += 1;
                } else {
                    live |= 1 << b;
                }
            }
        }
        live
    }

    /// The key of the plane of `tri` at the near corner of each of the 8
    /// pixels from `(i0, j)` on (a lower bound of its depth at their
    /// samples and centres), as [`plane_depth`] computes it (with AVX2:
    /// the same operations on 4 lanes at a time).
    #[inline(always)]
    pub(super) fn row_near_keys(&self, tri: &Tri, (i0, j): (u32, u32)) -> [i32; BLOCK as usize] {
        self.row_keys(&tri.plane, (i0, j), tri.near_corner)
    }

    /// The key of `plane` at the sample-hull corner `corner` of each of
    /// the 8 pixels from `(i0, j)` on, as [`plane_depth`] computes it.
    #[inline(always)]
    pub(super) fn row_keys(
        &self,
        plane: &PlaneEq,
        (i0, j): (u32, u32),
        corner: (i32, i32),
    ) -> [i32; BLOCK as usize] {
        #[cfg(target_arch = "x86_64")]
        if let Some(isa) = self.avx2 {
            return avx2::row_keys(isa, plane, (i0, j), corner);
        }
        std::array::from_fn(|k| depth_key(plane_depth(plane, i0 + k as u32, j, corner) as f32))
    }

    /// The pixels of the 8 from `(i0, j)` on (bit `k` = pixel `i0 + k`)
    /// that a triangle whose near keys there are `keys` loses entirely:
    /// strictly behind the farthest of the pixel's samples and centre.
    #[inline(always)]
    pub(super) fn row_culled(&self, keys: &[i32; BLOCK as usize], (i0, j): (u32, u32)) -> u32 {
        let row = (j - self.rect.1) as usize;
        let live = (self.touched[row] >> (i0 - self.rect.0)) as u32;
        let p = self.index(i0, j);
        let far = &self.far[p..p + BLOCK as usize];
        #[cfg(target_arch = "x86_64")]
        if let Some(isa) = self.avx2 {
            return avx2::greater(isa, keys, far.try_into().expect("8 keys")) & live;
        }
        let mut culled = 0u32;
        for (k, (&key, &far)) in keys.iter().zip(far).enumerate() {
            // An open pixel's farthest key is EMPTY: nothing is beyond it.
            culled |= u32::from(key > far) << k;
        }
        culled & live
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::Coverage;
    use crate::depth::{far_corner, near_corner};
    use crate::pattern::SamplePattern;
    use crate::test_rng::xorshift;
    use hider_geom::PlaneEq;
    use hider_geom::isa::Avx2;

    /// The AVX2 row of near keys and the AVX2 comparison give the portable
    /// results bit for bit, on planes of every scale and sign (negative
    /// depths, huge slopes, values that round to the same `f32`).
    #[test]
    fn row_keys_and_culling_equal_the_portable_ones() {
        let Some(isa) = Avx2::detect() else { return };
        let mut next = xorshift();
        let mut unit = move || (next() >> 11) as f64 / (1u64 << 53) as f64;
        let mut buffer = SampleBuffer::default();
        buffer.begin((64, 32, 127, 63), true);
        for case in 0..4000 {
            let scale = [1e-9, 1e-3, 1.0, 1e3, 1e12][case % 5];
            let plane = PlaneEq {
                x0: unit() * 2048.0 - 512.0,
                y0: unit() * 2048.0 - 512.0,
                value: (unit() - 0.5) * 4.0,
                dx: (unit() - 0.5) * scale,
                dy: (unit() - 0.5) * scale,
            };
            let hull = SamplePattern::ALL[case % 5].hull();
            let tri = Tri {
                plane,
                prim: 0,
                near_corner: near_corner(&plane, hull),
                far_corner: far_corner(&plane, hull),
                full: Coverage::default(),
                own_plane: None,
                pattern: SamplePattern::Grid32,
                grid: None,
            };
            let (i0, j) = (64 + (unit() * 56.0) as u32, 32 + (unit() * 32.0) as u32);
            buffer.avx2 = Some(isa);
            let wide = buffer.row_near_keys(&tri, (i0, j));
            buffer.avx2 = None;
            let portable = buffer.row_near_keys(&tri, (i0, j));
            assert_eq!(wide, portable, "case {case}: {plane:?} at {i0} {j}");
            for (k, &key) in portable.iter().enumerate() {
                let z = plane_depth(&plane, i0 + k as u32, j, tri.near_corner) as f32;
                assert_eq!(key, depth_key(z), "case {case} pixel {k}");
            }
            let other: [i32; 8] = std::array::from_fn(|k| {
                if k % 3 == 0 {
                    portable[k]
                } else {
                    next_key(&mut unit)
                }
            });
            let scalar = (0..8).fold(0u32, |m, k| m | u32::from(portable[k] > other[k]) << k);
            assert_eq!(avx2::greater(isa, &portable, &other), scalar, "case {case}");
        }
    }

    /// A key anywhere in the range, the empty one included.
    fn next_key(unit: &mut impl FnMut() -> f64) -> i32 {
        match (unit() * 4.0) as u32 {
            0 => EMPTY,
            1 => i32::MIN,
            _ => ((unit() - 0.5) * 2.0 * f64::from(i32::MAX)) as i32,
        }
    }
}
