//! Fragments and the pooled arena that holds the per-pixel lists.
//!
//! Carpenter's pixel holds either a depth or a pointer to a list of
//! fragments. Here every pixel has a [`PixelEntry`]: a list head (an index
//! into one pool, [`NIL`] when empty), a length, the `zmax` of the nearest
//! opaque fragment covering the whole pixel (the *occluder*, used to cull
//! and prune fragments hidden behind it) and the farthest `zmin` in the
//! list (so a new occluder walks the list only when it can prune). The
//! four share one 16-byte entry: a triangle touching a pixel costs one
//! cache line of the table, not four. Fragments live in one `Vec` reused
//! from frame to frame, with a free list for the slots of pruned
//! fragments, so no fragment costs an allocation. In per-sample depth mode
//! a second `Vec` holds `samples` depths per fragment at the same index.
//!
//! The memory bound is explicit: the pixel table is checked against
//! `max_bytes` before it is allocated, and the pool refuses the fragment
//! that would pass it, growing its buffers by at most doubling and never
//! beyond the bound.

use hider_scene::{Error, Result};

/// The "no fragment" index.
pub const NIL: u32 = u32::MAX;

/// One surface's share of one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment {
    /// Next fragment of the pixel's list, or [`NIL`].
    pub next: u32,
    /// Covered samples.
    pub mask: u32,
    /// Lowest primitive id merged into this fragment: the tie-break key
    /// between equal depths (lower id in front, as in every hider).
    pub prim: u32,
    /// Index in `ScreenScene::tris` of the last triangle merged in, for the
    /// adjacency test of the next merge.
    pub tri: u32,
    /// Primitive covering the pixel centre, or `NO_ID`.
    pub centre_prim: u32,
    /// Nearest window depth over the covered samples and the centre.
    pub zmin: f32,
    /// Farthest window depth over the covered samples and the centre.
    pub zmax: f32,
    /// Window depth at the pixel centre (`f64`, exactly what a pixel-centre
    /// z-buffer computes), `INFINITY` when the centre is not covered.
    pub centre_z: f64,
    /// Linear colour.
    pub rgb: [f32; 3],
    /// Opacity in [0, 1].
    pub alpha: f32,
}

impl Fragment {
    /// Whether the fragment covers the pixel centre.
    #[inline]
    pub fn covers_centre(&self) -> bool {
        self.centre_z.is_finite()
    }

    /// The resolve order: nearest `zmin` first, lower primitive id first on
    /// equal depths. Independent of submission order.
    #[inline]
    pub fn order(&self, other: &Fragment) -> std::cmp::Ordering {
        self.zmin
            .total_cmp(&other.zmin)
            .then(self.prim.cmp(&other.prim))
    }
}

/// One pixel's entry in the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelEntry {
    /// First fragment of the list, or [`NIL`].
    pub head: u32,
    /// Fragments in the list.
    pub len: u32,
    /// `zmax` of the nearest opaque fragment covering every sample and the
    /// centre (`INFINITY` when none).
    pub occluder: f32,
    /// An upper bound of the `zmin` of the fragments in the list
    /// (`-INFINITY` when it never held one).
    pub far: f32,
}

impl PixelEntry {
    const EMPTY: PixelEntry = PixelEntry {
        head: NIL,
        len: 0,
        occluder: f32::INFINITY,
        far: f32::NEG_INFINITY,
    };
}

/// Bytes of the per-pixel table per pixel.
pub const PIXEL_BYTES: u64 = std::mem::size_of::<PixelEntry>() as u64;

/// The per-pixel lists and the fragment pool.
#[derive(Clone, Debug, Default)]
pub struct FragmentPool {
    frags: Vec<Fragment>,
    depths: Vec<f32>,
    stride: usize,
    free: u32,
    pixels: Vec<PixelEntry>,
    cap: usize,
    max_bytes: u64,
    peak: usize,
}

