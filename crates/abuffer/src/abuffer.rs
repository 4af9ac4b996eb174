//! The A-buffer hider: fragment generation, insertion, merging, culling
//! and the overflow policy. Resolving the lists is in [`crate::resolve`].
//!
//! Carpenter (1984), "The A-buffer, an antialiased hidden surface method":
//! every primitive is scan-converted into *fragments*, one per pixel it
//! touches, each carrying a coverage mask (8 x 4 bits), its depth range,
//! colour and opacity. Nothing is decided while primitives arrive, except
//! what is provably invisible: a fragment entirely behind an opaque
//! fragment that covers the whole pixel is dropped (the paper's pixels hold
//! a plain depth in that case). Once every primitive is in, each pixel's
//! list is sorted and composited front to back ([`crate::resolve`]). The
//! result does not depend on the order primitives are submitted in, which
//! is what makes its transparency correct where a z-buffer's is not.

use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, ScreenTri, Stats, check_frame};

use crate::coverage::{Coverage, TriCoverage, pixel_range, sample_depth};
use crate::fragment::{Fragment, FragmentPool, NIL};
use crate::options::{ABufferOptions, DepthMode, MergePolicy, OverflowPolicy};
use crate::palette::prim_colors;
use crate::pattern::{CENTRE, MAX_SAMPLES};
use crate::resolve::{Resolver, hidden_in_every_sample};
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

/// A new occluder prunes the fragments behind it only from lists longer
/// than this. Measured on `random_soup(10_000)` at 1024 x 1024: pruning
/// every list costs a fifth of the frame in cache misses; the resolve
/// skips hidden fragments exactly, so short lists are left alone.
pub const PRUNE_LIST_LEN: u32 = 4;

/// Carpenter's A-buffer. See the crate documentation.
#[derive(Clone, Debug, Default)]
pub struct ABuffer {
    options: ABufferOptions,
    pool: FragmentPool,
    colors: Vec<[f32; 4]>,
    resolver: Resolver,
    width: u32,
    height: u32,
    last: ABufferStats,
}

