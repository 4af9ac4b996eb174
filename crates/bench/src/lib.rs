//! hider-bench: the comparative benchmark runner (being written), and the
//! [`registry`] of every hider in the workspace.

pub mod registry;
