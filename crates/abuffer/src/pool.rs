//! The pooled arena that holds the per-pixel fragment lists.
//!
//! Fragments live in one `Vec` reused from frame to frame, with a free list
//! for the slots of pruned fragments, so no fragment costs an allocation;
//! the pixel table of [`PixelEntry`] heads the lists.
//!
//! The memory bound is explicit: the pixel table is checked against
//! `max_bytes` before it is allocated, and the pool refuses the fragment or
//! merged entry that would pass it, growing its buffers by at most
//! doubling and never beyond the bound.

use hider_geom::PlaneEq;
use hider_scene::{Error, Result};

use crate::depth::plane_depth;
use crate::fragment::{
    FRAGMENT_BYTES, Fragment, MERGED_BASE, Merged, NIL, PIXEL_BYTES, PixelEntry,
};
use crate::pattern::MAX_SAMPLES;

/// The per-pixel lists and the fragment pool.
#[derive(Clone, Debug, Default)]
pub(crate) struct FragmentPool {
    frags: Vec<Fragment>,
    merged: Vec<Merged>,
    merged_depths: Vec<[f32; MAX_SAMPLES]>,
    keep_depths: bool,
    free: u32,
    pixels: Vec<PixelEntry>,
    max_bytes: u64,
    peak: usize,
}

/// Errors when the pixel table of `pixels` pixels is over `max_bytes`:
/// the first budget a frame meets, known from its size alone.
pub(crate) fn check_table(pixels: usize, max_bytes: u64) -> Result<()> {
    let table = pixels as u64 * PIXEL_BYTES;
    if table > max_bytes {
        return Err(Error::Budget {
            what: "A-buffer pixel table (bytes)",
            value: table,
            limit: max_bytes,
        });
    }
    Ok(())
}

impl FragmentPool {
    /// Empties the pool for a frame of `pixels` pixels, merged entries
    /// with sample depths when `keep_depths`, under `max_bytes`. The table
    /// is only allocated (empty) when its size changes, which the result
    /// says; otherwise clearing its entries is left to
    /// [`Self::clear_pixels`], tile by tile.
    pub(crate) fn reset(
        &mut self,
        pixels: usize,
        keep_depths: bool,
        max_bytes: u64,
    ) -> Result<bool> {
        check_table(pixels, max_bytes)?;
        self.keep_depths = keep_depths;
        self.max_bytes = max_bytes;
        self.frags.clear();
        self.merged.clear();
        self.merged_depths.clear();
        self.free = NIL;
        self.peak = 0;
        if self.pixels.len() == pixels {
            return Ok(false);
        }
        self.pixels.clear();
        self.pixels.resize(pixels, PixelEntry::EMPTY);
        Ok(true)
    }

    /// Empties the entries of pixels `start..start + len` (one tile row).
    #[inline]
    pub(crate) fn clear_pixels(&mut self, start: usize, len: usize) {
        self.pixels[start..start + len].fill(PixelEntry::EMPTY);
    }

    /// Bytes one merged entry costs.
    pub(crate) fn merged_bytes(&self) -> u64 {
        let depths = if self.keep_depths {
            std::mem::size_of::<[f32; MAX_SAMPLES]>()
        } else {
            0
        };
        (std::mem::size_of::<Merged>() + depths) as u64
    }

    /// Bytes in use: table, fragment slots, merged entries.
    fn used_bytes(&self, frags: usize, merged: usize) -> u64 {
        self.table_bytes() + frags as u64 * FRAGMENT_BYTES + merged as u64 * self.merged_bytes()
    }

    fn limit(&self, frags: usize, merged: usize) -> Error {
        Error::Budget {
            what: "A-buffer working memory (bytes)",
            value: self.used_bytes(frags, merged),
            limit: self.max_bytes,
        }
    }

    /// Stores `f` in a free slot or a new one.
    #[inline]
    pub(crate) fn alloc(&mut self, f: Fragment) -> Result<u32> {
        if self.free != NIL {
            let idx = self.free;
            self.free = self.frags[idx as usize].next;
            self.frags[idx as usize] = f;
            return Ok(idx);
        }
        let len = self.frags.len();
        if len == self.frags.capacity() {
            self.grow()?;
        }
        self.frags.push(f);
        self.peak = self.peak.max(len + 1);
        Ok(len as u32)
    }

