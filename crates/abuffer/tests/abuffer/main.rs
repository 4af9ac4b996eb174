//! Integration tests of hider-abuffer: exactness against the supersampled
//! z-buffer and the oracle, coverage convergence, order-independent
//! transparency, depth modes, merging and the memory bound.

mod baselines_lean;
mod coincident;
mod common;
mod convergence;
mod culling;
mod depth_modes;
mod exactness;
mod lean;
mod lean_shaded;
mod memory;
mod sample_tiles;
mod threads;
mod transparency;
