//! The streaming clear of the read-back: background written to the frame
//! with non-temporal stores (`movntdq`, SSE2, so every x86-64 CPU has it).
//!
//! A plain store first reads the cache line it writes (read for
//! ownership), so clearing memory moves every byte twice; a streaming
//! store writes whole lines through the write-combining buffers and reads
//! nothing, and leaves the caches to the tiles being drawn. Where nothing
//! was drawn the frame is written and not read again by the hider, which
//! is the case streaming stores are for (Intel's optimisation manual,
//! "non-temporal stores"; Drepper, *What Every Programmer Should Know
//! About Memory*, 6.1).
//!
//! Streaming stores are weakly ordered: [`fence`] must run after the last
//! one and before another thread may read the frame.

/// A 4-byte pixel value the read-back writes: an id, a depth, a colour.
pub(crate) trait Word: Copy {
    /// The value's bits, as they lie in memory.
    fn bits(self) -> u32;
}

impl Word for u32 {
    #[inline(always)]
    fn bits(self) -> u32 {
        self
    }
}

impl Word for f32 {
    #[inline(always)]
    fn bits(self) -> u32 {
        self.to_bits()
    }
}

impl Word for [u8; 4] {
    #[inline(always)]
    fn bits(self) -> u32 {
        u32::from_ne_bytes(self)
    }
}

/// Below this many values a plain fill: the streaming loop's aligned body
/// would be a few stores and a partial write-combining line costs more.
const MIN_STREAM: usize = 64;

/// Sets every value of `dst` to `value`, with streaming stores where
/// `stream` (the caller's choice: frames larger than the caches) and the
/// slice is long enough; call [`fence`] after the last.
#[inline]
pub(crate) fn fill<T: Word>(dst: &mut [T], value: T, stream: bool) {
    #[cfg(target_arch = "x86_64")]
    if stream && dst.len() >= MIN_STREAM {
        x86::fill(dst, value);
        return;
    }
    let _ = stream;
    dst.fill(value);
}

/// Orders the streaming stores before anything after it (`sfence`).
#[inline]
pub(crate) fn fence() {
    #[cfg(target_arch = "x86_64")]
    x86::fence();
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "SSE2 streaming stores through a pointer into a slice the code holds mutably, aligned by construction"
)]
mod x86 {
    use std::arch::x86_64::{__m128i, _mm_set1_epi32, _mm_sfence, _mm_stream_si128};

    use super::Word;

    #[inline(always)]
    pub(super) fn fill<T: Word>(dst: &mut [T], value: T) {
        debug_assert_eq!(std::mem::size_of::<T>(), 4);
        // The unaligned head and tail (under 16 bytes each) as plain
        // values, the 16-byte-aligned body streamed.
        let addr = dst.as_ptr() as usize;
        if addr % 4 != 0 {
            // A colour slice (`[u8; 4]`) need not be 4-aligned; then no
            // offset makes it 16-aligned.
            dst.fill(value);
            return;
        }
        let head = ((16 - addr % 16) % 16 / 4).min(dst.len());
        let (first, rest) = dst.split_at_mut(head);
        first.fill(value);
        let body = rest.len() / 4 * 4;
        let (body, last) = rest.split_at_mut(body);
        last.fill(value);
        // SAFETY: SSE2 is part of x86-64; this only builds a register.
        let v = unsafe { _mm_set1_epi32(value.bits() as i32) };
        let p = body.as_mut_ptr().cast::<__m128i>();
        for i in 0..body.len() / 4 {
            // SAFETY: `body` starts 16-byte aligned (the head took the
            // misaligned values: a 4-byte type's slice is at least
            // 4-aligned, and 16 - addr % 16 is a multiple of 4) and holds
            // `body.len()` 4-byte values, so `p + i` for i < len / 4 is an
            // aligned 16-byte place inside the slice we borrow mutably.
            unsafe { _mm_stream_si128(p.add(i), v) };
        }
    }

    #[inline(always)]
    pub(super) fn fence() {
        // SAFETY: `sfence` is SSE, part of x86-64; it only orders stores.
        unsafe { _mm_sfence() };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_offset_and_length_is_filled_exactly() {
        for offset in 0..8 {
            for len in [0, 1, 3, 63, 64, 65, 100, 257] {
                let mut v = vec![7_u32; offset + len + 5];
                fill(&mut v[offset..offset + len], 9, true);
                fence();
                for (i, &x) in v.iter().enumerate() {
                    let inside = (offset..offset + len).contains(&i);
                    assert_eq!(
                        x,
                        if inside { 9 } else { 7 },
                        "offset {offset} len {len} at {i}"
                    );
                }
                let mut c = vec![[1_u8; 4]; offset + len];
                fill(&mut c[offset..], [0, 0, 0, 255], true);
                assert!(c[offset..].iter().all(|&p| p == [0, 0, 0, 255]));
                assert!(c[..offset].iter().all(|&p| p == [1; 4]));
            }
        }
    }
}
