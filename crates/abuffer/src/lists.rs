//! The per-pixel fragment lists: insertion, merging of neighbouring
//! fragments of one surface, and the overflow policy.
//!
//! A fragment that survived culling goes to the front of its pixel's list
//! (a mesh's triangles arrive together, so its merge partner is near the
//! front), unless it merges into a neighbour of the same surface
//! (Carpenter's merge, [`MergePolicy`]). An opaque fragment may then lower
//! the pixel's opaque bound ([`crate::culling`]). A list at its length
//! bound is first pruned of the fragments hidden in every sample (exact);
//! if still full, the overflow policy fails the frame or drops the
//! farthest fragment.

use hider_scene::{Error, Result};

use crate::coverage::Coverage;
use crate::culling::{Culling, HiddenScratch, hidden_fragments, key_at_or_beyond};
use crate::depth::plane_depth;
use crate::fragment::{Fragment, MERGED_BASE, NIL, Shaded};
use crate::options::{ABufferOptions, DepthMode, MergePolicy, OverflowPolicy};
use crate::pattern::MAX_SAMPLES;
use crate::pool::FragmentPool;
use crate::source::{ColorCache, Source};
use crate::stats::ABufferStats;

/// Two colour channels closer than this count as equal for
/// [`MergePolicy::SameColor`]: far below one step of an 8-bit output
/// (1/255), so a merge never changes the image.
pub(crate) const MERGE_COLOR_TOLERANCE: f32 = 1e-5;

/// How many fragments at the front of a list are tried as merge partners.
/// The partner is the fragment of the neighbouring triangle, inserted
/// recently (a mesh's triangles arrive together), so a short search finds
/// it without making insertion cost grow with the list.
pub(crate) const MERGE_SEARCH: usize = 8;

/// Where a fragment goes, besides the fragment.
pub(crate) struct Ctx<'a> {
    /// The scene being rendered.
    pub(crate) scene: &'a Source<'a>,
    /// Index of the pixel in the frame.
    pub(crate) p: usize,
    /// The pixel.
    pub(crate) ij: (u32, u32),
    /// Index of the pixel in the tile (row-major, [`crate::bins::TILE`]
    /// per row).
    pub(crate) g: usize,
    /// Opacity of the fragment's primitive.
    pub(crate) alpha: f32,
}

/// The fragment lists of a frame and what filling them needs.
#[derive(Clone, Debug, Default)]
pub(crate) struct Lists {
    /// The lists and their fragments.
    pub(crate) pool: FragmentPool,
    /// Colour and opacity per primitive, computed on first use.
    pub(crate) colors: ColorCache,
    /// Opaque bounds being gathered, block bounds.
    pub(crate) culling: Culling,
    /// A list with its colours, while pruning.
    scratch: Vec<Shaded>,
    /// Which fragments of `scratch` are hidden, while pruning.
    hidden: Vec<bool>,
    /// Scratch of the pruning sweep.
    hidden_scratch: HiddenScratch,
    /// The options of the frame.
    options: ABufferOptions,
}

impl Lists {
    /// Starts a frame of `scene` with `options`: empty lists, no colour
    /// computed. Whether the pixel table was allocated afresh (see
    /// [`FragmentPool::reset`]).
    pub(crate) fn begin_frame(
        &mut self,
        scene: &Source<'_>,
        options: &ABufferOptions,
    ) -> Result<bool> {
        self.options = *options;
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        let per_sample = options.depth == DepthMode::PerSample;
        let fresh = self
            .pool
            .reset(w as usize * h as usize, per_sample, options.max_bytes)?;
        self.colors.begin(scene.prims());
        Ok(fresh)
    }

    /// The options of the frame.
    pub(crate) fn options(&self) -> &ABufferOptions {
        &self.options
    }

    /// The colour and opacity of shading index `shade` in pixel `ij` (a
    /// primitive's flat colour computed on first use, textured at the pixel
    /// centre).
    #[inline]
    pub(crate) fn rgba(&mut self, scene: &Source<'_>, shade: u32, ij: (u32, u32)) -> [f32; 4] {
        if shade >= MERGED_BASE {
            self.pool.merged(shade).rgba
        } else {
            self.colors.at_pixel(scene, self.options.shade, shade, ij)
        }
    }

