//! Resolving the fragment lists: sort, then composite front to back.
//!
//! Per pixel the list is sorted by `zmin` (lower primitive id first on
//! ties), then:
//! - **ids and depth**: the front-most fragment covering the pixel centre,
//!   by its exact `f64` centre depth (see [`crate::centre`]);
//! - **coverage**: covered samples of the union of all masks / samples;
//! - **colour**, summed over samples and divided by their number
//!   (the black background adds nothing), linear, then sRGB
//!   ([`crate::composite`]); a list of opaque fragments in
//!   [`DepthMode::PerSample`] counts the samples each primitive is in
//!   front in (by whole masks, or sample by sample where fragments
//!   overlap) and sums `colour * samples` by ascending primitive id, the
//!   canonical order the sample buffer of opaque tiles sums in too
//!   ([`crate::composite::opaque_sum`]); otherwise:
//!   - [`DepthMode::PerSample`]: when no two fragments with intersecting
//!     masks overlap in depth, the list order is every sample's order and
//!     the *mask path* composites whole masks at once (an opaque fragment
//!     costs one popcount); otherwise each sample sorts the fragments that
//!     cover it by their own depth at that sample (the triangle's plane at
//!     the sample, recomputed here with the expression that made the
//!     bounds, or a merged fragment's stored depths) — exact at
//!     intersections;
//!   - [`DepthMode::MinMax`]: Carpenter's `blender`, with the paper's
//!     estimate of where two fragments overlapping in depth cross;
//!   - [`DepthMode::ZminOrder`]: the same without the crossing estimate.
//!
//! A pixel is resolved right after its tile is rendered (its list is still
//! in cache); lists of one opaque fragment, or two opaque fragments with
//! disjoint masks, take shortcuts computing what every path computes for
//! them; neighbouring pixels with the same colour sum reuse the last sRGB
//! conversion, which is exact and table-driven ([`crate::palette`]).

use hider_scene::frame::{BACKGROUND, BACKGROUND_DEPTH};
use hider_scene::{Frame, NO_ID};

use crate::centre::in_front;
use crate::composite::{
    Shown, blend, mask_path, opaque_shown, opaque_sum, overlapping, per_sample,
};
use crate::fragment::{Fragment, NIL, Shaded};
use crate::options::{ABufferOptions, DepthMode};
use crate::palette::{Srgb, to_pixel};
use crate::pattern::SamplePattern;
use crate::pool::FragmentPool;
use crate::source::{ColorCache, Source};
use crate::stats::ABufferStats;

/// What the resolve reads: the lists, and how to colour their fragments.
pub(crate) struct Input<'a> {
    /// The scene the lists were made from.
    pub(crate) scene: &'a Source<'a>,
    /// The lists.
    pub(crate) pool: &'a FragmentPool,
    /// Colour and opacity per primitive, computed on first use.
    pub(crate) colors: &'a mut ColorCache,
    /// The options of the frame.
    pub(crate) options: &'a ABufferOptions,
}

impl Input<'_> {
    /// The colour and opacity of primitive `prim` in pixel `ij` (computed
    /// on first use, textured at the pixel centre).
    #[inline]
    pub(crate) fn prim_rgba(&mut self, prim: u32, ij: (u32, u32)) -> [f32; 4] {
        self.colors
            .at_pixel(self.scene, self.options.shade, prim, ij)
    }

    /// The colour and opacity of fragment `f` in pixel `ij` (textured at
    /// the pixel centre).
    #[inline]
    pub(crate) fn rgba(&mut self, f: &Fragment, ij: (u32, u32)) -> [f32; 4] {
        if f.is_merged() {
            self.pool.merged(f.shade).rgba
        } else {
            self.prim_rgba(f.shade, ij)
        }
    }
}

/// The rows of a frame that one band of tiles resolves into: the frame's
/// buffers from pixel `first` on (row-major), so that bands resolved by
/// different threads write disjoint memory.
pub(crate) struct Band<'a> {
    /// Frame width in pixels.
    pub(crate) width: usize,
    /// Index in the frame of the band's first pixel.
    pub(crate) first: usize,
    /// Visible primitive ids of the band's pixels.
    pub(crate) ids: &'a mut [u32],
    /// Window depths.
    pub(crate) depth: &'a mut [f32],
    /// Colours.
    pub(crate) color: &'a mut [[u8; 4]],
    /// Covered fractions.
    pub(crate) coverage: &'a mut [f32],
}

