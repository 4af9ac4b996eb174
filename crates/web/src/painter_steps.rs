//! The painter's step-through: Newell, Newell & Sancha's ordering replayed
//! from the painter's own trace ([`hider_painter::PainterTrace`]), one
//! event a step, with the pixels painted so far.

use hider_painter::{Painter, PainterOptions, Piece, TraceEvent, TraceTest};
use hider_scene::frame::id_to_i32;
use hider_scene::geom::fixed::{SUBPIXEL_SCALE, pixel_center};
use hider_scene::{Frame, Hider, ScreenScene};

use crate::session::Session;
use crate::steps::step_scene;

/// A recorded painter run: its events, the pieces it painted and the
/// screen scene they came from.
#[derive(Clone, Debug, Default)]
pub struct PainterSteps {
    side: u32,
    screen: Option<ScreenScene>,
    events: Vec<TraceEvent>,
    /// Per arena index, the piece when it was painted (halves split again
    /// are never painted and have none).
    painted: Vec<Option<Piece>>,
    /// Per arena index, the piece it was split from (`u32::MAX` for the
    /// scene's triangles).
    parent: Vec<u32>,
    /// Per arena index, its primitive id.
    prims: Vec<u32>,
    /// The painter's own frame, which the last step must equal.
    frame: Option<Frame>,
}

impl PainterSteps {
    /// Renders the session's scene and camera at `side` x `side` with the
    /// painter tracing ([`PainterOptions::with_trace`]).
    pub fn record(session: &Session, side: u32) -> Result<Self, String> {
        let (screen, mut frame) = step_scene(session, side)?;
        let mut painter = Painter::new(PainterOptions::default().with_trace(true));
        painter
            .render(&screen, &mut frame)
            .map_err(|e| e.to_string())?;
        let trace = painter.trace().ok_or("the painter recorded no trace")?;
        let n = trace.prims.len();
        let mut painted = vec![None; n];
        for (&id, piece) in trace.order.iter().zip(painter.ordered_pieces()) {
            painted[id as usize] = Some(piece.clone());
        }
        let mut parent = vec![u32::MAX; n];
        for e in &trace.events {
            if let TraceEvent::Split { piece, halves, .. } = *e {
                for h in halves {
                    parent[h as usize] = piece;
                }
            }
        }
        Ok(Self {
            side,
            events: trace.events.clone(),
            painted,
            parent,
            prims: trace.prims.clone(),
            screen: Some(screen),
            frame: Some(frame),
        })
    }

