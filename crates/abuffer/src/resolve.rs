//! Resolving the fragment lists: sort, then composite front to back.
//!
//! Per pixel the list is sorted by `zmin` (lower primitive id first on
//! ties), then:
//! - **ids and depth**: the front-most fragment covering the pixel centre,
//!   by its exact `f64` centre depth (see [`crate::centre`]);
//! - **coverage**: covered samples of the union of all masks / samples;
//! - **colour**, summed over samples and divided by their number
//!   (the black background adds nothing), linear, then sRGB:
//!   - [`DepthMode::PerSample`]: when no two fragments with intersecting
//!     masks overlap in depth, the list order is every sample's order and
//!     the *mask path* composites whole masks at once (an opaque fragment
//!     costs one popcount); otherwise each sample sorts the fragments that
//!     cover it by their own depth at that sample — exact at intersections;
//!   - [`DepthMode::MinMax`]: Carpenter's `blender`: a fragment splits the
//!     current mask into the samples it covers and those it does not; the
//!     ones it covers see its colour over (opacity) what lies behind;
//!     where the next fragment starts before this one ends in depth, the
//!     two are taken to cross inside the pixel, each as a plane rising
//!     across its depth range, so this one is in front over the fraction
//!     `vis = (zmax' - zmin) / ((zmax - zmin) + (zmax' - zmin'))` of the
//!     covered samples;
//!   - [`DepthMode::ZminOrder`]: the same without the crossing estimate.
//!
//! The recursion of the paper is run on an explicit stack: the result is
//! linear in the colours, so each pending `(fragment, mask)` carries the
//! weight its colour sum enters with. Masks split into disjoint parts, so
//! a list of `L` fragments costs at most `L * samples` steps.

use hider_scene::{Frame, NO_ID};

use crate::centre::in_front;
use crate::fragment::{Fragment, FragmentPool, NIL};
use crate::options::{ABufferOptions, DepthMode};
use crate::palette::to_pixel;
use crate::stats::ABufferStats;

/// Whether fragment `g` is hidden in every sample it covers, and at the
/// centre if it covers that, by opaque fragments of `list` lying entirely
/// in front of it. Exact: the depth ranges are strict bounds.
pub fn hidden_in_every_sample(g: &Fragment, list: &[Fragment], full: u32) -> bool {
    let mut cover = 0u32;
    let mut centre = !g.covers_centre();
    for h in list {
        if h.alpha >= 1.0 && h.zmax < g.zmin {
            cover |= h.mask;
            centre |= h.covers_centre();
        }
    }
    centre && (g.mask & full) & !cover == 0
}

/// Scratch memory of the resolve, kept between frames.
#[derive(Clone, Debug, Default)]
pub struct Resolver {
    list: Vec<u32>,
    frags: Vec<Fragment>,
    samples: Vec<(f32, u32, u32)>,
    stack: Vec<(u32, u32, f32)>,
}

impl Resolver {
    /// Resolves every pixel of `pool` into `frame`.
    pub fn resolve(
        &mut self,
        pool: &FragmentPool,
        options: &ABufferOptions,
        frame: &mut Frame,
        stats: &mut ABufferStats,
    ) {
        let n = options.pattern.count();
        let inv_n = 1.0 / n as f32;
        frame.coverage.clear();
        frame.coverage.resize(frame.len(), 0.0);
        let (mut lists, mut total) = (0u64, 0u64);
        for p in 0..frame.len() {
            let mut cur = pool.head(p);
            if cur == NIL {
                continue;
            }
            self.list.clear();
            while cur != NIL {
                self.list.push(cur);
                cur = pool.get(cur).next;
            }
            self.list
                .sort_unstable_by(|&a, &b| pool.get(a).order(pool.get(b)));
            self.frags.clear();
            self.frags.extend(self.list.iter().map(|&k| *pool.get(k)));
            lists += 1;
            total += self.list.len() as u64;
            stats.max_list_len = stats.max_list_len.max(self.list.len() as u64);

            let (mut z, mut id) = (f64::INFINITY, NO_ID);
            let mut union = 0u32;
            for f in &self.frags {
                if f.centre_prim != NO_ID && in_front(f.centre_z, f.centre_prim, z, id) {
                    (z, id) = (f.centre_z, f.centre_prim);
                }
                union |= f.mask;
            }
            if id != NO_ID {
                frame.ids[p] = id;
                frame.depth[p] = z as f32;
            }
            frame.coverage[p] = union.count_ones() as f32 * inv_n;

            let sum = match options.depth {
                DepthMode::PerSample if self.overlapping() => {
                    stats.per_sample_pixels += 1;
                    self.per_sample(pool, n)
                }
                DepthMode::PerSample => self.mask_path(options.pattern.full_mask()),
                DepthMode::MinMax => self.blend(options.pattern.full_mask(), true),
                DepthMode::ZminOrder => self.blend(options.pattern.full_mask(), false),
            };
            frame.color[p] = to_pixel(sum.map(|c| c * inv_n));
        }
        stats.mean_list_len = if lists == 0 {
            0.0
        } else {
            total as f64 / lists as f64
        };
    }