impl<'a> Band<'a> {
    /// `frame` cut into bands of `rows` rows each, top to bottom.
    pub(crate) fn split(frame: &'a mut Frame, rows: usize) -> Vec<Self> {
        let width = frame.width() as usize;
        let n = rows * width;
        frame
            .ids
            .chunks_mut(n)
            .zip(frame.depth.chunks_mut(n))
            .zip(frame.color.chunks_mut(n).zip(frame.coverage.chunks_mut(n)))
            .enumerate()
            .map(|(b, ((ids, depth), (color, coverage)))| Self {
                width,
                first: b * n,
                ids,
                depth,
                color,
                coverage,
            })
            .collect()
    }

    /// Clears the band: no id, the background's depth and colour, no
    /// coverage (what [`Frame::clear`] does to the whole frame, with the
    /// same constants).
    pub(crate) fn clear(&mut self) {
        self.ids.fill(NO_ID);
        self.depth.fill(BACKGROUND_DEPTH);
        self.color.fill(BACKGROUND);
        self.coverage.fill(0.0);
    }

    /// Writes the id and depth of frame pixel `p`.
    #[inline]
    pub(crate) fn set_id(&mut self, p: usize, id: u32, z: f32) {
        self.ids[p - self.first] = id;
        self.depth[p - self.first] = z;
    }

    /// Writes the covered fraction of frame pixel `p`.
    #[inline]
    pub(crate) fn set_coverage(&mut self, p: usize, c: f32) {
        self.coverage[p - self.first] = c;
    }
}

/// The sample pattern's numbers, per tile.
pub(crate) struct Samples {
    /// The mask of every sample.
    pub(crate) full: u32,
    /// One over the sample count.
    pub(crate) inv_n: f32,
    srgb: Srgb,
}

impl Samples {
    /// The numbers of `pattern`.
    pub(crate) fn new(pattern: SamplePattern) -> Self {
        Self {
            full: pattern.full_mask(),
            inv_n: 1.0 / pattern.count() as f32,
            srgb: Srgb::new(),
        }
    }
}

