//! The scanline sweep, row by row, from the trace the scanline records
//! itself ([`ScanlineOptions::record_spans`]): the edge table, each row's
//! active edge list and its runs. The page replays it.

use hider_scanline::{Resolution, Scanline, ScanlineOptions, ScanlineTrace, Side};
use hider_scene::Hider;
use hider_scene::frame::id_to_i32;
use wasm_bindgen::prelude::*;

use crate::session::Session;
use crate::steps::step_scene;
use crate::{JsResult, Page, js};

/// Numbers per edge in [`ScanlineSteps::edges`].
pub const EDGE_STRIDE: usize = 11;
/// Numbers per active edge in [`ScanlineSteps::active`].
pub const ACTIVE_STRIDE: usize = 3;
/// Numbers per run in [`ScanlineSteps::spans`].
pub const SPAN_STRIDE: usize = 9;

/// A recorded sweep and its image size.
#[derive(Clone, Debug, Default)]
pub struct ScanlineSteps {
    side: u32,
    trace: ScanlineTrace,
}

/// The page's code for how a run was decided: 1 whole span, 2 split where
/// depths cross, 3 the one-row depth buffer.
fn how_code(how: Resolution) -> u8 {
    match how {
        Resolution::Whole => 1,
        Resolution::Split => 2,
        Resolution::Fallback => 3,
    }
}

impl ScanlineSteps {
    /// Renders the session's scene and camera at `side` x `side` with the
    /// scanline recording its sweep.
    pub fn record(session: &Session, side: u32) -> Result<Self, String> {
        let (screen, mut frame) = step_scene(session, side)?;
        let mut scanline = Scanline::new(ScanlineOptions::default().with_record_spans(true));
        scanline
            .render(&screen, &mut frame)
            .map_err(|e| e.to_string())?;
        Ok(Self {
            side,
            trace: scanline.trace().clone(),
        })
    }

    /// The recorded trace.
    pub fn trace(&self) -> &ScanlineTrace {
        &self.trace
    }

    /// The sweep after `rows` rows: the ids the runs of those rows wrote
    /// (-1 elsewhere), and per pixel of the last of them how its run was
    /// decided (0 none, 1 whole span, 2 split, 3 the one-row fallback).
    pub fn step(&self, rows: u32) -> (Vec<i32>, Vec<u8>) {
        let w = self.side as usize;
        let mut ids = vec![-1; w * w];
        let mut how = vec![0u8; w * w];
        for s in self.trace.spans.iter().filter(|s| s.row < rows) {
            let base = s.row as usize * w;
            for x in s.x0..=s.x1 {
                ids[base + x as usize] = id_to_i32(s.prim);
                if s.row + 1 == rows {
                    how[base + x as usize] = how_code(s.how);
                }
            }
        }
        (ids, how)
    }

    /// The edge table in bucket order, [`EDGE_STRIDE`] numbers an edge:
    /// first row, last row, primitive, triangle, side (0 left, 1 right),
    /// x at the first row's centre, dx/dy, start x, start y, end x, end y
    /// (window pixels).
    pub fn edges(&self) -> Vec<f64> {
        let px = |v: i32| f64::from(v) / 256.0;
        (self.trace.edges.iter())
            .flat_map(|e| {
                [
                    f64::from(e.first_row),
                    f64::from(e.last_row),
                    f64::from(e.prim),
                    f64::from(e.triangle),
                    f64::from(u8::from(e.side == Side::Right)),
                    e.x_top(),
                    e.dx_dy(),
                    px(e.from.x),
                    px(e.from.y),
                    px(e.to.x),
                    px(e.to.y),
                ]
            })
            .collect()
    }

    /// Row `row`'s active edge list sorted by x, [`ACTIVE_STRIDE`] numbers
    /// an edge: its index in the edge table, x at the row's centre, the
    /// column bound the walker gives (first covered column for a left
    /// edge, last for a right one).
    pub fn active(&self, row: u32) -> Vec<f64> {
        (self.trace.active_edges(row).iter())
            .flat_map(|a| [f64::from(a.edge), a.x, a.bound as f64])
            .collect()
    }

    /// Row `row`'s runs, [`SPAN_STRIDE`] numbers a run: first and last
    /// column, primitive, how (1 whole, 2 split, 3 fallback), depth at both ends, the
    /// span's first and last column, the polygons covering the span.
    pub fn spans(&self, row: u32) -> Vec<f64> {
        (self.trace.row_spans(row).iter())
            .flat_map(|s| {
                [
                    f64::from(s.x0),
                    f64::from(s.x1),
                    f64::from(s.prim),
                    f64::from(how_code(s.how)),
                    s.depth0,
                    s.depth1,
                    f64::from(s.span.0),
                    f64::from(s.span.1),
                    f64::from(s.polygons),
                ]
            })
            .collect()
    }

