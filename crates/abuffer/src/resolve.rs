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
//!     cover it by their own depth at that sample (the triangle's plane at
//!     the sample, recomputed here with the expression that made the
//!     bounds, or a merged fragment's stored depths) — exact at
//!     intersections;
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
//!
//! A pixel is resolved right after its tile is rendered (its list is still
//! in cache); a list of one opaque fragment takes a shortcut computing what
//! every path computes for it; neighbouring pixels with the same colour sum
//! reuse the last sRGB conversion, which is exact and table-driven
//! ([`crate::palette`]).

use hider_geom::PlaneEq;
use hider_scene::{Frame, NO_ID, ScreenScene};

use crate::abuffer::{sample_depth_of, shade_of};
use crate::centre::in_front;
use crate::fragment::{Fragment, FragmentPool, MERGED_BASE, NIL};
use crate::options::{ABufferOptions, DepthMode};
use crate::palette::{Srgb, to_pixel};
use crate::stats::ABufferStats;

/// A fragment with its colour and opacity looked up, and its pool index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaded {
    /// The fragment.
    pub frag: Fragment,
    /// Linear colour.
    pub rgb: [f32; 3],
    /// Opacity in [0, 1].
    pub alpha: f32,
    /// Index in the pool.
    pub idx: u32,
}

impl Shaded {
    /// `f` (pool index `idx`) with colour and opacity `rgba`.
    #[inline]
    pub fn new(f: Fragment, rgba: [f32; 4], idx: u32) -> Self {
        Self {
            frag: f,
            rgb: [rgba[0], rgba[1], rgba[2]],
            alpha: rgba[3],
            idx,
        }
    }
}

/// Whether fragment `g` is hidden in every sample it covers, and at the
/// centre if it covers that, by opaque fragments of `list` lying entirely
/// in front of it. Exact: the depth ranges are strict bounds.
pub fn hidden_in_every_sample(g: &Shaded, list: &[Shaded], full: u32) -> bool {
    let mut cover = 0u32;
    let mut centre = !g.frag.covers_centre();
    for h in list {
        if h.alpha >= 1.0 && h.frag.zmax < g.frag.zmin {
            cover |= h.frag.mask;
            centre |= h.frag.covers_centre();
        }
    }
    centre && (g.frag.mask & full) & !cover == 0
}

/// Scratch memory of the resolve, kept between frames.
#[derive(Clone, Debug, Default)]
pub struct Resolver {
    frags: Vec<Shaded>,
    samples: Vec<(f32, u32, u32)>,
    stack: Vec<(u32, u32, f32)>,
    lists: u64,
    total: u64,
    /// The last colour sum converted and its pixel: neighbouring pixels
    /// often resolve to the same sum, and the sRGB conversion costs a
    /// `powf` per channel.
    memo: ([f32; 3], [u8; 4]),
    /// Shortcuts for lists of one or two opaque fragments off (tests).
    pub(crate) no_shortcuts: bool,
}

impl Resolver {
    /// Starts a frame.
    pub fn begin(&mut self) {
        self.lists = 0;
        self.total = 0;
        self.memo = ([0.0; 3], to_pixel([0.0; 3]));
    }

    /// Ends a frame: the mean list length.
    pub fn finish(&mut self, stats: &mut ABufferStats) {
        stats.mean_list_len = if self.lists == 0 {
            0.0
        } else {
            self.total as f64 / self.lists as f64
        };
    }

