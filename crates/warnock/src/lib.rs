//! hider-warnock: not written yet.
