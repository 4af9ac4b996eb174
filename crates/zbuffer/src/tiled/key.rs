//! Depth keys: each [`crate::DepthFormat`] as a compact value compared with LESS.
//!
//! The tiled rasteriser is generic over the key so that its inner loops are
//! compiled once per format, with no per-pixel `match`. Every encoding is
//! *exactly* the one [`crate::ZBuffer`]'s depth buffer applies to the same
//! `f64` window depth, and every decoding gives exactly the `f32` it writes
//! to the frame, so the two hiders agree bit for bit.
//!
//! Reversed Z stores `1 - d` and tests GREATER; here the key is the
//! *negated* stored value, `-((1 - d) as f32)`: negation is exact, so
//! `key_new < key_old` holds exactly when `stored_new > stored_old`, and the
//! one LESS loop serves all five formats.
//!
//! A pixel nothing has written holds the clear key: [`DepthKey::FAR`]
//! under [`crate::DepthTest::GlLess`], and under the default
//! [`crate::DepthTest::ViewVolume`] [`DepthKey::BLANK`], a key above every
//! encoded depth, so that LESS against it accepts any fragment (window
//! depth 1 included) and the one LESS loop still serves both tests.
//!
//! Hierarchical depth relies on one property of every `encode`: it is
//! monotone non-decreasing in the depth (rounding to f32, clamping,
//! scaling and rounding to an integer all are, and the reversed key is
//! the negation of a non-increasing function). So if a lower bound `z` of a
//! triangle's depths over a block has `encode(z) >= max key of the block`,
//! no pixel of the block can pass.

const MAX24: u32 = (1 << 24) - 1;
const MAX16: u32 = u16::MAX as u32;

/// A depth format as a key type: encoding, decoding, and the far value.
pub(crate) trait DepthKey: Copy + PartialOrd + Send + Sync + 'static {
    /// The key of window depth 1 (the far plane): GL's clear value.
    const FAR: Self;
    /// A key above the encoding of every depth (never produced by
    /// [`Self::encode`]): the clear value that lets a pixel accept any
    /// fragment.
    const BLANK: Self;
    /// The stored key of window depth `depth`, exactly as `ZBuffer` rounds.
    fn encode(depth: f64) -> Self;
    /// The window depth `ZBuffer` writes to the frame for a stored key.
    fn decode(self) -> f32;
    /// `new` where `mask` is all ones, `old` where it is zero, by bit
    /// operations: a select the compiler keeps branch-free and vectorises
    /// on baseline x86-64 (SSE2 has no blend), where `if` became a
    /// mispredicted branch per pixel.
    fn select(mask: u32, new: Self, old: Self) -> Self;
    /// The larger of two keys (for block maxima).
    #[inline]
    fn max_key(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
}

impl DepthKey for f32 {
    const FAR: Self = 1.0;
    const BLANK: Self = f32::INFINITY;
    #[inline(always)]
    fn select(mask: u32, new: Self, old: Self) -> Self {
        f32::from_bits((new.to_bits() & mask) | (old.to_bits() & !mask))
    }
    #[inline]
    fn encode(depth: f64) -> Self {
        depth as f32
    }
    #[inline]
    fn decode(self) -> f32 {
        // ZBuffer writes `f64::from(d) as f32`, which is `d`.
        self
    }
}

impl DepthKey for f64 {
    const FAR: Self = 1.0;
    const BLANK: Self = f64::INFINITY;
    #[inline(always)]
    fn select(mask: u32, new: Self, old: Self) -> Self {
        let mask = u64::from(mask) | (u64::from(mask) << 32);
        f64::from_bits((new.to_bits() & mask) | (old.to_bits() & !mask))
    }
    #[inline]
    fn encode(depth: f64) -> Self {
        depth
    }
    #[inline]
    fn decode(self) -> f32 {
        self as f32
    }
}

/// 24-bit unsigned normalised depth in a `u32`.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub(crate) struct Fixed24(pub(super) u32);

impl DepthKey for Fixed24 {
    const FAR: Self = Fixed24(MAX24);
    // Still below 2^31, where the wide kernel's signed comparison is the
    // unsigned one.
    const BLANK: Self = Fixed24(MAX24 + 1);
    #[inline(always)]
    fn select(mask: u32, new: Self, old: Self) -> Self {
        Fixed24((new.0 & mask) | (old.0 & !mask))
    }
    #[inline]
    fn encode(depth: f64) -> Self {
        Fixed24(quantize(depth, MAX24))
    }
    #[inline]
    fn decode(self) -> f32 {
        (f64::from(self.0) / f64::from(MAX24)) as f32
    }
}

/// 16-bit unsigned normalised depth, held in a `u32` so that the blank
/// key has room above the largest depth.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub(crate) struct Fixed16(u32);