    /// Resolves the pixels of rectangle `(x0, y0, x1, y1)` of `pool` into
    /// `frame` (whose coverage buffer is allocated).
    #[allow(clippy::too_many_arguments)]
    pub fn resolve_tile(
        &mut self,
        scene: &ScreenScene,
        pool: &FragmentPool,
        planes: &[PlaneEq],
        colors: &mut [[f32; 4]],
        options: &ABufferOptions,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        frame: &mut Frame,
        stats: &mut ABufferStats,
    ) {
        let pattern = options.pattern;
        let n = pattern.count();
        let full = pattern.full_mask();
        let inv_n = 1.0 / n as f32;
        let w = frame.width() as usize;
        let srgb = Srgb::new();
        for j in y0..=y1 {
            for i in x0..=x1 {
                let p = j as usize * w + i as usize;
                let mut cur = pool.head(p);
                if cur == NIL {
                    continue;
                }
                let first = pool.get(cur);
                let first_rgba = if first.is_merged() {
                    pool.merged(first.shade).rgba
                } else {
                    shade_of(colors, scene, options.shade, first.shade)
                };
                if first.next == NIL && first_rgba[3] >= 1.0 && !self.no_shortcuts {
                    // One opaque fragment: what every path computes for it.
                    self.lists += 1;
                    self.total += 1;
                    stats.max_list_len = stats.max_list_len.max(1);
                    if first.centre_prim != NO_ID {
                        frame.ids[p] = first.centre_prim;
                        frame.depth[p] = first.centre_z as f32;
                    }
                    frame.coverage[p] = first.mask.count_ones() as f32 * inv_n;
                    let rgba = first_rgba;
                    let weight = (first.mask & full).count_ones() as f32;
                    let sum = [0, 1, 2].map(|c| (0.0 + rgba[c] * weight) * inv_n);
                    if sum != self.memo.0 {
                        self.memo = (sum, srgb.pixel(sum));
                    }
                    frame.color[p] = self.memo.1;
                    continue;
                }
                if first.next != NIL && first_rgba[3] >= 1.0 && !self.no_shortcuts {
                    let second = pool.get(first.next);
                    if second.next == NIL && second.mask & first.mask == 0 {
                        let second_rgba = if second.is_merged() {
                            pool.merged(second.shade).rgba
                        } else {
                            shade_of(colors, scene, options.shade, second.shade)
                        };
                        if second_rgba[3] >= 1.0 {
                            // Two opaque fragments with disjoint masks: each
                            // shows all its samples, so every path (mask
                            // path or blender, in either depth order) adds
                            // `rgb * samples` of each to zero, and a sum of
                            // two terms does not depend on their order.
                            self.lists += 1;
                            self.total += 2;
                            stats.max_list_len = stats.max_list_len.max(2);
                            let (mut z, mut id) = (f64::INFINITY, NO_ID);
                            for f in [first, second] {
                                if f.centre_prim != NO_ID
                                    && in_front(f.centre_z, f.centre_prim, z, id)
                                {
                                    (z, id) = (f.centre_z, f.centre_prim);
                                }
                            }
                            if id != NO_ID {
                                frame.ids[p] = id;
                                frame.depth[p] = z as f32;
                            }
                            frame.coverage[p] =
                                (first.mask | second.mask).count_ones() as f32 * inv_n;
                            let wa = (first.mask & full).count_ones() as f32;
                            let wb = (second.mask & full).count_ones() as f32;
                            let sum = [0, 1, 2]
                                .map(|c| (0.0 + first_rgba[c] * wa + second_rgba[c] * wb) * inv_n);
                            if sum != self.memo.0 {
                                self.memo = (sum, srgb.pixel(sum));
                            }
                            frame.color[p] = self.memo.1;
                            continue;
                        }
                    }
                }
                self.frags.clear();
                while cur != NIL {
                    let f = pool.get(cur);
                    let rgba = if f.shade >= MERGED_BASE {
                        pool.merged(f.shade).rgba
                    } else {
                        shade_of(colors, scene, options.shade, f.shade)
                    };
                    self.frags.push(Shaded::new(*f, rgba, cur));
                    cur = f.next;
                }
                // Lists are short: insertion sort, stable on exact ties.
                for a in 1..self.frags.len() {
                    let mut b = a;
                    while b > 0 && self.frags[b - 1].frag.order(&self.frags[b].frag).is_gt() {
                        self.frags.swap(b - 1, b);
                        b -= 1;
                    }
                }
                let len = self.frags.len() as u64;
                self.lists += 1;
                self.total += len;
                stats.max_list_len = stats.max_list_len.max(len);

                let (mut z, mut id) = (f64::INFINITY, NO_ID);
                let mut union = 0u32;
                for s in &self.frags {
                    let f = &s.frag;
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

                let sum = if len == 1 && self.frags[0].alpha >= 1.0 && !self.no_shortcuts {
                    // What every path computes for one opaque fragment.
                    let s = &self.frags[0];
                    let weight = (s.frag.mask & full).count_ones() as f32;
                    s.rgb.map(|c| 0.0 + c * weight)
                } else {
                    match options.depth {
                        DepthMode::PerSample if self.overlapping() => {
                            stats.per_sample_pixels += 1;
                            self.per_sample(pool, planes, (i, j), pattern.positions())
                        }
                        DepthMode::PerSample => self.mask_path(full),
                        DepthMode::MinMax => self.blend(full, true),
                        DepthMode::ZminOrder => self.blend(full, false),
                    }
                };
                let sum = sum.map(|c| c * inv_n);
                if sum != self.memo.0 {
                    self.memo = (sum, srgb.pixel(sum));
                }
                frame.color[p] = self.memo.1;
            }
        }
    }

    /// Whether two fragments with intersecting masks overlap (or touch) in
    /// depth, so that the list order may not be every sample's order.
    fn overlapping(&self) -> bool {
        let f = &self.frags;
        (1..f.len()).any(|j| {
            (0..j).any(|i| f[i].frag.zmax >= f[j].frag.zmin && f[i].frag.mask & f[j].frag.mask != 0)
        })
    }

    /// Front-to-back compositing of whole masks, exact when the list order
    /// is every sample's depth order.
    fn mask_path(&self, full: u32) -> [f32; 3] {
        let mut sum = [0.0f32; 3];
        let mut alive = full;
        let mut transmit = [1.0f32; 32];
        // Until a translucent fragment shows, every `transmit` is 1.
        let mut any_translucent = false;
        for s in &self.frags {
            let f = &s.frag;
            let vis = f.mask & alive;
            if vis == 0 {
                continue;
            }
            if s.alpha >= 1.0 {
                let weight = if any_translucent {
                    bits(vis).map(|k| transmit[k]).sum()
                } else {
                    vis.count_ones() as f32
                };
                add(&mut sum, s.rgb, weight);
                alive &= !f.mask;
                if alive == 0 {
                    break;
                }
            } else {
                any_translucent = true;
                for k in bits(vis) {
                    add(&mut sum, s.rgb, transmit[k] * s.alpha);
                    transmit[k] *= 1.0 - s.alpha;
                }
            }
        }
        sum
    }

    /// Sample-by-sample compositing in each sample's own depth order.
    fn per_sample(
        &mut self,
        pool: &FragmentPool,
        planes: &[PlaneEq],
        ij: (u32, u32),
        positions: &[(i32, i32)],
    ) -> [f32; 3] {
        let mut sum = [0.0f32; 3];
        for k in 0..positions.len() {
            self.samples.clear();
            for (i, s) in self.frags.iter().enumerate() {
                if s.frag.mask >> k & 1 == 1 {
                    let z = sample_depth_of(pool, planes, &s.frag, ij, positions, k);
                    self.samples.push((z, s.frag.prim, i as u32));
                }
            }
            self.samples
                .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut transmit = 1.0f32;
            for &(_, _, i) in &self.samples {
                let s = &self.frags[i as usize];
                add(&mut sum, s.rgb, transmit * s.alpha);
                transmit *= 1.0 - s.alpha;
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
            let Some(pos) = rest.iter().position(|s| s.frag.mask & mask != 0) else {
                continue; // background: black
            };
            let s = &rest[pos];
            let f = &s.frag;
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
                    .map(|g| &g.frag)
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
            let front = vis * s.alpha;
            let behind_weight = 1.0 - front;
            add(&mut sum, s.rgb, weight * front * inside.count_ones() as f32);
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

    fn frag(mask: u32, zmin: f32, zmax: f32, rgb: [f32; 3], alpha: f32) -> Shaded {
        let f = Fragment {
            next: NIL,
            mask,
            prim: 0,
            tri: 0,
            centre_prim: NO_ID,
            shade: 0,
            zmin,
            zmax,
            centre_z: f64::INFINITY,
        };
        Shaded::new(f, [rgb[0], rgb[1], rgb[2], alpha], 0)
    }

    fn resolver(frags: Vec<Shaded>) -> Resolver {
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