    /// Adds fragment `f` (which survived culling, with coverage `c`) to
    /// pixel `ctx.p`.
    pub(crate) fn insert(
        &mut self,
        ctx: &Ctx<'_>,
        f: Fragment,
        c: Coverage,
        stats: &mut ABufferStats,
    ) -> Result<()> {
        let full = self.options.pattern.full_mask();
        // A full mask has no disjoint partner: interior pixels skip the
        // search entirely.
        if self.options.merge != MergePolicy::Off
            && !c.full
            && f.mask != full
            && let Some(idx) = self.try_merge(ctx, &f)?
        {
            stats.merged += 1;
            if ctx.alpha >= 1.0 {
                self.culling.opaque_entered(ctx.g);
            }
            let merged = *self.pool.get(idx);
            self.note_opaque(ctx, &f, &merged, stats);
            return Ok(());
        }
        if !self.make_room(ctx, &f, stats)? {
            return Ok(());
        }
        let idx = self.pool.alloc(f)?;
        self.pool.push_front(ctx.p, idx);
        self.culling.entered(ctx.g, (f.zmin, f.prim));
        if ctx.alpha >= 1.0 {
            self.culling.opaque_entered(ctx.g);
        }
        self.note_opaque(ctx, &f, &f, stats);
        Ok(())
    }

    /// Makes room for `f` in a list at its length bound: prunes the
    /// fragments hidden in every sample, then applies the overflow policy.
    /// False when `f` itself is the one dropped.
    fn make_room(&mut self, ctx: &Ctx<'_>, f: &Fragment, stats: &mut ABufferStats) -> Result<bool> {
        let p = ctx.p;
        let max = self.options.max_list_len;
        if self.pool.len(p) >= max && self.culling.take_prune(ctx.g) {
            let full = self.options.pattern.full_mask();
            stats.pruned += self.prune_hidden(ctx.scene, p, full);
        }
        if self.pool.len(p) < max {
            return Ok(true);
        }
        match self.options.overflow {
            OverflowPolicy::Error => Err(Error::Render {
                hider: "abuffer".into(),
                message: format!(
                    "pixel ({}, {}) needs more than {} fragments (max_list_len); \
                     raise it or use OverflowPolicy::DropFarthest",
                    ctx.ij.0, ctx.ij.1, max
                ),
            }),
            OverflowPolicy::DropFarthest => {
                stats.dropped += 1;
                let key = (f.zmin, f.prim);
                if self
                    .culling
                    .far_bound(ctx.g)
                    .is_some_and(|bound| key_at_or_beyond(key, bound))
                {
                    // No fragment of the list comes after `f`: it is the
                    // farthest, dropped without a walk (hundreds of
                    // coincident translucent layers arrive this way).
                    return Ok(false);
                }
                let mut far = *f;
                let mut cur = self.pool.head(p);
                while cur != NIL {
                    let g = self.pool.get(cur);
                    if g.order(&far).is_gt() {
                        far = *g;
                    }
                    cur = g.next;
                }
                self.culling.set_far_bound(ctx.g, (far.zmin, far.prim));
                if far == *f {
                    return Ok(false);
                }
                let mut once = true;
                self.pool.remove_where(p, |g| {
                    let hit = once && *g == far;
                    once &= !hit;
                    hit
                });
                // What was gathered may have included it.
                self.culling.forget(ctx.g);
                Ok(true)
            }
        }
    }

    /// After opaque fragment `f` entered pixel `ctx.p` (as itself or merged
    /// into `m`): updates the pixel's opaque bound and prunes what lies
    /// behind it ([`Culling::note_opaque`]), unless culling is off.
    fn note_opaque(&mut self, ctx: &Ctx<'_>, f: &Fragment, m: &Fragment, stats: &mut ABufferStats) {
        if ctx.alpha < 1.0 || !self.options.occlusion_culling {
            return;
        }
        let full = self.options.pattern.full_mask();
        stats.pruned += self
            .culling
            .note_opaque(&mut self.pool, full, (ctx.p, ctx.g), f, m);
    }

    /// Removes the fragments of pixel `p` hidden in every sample and at the
    /// centre by nearer opaque fragments; returns how many.
    fn prune_hidden(&mut self, scene: &Source<'_>, p: usize, full: u32) -> u64 {
        let mut list = std::mem::take(&mut self.scratch);
        list.clear();
        let w = scene.viewport.width as usize;
        let ij = ((p % w) as u32, (p / w) as u32);
        let mut cur = self.pool.head(p);
        while cur != NIL {
            let f = *self.pool.get(cur);
            list.push(Shaded::new(f, self.rgba(scene, f.shade, ij), cur));
            cur = f.next;
        }
        let mut hidden = std::mem::take(&mut self.hidden);
        hidden_fragments(&list, full, &mut self.hidden_scratch, &mut hidden);
        let mut k = 0;
        let removed = self.pool.remove_where(p, |_| {
            k += 1;
            hidden[k - 1]
        });
        self.scratch = list;
        self.hidden = hidden;
        removed
    }