    /// Makes room for at least one more fragment: doubling, but never past
    /// the bound.
    #[cold]
    fn grow(&mut self) -> Result<()> {
        let len = self.frags.len();
        let room = self
            .max_bytes
            .saturating_sub(self.used_bytes(len, self.merged.len()))
            / FRAGMENT_BYTES;
        let cap = (len as u64 + room).min(u64::from(NIL)) as usize;
        if len >= cap {
            return Err(self.limit(len + 1, self.merged.len()));
        }
        let want = (2 * len).max(1024).min(cap) - len;
        self.frags.reserve_exact(want);
        Ok(())
    }

    /// Adds a merged entry with colour `rgba` and (when depths are kept)
    /// sample depths `depths`; returns its shading index.
    pub(crate) fn add_merged(
        &mut self,
        rgba: [f32; 4],
        depths: &[f32; MAX_SAMPLES],
    ) -> Result<u32> {
        let n = self.merged.len();
        if self.used_bytes(self.frags.len(), n + 1) > self.max_bytes
            || n as u32 >= NIL - MERGED_BASE
        {
            return Err(self.limit(self.frags.len(), n + 1));
        }
        self.merged.push(Merged { rgba });
        if self.keep_depths {
            self.merged_depths.push(*depths);
        }
        Ok(MERGED_BASE + n as u32)
    }

    /// The merged entry of shading index `shade` (at least [`MERGED_BASE`]).
    #[inline]
    pub(crate) fn merged(&self, shade: u32) -> &Merged {
        &self.merged[(shade - MERGED_BASE) as usize]
    }

    /// The merged entry of shading index `shade`, mutably.
    #[inline]
    pub(crate) fn merged_mut(&mut self, shade: u32) -> &mut Merged {
        &mut self.merged[(shade - MERGED_BASE) as usize]
    }

    /// The sample depths of merged entry `shade` (per-sample mode only).
    #[inline]
    pub(crate) fn merged_depths(&self, shade: u32) -> &[f32; MAX_SAMPLES] {
        &self.merged_depths[(shade - MERGED_BASE) as usize]
    }

    /// The sample depths of merged entry `shade`, mutably.
    #[inline]
    pub(crate) fn merged_depths_mut(&mut self, shade: u32) -> &mut [f32; MAX_SAMPLES] {
        &mut self.merged_depths[(shade - MERGED_BASE) as usize]
    }

    /// Returns slot `idx` to the free list (the caller has unlinked it).
    #[inline]
    pub(crate) fn release(&mut self, idx: u32) {
        self.frags[idx as usize].next = self.free;
        self.free = idx;
    }

    /// The fragment at `idx`.
    #[inline]
    pub(crate) fn get(&self, idx: u32) -> &Fragment {
        &self.frags[idx as usize]
    }

    /// The fragment at `idx`, mutably.
    #[inline]
    pub(crate) fn get_mut(&mut self, idx: u32) -> &mut Fragment {
        &mut self.frags[idx as usize]
    }

    /// First fragment of pixel `p`'s list.
    #[inline]
    pub(crate) fn head(&self, p: usize) -> u32 {
        self.pixels[p].head
    }

    /// Length of pixel `p`'s list.
    #[inline]
    pub(crate) fn len(&self, p: usize) -> u32 {
        self.pixels[p].len
    }

    /// Pixel `p`'s table entry.
    #[inline]
    pub(crate) fn pixel(&self, p: usize) -> &PixelEntry {
        &self.pixels[p]
    }

    /// Sets the opaque bound of pixel `p`.
    #[inline]
    pub(crate) fn set_occluder(&mut self, p: usize, z: f32) {
        self.pixels[p].occluder = z;
    }

    /// Puts fragment `idx` at the front of pixel `p`'s list.
    #[inline]
    pub(crate) fn push_front(&mut self, p: usize, idx: u32) {
        let f = &mut self.frags[idx as usize];
        let e = &mut self.pixels[p];
        f.next = e.head;
        e.head = idx;
        e.len += 1;
        e.far = e.far.max(f.zmin);
    }