    /// The active edges (table indices) whose crossing bounds the span of
    /// run `k` of `row`: a left edge whose first covered column is the
    /// span's first (or one past its last), a right edge whose last covered
    /// column is the span's last (or one before its first).
    pub fn span_edges(&self, row: u32, k: usize) -> Vec<u32> {
        let Some(s) = self.trace.row_spans(row).get(k) else {
            return Vec::new();
        };
        let (a, b) = (i64::from(s.span.0), i64::from(s.span.1));
        (self.trace.active_edges(row).iter())
            .filter(|e| match self.trace.edges[e.edge as usize].side {
                Side::Left => e.bound == a || e.bound == b + 1,
                Side::Right => e.bound == b || e.bound == a - 1,
            })
            .map(|e| e.edge)
            .collect()
    }
}

#[wasm_bindgen]
impl Page {
    /// Records the scanline's sweep of the current scene and camera at
    /// `side` x `side` (1 to 128); returns the number of rows (steps).
    pub fn scanline_trace(&mut self, side: u32) -> JsResult<u32> {
        self.scanline = ScanlineSteps::record(&self.session, side).map_err(js)?;
        Ok(side)
    }

    /// The ids after the first `rows` rows of the recorded sweep, -1
    /// elsewhere.
    pub fn scanline_ids(&self, rows: u32) -> Vec<i32> {
        self.scanline.step(rows).0
    }

    /// How each run of row `rows - 1` was decided, per pixel: 0 none, 1
    /// whole span, 2 split where depths cross, 3 the one-row depth buffer.
    pub fn scanline_how(&self, rows: u32) -> Vec<u8> {
        self.scanline.step(rows).1
    }

    /// The edge table, 11 numbers an edge (see `ScanlineSteps::edges`).
    pub fn scanline_edges(&self) -> Vec<f64> {
        self.scanline.edges()
    }

    /// Row `row`'s active edge list, 3 numbers an edge (edge, x, bound).
    pub fn scanline_active(&self, row: u32) -> Vec<f64> {
        self.scanline.active(row)
    }

    /// Row `row`'s runs, 9 numbers a run (see `ScanlineSteps::spans`).
    pub fn scanline_spans(&self, row: u32) -> Vec<f64> {
        self.scanline.spans(row)
    }

    /// The edges bounding the span of run `k` of row `row`.
    pub fn scanline_span_edges(&self, row: u32, k: usize) -> Vec<u32> {
        self.scanline.span_edges(row, k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sweep_ends_on_the_scanline_frame_and_names_its_structures() {
        for spec in ["gen:cyclic", "gen:intersecting", "gen:soup:80"] {
            let mut session = Session::new();
            session.set_scene(crate::scenes::from_spec(spec).unwrap());
            session.set_size(40, 40).unwrap();
            let steps = ScanlineSteps::record(&session, 40).unwrap();
            let (ids, _) = steps.step(40);
            assert_eq!(ids, session.render("scanline").unwrap().ids(), "{spec}");
            assert!(steps.step(0).0.iter().all(|&id| id == -1));
            let edges = steps.edges();
            assert_eq!(edges.len(), steps.trace().edges.len() * EDGE_STRIDE);
            let mut runs = 0;
            for row in 0..40 {
                let active = steps.active(row);
                assert_eq!(
                    active.len(),
                    steps.trace().active_edges(row).len() * ACTIVE_STRIDE
                );
                let spans = steps.spans(row);
                for k in 0..spans.len() / SPAN_STRIDE {
                    runs += 1;
                    let run = &spans[k * SPAN_STRIDE..(k + 1) * SPAN_STRIDE];
                    // A span that starts at an edge's crossing names it.
                    let bounding = steps.span_edges(row, k);
                    if run[6] > 0.0 && run[7] < 39.0 {
                        assert!(!bounding.is_empty(), "{spec} row {row} run {k}");
                    }
                    for e in bounding {
                        let first = edges[e as usize * EDGE_STRIDE];
                        let last = edges[e as usize * EDGE_STRIDE + 1];
                        assert!(first <= f64::from(row) && f64::from(row) <= last);
                    }
                }
            }
            assert_eq!(runs, steps.trace().spans.len(), "{spec}");
        }
        assert!(ScanlineSteps::record(&Session::new(), 500).is_err());
    }
}
