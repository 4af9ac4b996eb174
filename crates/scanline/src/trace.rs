//! An optional record of how every run of pixels was resolved, for
//! pictures and debugging ([`crate::ScanlineOptions::record_spans`]).

/// How a run of pixels got its visible polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Resolution {
    /// The nearest polygon at the span's left end stayed nearest to its
    /// right end: one decision for the whole span.
    Whole,
    /// A piece of a span split where two polygons' depths cross.
    Split,
    /// Resolved pixel by pixel in the one-row depth buffer fallback (a run
    /// of equal ids within it).
    Fallback,
}

/// One run of pixels on a row with one visible primitive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpanRecord {
    /// Image row.
    pub row: u32,
    /// First column.
    pub x0: u32,
    /// Last column (inclusive).
    pub x1: u32,
    /// The visible primitive.
    pub prim: u32,
    /// How it was decided.
    pub how: Resolution,
}
