//! The unit tests' random numbers: one xorshift generator (Marsaglia's
//! 13/7/17 shifts on 64 bits) from one fixed seed, so that every test
//! draws the same cases on every run.

/// A deterministic stream of pseudo-random `u64`s.
pub(crate) fn xorshift() -> impl FnMut() -> u64 {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    }
}
