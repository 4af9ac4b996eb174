//! hider-painter: not written yet.
