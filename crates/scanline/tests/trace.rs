//! The recorded sweep (`ScanlineOptions::record_spans`) against what it
//! claims: the edge table, each row's active edge list and runs, and the
//! frame they add up to.

mod common;

use hider_scanline::scene::{Frame, Hider, NO_ID, ScreenScene, procedural};
use hider_scanline::{Resolution, Scanline, ScanlineOptions, ScanlineTrace, Side};

/// Renders `s` with the trace on; the frame and the trace.
fn traced(s: &ScreenScene) -> (Frame, ScanlineTrace) {
    let (w, h) = (s.viewport.width, s.viewport.height);
    let mut hider = Scanline::new(ScanlineOptions::default().with_record_spans(true));
    let mut frame = Frame::new(w, h).unwrap();
    hider.render(s, &mut frame).unwrap();
    let mut plain = Frame::new(w, h).unwrap();
    Scanline::default().render(s, &mut plain).unwrap();
    assert_eq!(frame.ids, plain.ids, "recording changed the ids");
    assert_eq!(frame.depth, plain.depth, "recording changed the depth");
    (frame, hider.trace().clone())
}

/// The rows of the polygon of triangle `t` (the centres it can cover).
fn centre_rows(s: &ScreenScene, triangle: u32) -> (f64, f64) {
    let v = &s.tris[triangle as usize].v;
    let ys = v.map(|p| f64::from(p.y) / 256.0);
    (
        ys.iter().copied().fold(f64::INFINITY, f64::min),
        ys.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

fn check(s: &ScreenScene, what: &str) {
    let (frame, trace) = traced(s);
    let (w, h) = (frame.width(), frame.height());
    assert_eq!(trace.rows(), h, "{what}");
    assert!(!trace.edges.is_empty(), "{what}: no edges");
    // The edge table: bucketed by first row, each edge inside its
    // triangle's vertical extent and crossing a row centre at each end.
    for pair in trace.edges.windows(2) {
        assert!(
            pair[0].first_row <= pair[1].first_row,
            "{what}: bucket order"
        );
    }
    let mut bucketed = 0;
    for e in &trace.edges {
        let (lo, hi) = centre_rows(s, e.triangle);
        assert!(e.first_row <= e.last_row && e.last_row < h, "{what}: {e:?}");
        let (fy, ty) = (f64::from(e.from.y) / 256.0, f64::from(e.to.y) / 256.0);
        for row in [e.first_row, e.last_row] {
            let c = f64::from(row) + 0.5;
            assert!(
                c >= fy.min(ty) && c <= fy.max(ty),
                "{what}: {e:?} row {row}"
            );
            assert!(c >= lo && c <= hi, "{what}: {e:?} outside its triangle");
        }
        assert_eq!(e.prim, s.tris[e.triangle as usize].prim, "{what}");
        // Left edges go up the screen (a > 0 in E = a x + b y + c).
        assert_eq!(e.side == Side::Left, e.to.y < e.from.y, "{what}: {e:?}");
    }
    for row in 0..h {
        bucketed += trace.bucket(row).len();
        assert!(trace.bucket(row).iter().all(|e| e.first_row == row));
    }
    assert_eq!(bucketed, trace.edges.len(), "{what}");
    let mut ids = vec![NO_ID; (w * h) as usize];
    for row in 0..h {
        // The active edge list: the table's edges whose rows hold this one,
        // sorted by x, each at its crossing of the row centre.
        let active = trace.active_edges(row);
        let mut got: Vec<u32> = active.iter().map(|a| a.edge).collect();
        let mut want: Vec<u32> = (0..trace.edges.len() as u32)
            .filter(|&k| {
                let e = &trace.edges[k as usize];
                (e.first_row..=e.last_row).contains(&row)
            })
            .collect();
        assert!(
            active.windows(2).all(|p| p[0].x <= p[1].x),
            "{what} row {row}: x order"
        );
        got.sort_unstable();
        want.sort_unstable();
        assert_eq!(got, want, "{what} row {row}");
        let y = f64::from(row) + 0.5;
        for a in active {
            let e = &trace.edges[a.edge as usize];
            let (fx, fy) = (f64::from(e.from.x) / 256.0, f64::from(e.from.y) / 256.0);
            let (tx, ty) = (f64::from(e.to.x) / 256.0, f64::from(e.to.y) / 256.0);
            let x = fx + (y - fy) * (tx - fx) / (ty - fy);
            assert!((a.x - x).abs() < 1e-9, "{what} row {row}: {a:?} vs {x}");
            // The walker's column bound is the first (last) pixel centre
            // on the inner side of the crossing, to the fill rule's 1/256.
            let tol = 1.0 / 256.0 + 1e-9;
            match e.side {
                Side::Left => {
                    let c = a.bound as f64 + 0.5;
                    assert!(
                        c >= x - tol && c - 1.0 <= x + tol,
                        "{what} row {row}: {a:?}"
                    )
                }
                Side::Right => {
                    let c = a.bound as f64 + 0.5;
                    assert!(
                        c <= x + tol && c + 1.0 >= x - tol,
                        "{what} row {row}: {a:?}"
                    )
                }
            }
        }
        // The runs tile the row's covered pixels, left to right, each
        // inside its span, with the frame's depth at its ends.
        let mut next = 0;
        for r in trace.row_spans(row) {
            assert_eq!(r.row, row);
            assert!(r.x0 >= next && r.x0 <= r.x1 && r.x1 < w, "{what}: {r:?}");
            assert!(r.span.0 <= r.x0 && r.x1 <= r.span.1, "{what}: {r:?}");
            assert!(r.polygons >= 1, "{what}: {r:?}");
            if r.how == Resolution::Whole {
                assert_eq!(r.span, (r.x0, r.x1), "{what}: a whole span is one run");
            }
            for x in next..r.x0 {
                assert_eq!(
                    frame.ids[(row * w + x) as usize],
                    NO_ID,
                    "{what}: gap {x},{row}"
                );
            }
            for x in r.x0..=r.x1 {
                ids[(row * w + x) as usize] = r.prim;
            }
            let at = |x: u32| frame.depth[(row * w + x) as usize];
            assert_eq!(
                (r.depth0 as f32, r.depth1 as f32),
                (at(r.x0), at(r.x1)),
                "{what}"
            );
            next = r.x1 + 1;
        }
        for x in next..w {
            assert_eq!(
                frame.ids[(row * w + x) as usize],
                NO_ID,
                "{what}: gap {x},{row}"
            );
        }
    }
    // All rows together are the frame, bit for bit.
    assert_eq!(ids, frame.ids, "{what}");
}

#[test]
fn the_trace_is_the_sweep() {
    let scenes = [
        ("intersecting", procedural::intersecting_pair()),
        ("cyclic", procedural::cyclic_triple()),
        ("sphere", procedural::uv_sphere(12)),
        ("soup", procedural::random_soup(60, 7)),
    ];
    for (what, scene) in scenes {
        for size in [(33, 40), (64, 64)] {
            check(&common::screen_from(&scene, None, size.0, size.1), what);
        }
    }
    check(&common::knot(12, 64, 4), "knot");
}

#[test]
fn the_trace_is_off_by_default_and_within_the_budget() {
    let s = common::screen_from(&procedural::uv_sphere(12), None, 64, 64);
    let mut hider = Scanline::default();
    let mut frame = Frame::new(64, 64).unwrap();
    hider.render(&s, &mut frame).unwrap();
    assert!(hider.trace().edges.is_empty() && hider.trace().rows() == 0);
    // Enough for the tables, not for the trace: refused, naming it.
    let none = ScanlineOptions::default().with_max_bytes(0);
    let tables = match Scanline::new(none).render(&s, &mut frame) {
        Err(hider_scanline::scene::Error::Budget { value, .. }) => value,
        other => panic!("{other:?}"),
    };
    Scanline::new(ScanlineOptions::default().with_max_bytes(tables))
        .render(&s, &mut frame)
        .unwrap();
    let options = ScanlineOptions::default()
        .with_record_spans(true)
        .with_max_bytes(tables);
    let err = Scanline::new(options).render(&s, &mut frame).unwrap_err();
    assert!(err.to_string().contains("record_spans"), "{err}");
}