    /// Whether two fragments with intersecting masks overlap (or touch) in
    /// depth, so that the list order may not be every sample's order.
    fn overlapping(&self) -> bool {
        let f = &self.frags;
        (1..f.len()).any(|j| (0..j).any(|i| f[i].zmax >= f[j].zmin && f[i].mask & f[j].mask != 0))
    }

    /// Front-to-back compositing of whole masks, exact when the list order
    /// is every sample's depth order.
    fn mask_path(&self, full: u32) -> [f32; 3] {
        let mut sum = [0.0f32; 3];
        let mut alive = full;
        let mut transmit = [1.0f32; 32];
        let mut any_translucent = false;
        for f in &self.frags {
            let vis = f.mask & alive;
            if vis == 0 {
                continue;
            }
            if f.alpha >= 1.0 {
                let weight = if any_translucent {
                    bits(vis).map(|k| transmit[k]).sum()
                } else {
                    vis.count_ones() as f32
                };
                add(&mut sum, f.rgb, weight);
                alive &= !f.mask;
                if alive == 0 {
                    break;
                }
            } else {
                any_translucent = true;
                for k in bits(vis) {
                    add(&mut sum, f.rgb, transmit[k] * f.alpha);
                    transmit[k] *= 1.0 - f.alpha;
                }
            }
        }
        sum
    }

    /// Sample-by-sample compositing in each sample's own depth order.
    fn per_sample(&mut self, pool: &FragmentPool, n: usize) -> [f32; 3] {
        let mut sum = [0.0f32; 3];
        for k in 0..n {
            self.samples.clear();
            for (i, (f, &idx)) in self.frags.iter().zip(&self.list).enumerate() {
                if f.mask >> k & 1 == 1 {
                    self.samples.push((pool.depths(idx)[k], f.prim, i as u32));
                }
            }
            self.samples
                .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut transmit = 1.0f32;
            for &(_, _, i) in &self.samples {
                let f = &self.frags[i as usize];
                add(&mut sum, f.rgb, transmit * f.alpha);
                transmit *= 1.0 - f.alpha;
                if transmit <= 0.0 {
                    break;
                }
            }
        }
        sum
    }

    /// Carpenter's blender on an explicit stack (see the module
    /// documentation); `crossing` enables the interpenetration estimate.
    fn blend(&mut self, full: u32, crossing: bool) -> [f32; 3] {
        let mut sum = [0.0f32; 3];
        self.stack.clear();
        self.stack.push((0, full, 1.0));
        while let Some((start, mask, weight)) = self.stack.pop() {
            let rest = &self.frags[start as usize..];
            let Some(pos) = rest.iter().position(|f| f.mask & mask != 0) else {
                continue; // background: black
            };
            let f = &rest[pos];
            let next = start + pos as u32 + 1;
            let inside = mask & f.mask;
            let outside = mask & !f.mask;
            if outside != 0 {
                self.stack.push((next, outside, weight));
            }
            let behind = &self.frags[next as usize..];
            let vis = if crossing {
                behind
                    .iter()
                    .find(|g| g.mask & inside != 0)
                    .filter(|g| g.zmin < f.zmax)
                    .map(|g| {
                        let spread = (f.zmax - f.zmin) + (g.zmax - g.zmin);
                        if spread > 0.0 {
                            ((g.zmax - f.zmin) / spread).clamp(0.0, 1.0)
                        } else {
                            1.0
                        }
                    })
            } else {
                None
            };
            // In the covered samples: vis * (a*c + (1-a)*B) + (1-vis) * B,
            // B being what lies behind (vis = 1 without a crossing).
            let vis = vis.unwrap_or(1.0);
            let front = vis * f.alpha;
            let behind_weight = 1.0 - front;
            add(&mut sum, f.rgb, weight * front * inside.count_ones() as f32);
            if behind_weight > 0.0 {
                self.stack.push((next, inside, weight * behind_weight));
            }
        }
        sum
    }
}

