//! The scan loop: rows top to bottom, edges and polygons activated from the
//! bucketed tables, per-row crossings sorted into spans.

use hider_scene::{Frame, Hider, Result, ScreenScene, check_frame};

use crate::edge_table::{EdgeTable, NAME, table_bytes};
use crate::options::ScanlineOptions;
use crate::span::{Active, RowOut, SpanResolver};
use crate::stats::ScanlineStats;
use crate::trace::{ScanlineTrace, SpanRecord, trace_bytes};
use crate::walker::{Edge, Side};

/// Crossing key bit marking a polygon entering (its first covered column);
/// without it the key marks the column just after its last one.
const ENTER: u64 = 1 << 31;
/// Mask of the polygon slot in a crossing key.
const SLOT: u64 = ENTER - 1;

/// The scanline hidden-surface algorithm (Wylie et al. 1967, Watkins 1970).
///
/// Built with [`Hider::new`] (or `Default`, the accurate options). Keeps its
/// edge table, active lists and row buffer between frames: rendering
/// several frames with one `Scanline` reuses their memory.
#[derive(Clone, Debug, Default)]
pub struct Scanline {
    options: ScanlineOptions,
    table: EdgeTable,
    /// The active edge list.
    ael: Vec<Edge>,
    /// Slots of the polygons whose row range covers the current row.
    active_polys: Vec<u32>,
    /// The current row's crossings, packed `column << 32 | ENTER? | slot`.
    crossings: Vec<u64>,
    /// The active polygon list of the current span.
    apl: Vec<Active>,
    resolver: SpanResolver,
    /// The sweep of the last frame, when recording.
    trace: ScanlineTrace,
}

impl Scanline {
    /// Renders the rows of `frame` (already cleared) from the built tables.
    fn scan(&mut self, frame: &mut Frame, stats: &mut ScanlineStats) {
        let (width, height) = (frame.width(), frame.height());
        let mut trace = std::mem::take(&mut self.trace);
        // Lent to the rows (the row loop needs `&mut self` beside them).
        let surfaces = std::mem::take(&mut self.table.surfaces);
        let w = width as usize;
        for (row, (ids, depth)) in (0..height).zip(
            frame
                .ids
                .chunks_exact_mut(w)
                .zip(frame.depth.chunks_exact_mut(w)),
        ) {
            // A row costs far more than the poll; `render` returns the error.
            if self.options.cancel.check().is_err() {
                break;
            }
            let mut out = RowOut {
                row,
                ids,
                depth,
                surfaces: &surfaces,
                trace: self.options.record_spans.then_some(&mut trace),
                span: (0, 0, 0),
            };
            if let Some(t) = out.trace.as_deref_mut() {
                t.start_row();
            }
            self.scan_row(&mut out, stats);
            if let Some(t) = out.trace.as_deref_mut() {
                t.end_row();
            }
        }
        self.trace = trace;
        self.table.surfaces = surfaces;
    }

    /// One row: activate, walk the active edges, sort the crossings, resolve
    /// the spans between them.
    fn scan_row(&mut self, out: &mut RowOut<'_>, stats: &mut ScanlineStats) {
        let row = out.row;
        let (new_polys, new_edges) = self.table.bucket(row);
        self.active_polys.extend_from_slice(new_polys);
        self.ael.extend_from_slice(new_edges);
        if self.active_polys.is_empty() {
            return;
        }
        let active = self.active_polys.len() as u64;
        stats.active_polygons_max = stats.active_polygons_max.max(active);
        stats.active_polygon_rows += active;
        self.walk_edges(row, out.ids.len() as i64 - 1, out.trace.as_deref_mut());
        self.crossings.sort_unstable();
        stats.crossings += self.crossings.len() as u64;
        self.sweep(out, stats);
    }

    /// Steps the active edge list to `row`, turning each active polygon's
    /// edges into its run's two crossings, and retires what ends here.
    fn walk_edges(&mut self, row: u32, last_column: i64, trace: Option<&mut ScanlineTrace>) {
        // Each polygon's run on this row: the tightest of its active left
        // and right edges (every row of a polygon has at least one of each).
        let polys = &mut self.table.polys;
        for &s in &self.active_polys {
            let p = &mut polys[s as usize];
            p.l = i64::MIN;
            p.r = i64::MAX;
        }
        // Recorded in a pass of its own, keeping the walk's loop as it is.
        if let Some(t) = trace {
            for e in &self.ael {
                t.active_edge(e.id, row, e.bound());
            }
        }
        self.ael.retain_mut(|e| {
            let p = &mut polys[e.poly as usize];
            match e.side {
                Side::Left => p.l = p.l.max(e.bound()),
                Side::Right => p.r = p.r.min(e.bound()),
            }
            if e.last_row == row {
                false
            } else {
                e.advance();
                true
            }
        });
        self.crossings.clear();
        for &s in &self.active_polys {
            let p = &polys[s as usize];
            let (l, r) = (p.l.max(0), p.r.min(last_column));
            if l <= r {
                self.crossings.push((l as u64) << 32 | ENTER | u64::from(s));
                self.crossings.push(((r + 1) as u64) << 32 | u64::from(s));
            }
        }
        self.active_polys
            .retain(|&s| polys[s as usize].last_row > row);
    }

