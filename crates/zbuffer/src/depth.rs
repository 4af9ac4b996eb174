//! Depth storage: one buffer, several formats, all compared with LESS on
//! an encoded value so the rasteriser's inner loop is the same for all; a
//! pixel nothing has written can be told to accept any depth (see
//! [`crate::DepthTest`]).

use crate::options::DepthFormat;

/// The depth buffer's storage, kept between frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct DepthBuffer {
    format: DepthFormat,
    /// One vector per storage width; only the active format's is non-empty,
    /// so the buffer holds exactly the format's own bytes per pixel.
    f32s: Vec<f32>,
    f64s: Vec<f64>,
    u32s: Vec<u32>,
    u16s: Vec<u16>,
}

impl DepthBuffer {
    /// Resets the buffer to `len` pixels of "far" in `format`.
    pub(crate) fn clear(&mut self, format: DepthFormat, len: usize) {
        self.format = format;
        // Release the other formats' memory so `bytes` is honest.
        let keep = |v: bool, len: usize| if v { len } else { 0 };
        let (f32_len, f32_far) = match format {
            DepthFormat::F32 => (len, 1.0),
            // Reversed Z stores 1 - depth: the far plane is 0.
            DepthFormat::ReversedF32 => (len, 0.0),
            _ => (0, 1.0),
        };
        resize_fill(&mut self.f32s, f32_len, f32_far);
        resize_fill(
            &mut self.f64s,
            keep(matches!(format, DepthFormat::F64), len),
            1.0,
        );
        resize_fill(
            &mut self.u32s,
            keep(matches!(format, DepthFormat::Fixed24), len),
            MAX24,
        );
        resize_fill(
            &mut self.u16s,
            keep(matches!(format, DepthFormat::Fixed16), len),
            u16::MAX,
        );
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.f32s.capacity() * 4
            + self.f64s.capacity() * 8
            + self.u32s.capacity() * 4
            + self.u16s.capacity() * 2
    }

    /// The depth test and write: if `depth` (window depth in [0, 1], f64)
    /// passes LESS against pixel `i`, or `fresh` says the pixel is to accept
    /// any depth (nothing has written it and the test is
    /// [`crate::DepthTest::ViewVolume`]), stores it and returns the stored
    /// value decoded back to window depth.
    #[inline]
    pub(crate) fn test_and_set(&mut self, i: usize, depth: f64, fresh: bool) -> Option<f64> {
        match self.format {
            DepthFormat::F32 => {
                let d = depth as f32;
                (fresh || d < self.f32s[i]).then(|| {
                    self.f32s[i] = d;
                    f64::from(d)
                })
            }
            DepthFormat::ReversedF32 => {
                let d = (1.0 - depth) as f32;
                (fresh || d > self.f32s[i]).then(|| {
                    self.f32s[i] = d;
                    1.0 - f64::from(d)
                })
            }
            DepthFormat::F64 => (fresh || depth < self.f64s[i]).then(|| {
                self.f64s[i] = depth;
                depth
            }),
            DepthFormat::Fixed24 => {
                let q = quantize(depth, MAX24);
                (fresh || q < self.u32s[i]).then(|| {
                    self.u32s[i] = q;
                    f64::from(q) / f64::from(MAX24)
                })
            }
            DepthFormat::Fixed16 => {
                let q = quantize(depth, u32::from(u16::MAX)) as u16;
                (fresh || q < self.u16s[i]).then(|| {
                    self.u16s[i] = q;
                    f64::from(q) / f64::from(u16::MAX)
                })
            }
        }
    }
}

const MAX24: u32 = (1 << 24) - 1;

/// GL's conversion of a [0, 1] depth to unsigned normalised fixed point:
/// `round(d * (2^n - 1))`, clamped.
fn quantize(depth: f64, max: u32) -> u32 {
    (depth.clamp(0.0, 1.0) * f64::from(max)).round() as u32
}

fn resize_fill<T: Copy>(v: &mut Vec<T>, len: usize, value: T) {
    if len == 0 {
        *v = Vec::new();
    } else {
        v.clear();
        v.resize(len, value);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_format_keeps_the_nearer_of_two_distinct_depths() {
        for format in DepthFormat::ALL {
            let mut b = DepthBuffer::default();
            b.clear(format, 1);
            assert!(b.test_and_set(0, 0.7, false).is_some(), "{format:?}");
            assert!(b.test_and_set(0, 0.8, false).is_none(), "{format:?}");
            let kept = b.test_and_set(0, 0.3, false).unwrap();
            assert!((kept - 0.3).abs() < 1e-4, "{format:?} {kept}");
            assert!(
                b.test_and_set(0, 0.3, false).is_none(),
                "LESS rejects equal depth"
            );
        }
    }

    #[test]
    fn resolution_of_each_format() {
        // Two depths 1e-6 apart near the far plane: f64 and reversed f32
        // separate them, f32 (ulp ~6e-8 near 1) does too, fixed 24 (step
        // 6e-8) does, fixed 16 (step 1.5e-5) cannot.
        let (far, nearer) = (0.999_9, 0.999_9 - 1e-6);
        for (format, separates) in [
            (DepthFormat::F64, true),
            (DepthFormat::F32, true),
            (DepthFormat::ReversedF32, true),
            (DepthFormat::Fixed24, true),
            (DepthFormat::Fixed16, false),
        ] {
            let mut b = DepthBuffer::default();
            b.clear(format, 1);
            b.test_and_set(0, far, false);
            assert_eq!(
                b.test_and_set(0, nearer, false).is_some(),
                separates,
                "{format:?}"
            );
        }
        // Far from the near plane f32 loses what reversed f32 keeps: depths
        // 1e-9 apart at 0.99999.
        let (a, c) = (0.999_99, 0.999_99 - 1e-9);
        let mut f = DepthBuffer::default();
        f.clear(DepthFormat::F32, 1);
        f.test_and_set(0, a, false);
        assert!(f.test_and_set(0, c, false).is_none());
        let mut r = DepthBuffer::default();
        r.clear(DepthFormat::ReversedF32, 1);
        r.test_and_set(0, a, false);
        assert!(r.test_and_set(0, c, false).is_some());
    }

    #[test]
    fn a_fresh_pixel_accepts_the_far_plane_in_every_format() {
        for format in DepthFormat::ALL {
            let mut b = DepthBuffer::default();
            b.clear(format, 1);
            // GL's LESS against the clear value drops depth 1...
            assert!(b.test_and_set(0, 1.0, false).is_none(), "{format:?}");
            // ...a fresh pixel keeps it, and then LESS decides again.
            assert_eq!(b.test_and_set(0, 1.0, true), Some(1.0), "{format:?}");
            assert!(b.test_and_set(0, 1.0, false).is_none(), "{format:?}");
            assert!(b.test_and_set(0, 0.5, false).is_some(), "{format:?}");
        }
    }

    #[test]
    fn only_the_active_format_holds_memory() {
        let mut b = DepthBuffer::default();
        b.clear(DepthFormat::F64, 100);
        assert_eq!(b.bytes(), 800);
        b.clear(DepthFormat::Fixed16, 100);
        assert_eq!(b.bytes(), 200);
    }
}
