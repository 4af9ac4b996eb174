//! hider-abuffer: not written yet.