    /// Unlinks and frees every fragment of pixel `p` for which `remove`
    /// says so; returns how many. Recomputes the pixel's `far`.
    pub(crate) fn remove_where(
        &mut self,
        p: usize,
        mut remove: impl FnMut(&Fragment) -> bool,
    ) -> u64 {
        let mut removed = 0;
        let mut prev = NIL;
        let mut cur = self.pixels[p].head;
        let mut far = f32::NEG_INFINITY;
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
                far = far.max(self.frags[cur as usize].zmin);
                prev = cur;
            }
            cur = next;
        }
        self.pixels[p].far = far;
        removed
    }

    /// Bytes of the pixel table.
    pub(crate) fn table_bytes(&self) -> u64 {
        self.pixels.len() as u64 * PIXEL_BYTES
    }

    /// Most fragment slots in use at once this frame.
    pub(crate) fn peak_fragments(&self) -> usize {
        self.peak
    }

    /// Merged entries this frame.
    #[cfg(test)]
    pub(crate) fn merged_entries(&self) -> usize {
        self.merged.len()
    }

    /// Peak working memory this frame: pixel table plus the fragment slots
    /// and merged entries used.
    pub(crate) fn peak_bytes(&self) -> u64 {
        self.used_bytes(self.peak, self.merged.len())
    }

    /// The depth of fragment `f` of pixel `(i, j)` at sample `k` (per-sample
    /// mode): from its merged entry, or `plane`, its triangle's depth plane,
    /// with the expression the supersampled z-buffer uses.
    #[inline]
    pub(crate) fn sample_depth(
        &self,
        plane: &PlaneEq,
        f: &Fragment,
        (i, j): (u32, u32),
        positions: &[(i32, i32)],
        k: usize,
    ) -> f32 {
        if f.is_merged() {
            self.merged_depths(f.shade)[k]
        } else {
            plane_depth(plane, i, j, positions[k]) as f32
        }
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
            shade: 0,
            zmin,
            zmax: zmin,
            centre_z: f64::INFINITY,
        }
    }

    #[test]
    fn freed_slots_are_reused_and_lists_stay_linked() {
        let mut pool = FragmentPool::default();
        assert!(
            pool.reset(4, true, 1 << 20).unwrap(),
            "a new table is fresh"
        );
        for z in [0.1, 0.2, 0.3] {
            let idx = pool.alloc(frag(z)).unwrap();
            pool.push_front(1, idx);
        }
        assert_eq!(pool.len(1), 3);
        assert_eq!(pool.pixel(1).far, 0.3);
        assert_eq!(pool.remove_where(1, |f| f.zmin > 0.15 && f.zmin < 0.25), 1);
        assert_eq!(pool.len(1), 2);
        let idx = pool.alloc(frag(0.4)).unwrap();
        assert_eq!(idx, 1, "the freed slot is reused");
        assert_eq!(pool.peak_fragments(), 3);
        let mut zs = Vec::new();
        let mut cur = pool.head(1);
        while cur != NIL {
            zs.push(pool.get(cur).zmin);
            cur = pool.get(cur).next;
        }
        assert_eq!(zs, vec![0.3, 0.1]);
        // Same size: the table is kept, and cleared by the caller.
        assert!(!pool.reset(4, true, 1 << 20).unwrap());
        pool.clear_pixels(0, 4);
        assert_eq!(pool.head(1), NIL);
    }

    #[test]
    fn merged_entries_hold_colour_and_depths() {
        let mut pool = FragmentPool::default();
        pool.reset(4, true, 1 << 20).unwrap();
        let mut depths = [f32::INFINITY; MAX_SAMPLES];
        depths[3] = 0.5;
        let shade = pool.add_merged([0.1, 0.2, 0.3, 1.0], &depths).unwrap();
        assert!(shade >= MERGED_BASE);
        assert_eq!(pool.merged(shade).rgba, [0.1, 0.2, 0.3, 1.0]);
        assert_eq!(pool.merged_depths(shade)[3], 0.5);
        assert_eq!(pool.merged_entries(), 1);
        assert_eq!(pool.merged_bytes(), 16 + 128);
        pool.reset(4, false, 1 << 20).unwrap();
        assert_eq!(pool.merged_bytes(), 16);
    }

    #[test]
    fn the_memory_bound_is_a_typed_error() {
        let mut pool = FragmentPool::default();
        assert!(matches!(
            pool.reset(1000, false, 100),
            Err(Error::Budget {
                value: 16_000,
                limit: 100,
                ..
            })
        ));
        let room = PIXEL_BYTES * 4 + 3 * FRAGMENT_BYTES;
        pool.reset(4, false, room).unwrap();
        for _ in 0..3 {
            pool.alloc(frag(0.5)).unwrap();
        }
        let e = pool.alloc(frag(0.5)).unwrap_err();
        assert!(matches!(e, Error::Budget { .. }), "{e}");
        assert!(pool.peak_bytes() <= room);
        // Merged entries count against the same bound.
        let e = pool.add_merged([0.0; 4], &[0.0; MAX_SAMPLES]).unwrap_err();
        assert!(matches!(e, Error::Budget { .. }), "{e}");
    }
}
