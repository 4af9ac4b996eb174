//! The sample buffer's resolve: per written pixel, its coverage, the
//! centre's id and depth, and the colour sum of the samples' front
//! primitives in the canonical order the lists use too
//! ([`crate::composite::opaque_sum`]), so both give the same image.

use hider_scene::NO_ID;

use super::SampleBuffer;
use crate::bins::TILE;
use crate::composite::{Shown, opaque_sum};
use crate::pattern::MAX_SAMPLES;
use crate::resolve::{Band, Input, Resolver, Samples};

/// Whole pixels a row needs before they are resolved as runs
/// ([`SampleBuffer::resolve_whole_runs`]): fewer, in short runs between
/// partial pixels, resolve faster one by one.
const RUN_PIXELS: u32 = 16;

#[cfg(target_arch = "x86_64")]
use super::avx2;

impl SampleBuffer {
    /// The mask of the samples of `prims` equal to `value`.
    #[inline(always)]
    pub(super) fn equal_mask(&self, prims: &[u32; MAX_SAMPLES], value: u32) -> u32 {
        #[cfg(target_arch = "x86_64")]
        if let Some(isa) = self.avx2 {
            return avx2::equal_mask(isa, prims, value);
        }
        let mut mask = 0u32;
        for (k, &id) in prims.iter().enumerate() {
            mask |= u32::from(id == value) << k;
        }
        mask
    }

    /// Resolves the pass's written pixels into `frame`: coverage, the
    /// centre's id and depth, and the colour sum of the samples' front
    /// primitives in the lists' canonical order.
    pub(crate) fn resolve(
        &mut self,
        input: &mut Input<'_>,
        resolver: &mut Resolver,
        k: &Samples,
        frame: &mut Band<'_>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if let Some(isa) = self.avx2 {
            // The whole loop compiled for AVX2, so that the per-primitive
            // sample counts inline into it.
            avx2::resolve(isa, self, (input, resolver), k, frame);
            return;
        }
        self.resolve_with(input, resolver, k, frame);
    }

    /// [`Self::resolve`], inlined into its AVX2 and portable callers.
    #[inline(always)]
    pub(crate) fn resolve_with(
        &mut self,
        input: &mut Input<'_>,
        resolver: &mut Resolver,
        k: &Samples,
        frame: &mut Band<'_>,
    ) {
        let (x0, y0, _, y1) = self.rect;
        let w = frame.width;
        let flat = input.scene.flat_colors();
        for j in y0..=y1 {
            let mut row = self.touched[(j - y0) as usize];
            let whole = row & self.whole[(j - y0) as usize];
            if flat && whole.count_ones() >= RUN_PIXELS {
                self.resolve_whole_runs(input, resolver, k, frame, (j, whole));
                row &= !whole;
            }
            while row != 0 {
                let i = x0 + row.trailing_zeros();
                row &= row - 1;
                let q = self.index(i, j);
                let p = j as usize * w + i as usize;
                if self.centre_prim[q] != NO_ID {
                    frame.set_id(p, self.centre_prim[q], self.centre_z[q] as f32);
                }
                let all = k.full;
                if self.whole[(j - y0) as usize] >> (i - x0) & 1 == 1 {
                    // What the samples say of a whole pixel: its one
                    // primitive at every sample. The colour sum of one
                    // primitive, as `opaque_sum` computes it (`0 + rgb *
                    // n`, then `* (1 / n)`), without the list it sorts.
                    let rgba = input.prim_rgba(self.centre_prim[q], (i, j));
                    let n = all.count_ones() as f32;
                    frame.set_coverage(p, n * k.inv_n);
                    let sum = [0, 1, 2].map(|c| (0.0 + rgba[c] * n) * k.inv_n);
                    resolver.write_color(k, sum, frame, p);
                    continue;
                }
                self.shown.clear();
                let covered = {
                    let prims = &self.prims[q];
                    let mut covered = 0u32;
                    let mut left = !self.equal_mask(prims, NO_ID) & all;
                    while left != 0 {
                        let prim = prims[left.trailing_zeros() as usize];
                        let same = self.equal_mask(prims, prim) & all;
                        left &= !same;
                        covered += show(&mut self.shown, input, prim, same, (i, j));
                    }
                    covered
                };
                frame.set_coverage(p, covered as f32 * k.inv_n);
                let sum = opaque_sum(&mut self.shown).map(|c| c * k.inv_n);
                resolver.write_color(k, sum, frame, p);
            }
        }
    }

    /// Resolves the whole pixels `whole` (bit = column of the pass) of row
    /// `j` of a scene whose colours are flat: a run of them held by one
    /// primitive shares its colour, coverage and id, and only the depth
    /// differs, so each run is written at once. The values are the ones
    /// [`Self::resolve_with`] writes pixel by pixel (which cost a large
    /// triangle's frame as much as drawing it).
    #[inline(never)]
    fn resolve_whole_runs(
        &self,
        input: &mut Input<'_>,
        resolver: &mut Resolver,
        k: &Samples,
        frame: &mut Band<'_>,
        (j, whole): (u32, u64),
    ) {
        let (x0, y0) = (self.rect.0, self.rect.1);
        let n = k.full.count_ones() as f32;
        let coverage = n * k.inv_n;
        let mut left = whole;
        while left != 0 {
            let start = left.trailing_zeros();
            let len = (!(left >> start)).trailing_zeros();
            left &= !(u64::MAX >> (64 - len) << start);
            let q0 = ((j - y0) * TILE + start) as usize;
            let p0 = j as usize * frame.width + (x0 + start) as usize - frame.first;
            let mut a = 0;
            while a < len as usize {
                let prim = self.centre_prim[q0 + a];
                let b = a
                    + 1
                    + self.centre_prim[q0 + a + 1..q0 + len as usize]
                        .iter()
                        .take_while(|&&id| id == prim)
                        .count();
                // The colour sum of one primitive, as `opaque_sum`
                // computes it (`0 + rgb * n`, then `* (1 / n)`).
                let rgba = input.prim_rgba(prim, (x0 + start + a as u32, j));
                let color = resolver.color(k, [0, 1, 2].map(|c| (0.0 + rgba[c] * n) * k.inv_n));
                frame.ids[p0 + a..p0 + b].fill(prim);
                frame.coverage[p0 + a..p0 + b].fill(coverage);
                frame.color[p0 + a..p0 + b].fill(color);
                for (d, &z) in frame.depth[p0 + a..p0 + b]
                    .iter_mut()
                    .zip(&self.centre_z[q0 + a..q0 + b])
                {
                    *d = z as f32;
                }
                a = b;
            }
        }
    }
}

/// Notes in `shown` that primitive `prim` is the front surface at the
/// samples of `mask` of pixel `ij` (its colour there from `input`);
/// returns how many samples that is.
#[inline(always)]
fn show(
    shown: &mut Vec<Shown>,
    input: &mut Input<'_>,
    prim: u32,
    mask: u32,
    ij: (u32, u32),
) -> u32 {
    let rgba = input.prim_rgba(prim, ij);
    shown.push(Shown {
        prim,
        samples: mask.count_ones(),
        rgb: [rgba[0], rgba[1], rgba[2]],
    });
    mask.count_ones()
}