impl ABuffer {
    /// An A-buffer with the given options.
    pub fn new(options: ABufferOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
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
        let n = self.options.pattern.count();
        let pixels = self.width as usize * self.height as usize;
        let per_sample = self.options.depth == DepthMode::PerSample;
        let mut out = vec![NO_ID; pixels * n];
        let mut best = vec![f32::INFINITY; n];
        for p in 0..pixels {
            best.fill(f32::INFINITY);
            let ids = &mut out[p * n..(p + 1) * n];
            let mut cur = self.pool.head(p);
            while cur != NIL {
                let f = self.pool.get(cur);
                let depths = self.pool.depths(cur);
                for k in (0..n).filter(|&k| f.mask >> k & 1 == 1) {
                    let z = if per_sample { depths[k] } else { f.zmin };
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

    /// Depth range of a fragment and, in per-sample mode, its sample
    /// depths (`INFINITY` for uncovered samples).
    fn fragment_depths(
        &self,
        tri: &ScreenTri,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
        depths: &mut [f32; MAX_SAMPLES],
    ) -> (f32, f32) {
        let pattern = self.options.pattern;
        let (mut lo, mut hi) = if c.centre {
            (centre_z, centre_z)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
        let mut see = |z: f64| {
            lo = lo.min(z);
            hi = hi.max(z);
        };
        if self.options.depth == DepthMode::PerSample {
            for (k, &pos) in pattern.positions().iter().enumerate() {
                depths[k] = if c.mask >> k & 1 == 1 {
                    let z = sample_depth(tri, i, j, pos);
                    see(z);
                    z as f32
                } else {
                    f32::INFINITY
                };
            }
        } else if c.full {
            // The plane is affine: its extremes over the samples lie at the
            // corners of their hull.
            let (x0, y0, x1, y1) = pattern.hull();
            for pos in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
                see(sample_depth(tri, i, j, pos));
            }
        } else {
            for (k, &pos) in pattern.positions().iter().enumerate() {
                if c.mask >> k & 1 == 1 {
                    see(sample_depth(tri, i, j, pos));
                }
            }
        }
        // `as f32` rounds to nearest, which is monotonic: every stored
        // sample depth and the centre depth stay inside [zmin, zmax], so the
        // strict comparisons of culling and pruning stay exact.
        (lo as f32, hi as f32)
    }

    /// Adds fragment `f` to pixel `p`.
    fn insert(
        &mut self,
        scene: &ScreenScene,
        p: usize,
        f: Fragment,
        depths: &[f32],
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let full = self.options.pattern.full_mask();
        if f.zmin > self.pool.pixel(p).occluder {
            stats.culled += 1;
            return Ok(());
        }
        // A full mask has no disjoint partner: interior pixels skip the
        // search (and its cache misses) entirely.
        if self.options.merge != MergePolicy::Off
            && f.mask != full
            && let Some(idx) = self.try_merge(scene, p, &f, depths)
        {
            stats.merged += 1;
            let merged = *self.pool.get(idx);
            self.note_occluder(p, &merged, full, stats);
            return Ok(());
        }
        if self.pool.len(p) >= self.options.max_list_len {
            stats.pruned += self.prune_hidden(p, full);
        }
        if self.pool.len(p) >= self.options.max_list_len {
            match self.options.overflow {
                OverflowPolicy::Error => {
                    let w = self.width as usize;
                    return Err(Error::Render {
                        hider: "abuffer".into(),
                        message: format!(
                            "pixel ({}, {}) needs more than {} fragments (max_list_len); \
                             raise it or use OverflowPolicy::DropFarthest",
                            p % w,
                            p / w,
                            self.options.max_list_len
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
                }
            }
        }
        let idx = self.pool.alloc(f, depths)?;
        self.pool.push_front(p, idx);
        self.note_occluder(p, &f, full, stats);
        Ok(())
    }

    /// If `f` is an opaque fragment covering every sample and the centre and
    /// nearer than the pixel's occluder, makes it the occluder and prunes
    /// the fragments entirely behind it.
    fn note_occluder(&mut self, p: usize, f: &Fragment, full: u32, stats: &mut ABufferStats) {
        let e = *self.pool.pixel(p);
        if f.mask == full && f.covers_centre() && f.alpha >= 1.0 && f.zmax < e.occluder {
            let z = f.zmax;
            self.pool.set_occluder(p, z);
            // Walk the list (a cache miss per fragment) only if something
            // may be behind and the list is long enough to be worth it:
            // short lists are cheaper to leave to the resolve, which skips
            // hidden fragments exactly anyway.
            if e.far > z && e.len > PRUNE_LIST_LEN {
                stats.pruned += self.pool.remove_where(p, |g| g.zmin > z);
            }
        }
    }

    /// Removes the fragments of pixel `p` hidden in every sample and at the
    /// centre by nearer opaque fragments; returns how many.
    fn prune_hidden(&mut self, p: usize, full: u32) -> u64 {
        let mut list = Vec::new();
        let mut cur = self.pool.head(p);
        while cur != NIL {
            list.push(*self.pool.get(cur));
            cur = self.pool.get(cur).next;
        }
        self.pool
            .remove_where(p, |g| hidden_in_every_sample(g, &list, full))
    }

    /// Looks for a merge partner of `f` among the first fragments of pixel
    /// `p`'s list and merges into it, returning its index.
    fn try_merge(
        &mut self,
        scene: &ScreenScene,
        p: usize,
        f: &Fragment,
        depths: &[f32],
    ) -> Option<u32> {
        let tri = &scene.tris[f.tri as usize];
        let material = scene.prims[f.prim as usize].material;
        let mut cur = self.pool.head(p);
        for _ in 0..MERGE_SEARCH {
            if cur == NIL {
                return None;
            }
            let g = *self.pool.get(cur);
            // Fields of the fragment first; the scene lookups last.
            let mergeable = g.mask & f.mask == 0
                && !(g.covers_centre() && f.covers_centre())
                && g.alpha == f.alpha
                && (self.options.merge == MergePolicy::SameSurface
                    || (0..3).all(|c| (g.rgb[c] - f.rgb[c]).abs() <= MERGE_COLOR_TOLERANCE))
                && {
                    let other = &scene.tris[g.tri as usize];
                    other.front_facing == tri.front_facing
                        && scene.prims[g.prim as usize].material == material
                        && tri.v.iter().any(|v| other.v.contains(v))
                };
            if mergeable {
                let (wg, wf) = (g.mask.count_ones() as f32, f.mask.count_ones() as f32);
                let m = self.pool.get_mut(cur);
                if wg + wf > 0.0 {
                    m.rgb = [0, 1, 2].map(|c| (g.rgb[c] * wg + f.rgb[c] * wf) / (wg + wf));
                }
                m.mask |= f.mask;
                m.zmin = g.zmin.min(f.zmin);
                m.zmax = g.zmax.max(f.zmax);
                m.prim = g.prim.min(f.prim);
                m.tri = f.tri;
                if f.covers_centre() {
                    m.centre_z = f.centre_z;
                    m.centre_prim = f.centre_prim;
                }
                let stored = self.pool.depths_mut(cur);
                for (k, d) in stored.iter_mut().enumerate() {
                    if f.mask >> k & 1 == 1 {
                        *d = depths[k];
                    }
                }
                return Some(cur);
            }
            cur = g.next;
        }
        None
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
        let pattern = self.options.pattern;
        let stride = match self.options.depth {
            DepthMode::PerSample => pattern.count(),
            _ => 0,
        };
        self.pool
            .reset(w as usize * h as usize, stride, self.options.max_bytes)?;
        let mut colors = std::mem::take(&mut self.colors);
        prim_colors(scene, self.options.shade, &mut colors);
        let mut stats = ABufferStats::default();
        let mut depths = [f32::INFINITY; MAX_SAMPLES];
        let result = (|| {
            for (t, tri) in scene.tris.iter().enumerate() {
                let Some((x0, y0, x1, y1)) = pixel_range(tri, pattern, w, h) else {
                    continue;
                };
                let setup = TriCoverage::new(tri, pattern);
                let [r, g, b, alpha] = colors[tri.prim as usize];
                for j in y0..=y1 {
                    for (i, c) in setup.row(x0, x1, j) {
                        stats.fragments += 1;
                        stats.full_coverage += u64::from(c.full);
                        let centre_z = if c.centre {
                            sample_depth(tri, i, j, CENTRE)
                        } else {
                            f64::INFINITY
                        };
                        let (zmin, zmax) =
                            self.fragment_depths(tri, (i, j), c, centre_z, &mut depths);
                        let f = Fragment {
                            next: NIL,
                            mask: c.mask,
                            prim: tri.prim,
                            tri: t as u32,
                            centre_prim: if c.centre { tri.prim } else { NO_ID },
                            zmin,
                            zmax,
                            centre_z,
                            rgb: [r, g, b],
                            alpha,
                        };
                        let p = j as usize * w as usize + i as usize;
                        self.insert(scene, p, f, &depths, &mut stats)?;
                    }
                }
            }
            Ok::<(), Error>(())
        })();
        self.colors = colors;
        result?;
        self.resolver
            .resolve(&self.pool, &self.options, frame, &mut stats);
        stats.pool_fragments = self.pool.peak_fragments() as u64;
        stats.bytes = self.pool.peak_bytes();
        self.last = stats;
        Ok(stats.into())
    }

    fn resolves_color(&self) -> bool {
        true
    }
}