impl DepthKey for Fixed16 {
    const FAR: Self = Fixed16(MAX16);
    const BLANK: Self = Fixed16(MAX16 + 1);
    #[inline(always)]
    fn select(mask: u32, new: Self, old: Self) -> Self {
        Fixed16((new.0 & mask) | (old.0 & !mask))
    }
    #[inline]
    fn encode(depth: f64) -> Self {
        Fixed16(quantize(depth, MAX16))
    }
    #[inline]
    fn decode(self) -> f32 {
        (f64::from(self.0) / f64::from(MAX16)) as f32
    }
}

/// Reversed f32 depth, stored negated so that LESS is the test (see the
/// module documentation).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub(crate) struct Reversed(pub(super) f32);

impl DepthKey for Reversed {
    // ZBuffer clears reversed depth to 0; its negation is -0, which
    // compares equal to 0, so under GL's test nothing at the far plane
    // passes, as there.
    const FAR: Self = Reversed(-0.0);
    const BLANK: Self = Reversed(f32::INFINITY);
    #[inline(always)]
    fn select(mask: u32, new: Self, old: Self) -> Self {
        Reversed(f32::select(mask, new.0, old.0))
    }
    #[inline]
    fn encode(depth: f64) -> Self {
        Reversed(-((1.0 - depth) as f32))
    }
    #[inline]
    fn decode(self) -> f32 {
        (1.0 - f64::from(-self.0)) as f32
    }
}

/// GL's conversion of a [0, 1] depth to unsigned normalised fixed point,
/// the same expression as the reference depth buffer's.
#[inline]
fn quantize(depth: f64, max: u32) -> u32 {
    (depth.clamp(0.0, 1.0) * f64::from(max)).round() as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::depth::DepthBuffer;
    use crate::options::DepthFormat;

    /// Replays a sequence of depths through the reference buffer and the
    /// key, under both depth tests, checking pass/fail and the decoded
    /// frame depth agree.
    fn agree<K: DepthKey>(format: DepthFormat, depths: &[f64]) {
        agree_from::<K>(format, depths, K::FAR);
        agree_from::<K>(format, depths, K::BLANK);
    }

    fn agree_from<K: DepthKey>(format: DepthFormat, depths: &[f64], clear: K) {
        let mut reference = DepthBuffer::default();
        reference.clear(format, 1);
        let mut key = clear;
        let mut frame_depth = 1.0f32;
        let mut written = false;
        assert_eq!(K::FAR.decode(), 1.0, "{:?}: far decodes to 1", format);
        for &d in depths {
            let new = K::encode(d);
            assert!(
                new < K::BLANK,
                "{:?}: {d} encodes below the blank key",
                format
            );
            let pass = new < key;
            let fresh = clear == K::BLANK && !written;
            let stored = reference.test_and_set(0, d, fresh);
            assert_eq!(pass, stored.is_some(), "{:?} at {d}", format);
            if let Some(s) = stored {
                key = new;
                frame_depth = s as f32;
                written = true;
            }
            if !written {
                continue;
            }
            assert_eq!(
                key.decode().to_bits(),
                frame_depth.to_bits(),
                "{:?}",
                format
            );
        }
    }

    #[test]
    fn keys_replay_the_reference_buffer_exactly() {
        let depths = [
            1.0,
            0.9,
            0.95,
            0.5,
            0.5,
            0.500_000_01,
            0.499_999_99,
            1e-9,
            0.0,
            -0.0,
            0.3,
            1.0,
            1.5,
            -0.5,
            0.999_999_9,
            0.2,
            0.2 + 1e-17,
            0.1,
        ];
        agree::<f32>(DepthFormat::F32, &depths);
        agree::<f64>(DepthFormat::F64, &depths);
        agree::<Fixed24>(DepthFormat::Fixed24, &depths);
        agree::<Fixed16>(DepthFormat::Fixed16, &depths);
        agree::<Reversed>(DepthFormat::ReversedF32, &depths);
        let mut rev = depths;
        rev.reverse();
        agree::<f32>(DepthFormat::F32, &rev);
        agree::<Reversed>(DepthFormat::ReversedF32, &rev);
        agree::<Fixed24>(DepthFormat::Fixed24, &rev);
    }

    fn monotone<K: DepthKey>(format: DepthFormat) {
        let mut x = -0.25f64;
        let mut last = K::encode(x);
        while x < 1.25 {
            x += 0.000_37;
            for d in [x, x + 1e-12, x + 1e-7] {
                let k = K::encode(d);
                assert!(k >= last, "{:?} not monotone at {d}", format);
                last = k;
            }
        }
    }

    #[test]
    fn every_encoding_is_monotone() {
        monotone::<f32>(DepthFormat::F32);
        monotone::<f64>(DepthFormat::F64);
        monotone::<Fixed24>(DepthFormat::Fixed24);
        monotone::<Fixed16>(DepthFormat::Fixed16);
        monotone::<Reversed>(DepthFormat::ReversedF32);
    }
}
