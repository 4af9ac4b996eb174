//! The pixel-centre depth test the baselines use for `Frame::ids` and
//! `Frame::depth`.
//!
//! Every hider of this crate reports, per pixel, the front-most surface
//! covering the pixel *centre* (whatever its opacity), with window depth
//! from the triangle's depth plane at the centre in `f64` and ties going to
//! the lower primitive id: exactly what a pixel-centre z-buffer reports, so
//! ids and coverage compare one to one with the pixel-centre hiders and the
//! oracle, while colour and `Frame::coverage` carry the anti-aliased
//! answer.

use hider_scene::{Frame, NO_ID};

/// Whether `(z, prim)` is in front of `(z0, prim0)`: nearer, or as near
/// with a lower primitive id. The one depth order of this crate; it does not
/// depend on submission order.
#[inline]
pub(crate) fn in_front<Z: PartialOrd>(z: Z, prim: u32, z0: Z, prim0: u32) -> bool {
    // Non-short-circuit: no branch for callers to mispredict.
    (z < z0) | ((z == z0) & (prim < prim0))
}

/// A one-sample depth buffer at pixel centres.
#[derive(Clone, Debug, Default)]
pub(crate) struct CentreBuffer {
    depth: Vec<f64>,
    ids: Vec<u32>,
}

impl CentreBuffer {
    /// Clears to `pixels` background pixels, reusing memory.
    pub(crate) fn reset(&mut self, pixels: usize) {
        self.depth.clear();
        self.depth.resize(pixels, f64::INFINITY);
        self.ids.clear();
        self.ids.resize(pixels, NO_ID);
    }

    /// Keeps `(z, prim)` at pixel `p` if it is in front of what is there.
    #[inline]
    pub(crate) fn test(&mut self, p: usize, z: f64, prim: u32) {
        if in_front(z, prim, self.depth[p], self.ids[p]) {
            self.depth[p] = z;
            self.ids[p] = prim;
        }
    }

    /// Writes ids and depths (`f32`, 1.0 for background) into `frame`.
    pub(crate) fn write(&self, frame: &mut Frame) {
        for (k, (&z, &id)) in self.depth.iter().zip(&self.ids).enumerate() {
            frame.ids[k] = id;
            frame.depth[k] = if id == NO_ID { 1.0 } else { z as f32 };
        }
    }
}
