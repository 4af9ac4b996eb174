//! hider-oracle: not written yet.