    /// Sweeps the sorted crossings left to right: applies every crossing at
    /// a column to the active polygon list, then resolves the span up to
    /// the next crossing column.
    fn sweep(&mut self, out: &mut RowOut<'_>, stats: &mut ScanlineStats) {
        let keys = &self.crossings;
        let polys = &self.table.polys;
        let last_column = out.ids.len() as i64 - 1;
        let mut k = 0;
        while k < keys.len() {
            let x = (keys[k] >> 32) as u32;
            let mut leaving = false;
            while k < keys.len() && (keys[k] >> 32) as u32 == x {
                let slot = (keys[k] & SLOT) as u32;
                if keys[k] & ENTER != 0 {
                    self.apl.push(Active { depth: 0.0, slot });
                } else {
                    leaving = true;
                }
                k += 1;
            }
            if leaving {
                // Every polygon whose run ends before `x` leaves at once,
                // in one pass that keeps the depth order for the next
                // span's sort: removing them one by one (a search and a
                // shift each) was quadratic when thousands of polygons
                // end on the same column.
                stats.apl_removal_passes += 1;
                stats.apl_removal_scanned += self.apl.len() as u64;
                self.apl
                    .retain(|a| polys[a.slot as usize].r.min(last_column) >= i64::from(x));
            }
            if k < keys.len() && !self.apl.is_empty() {
                let next = (keys[k] >> 32) as u32;
                self.resolver.resolve(
                    &mut self.apl,
                    x,
                    next - 1,
                    out,
                    self.options.max_splits_per_span,
                    stats,
                );
            }
        }
        // Every run's end was a crossing, so the list is empty again.
        debug_assert!(self.apl.is_empty());
        self.apl.clear();
    }

    /// The runs of the last frame in row order, left to right, each with its
    /// visible primitive and how it was decided; empty unless
    /// [`ScanlineOptions::record_spans`] is on.
    pub fn spans(&self) -> &[SpanRecord] {
        &self.trace.spans
    }

    /// The whole record of the last frame's sweep: the edge table, each
    /// row's active edge list and runs; empty unless
    /// [`ScanlineOptions::record_spans`] is on.
    pub fn trace(&self) -> &ScanlineTrace {
        &self.trace
    }

    /// Bytes held by the working tables and lists (capacity).
    pub fn bytes(&self) -> u64 {
        use std::mem::size_of;
        self.table.bytes()
            + (self.ael.capacity() * size_of::<Edge>()
                + self.active_polys.capacity() * 4
                + self.crossings.capacity() * 8
                + self.apl.capacity() * size_of::<Active>()) as u64
            + self.resolver.bytes()
            + self.trace.bytes()
    }
}

impl Hider for Scanline {
    type Options = ScanlineOptions;
    type Stats = ScanlineStats;

    fn new(options: ScanlineOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    fn options(&self) -> &ScanlineOptions {
        &self.options
    }

    fn name(&self) -> &str {
        NAME
    }

    /// Renders `scene` into `frame` (ids and window depth; colour is left
    /// to [`hider_scene::shade_frame`]).
    ///
    /// Errors, before touching the frame's contents, when the frame size
    /// differs from the scene's viewport, the tables would exceed
    /// [`ScanlineOptions::max_bytes`], or a triangle is unusable (not
    /// positively oriented, beyond the fixed-point range, non-finite depth
    /// plane).
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<ScanlineStats> {
        check_frame(NAME, scene, frame)?;
        let (width, height) = (scene.viewport.width, scene.viewport.height);
        let need = table_bytes(scene.tris.len(), width, height);
        let record = self.options.record_spans;
        self.trace.clear();
        let edge_rows = self.table.build(
            &scene.tris,
            height,
            self.options.max_bytes,
            need,
            record.then_some(&mut self.trace.edges),
        )?;
        if record {
            let pixels = u64::from(width) * u64::from(height);
            let edges = self.table.edge_count() as u64;
            let with_trace = need + trace_bytes(edges, edge_rows, pixels, height);
            if with_trace > self.options.max_bytes {
                return Err(hider_scene::Error::Budget {
                    what: "scanline table and trace bytes (record_spans)",
                    value: with_trace,
                    limit: self.options.max_bytes,
                });
            }
        }
        self.resolver.prepare(width);
        frame.clear();
        self.ael.clear();
        self.active_polys.clear();
        self.apl.clear();
        let mut stats = ScanlineStats {
            polygons: self.table.polygon_count() as u64,
            edges: self.table.edge_count() as u64,
            rows: u64::from(height),
            ..ScanlineStats::default()
        };
        self.scan(frame, &mut stats);
        self.options.cancel.poll()?;
        stats.pixels_written = frame.covered_count() as u64;
        stats.peak_bytes = self.bytes();
        stats.finish();
        Ok(stats)
    }
}
