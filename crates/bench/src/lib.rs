//! hider-bench: not written yet.
