//! hider-scanline: not written yet.