impl FragmentPool {
    /// Empties the pool for a frame of `pixels` pixels, with `stride`
    /// per-sample depths per fragment (0 when not kept), under `max_bytes`.
    pub fn reset(&mut self, pixels: usize, stride: usize, max_bytes: u64) -> Result<()> {
        let table = pixels as u64 * PIXEL_BYTES;
        if table > max_bytes {
            return Err(Error::Limit {
                what: "A-buffer pixel table (bytes)",
                value: table,
                limit: max_bytes,
            });
        }
        self.stride = stride;
        self.max_bytes = max_bytes;
        self.cap = ((max_bytes - table) / Self::fragment_bytes(stride)) as usize;
        self.cap = self.cap.min(NIL as usize);
        self.frags.clear();
        self.depths.clear();
        self.free = NIL;
        self.peak = 0;
        self.pixels.clear();
        self.pixels.resize(pixels, PixelEntry::EMPTY);
        Ok(())
    }

    /// Bytes one fragment costs with `stride` per-sample depths.
    pub fn fragment_bytes(stride: usize) -> u64 {
        (std::mem::size_of::<Fragment>() + 4 * stride) as u64
    }

    /// Stores `f` (and its per-sample depths) in a free slot or a new one.
    pub fn alloc(&mut self, f: Fragment, depths: &[f32]) -> Result<u32> {
        let idx = if self.free != NIL {
            let idx = self.free;
            self.free = self.frags[idx as usize].next;
            self.frags[idx as usize] = f;
            idx
        } else {
            let len = self.frags.len();
            if len >= self.cap {
                return Err(Error::Limit {
                    what: "A-buffer working memory (bytes)",
                    value: self.table_bytes()
                        + (len as u64 + 1) * Self::fragment_bytes(self.stride),
                    limit: self.max_bytes,
                });
            }
            if len == self.frags.capacity() {
                // Grow by doubling, but never past the bound.
                let want = (2 * len).max(1024).min(self.cap) - len;
                self.frags.reserve_exact(want);
                self.depths.reserve_exact(want * self.stride);
            }
            self.frags.push(f);
            self.depths.extend_from_slice(&depths[..self.stride]);
            self.peak = self.peak.max(self.frags.len());
            len as u32
        };
        if self.stride > 0 {
            let s = idx as usize * self.stride;
            self.depths[s..s + self.stride].copy_from_slice(&depths[..self.stride]);
        }
        Ok(idx)
    }

    /// Returns slot `idx` to the free list (the caller has unlinked it).
    pub fn release(&mut self, idx: u32) {
        self.frags[idx as usize].next = self.free;
        self.free = idx;
    }

    /// The fragment at `idx`.
    #[inline]
    pub fn get(&self, idx: u32) -> &Fragment {
        &self.frags[idx as usize]
    }

    /// The fragment at `idx`, mutably.
    #[inline]
    pub fn get_mut(&mut self, idx: u32) -> &mut Fragment {
        &mut self.frags[idx as usize]
    }

    /// The per-sample depths of fragment `idx` (empty when not kept).
    #[inline]
    pub fn depths(&self, idx: u32) -> &[f32] {
        let s = idx as usize * self.stride;
        &self.depths[s..s + self.stride]
    }

    /// The per-sample depths of fragment `idx`, mutably.
    #[inline]
    pub fn depths_mut(&mut self, idx: u32) -> &mut [f32] {
        let s = idx as usize * self.stride;
        &mut self.depths[s..s + self.stride]
    }

    /// First fragment of pixel `p`'s list.
    #[inline]
    pub fn head(&self, p: usize) -> u32 {
        self.pixels[p].head
    }

    /// Length of pixel `p`'s list.
    #[inline]
    pub fn len(&self, p: usize) -> u32 {
        self.pixels[p].len
    }

    /// Pixel `p`'s table entry.
    #[inline]
    pub fn pixel(&self, p: usize) -> &PixelEntry {
        &self.pixels[p]
    }

