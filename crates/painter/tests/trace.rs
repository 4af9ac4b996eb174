//! The opt-in trace of the ordering (`PainterTrace`): its final order is
//! the order the painter draws, its events account for the counters, and
//! tracing changes nothing else.

use glam::DVec3;
use hider_painter::{Painter, PainterOptions, PainterStats, PainterTrace, TraceEvent, TraceTest};
use hider_scene::procedural::SplitMix64;
use hider_scene::{Frame, Hider, Scene, ScreenScene, procedural};
use hider_testkit::{render, screen};

fn traced(s: &ScreenScene) -> (Painter, Frame, PainterStats) {
    let mut painter = Painter::new(PainterOptions::default().with_trace(true));
    let (frame, stats) = render(&mut painter, s);
    (painter, frame, stats)
}

fn count(trace: &PainterTrace, f: impl Fn(&TraceEvent) -> bool) -> u64 {
    trace.events.iter().filter(|e| f(e)).count() as u64
}

fn scenes() -> Vec<(&'static str, ScreenScene)> {
    let mut rng = SplitMix64::new(3);
    let cube: Vec<DVec3> = (0..60 * 3)
        .map(|_| {
            DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
        })
        .collect();
    vec![
        (
            "intersecting pair",
            screen(&procedural::intersecting_pair(), 48, 48),
        ),
        (
            "cyclic triple",
            screen(&procedural::cyclic_triple(), 48, 48),
        ),
        ("cube", screen(&procedural::cube(), 48, 48)),
        ("60 in a cube", screen(&Scene::from_triangles(cube), 64, 64)),
    ]
}

#[test]
fn the_traced_order_is_the_drawing_order() {
    for (what, s) in scenes() {
        let (painter, frame, stats) = traced(&s);
        let trace = painter.trace().expect("traced");
        let drawn: Vec<u32> = painter.ordered_pieces().map(|p| p.prim).collect();
        let listed: Vec<u32> = trace
            .order
            .iter()
            .map(|&k| trace.prims[k as usize])
            .collect();
        assert_eq!(listed, drawn, "{what}");
        // The painted events, in order, are the drawing order.
        let painted: Vec<u32> = trace
            .events
            .iter()
            .filter_map(|e| match e {
                TraceEvent::Painted { piece } => Some(*piece),
                _ => None,
            })
            .collect();
        assert_eq!(painted, trace.order, "{what}");
        // The events account for the counters.
        assert_eq!(
            count(trace, |e| matches!(e, TraceEvent::Split { .. })),
            stats.splits,
            "{what}"
        );
        assert_eq!(
            count(trace, |e| matches!(e, TraceEvent::Move { .. })),
            stats.moves,
            "{what}"
        );
        assert_eq!(
            count(trace, |e| matches!(e, TraceEvent::Culled { .. })),
            stats.culled,
            "{what}"
        );
        assert_eq!(
            count(trace, |e| matches!(
                e,
                TraceEvent::Test {
                    test: TraceTest::Blocked,
                    ..
                }
            )),
            stats.blocked,
            "{what}"
        );
        // Tracing changes neither the frame nor the counters.
        let (plain_frame, plain_stats) = render(&mut Painter::default(), &s);
        assert_eq!(plain_frame, frame, "{what}");
        assert_eq!(plain_stats, stats, "{what}");
    }
}

/// In a scene with cycles (60 random triangles in a cube), each broken
/// cycle is followed by the split that breaks it, and its blocker was
/// moved before.
#[test]
fn broken_cycles_are_traced_with_the_split_that_breaks_them() {
    let (_, s) = scenes().pop().unwrap();
    let (painter, _, _) = traced(&s);
    let events = &painter.trace().unwrap().events;
    let mut cycles = 0;
    for (k, e) in events.iter().enumerate() {
        if let TraceEvent::CycleBroken { q, .. } = *e {
            cycles += 1;
            assert!(
                matches!(events[k + 1], TraceEvent::Split { .. }),
                "{:?}",
                &events[k..k + 2]
            );
            assert!(
                events[..k].contains(&TraceEvent::Move { piece: q }),
                "{q} was never moved"
            );
        }
    }
    assert!(cycles > 0);
}

#[test]
fn no_trace_unless_asked() {
    let s = screen(&procedural::intersecting_pair(), 32, 32);
    let mut painter = Painter::default();
    render(&mut painter, &s);
    assert!(painter.trace().is_none());
}