    /// The number of steps (events).
    pub fn len(&self) -> usize {
        self.events.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// The painter's frame of the recorded view.
    pub fn frame(&self) -> Option<&Frame> {
        self.frame.as_ref()
    }

    /// The ids after the first `k` events: every piece painted by then,
    /// far to near, at the pixel centres it covers ([`Piece::covers`]),
    /// keeping the lower id where two pieces have exactly the same depth
    /// (the painter's tie rule); -1 for background.
    pub fn ids(&self, k: usize) -> Vec<i32> {
        let w = self.side as usize;
        let mut ids = vec![-1i32; w * w];
        let mut depth = vec![f64::INFINITY; w * w];
        let Some(screen) = &self.screen else {
            return ids;
        };
        for e in self.events.iter().take(k) {
            let TraceEvent::Painted { piece } = *e else {
                continue;
            };
            let Some(p) = &self.painted[piece as usize] else {
                continue;
            };
            let tri = &screen.tris[p.source as usize];
            let Some((x0, y0, x1, y1)) = tri.pixel_bounds(screen.viewport) else {
                continue;
            };
            for j in y0..=y1 {
                let y = i64::from(pixel_center(j as i32));
                for i in x0..=x1 {
                    if !p.covers(tri, i64::from(pixel_center(i as i32)), y) {
                        continue;
                    }
                    let at = j as usize * w + i as usize;
                    let z = tri.depth.eval(f64::from(i) + 0.5, f64::from(j) + 0.5);
                    let prim = id_to_i32(p.prim);
                    if z == depth[at] && ids[at] < prim {
                        continue;
                    }
                    depth[at] = z;
                    ids[at] = prim;
                }
            }
        }
        ids
    }

    /// The outline of piece `id` in window pixels (`x0 y0 x1 y1 ...`): its
    /// own polygon when it was painted, else its triangle's (a piece split
    /// again before painting is not kept by the painter).
    pub fn outline(&self, id: u32) -> Vec<f64> {
        if let Some(p) = self.painted.get(id as usize).and_then(Option::as_ref) {
            return p.polygon.iter().flat_map(|v| [v.x, v.y]).collect();
        }
        let (Some(screen), true) = (&self.screen, (id as usize) < self.parent.len()) else {
            return Vec::new();
        };
        let mut root = id;
        while self.parent[root as usize] != u32::MAX {
            root = self.parent[root as usize];
        }
        let scale = f64::from(SUBPIXEL_SCALE);
        screen.tris[root as usize]
            .v
            .iter()
            .flat_map(|v| [f64::from(v.x) / scale, f64::from(v.y) / scale])
            .collect()
    }

    /// Event `k - 1` (the one step `k` shows): its kind, the pieces it
    /// names (-1 where none), and a sentence for the page.
    pub fn event(&self, k: usize) -> (String, [i64; 3], String) {
        let Some(e) = k.checked_sub(1).and_then(|i| self.events.get(i)) else {
            return ("none".into(), [-1; 3], "nothing painted yet".into());
        };
        let tri = |p: u32| format!("piece {p} (triangle {})", self.prims[p as usize]);
        match *e {
            TraceEvent::Test { p, q, test } => (
                if test == TraceTest::Blocked {
                    "blocked"
                } else {
                    "test"
                }
                .into(),
                [p.into(), q.into(), -1],
                format!("{} against {}: {}", tri(p), tri(q), test_text(test)),
            ),
            TraceEvent::Move { piece } => (
                "move".into(),
                [piece.into(), -1, -1],
                format!("{} may go first: moved to the head of the list", tri(piece)),
            ),
            TraceEvent::CycleBroken { p, q } => (
                "cycle".into(),
                [p.into(), q.into(), -1],
                format!(
                    "{} is blocked again by {}, moved before: a cycle, broken by a split",
                    tri(p),
                    tri(q)
                ),
            ),
            TraceEvent::Split {
                piece,
                halves,
                plane,
            } => (
                "split".into(),
                [piece.into(), halves[0].into(), halves[1].into()],
                format!(
                    "{} split into pieces {} and {} {}",
                    tri(piece),
                    halves[0],
                    halves[1],
                    match plane {
                        Some(t) => format!("along the plane of triangle {t}"),
                        None => "along a screen line".into(),
                    }
                ),
            ),
            TraceEvent::Culled { piece } => (
                "culled".into(),
                [piece.into(), -1, -1],
                format!("{} is hidden everywhere: dropped", tri(piece)),
            ),
            TraceEvent::Painted { piece } => (
                "painted".into(),
                [piece.into(), -1, -1],
                format!("{} painted", tri(piece)),
            ),
        }
    }

    /// How many events of each test kind, as `name count` lines (the
    /// page's table of which Newell test decided how often).
    pub fn test_counts(&self) -> String {
        let all = [
            TraceTest::Depth,
            TraceTest::X,
            TraceTest::Y,
            TraceTest::PBehind,
            TraceTest::QInFront,
            TraceTest::Projection,
            TraceTest::Centre,
            TraceTest::Blocked,
        ];
        let counts = all.map(|t| {
            let n = self
                .events
                .iter()
                .filter(|e| matches!(e, TraceEvent::Test { test, .. } if *test == t))
                .count();
            (t, n)
        });
        counts
            .iter()
            .filter(|(_, c)| *c > 0)
            .map(|(t, c)| format!("{}\t{c}", test_text(*t)))
            .collect::<Vec<_>>()
            .join("\n")
    }
}

/// The page's words for a Newell test's outcome.
fn test_text(test: TraceTest) -> &'static str {
    match test {
        TraceTest::Depth => "test 1, depth extents do not overlap",
        TraceTest::X => "test 2, x extents do not overlap",
        TraceTest::Y => "test 3, y extents do not overlap",
        TraceTest::PBehind => "test 4, P behind Q's plane",
        TraceTest::QInFront => "test 5, Q in front of P's plane",
        TraceTest::Projection => "test 6, projections do not overlap",
        TraceTest::Centre => "pixel centres: P not nearer on the one shared centre",
        TraceTest::Blocked => "every test failed: blocked",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_step_is_the_painters_frame_and_the_cycle_is_split() {
        for spec in [
            "gen:cyclic",
            "gen:intersecting",
            "gen:soup:80",
            "hard:cyclic_overlap",
            // Exact depth ties: the painter's tie rule decides.
            "gen:coplanar",
        ] {
            let mut session = Session::new();
            session.set_scene(crate::scenes::from_spec(spec).unwrap());
            session.set_size(48, 48).unwrap();
            let steps = PainterSteps::record(&session, 48).unwrap();
            let last = steps.ids(steps.len());
            assert_eq!(last, session.render("painter").unwrap().ids(), "{spec}");
            assert!(steps.ids(0).iter().all(|&id| id == -1));
            if spec == "gen:cyclic" {
                let kinds: Vec<String> = (1..=steps.len()).map(|k| steps.event(k).0).collect();
                assert!(kinds.iter().any(|k| k == "split"), "{kinds:?}");
                assert!(kinds.iter().any(|k| k == "blocked"), "{kinds:?}");
                // Every piece named has an outline.
                for k in 1..=steps.len() {
                    for p in steps.event(k).1.into_iter().filter(|&p| p >= 0) {
                        assert!(steps.outline(p as u32).len() >= 6);
                    }
                }
            }
        }
        assert!(PainterSteps::record(&Session::new(), 0).is_err());
    }
}