    /// Sets the occluder depth of pixel `p`.
    #[inline]
    pub fn set_occluder(&mut self, p: usize, z: f32) {
        self.pixels[p].occluder = z;
    }

    /// Puts fragment `idx` at the front of pixel `p`'s list.
    #[inline]
    pub fn push_front(&mut self, p: usize, idx: u32) {
        let f = &mut self.frags[idx as usize];
        let e = &mut self.pixels[p];
        f.next = e.head;
        e.head = idx;
        e.len += 1;
        e.far = e.far.max(f.zmin);
    }

    /// Unlinks and frees every fragment of pixel `p` for which `remove`
    /// says so; returns how many.
    pub fn remove_where(&mut self, p: usize, mut remove: impl FnMut(&Fragment) -> bool) -> u64 {
        let mut removed = 0;
        let mut prev = NIL;
        let mut cur = self.pixels[p].head;
        while cur != NIL {
            let next = self.frags[cur as usize].next;
            if remove(&self.frags[cur as usize]) {
                if prev == NIL {
                    self.pixels[p].head = next;
                } else {
                    self.frags[prev as usize].next = next;
                }
                self.release(cur);
                self.pixels[p].len -= 1;
                removed += 1;
            } else {
                prev = cur;
            }
            cur = next;
        }
        removed
    }

    /// Bytes of the pixel table.
    pub fn table_bytes(&self) -> u64 {
        self.pixels.len() as u64 * PIXEL_BYTES
    }

    /// Most fragment slots in use at once this frame.
    pub fn peak_fragments(&self) -> usize {
        self.peak
    }

    /// Peak working memory this frame: pixel table plus the fragment slots
    /// used.
    pub fn peak_bytes(&self) -> u64 {
        self.table_bytes() + self.peak as u64 * Self::fragment_bytes(self.stride)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frag(zmin: f32) -> Fragment {
        Fragment {
            next: NIL,
            mask: 1,
            prim: 0,
            tri: 0,
            centre_prim: u32::MAX,
            zmin,
            zmax: zmin,
            centre_z: f64::INFINITY,
            rgb: [0.0; 3],
            alpha: 1.0,
        }
    }

    #[test]
    fn freed_slots_are_reused_and_lists_stay_linked() {
        let mut pool = FragmentPool::default();
        pool.reset(4, 2, 1 << 20).unwrap();
        for z in [0.1, 0.2, 0.3] {
            let idx = pool.alloc(frag(z), &[z, z]).unwrap();
            pool.push_front(1, idx);
        }
        assert_eq!(pool.len(1), 3);
        assert_eq!(pool.remove_where(1, |f| f.zmin > 0.15 && f.zmin < 0.25), 1);
        assert_eq!(pool.len(1), 2);
        let idx = pool.alloc(frag(0.4), &[0.4, 0.4]).unwrap();
        assert_eq!(idx, 1, "the freed slot is reused");
        assert_eq!(pool.depths(idx), &[0.4, 0.4]);
        assert_eq!(pool.peak_fragments(), 3);
        let mut zs = Vec::new();
        let mut cur = pool.head(1);
        while cur != NIL {
            zs.push(pool.get(cur).zmin);
            cur = pool.get(cur).next;
        }
        assert_eq!(zs, vec![0.3, 0.1]);
    }

    #[test]
    fn the_memory_bound_is_a_typed_error() {
        let mut pool = FragmentPool::default();
        assert!(matches!(
            pool.reset(1000, 0, 100),
            Err(Error::Limit {
                value: 16_000,
                limit: 100,
                ..
            })
        ));
        let room = PIXEL_BYTES * 4 + 3 * FragmentPool::fragment_bytes(0);
        pool.reset(4, 0, room).unwrap();
        for _ in 0..3 {
            pool.alloc(frag(0.5), &[]).unwrap();
        }
        let e = pool.alloc(frag(0.5), &[]).unwrap_err();
        assert!(matches!(e, Error::Limit { .. }), "{e}");
        assert!(pool.peak_bytes() <= room);
    }
}
