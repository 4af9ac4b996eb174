//! Fragments, the per-pixel entries that head their lists, and the
//! shading a merged fragment carries.
//!
//! Carpenter's pixel holds either a depth or a pointer to a list of
//! fragments. Here every pixel has a [`PixelEntry`]: a list head (an index
//! into one pool, [`NIL`] when empty), a length, the *opaque bound* (a
//! depth behind which every sample and the centre are already hidden by
//! opaque fragments of the list, used to cull and prune) and the farthest
//! `zmin` in the list (so a new bound walks the list only when it can
//! prune). The four share one 16-byte entry.
//!
//! A fragment is 40 bytes: it names its triangle and its shading instead
//! of carrying a colour and 32 sample depths. Its per-sample depths are the
//! triangle's depth plane at the samples, recomputed (with the very
//! expression that made them, [`crate::depth::plane_depth`]) only where
//! the resolve needs them; its colour is the primitive's. Only a fragment
//! that two triangles were *merged* into needs more: its shading is then a
//! [`Merged`] entry of the pool (averaged colour and, in per-sample depth
//! mode, the 32 sample depths, each from the triangle that covered it).
//! The arena that holds them all is the fragment pool.

/// The "no fragment" index.
pub(crate) const NIL: u32 = u32::MAX;

/// Shading indices from this value on name a [`Merged`] entry of the pool
/// (`shade - MERGED_BASE`); below it, a primitive (its colour).
pub(crate) const MERGED_BASE: u32 = 1 << 31;

/// One surface's share of one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Fragment {
    /// Next fragment of the pixel's list, or [`NIL`].
    pub next: u32,
    /// Covered samples.
    pub mask: u32,
    /// Lowest primitive id merged into this fragment: the tie-break key
    /// between equal depths (lower id in front, as in every hider).
    pub prim: u32,
    /// Index in `ScreenScene::tris` of the last triangle merged in: the
    /// adjacency test of the next merge, and the depth plane of an unmerged
    /// fragment.
    pub tri: u32,
    /// Primitive covering the pixel centre, or `NO_ID`.
    pub centre_prim: u32,
    /// Colour and opacity: the primitive `shade` when below
    /// [`MERGED_BASE`], else merged entry `shade - MERGED_BASE` (which also
    /// holds the sample depths in per-sample mode).
    pub shade: u32,
    /// Nearest window depth over the covered samples and the centre.
    pub zmin: f32,
    /// Farthest window depth over the covered samples and the centre.
    pub zmax: f32,
    /// Window depth at the pixel centre (`f64`, exactly what a pixel-centre
    /// z-buffer computes), `INFINITY` when the centre is not covered.
    pub centre_z: f64,
}

#[cfg(test)]
impl Fragment {
    /// An unmerged fragment of primitive 0 with these samples and depth
    /// range, not covering the centre: what the unit tests build lists of.
    pub(crate) fn with_mask(mask: u32, zmin: f32, zmax: f32) -> Self {
        Self {
            next: NIL,
            mask,
            prim: 0,
            tri: 0,
            centre_prim: hider_scene::NO_ID,
            shade: 0,
            zmin,
            zmax,
            centre_z: f64::INFINITY,
        }
    }
}

impl Fragment {
    /// Whether the fragment covers the pixel centre.
    #[inline]
    pub(crate) fn covers_centre(&self) -> bool {
        self.centre_z.is_finite()
    }

    /// Whether two or more triangles were merged into it.
    #[inline]
    pub(crate) fn is_merged(&self) -> bool {
        self.shade >= MERGED_BASE
    }

    /// The resolve order: nearest `zmin` first, lower primitive id first on
    /// equal depths. Independent of submission order.
    #[inline]
    pub(crate) fn order(&self, other: &Fragment) -> std::cmp::Ordering {
        self.zmin
            .total_cmp(&other.zmin)
            .then(self.prim.cmp(&other.prim))
    }
}

/// The shading of a merged fragment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Merged {
    /// Linear colour and opacity.
    pub rgba: [f32; 4],
}

/// One pixel's entry in the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PixelEntry {
    /// First fragment of the list, or [`NIL`].
    pub head: u32,
    /// Fragments in the list.
    pub len: u32,
    /// The opaque bound: every sample and the centre are covered by opaque
    /// fragments of the list whose depth there is at most this
    /// (`INFINITY` until that holds). A fragment whose `zmin` is beyond it
    /// is hidden everywhere.
    pub occluder: f32,
    /// An upper bound of the `zmin` of the fragments in the list
    /// (`-INFINITY` when it never held one).
    pub far: f32,
}

impl PixelEntry {
    /// An empty pixel.
    pub(crate) const EMPTY: PixelEntry = PixelEntry {
        head: NIL,
        len: 0,
        occluder: f32::INFINITY,
        far: f32::NEG_INFINITY,
    };
}

/// Bytes of the per-pixel table per pixel.
pub(crate) const PIXEL_BYTES: u64 = std::mem::size_of::<PixelEntry>() as u64;

/// Bytes of one fragment slot.
pub(crate) const FRAGMENT_BYTES: u64 = std::mem::size_of::<Fragment>() as u64;

/// A fragment with its colour and opacity looked up, and its pool index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Shaded {
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
    pub(crate) fn new(f: Fragment, rgba: [f32; 4], idx: u32) -> Self {
        Self {
            frag: f,
            rgb: [rgba[0], rgba[1], rgba[2]],
            alpha: rgba[3],
            idx,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fragments_are_40_bytes() {
        assert_eq!(FRAGMENT_BYTES, 40);
        assert_eq!(PIXEL_BYTES, 16);
    }
}
