//! Compositing one pixel's sorted fragment list into a colour sum, in the
//! three ways the depth modes call for: whole masks front to back, sample
//! by sample in each sample's own depth order, or Carpenter's blender.
//!
//! Each returns the sum over the samples of the composited linear colour
//! (the black background adding nothing); the caller divides by the
//! sample count.

use crate::bins::BinItem;

use crate::fragment::Shaded;
use crate::pool::FragmentPool;

/// Whether two fragments of `frags` with intersecting masks overlap (or
/// touch) in depth, so that the list order may not be every sample's order.
pub(crate) fn overlapping(frags: &[Shaded]) -> bool {
    let f = frags;
    (1..f.len()).any(|j| {
        (0..j).any(|i| f[i].frag.zmax >= f[j].frag.zmin && f[i].frag.mask & f[j].frag.mask != 0)
    })
}

/// Front-to-back compositing of whole masks (`full`: every sample), exact
/// when the list order is every sample's depth order.
pub(crate) fn mask_path(frags: &[Shaded], full: u32) -> [f32; 3] {
    let mut sum = [0.0f32; 3];
    let mut alive = full;
    let mut transmit = [1.0f32; 32];
    // Until a translucent fragment shows, every `transmit` is 1.
    let mut any_translucent = false;
    for s in frags {
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

/// How many of a pixel's samples show one opaque primitive, and its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Shown {
    /// The primitive.
    pub(crate) prim: u32,
    /// Samples in which it is the front surface.
    pub(crate) samples: u32,
    /// Its linear colour in this pixel.
    pub(crate) rgb: [f32; 3],
}

/// The colour sum of a pixel whose samples show opaque surfaces only,
/// from how many samples each primitive shows in: the primitives in
/// ascending id, each adding `rgb * samples` once (entries of one
/// primitive are first added up).
///
/// One canonical order, whatever produced the counts: fragment lists in
/// any order, merged or not, composited by whole masks or sample by sample,
/// and the tiles resolved from a sample buffer ([`crate::samples`]) give
/// the same sum bit for bit. (Floating-point addition is not associative:
/// summing per fragment in depth order, as before, made the last bit
/// depend on how the samples were grouped into fragments.) `shown` is
/// sorted in place.
pub(crate) fn opaque_sum(shown: &mut [Shown]) -> [f32; 3] {
    // Short lists: insertion sort.
    for a in 1..shown.len() {
        let mut b = a;
        while b > 0 && shown[b - 1].prim > shown[b].prim {
            shown.swap(b - 1, b);
            b -= 1;
        }
    }
    let mut sum = [0.0f32; 3];
    let mut k = 0;
    while k < shown.len() {
        let (prim, rgb) = (shown[k].prim, shown[k].rgb);
        let mut samples = 0;
        while k < shown.len() && shown[k].prim == prim {
            samples += shown[k].samples;
            k += 1;
        }
        if samples > 0 {
            add(&mut sum, rgb, samples as f32);
        }
    }
    sum
}

/// How many samples each fragment of an opaque list (sorted by
/// [`crate::fragment::Fragment::order`]) is the front surface in, in
/// `shown` (one entry per fragment, list order): by whole masks when the
/// list order is every sample's order (`overlap` false), else sample by
/// sample in each sample's own depth order (depths from `pool` and
/// the planes of `tris`, the frame's binned triangles, at `positions`).
pub(crate) fn opaque_shown(
    frags: &[Shaded],
    overlap: bool,
    (pool, tris): (&FragmentPool, &[BinItem]),
    ij: (u32, u32),
    positions: &[(i32, i32)],
    shown: &mut Vec<Shown>,
) {
    shown.clear();
    shown.extend(frags.iter().map(|s| Shown {
        prim: s.frag.prim,
        samples: 0,
        rgb: s.rgb,
    }));
    if !overlap {
        let mut alive = u32::MAX;
        for (s, out) in frags.iter().zip(shown.iter_mut()) {
            out.samples = (s.frag.mask & alive).count_ones();
            alive &= !s.frag.mask;
        }
        return;
    }
    for k in 0..positions.len() {
        let mut best: Option<(f32, u32, usize)> = None;
        for (i, s) in frags.iter().enumerate() {
            if s.frag.mask >> k & 1 == 1 {
                let plane = &tris[s.frag.tri as usize].plane;
                let z = pool.sample_depth(plane, &s.frag, ij, positions, k);
                let nearer = best
                    .is_none_or(|(bz, bp, _)| z.total_cmp(&bz).then(s.frag.prim.cmp(&bp)).is_lt());
                if nearer {
                    best = Some((z, s.frag.prim, i));
                }
            }
        }
        if let Some((_, _, i)) = best {
            shown[i].samples += 1;
        }
    }
}

/// Sample-by-sample compositing of the fragments of pixel `ij` in each
/// sample's own depth order (the depths from `pool` and the planes of `tris`, at
/// `positions`); `samples` is scratch memory.
pub(crate) fn per_sample(
    frags: &[Shaded],
    samples: &mut Vec<(f32, u32, u32)>,
    (pool, tris): (&FragmentPool, &[BinItem]),
    ij: (u32, u32),
    positions: &[(i32, i32)],
) -> [f32; 3] {
    let mut sum = [0.0f32; 3];
    for k in 0..positions.len() {
        samples.clear();
        for (i, s) in frags.iter().enumerate() {
            if s.frag.mask >> k & 1 == 1 {
                let plane = &tris[s.frag.tri as usize].plane;
                let z = pool.sample_depth(plane, &s.frag, ij, positions, k);
                samples.push((z, s.frag.prim, i as u32));
            }
        }
        samples.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut transmit = 1.0f32;
        for &(_, _, i) in samples.iter() {
            let s = &frags[i as usize];
            add(&mut sum, s.rgb, transmit * s.alpha);
            transmit *= 1.0 - s.alpha;
            if transmit <= 0.0 {
                break;
            }
        }
    }
    sum
}

/// Carpenter's blender on an explicit stack (`stack` is scratch memory);
/// `crossing` enables the interpenetration estimate.
///
/// A fragment splits the current mask into the samples it covers and
/// those it does not; the ones it covers see its colour over (opacity)
/// what lies behind; where the next fragment starts before this one ends
/// in depth, the two are taken to cross inside the pixel, each as a plane
/// rising across its depth range, so this one is in front over the
/// fraction `vis = (zmax' - zmin) / ((zmax - zmin) + (zmax' - zmin'))` of
/// the covered samples. The result is linear in the colours, so each
/// pending `(fragment, mask)` carries the weight its colour sum enters
/// with. Masks split into disjoint parts, so a list of `L` fragments costs
/// at most `L * samples` steps.
pub(crate) fn blend(
    frags: &[Shaded],
    stack: &mut Vec<(u32, u32, f32)>,
    full: u32,
    crossing: bool,
) -> [f32; 3] {
    let mut sum = [0.0f32; 3];
    stack.clear();
    stack.push((0, full, 1.0));
    while let Some((start, mask, weight)) = stack.pop() {
        let rest = &frags[start as usize..];
        let Some(pos) = rest.iter().position(|s| s.frag.mask & mask != 0) else {
            continue; // background: black
        };
        let s = &rest[pos];
        let f = &s.frag;
        let next = start + pos as u32 + 1;
        let inside = mask & f.mask;
        let outside = mask & !f.mask;
        if outside != 0 {
            stack.push((next, outside, weight));
        }
        let behind = &frags[next as usize..];
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
            stack.push((next, inside, weight * behind_weight));
        }
    }
    sum
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
    use crate::fragment::Fragment;

    fn frag(mask: u32, zmin: f32, zmax: f32, rgb: [f32; 3], alpha: f32) -> Shaded {
        let f = Fragment::with_mask(mask, zmin, zmax);
        Shaded::new(f, [rgb[0], rgb[1], rgb[2], alpha], 0)
    }

    #[test]
    fn mask_path_weighs_masks_and_opacity() {
        // Left half red opaque; everything under a half-transparent green.
        let frags = [
            frag(u32::MAX, 0.1, 0.1, [0.0, 1.0, 0.0], 0.5),
            frag(0x0f0f_0f0f, 0.5, 0.5, [1.0, 0.0, 0.0], 1.0),
        ];
        let s = mask_path(&frags, u32::MAX);
        assert!((s[1] - 16.0).abs() < 1e-5, "{s:?}"); // 32 * 0.5
        assert!((s[0] - 8.0).abs() < 1e-5, "{s:?}"); // 16 * 0.5
        // The blender without crossings gives the same answer.
        let b = blend(&frags, &mut Vec::new(), u32::MAX, false);
        assert!((0..3).all(|c| (b[c] - s[c]).abs() < 1e-4), "{b:?} vs {s:?}");
    }

    #[test]
    fn crossing_estimate_splits_two_opposite_ramps_evenly() {
        // Two full-pixel fragments with the same depth range, crossing in
        // the middle: each is in front over half the pixel.
        let frags = [
            frag(u32::MAX, 0.4, 0.6, [1.0, 0.0, 0.0], 1.0),
            frag(u32::MAX, 0.4, 0.6, [0.0, 0.0, 1.0], 1.0),
        ];
        let mut stack = Vec::new();
        let s = blend(&frags, &mut stack, u32::MAX, true);
        assert!(
            (s[0] - 16.0).abs() < 1e-4 && (s[2] - 16.0).abs() < 1e-4,
            "{s:?}"
        );
        let s = blend(&frags, &mut stack, u32::MAX, false);
        assert_eq!(s, [32.0, 0.0, 0.0]);
    }
}
