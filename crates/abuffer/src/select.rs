//! Branch-free selects, for choices that are a coin toss per pixel (a
//! partial fragment covering the centre, a mask row being empty): as
//! branches they mispredicted (callgrind's branch simulation showed
//! them). The standard `select_unpredictable` is newer than the crate's
//! MSRV.

/// `a` if `take`, else `b`, by masks.
#[inline(always)]
pub(crate) fn pick(take: bool, a: u64, b: u64) -> u64 {
    let all = u64::from(take).wrapping_neg();
    (a & all) | (b & !all)
}

/// [`pick`] of two `f64`, bit for bit.
#[inline(always)]
pub(crate) fn pick_f64(take: bool, a: f64, b: f64) -> f64 {
    f64::from_bits(pick(take, a.to_bits(), b.to_bits()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_first_when_taken() {
        assert_eq!(pick(true, 7, u64::MAX), 7);
        assert_eq!(pick(false, 7, u64::MAX), u64::MAX);
        assert_eq!(pick_f64(true, -0.0, 1.0).to_bits(), (-0.0f64).to_bits());
        assert!(pick_f64(false, 1.0, f64::NAN).is_nan());
    }
}