/// Scratch memory of the resolve, kept between frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct Resolver {
    frags: Vec<Shaded>,
    samples: Vec<(f32, u32, u32)>,
    stack: Vec<(u32, u32, f32)>,
    shown: Vec<Shown>,
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
    pub(crate) fn begin(&mut self) {
        self.lists = 0;
        self.total = 0;
        self.memo = ([0.0; 3], to_pixel([0.0; 3]));
    }

    /// The lists resolved since [`Self::begin`] and their total length.
    pub(crate) fn list_counts(&self) -> (u64, u64) {
        (self.lists, self.total)
    }

    /// Resolves the pixels of rectangle `(x0, y0, x1, y1)` of `input` into
    /// `frame`, the band of the frame that holds them.
    pub(crate) fn resolve_tile(
        &mut self,
        input: &mut Input<'_>,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        frame: &mut Band<'_>,
        stats: &mut ABufferStats,
    ) {
        let k = Samples::new(input.options.pattern);
        let w = frame.width;
        for j in y0..=y1 {
            for i in x0..=x1 {
                let p = j as usize * w + i as usize;
                let head = input.pool.head(p);
                if head == NIL {
                    continue;
                }
                if !self.no_shortcuts && self.shortcut(input, &k, (p, (i, j)), frame, stats) {
                    continue;
                }
                self.general(input, &k, (p, (i, j)), frame, stats);
            }
        }
    }

    /// Writes the colour of colour sum `sum` (already divided by the sample
    /// count) to pixel `p`.
    #[inline]
    pub(crate) fn write_color(
        &mut self,
        k: &Samples,
        sum: [f32; 3],
        frame: &mut Band<'_>,
        p: usize,
    ) {
        frame.color[p - frame.first] = self.color(k, sum);
    }

    /// The pixel colour of colour sum `sum` (already divided by the sample
    /// count).
    #[inline]
    pub(crate) fn color(&mut self, k: &Samples, sum: [f32; 3]) -> [u8; 4] {
        if sum != self.memo.0 {
            self.memo = (sum, k.srgb.pixel(sum));
        }
        self.memo.1
    }

    /// Resolves pixel `p` when its list is one opaque fragment, or two
    /// opaque fragments with disjoint masks, computing what every path
    /// computes for such a list; false (nothing written) for other lists.
    fn shortcut(
        &mut self,
        input: &mut Input<'_>,
        k: &Samples,
        (p, ij): (usize, (u32, u32)),
        frame: &mut Band<'_>,
        stats: &mut ABufferStats,
    ) -> bool {
        let pool = input.pool;
        let first = pool.get(pool.head(p));
        let opaque = |rgba: [f32; 4]| rgba[3] >= 1.0;
        let first_rgba = input.rgba(first, ij);
        if !opaque(first_rgba) {
            return false;
        }
        if first.next == NIL {
            self.lists += 1;
            self.total += 1;
            stats.max_list_len = stats.max_list_len.max(1);
            if first.centre_prim != NO_ID {
                frame.set_id(p, first.centre_prim, first.centre_z as f32);
            }
            frame.set_coverage(p, first.mask.count_ones() as f32 * k.inv_n);
            let weight = (first.mask & k.full).count_ones() as f32;
            let sum = [0, 1, 2].map(|c| (0.0 + first_rgba[c] * weight) * k.inv_n);
            self.write_color(k, sum, frame, p);
            return true;
        }
        let second = pool.get(first.next);
        if second.next != NIL || second.mask & first.mask != 0 {
            return false;
        }
        let second_rgba = input.rgba(second, ij);
        if !opaque(second_rgba) {
            return false;
        }
        // Two opaque fragments with disjoint masks: each shows all its
        // samples, so every path (mask path or blender, in either depth
        // order) adds `rgb * samples` of each to zero, and a sum of two
        // terms does not depend on their order; in per-sample mode two
        // fragments of one primitive count as one ([`opaque_sum`]), the
        // blender of the other modes adds them one by one.
        self.lists += 1;
        self.total += 2;
        stats.max_list_len = stats.max_list_len.max(2);
        let (mut z, mut id) = (f64::INFINITY, NO_ID);
        for f in [first, second] {
            if f.centre_prim != NO_ID && in_front(f.centre_z, f.centre_prim, z, id) {
                (z, id) = (f.centre_z, f.centre_prim);
            }
        }
        if id != NO_ID {
            frame.set_id(p, id, z as f32);
        }
        frame.set_coverage(p, (first.mask | second.mask).count_ones() as f32 * k.inv_n);
        let wa = (first.mask & k.full).count_ones() as f32;
        let wb = (second.mask & k.full).count_ones() as f32;
        let sum = if first.prim == second.prim && input.options.depth == DepthMode::PerSample {
            [0, 1, 2].map(|c| (0.0 + first_rgba[c] * (wa + wb)) * k.inv_n)
        } else {
            [0, 1, 2].map(|c| (0.0 + first_rgba[c] * wa + second_rgba[c] * wb) * k.inv_n)
        };
        self.write_color(k, sum, frame, p);
        true
    }

    /// Resolves pixel `p` (at `ij`) from its whole list, sorted.
    fn general(
        &mut self,
        input: &mut Input<'_>,
        k: &Samples,
        (p, ij): (usize, (u32, u32)),
        frame: &mut Band<'_>,
        stats: &mut ABufferStats,
    ) {
        self.frags.clear();
        let mut cur = input.pool.head(p);
        while cur != NIL {
            let f = input.pool.get(cur);
            let rgba = input.rgba(f, ij);
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
            frame.set_id(p, id, z as f32);
        }
        frame.set_coverage(p, union.count_ones() as f32 * k.inv_n);

        let sum = if len == 1 && self.frags[0].alpha >= 1.0 && !self.no_shortcuts {
            // What every path computes for one opaque fragment.
            let s = &self.frags[0];
            let weight = (s.frag.mask & k.full).count_ones() as f32;
            s.rgb.map(|c| 0.0 + c * weight)
        } else {
            let positions = input.options.pattern.positions();
            let lists = (input.pool, input.scene.items);
            let opaque = self.frags.iter().all(|s| s.alpha >= 1.0);
            match input.options.depth {
                DepthMode::PerSample if opaque => {
                    let overlap = overlapping(&self.frags);
                    stats.per_sample_pixels += u64::from(overlap);
                    let shown = &mut self.shown;
                    opaque_shown(&self.frags, overlap, lists, ij, positions, shown);
                    opaque_sum(shown)
                }
                DepthMode::PerSample if overlapping(&self.frags) => {
                    stats.per_sample_pixels += 1;
                    per_sample(&self.frags, &mut self.samples, lists, ij, positions)
                }
                DepthMode::PerSample => mask_path(&self.frags, k.full),
                DepthMode::MinMax => blend(&self.frags, &mut self.stack, k.full, true),
                DepthMode::ZminOrder => blend(&self.frags, &mut self.stack, k.full, false),
            }
        };
        let sum = sum.map(|c| c * k.inv_n);
        self.write_color(k, sum, frame, p);
    }
}
