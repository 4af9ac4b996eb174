//! An opt-in record of what the painter did, as plain data: for teaching
//! (a page that replays Newell, Newell & Sancha step by step) and for
//! tests.
//!
//! Off by default ([`crate::PainterOptions::trace`]); when off, each place
//! an event would be recorded costs one test of an `Option`.

use crate::newell::Decided;

/// Which of Newell, Newell & Sancha's tests settled a pair, or that none
/// did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceTest {
    /// Test 1: the depth extents do not overlap.
    Depth,
    /// Test 2: the x extents do not overlap.
    X,
    /// Test 3: the y extents do not overlap.
    Y,
    /// Test 4: P lies behind Q's plane.
    PBehind,
    /// Test 5: Q lies in front of P's plane.
    QInFront,
    /// Test 6: the projections do not overlap.
    Projection,
    /// One of the two covers at most one pixel centre, and on it P is not
    /// nearer than Q (or they share none).
    Centre,
    /// Every test failed: Q may have to be painted before P.
    Blocked,
}

impl From<Decided> for TraceTest {
    fn from(d: Decided) -> Self {
        match d {
            Decided::Depth => TraceTest::Depth,
            Decided::X => TraceTest::X,
            Decided::Y => TraceTest::Y,
            Decided::PBehind => TraceTest::PBehind,
            Decided::QInFront => TraceTest::QInFront,
            Decided::Projection => TraceTest::Projection,
            Decided::Centre => TraceTest::Centre,
        }
    }
}

/// One step of the ordering. Pieces are indices into the frame's piece
/// arena: `0..n` are the scene's triangles in order, later ones are
/// halves made by splits ([`TraceEvent::Split`] names them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceEvent {
    /// The candidate `p` (the next to paint) was compared with `q`, and
    /// `test` settled the pair (or it was blocked).
    Test {
        /// The candidate.
        p: u32,
        /// The piece it was compared with.
        q: u32,
        /// Which test settled it.
        test: TraceTest,
    },
    /// `piece` blocked the candidate and may itself go first: it was moved
    /// to the head of the list (Newell's mark set).
    Move {
        /// The moved piece.
        piece: u32,
    },
    /// The candidate `p` and `q` form a cycle (`q` was moved before, so
    /// moving it again would loop): the split that follows breaks it.
    CycleBroken {
        /// The candidate.
        p: u32,
        /// The moved piece it is blocked by again.
        q: u32,
    },
    /// `piece` was split into `halves` along the plane of triangle
    /// `plane` (an index into the scene's triangles), or along a screen
    /// line (an edge of the other piece, a bisector) when `None`.
    Split {
        /// The piece split (never painted).
        piece: u32,
        /// Its two halves, new pieces.
        halves: [u32; 2],
        /// The triangle whose plane cut it, if a plane did.
        plane: Option<u32>,
    },
    /// `piece` is hidden at every point (`cull.rs`) and was dropped.
    Culled {
        /// The dropped piece.
        piece: u32,
    },
    /// `piece` was painted: appended to the drawing order.
    Painted {
        /// The painted piece.
        piece: u32,
    },
}

/// What the painter did in its last frame, when
/// [`crate::PainterOptions::trace`] is on ([`crate::Painter::trace`]):
/// every event in the order it happened, and the final drawing order.
///
/// Bulk decisions are not listed pair by pair: when the sorted list is
/// scanned, test 1 settles every piece past the first whose depth extent
/// lies wholly in front of the candidate at once, and pieces whose screen
/// boxes cannot meet the candidate's are never visited (the bin grid).
///
/// ```
/// use hider_painter::{Painter, PainterOptions, TraceEvent};
/// use hider_scene::{prepare, procedural, Frame, Hider, PrepareOptions, View};
///
/// let scene = procedural::intersecting_pair();
/// let screen = prepare(&scene, &View::for_scene(&scene, 48, 48)?, &PrepareOptions::default())?;
/// let mut painter = Painter::new(PainterOptions::default().with_trace(true));
/// painter.render(&screen, &mut Frame::new(48, 48)?)?;
/// let trace = painter.trace().expect("tracing was on");
/// // The two triangles pierce each other: one is split by the other's plane.
/// assert!(trace.events.iter().any(|e| matches!(e, TraceEvent::Split { plane: Some(_), .. })));
/// assert_eq!(trace.order.len(), painter.ordered_pieces().len());
/// # Ok::<(), hider_scene::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PainterTrace {
    /// Everything recorded, in order.
    pub events: Vec<TraceEvent>,
    /// The drawing order: piece indices, farthest first, as
    /// [`crate::Painter::ordered_pieces`] lists them.
    pub order: Vec<u32>,
    /// Per piece index, the primitive id of its triangle.
    pub prims: Vec<u32>,
}

impl PainterTrace {
    /// Forgets the last frame.
    pub(crate) fn clear(&mut self) {
        self.events.clear();
        self.order.clear();
        self.prims.clear();
    }
}