/// The set bits of a mask.
fn bits(mask: u32) -> impl Iterator<Item = usize> {
    let mut m = mask;
    std::iter::from_fn(move || {
        (m != 0).then(|| {
            let k = m.trailing_zeros() as usize;
            m &= m - 1;
            k
        })
    })
}

#[inline]
fn add(sum: &mut [f32; 3], rgb: [f32; 3], weight: f32) {
    for c in 0..3 {
        sum[c] += rgb[c] * weight;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frag(mask: u32, zmin: f32, zmax: f32, rgb: [f32; 3], alpha: f32) -> Fragment {
        Fragment {
            next: NIL,
            mask,
            prim: 0,
            tri: 0,
            centre_prim: NO_ID,
            zmin,
            zmax,
            centre_z: f64::INFINITY,
            rgb,
            alpha,
        }
    }

    fn resolver(frags: Vec<Fragment>) -> Resolver {
        Resolver {
            frags,
            ..Resolver::default()
        }
    }

    #[test]
    fn mask_path_weighs_masks_and_opacity() {
        // Left half red opaque; everything under a half-transparent green.
        let r = resolver(vec![
            frag(u32::MAX, 0.1, 0.1, [0.0, 1.0, 0.0], 0.5),
            frag(0x0f0f_0f0f, 0.5, 0.5, [1.0, 0.0, 0.0], 1.0),
        ]);
        let s = r.mask_path(u32::MAX);
        assert!((s[1] - 16.0).abs() < 1e-5, "{s:?}"); // 32 * 0.5
        assert!((s[0] - 8.0).abs() < 1e-5, "{s:?}"); // 16 * 0.5
        // The blender without crossings gives the same answer.
        let mut r = r;
        let b = r.blend(u32::MAX, false);
        assert!((0..3).all(|c| (b[c] - s[c]).abs() < 1e-4), "{b:?} vs {s:?}");
    }

    #[test]
    fn crossing_estimate_splits_two_opposite_ramps_evenly() {
        // Two full-pixel fragments with the same depth range, crossing in
        // the middle: each is in front over half the pixel.
        let mut r = resolver(vec![
            frag(u32::MAX, 0.4, 0.6, [1.0, 0.0, 0.0], 1.0),
            frag(u32::MAX, 0.4, 0.6, [0.0, 0.0, 1.0], 1.0),
        ]);
        let s = r.blend(u32::MAX, true);
        assert!(
            (s[0] - 16.0).abs() < 1e-4 && (s[2] - 16.0).abs() < 1e-4,
            "{s:?}"
        );
        let s = r.blend(u32::MAX, false);
        assert_eq!(s, [32.0, 0.0, 0.0]);
    }

    #[test]
    fn hidden_fragments_are_found_exactly() {
        let full = u32::MAX;
        let a = frag(0xffff, 0.1, 0.2, [0.0; 3], 1.0);
        let b = frag(0xffff_0000, 0.1, 0.3, [0.0; 3], 1.0);
        let behind = frag(0x00ff_ff00, 0.35, 0.4, [0.0; 3], 1.0);
        let touching = frag(0x00ff_ff00, 0.3, 0.4, [0.0; 3], 1.0);
        let list = [a, b, behind, touching];
        assert!(hidden_in_every_sample(&behind, &list, full));
        assert!(
            !hidden_in_every_sample(&touching, &list, full),
            "equal depth is not hidden"
        );
        assert!(!hidden_in_every_sample(&a, &list, full));
        let glass = frag(0xffff_0000, 0.1, 0.3, [0.0; 3], 0.5);
        assert!(!hidden_in_every_sample(&behind, &[a, glass], full));
    }
}