    /// Looks for a merge partner of `f` among the first fragments of pixel
    /// `ctx.p`'s list and merges into it, returning its index.
    fn try_merge(&mut self, ctx: &Ctx<'_>, f: &Fragment) -> Result<Option<u32>> {
        let scene = ctx.scene;
        // `f`'s colour only once a partner passes the mask tests: on a
        // pile of fragments that all cover the centre none does, and the
        // colour lookup is a cache miss per primitive.
        let mut f_color = None;
        let mut cur = self.pool.head(ctx.p);
        for _ in 0..MERGE_SEARCH {
            if cur == NIL {
                return Ok(None);
            }
            let g = *self.pool.get(cur);
            // Fields of the fragment first; the colours and the scene
            // lookups last.
            if g.mask & f.mask != 0 || (g.covers_centre() && f.covers_centre()) {
                cur = g.next;
                continue;
            }
            let f_rgba = match f_color {
                Some(c) => c,
                None => *f_color.insert(self.rgba(scene, f.shade, ctx.ij)),
            };
            let g_rgba = self.rgba(scene, g.shade, ctx.ij);
            let mergeable = g_rgba[3] == f_rgba[3]
                && (self.options.merge == MergePolicy::SameSurface
                    || (0..3).all(|c| (g_rgba[c] - f_rgba[c]).abs() <= MERGE_COLOR_TOLERANCE))
                && {
                    // Scene lookups (cache misses) only for candidates.
                    let (tri, other) = (&scene.items[f.tri as usize], &scene.items[g.tri as usize]);
                    other.front_facing == tri.front_facing
                        && scene.material(g.prim) == scene.material(f.prim)
                        && tri.v.iter().any(|v| other.v.contains(v))
                };
            if mergeable {
                self.merge_into(ctx, cur, (g, g_rgba), (f, f_rgba))?;
                return Ok(Some(cur));
            }
            cur = g.next;
        }
        Ok(None)
    }

    /// Merges `f` (colour `f_rgba`) into fragment `g` (colour `g_rgba`) at
    /// index `idx` of pixel `ctx.p`'s list.
    fn merge_into(
        &mut self,
        ctx: &Ctx<'_>,
        idx: u32,
        (g, g_rgba): (Fragment, [f32; 4]),
        (f, f_rgba): (&Fragment, [f32; 4]),
    ) -> Result<()> {
        let (i, j) = ctx.ij;
        let tris = ctx.scene.items;
        let (wg, wf) = (g.mask.count_ones() as f32, f.mask.count_ones() as f32);
        let mut rgba = g_rgba;
        if wg + wf > 0.0 {
            for c in 0..3 {
                rgba[c] = (g_rgba[c] * wg + f_rgba[c] * wf) / (wg + wf);
            }
        }
        let keep_depths = self.options.depth == DepthMode::PerSample;
        let positions = self.options.pattern.positions();
        let shade = if g.is_merged() {
            self.pool.merged_mut(g.shade).rgba = rgba;
            g.shade
        } else {
            // The first merge into `g`: its shading and (per-sample mode)
            // its sample depths move to a merged entry.
            let mut depths = [f32::INFINITY; MAX_SAMPLES];
            if keep_depths {
                let plane = &tris[g.tri as usize].plane;
                for (k, &pos) in positions.iter().enumerate() {
                    if g.mask >> k & 1 == 1 {
                        depths[k] = plane_depth(plane, i, j, pos) as f32;
                    }
                }
            }
            self.pool.add_merged(rgba, &depths)?
        };
        if keep_depths {
            let plane = tris[f.tri as usize].plane;
            let stored = self.pool.merged_depths_mut(shade);
            for (k, &pos) in positions.iter().enumerate() {
                if f.mask >> k & 1 == 1 {
                    stored[k] = plane_depth(&plane, i, j, pos) as f32;
                }
            }
        }
        let m = self.pool.get_mut(idx);
        m.shade = shade;
        m.mask |= f.mask;
        m.zmin = g.zmin.min(f.zmin);
        m.zmax = g.zmax.max(f.zmax);
        m.prim = g.prim.min(f.prim);
        m.tri = f.tri;
        if f.covers_centre() {
            m.centre_z = f.centre_z;
            m.centre_prim = f.centre_prim;
        }
        // The pixel's `far` stays an upper bound: the merged zmin is at
        // most g's.
        Ok(())
    }
}
