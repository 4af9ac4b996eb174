//! An optional record of the sweep, for pictures, teaching and debugging
//! ([`crate::ScanlineOptions::record_spans`]): the edge table once, and per
//! row the active edge list and the runs of pixels the spans resolved to.
//!
//! It is written by the scan loop itself as it runs (the table as it is
//! bucketed, each row's edges as they are walked, each run as it is
//! filled), so it shows what the algorithm did, not a re-enactment.

use hider_geom::FixedPt;

pub use crate::walker::Side;

/// How a run of pixels got its visible polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Resolution {
    /// The nearest polygon at the span's left end stayed nearest to its
    /// right end: one decision for the whole span (the depth comparison at
    /// the span's two ends).
    Whole,
    /// A piece of a span split where two polygons' depths cross.
    Split,
    /// Resolved pixel by pixel in the one-row depth buffer fallback (a run
    /// of equal ids within it).
    Fallback,
}

/// One run of pixels on a row with one visible primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
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
    /// The visible primitive's window depth at the centre of column `x0`.
    pub depth0: f64,
    /// Its window depth at the centre of column `x1`.
    pub depth1: f64,
    /// The span this run belongs to: the columns between two consecutive
    /// crossings (first, last inclusive), where the same polygons cover
    /// every pixel. A `Whole` run is its span.
    pub span: (u32, u32),
    /// How many polygons cover the span (its active polygon list).
    pub polygons: u32,
}

/// An edge of the edge table: a non-horizontal triangle edge crossing at
/// least one row centre of its polygon's rows.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EdgeRecord {
    /// First row on which it is active: its bucket in the edge table.
    pub first_row: u32,
    /// Last row on which it is active.
    pub last_row: u32,
    /// Its triangle's primitive id.
    pub prim: u32,
    /// Its triangle's index in the scene's triangle list.
    pub triangle: u32,
    /// Which end of its polygon's run it bounds.
    pub side: Side,
    /// Start vertex, fixed point.
    pub from: FixedPt,
    /// End vertex, fixed point.
    pub to: FixedPt,
}

impl EdgeRecord {
    /// The x (window pixels) where the edge's line crosses the centre of
    /// `row` (`y = row + 0.5`).
    pub fn x_at(&self, row: u32) -> f64 {
        let (fx, fy) = (f64::from(self.from.x), f64::from(self.from.y));
        let y = (f64::from(row) + 0.5) * 256.0;
        (fx + (y - fy) * self.dx_dy()) / 256.0
    }

    /// The x at the centre of its first row.
    pub fn x_top(&self) -> f64 {
        self.x_at(self.first_row)
    }

    /// The step of x per row (`dx/dy`): the constant increment the active
    /// edge list adds from one row to the next.
    pub fn dx_dy(&self) -> f64 {
        f64::from(self.to.x - self.from.x) / f64::from(self.to.y - self.from.y)
    }
}

/// An edge of the active edge list on one row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActiveEdge {
    /// Its index in [`ScanlineTrace::edges`].
    pub edge: u32,
    /// Where it crosses the row's centre, window pixels.
    pub x: f64,
    /// The column bound the exact walker gives on this row: the first
    /// covered column of its polygon for a left edge, the last for a right
    /// edge (before clipping to the image).
    pub bound: i64,
}

/// The record of one frame's sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScanlineTrace {
    /// The edge table in bucket order: sorted by first row, so bucket `j`
    /// is the run of edges whose `first_row` is `j`.
    pub edges: Vec<EdgeRecord>,
    /// Every row's active edges, row after row.
    pub active: Vec<ActiveEdge>,
    /// Every row's runs, row after row, left to right.
    pub spans: Vec<SpanRecord>,
    /// `active[row_active[j]..row_active[j + 1]]` is row `j`'s.
    pub(crate) row_active: Vec<u32>,
    /// `spans[row_spans[j]..row_spans[j + 1]]` is row `j`'s.
    pub(crate) row_spans: Vec<u32>,
}

impl ScanlineTrace {
    /// Number of rows recorded.
    pub fn rows(&self) -> u32 {
        self.row_active.len().saturating_sub(1) as u32
    }

    /// The active edge list on `row`, sorted by x (ties by edge index).
    ///
    /// The scan loop keeps its list in table order and sorts the polygons'
    /// run ends (the crossings) instead; sorted by x it is Watkins' list.
    pub fn active_edges(&self, row: u32) -> &[ActiveEdge] {
        Self::slice(&self.active, &self.row_active, row)
    }

    /// The runs of `row`, left to right.
    pub fn row_spans(&self, row: u32) -> &[SpanRecord] {
        Self::slice(&self.spans, &self.row_spans, row)
    }

    /// The edges of the edge table's bucket `row` (those starting there).
    pub fn bucket(&self, row: u32) -> &[EdgeRecord] {
        let lo = self.edges.partition_point(|e| e.first_row < row);
        let hi = self.edges.partition_point(|e| e.first_row <= row);
        &self.edges[lo..hi]
    }

    fn slice<'a, T>(all: &'a [T], starts: &[u32], row: u32) -> &'a [T] {
        let j = row as usize;
        match (starts.get(j), starts.get(j + 1)) {
            (Some(&a), Some(&b)) => &all[a as usize..b as usize],
            _ => &[],
        }
    }

    /// Forgets everything, keeping the memory.
    pub(crate) fn clear(&mut self) {
        self.edges.clear();
        self.active.clear();
        self.spans.clear();
        self.row_active.clear();
        self.row_spans.clear();
    }

    /// Opens row `row`'s records (rows come in order).
    pub(crate) fn start_row(&mut self) {
        if self.row_active.is_empty() {
            self.row_active.push(0);
            self.row_spans.push(0);
        }
    }

    /// Closes the current row: sorts its active edges by x.
    pub(crate) fn end_row(&mut self) {
        let start = *self.row_active.last().unwrap_or(&0) as usize;
        self.active[start..].sort_by(|a, b| a.x.total_cmp(&b.x).then(a.edge.cmp(&b.edge)));
        self.row_active.push(self.active.len() as u32);
        self.row_spans.push(self.spans.len() as u32);
    }

    /// Records edge `edge` active on `row` with column bound `bound`.
    pub(crate) fn active_edge(&mut self, edge: u32, row: u32, bound: i64) {
        let x = self.edges[edge as usize].x_at(row);
        self.active.push(ActiveEdge { edge, x, bound });
    }

    /// Bytes held (capacity).
    pub(crate) fn bytes(&self) -> u64 {
        use std::mem::size_of;
        (self.edges.capacity() * size_of::<EdgeRecord>()
            + self.active.capacity() * size_of::<ActiveEdge>()
            + self.spans.capacity() * size_of::<SpanRecord>()
            + (self.row_active.capacity() + self.row_spans.capacity()) * 4) as u64
    }
}

/// Upper bound of a trace's bytes: every edge, each edge on each of its
/// rows (`edge_rows`, known once the table is built), at most one run per
/// pixel.
pub(crate) fn trace_bytes(edges: u64, edge_rows: u64, pixels: u64, height: u32) -> u64 {
    use std::mem::size_of;
    edges * size_of::<EdgeRecord>() as u64
        + edge_rows * size_of::<ActiveEdge>() as u64
        + pixels * size_of::<SpanRecord>() as u64
        + 2 * (u64::from(height) + 1) * 4
}
