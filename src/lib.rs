//! The library of the `hider` command-line tool: what the `hider` binary
//! and the benchmark's `hider-bench` share, so that both report a usage
//! error the same way (one line, exit status 2).
//!
//! The hidden-surface algorithms themselves are the `hider` library (the
//! facade in `crates/hider`) and the crates it re-exports; this package is
//! the program built on them.

pub mod cli_error;
