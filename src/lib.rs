//! hider
