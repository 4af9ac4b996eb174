//! The recorded windows and classes (`WarnockOptions::record_classes`)
//! against a brute-force classification over each window's pixel centres,
//! and against the decisions they led to.

use hider_geom::edge::triangle_covers;
use hider_geom::fixed::pixel_center;
use hider_scene::{Frame, Hider, PrepareOptions, ScreenScene, View, prepare, procedural};
use hider_warnock::{
    Class, Look, Outcome, Rule, Warnock, WarnockOptions, WindowClasses, WindowRecord,
};

fn screen(scene: &hider_scene::Scene, w: u32, h: u32) -> ScreenScene {
    let view = View::for_scene(scene, w, h).unwrap();
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

/// How many of window `w`'s pixel centres triangle `t` covers, of how many.
fn covered(s: &ScreenScene, t: u32, w: &WindowRecord) -> (u64, u64) {
    let v = &s.tris[t as usize].v;
    let mut n = 0;
    for y in w.y0..w.y1 {
        for x in w.x0..w.x1 {
            let (cx, cy) = (pixel_center(x as i32), pixel_center(y as i32));
            n += u64::from(triangle_covers(v, i64::from(cx), i64::from(cy)));
        }
    }
    (n, u64::from(w.x1 - w.x0) * u64::from(w.y1 - w.y0))
}

/// Whether triangle `t`'s vertices lie inside window `w`'s area.
fn inside_area(s: &ScreenScene, t: u32, w: &WindowRecord) -> bool {
    s.tris[t as usize].v.iter().all(|p| {
        (i64::from(w.x0) * 256..i64::from(w.x1) * 256).contains(&i64::from(p.x))
            && (i64::from(w.y0) * 256..i64::from(w.y1) * 256).contains(&i64::from(p.y))
    })
}

fn holds(outer: &WindowRecord, inner: &WindowRecord) -> bool {
    outer.x0 <= inner.x0 && outer.y0 <= inner.y0 && outer.x1 >= inner.x1 && outer.y1 >= inner.y1
}

fn check(s: &ScreenScene, what: &str) -> WindowClasses {
    let (w, h) = (s.viewport.width, s.viewport.height);
    let mut plain = Frame::new(w, h).unwrap();
    Warnock::default().render(s, &mut plain).unwrap();
    let options = WarnockOptions::default()
        .with_record_classes(true)
        .with_record_regions(true);
    let mut warnock = Warnock::new(options);
    let mut frame = Frame::new(w, h).unwrap();
    warnock.render(s, &mut frame).unwrap();
    assert_eq!(frame.ids, plain.ids, "{what}: recording changed the ids");
    assert_eq!(frame.depth, plain.depth, "{what}");
    let record = warnock.window_classes().clone();
    assert!(!record.truncated, "{what}");
    // The windows are the regions: the decided ones the leaves, the cut
    // ones the cut regions.
    let key = |r: &WindowRecord| (r.level, r.x0, r.y0, r.x1, r.y1);
    let mut leaves: Vec<_> = (record.windows.iter())
        .filter(|r| r.outcome != Outcome::Cut)
        .map(|r| (key(r), r.outcome))
        .collect();
    let mut want: Vec<_> = (warnock.leaf_regions().iter())
        .map(|l| ((l.level, l.x0, l.y0, l.x1, l.y1), Outcome::Decided(l.rule)))
        .collect();
    leaves.sort_by_key(|l| l.0);
    want.sort_by_key(|l| l.0);
    assert_eq!(leaves, want, "{what}");
    let mut cuts: Vec<_> = (record.windows.iter())
        .filter(|r| r.outcome == Outcome::Cut)
        .map(key)
        .collect();
    let mut want: Vec<_> = (warnock.cut_regions().iter())
        .map(|c| (c.level, c.x0, c.y0, c.x1, c.y1))
        .collect();
    cuts.sort_unstable();
    want.sort_unstable();
    assert_eq!(cuts, want, "{what}");
    let all = s.tris.len() as u32;
    for (k, win) in record.windows.iter().enumerate() {
        let classes = record.classes_of(win);
        if win.look == Look::PassedThrough {
            assert!(classes.is_empty() && win.outcome == Outcome::Cut, "{what}");
            continue;
        }
        // Each class is what the window's pixel centres say (disjoint may
        // be claimed only of a polygon covering none; a polygon covering
        // none may still be kept as intersecting: the rectangle test is
        // conservative that way).
        for c in classes {
            let (n, total) = covered(s, c.triangle, win);
            let why = format!("{what}: window {k} {win:?}, {c:?}, covers {n} of {total}");
            assert_eq!(c.class == Class::Surrounding, n == total, "{why}");
            match c.class {
                Class::Disjoint => assert_eq!(n, 0, "{why}"),
                Class::Contained => assert!(inside_area(s, c.triangle, win), "{why}"),
                Class::Intersecting => {
                    assert!(
                        !inside_area(s, c.triangle, win) || win.look == Look::Sample,
                        "{why}"
                    )
                }
                Class::Surrounding => {}
            }
            assert!(!c.hidden || c.class != Class::Disjoint, "{why}");
        }
        // Every polygon missing from the list was dropped above: disjoint
        // from, or hidden in, a window holding this one.
        let listed: Vec<u32> = classes.iter().map(|c| c.triangle).collect();
        for t in (0..all).filter(|t| !listed.contains(t)) {
            assert!(win.level > 0, "{what}: the whole image lists everything");
            let dropped = record.windows.iter().any(|a| {
                a.level < win.level
                    && holds(a, win)
                    && (record.classes_of(a).iter())
                        .any(|c| c.triangle == t && (c.class == Class::Disjoint || c.hidden))
            });
            assert!(
                dropped,
                "{what}: triangle {t} vanished before window {k} {win:?}"
            );
        }
        // The decision follows from the classes.
        let live: Vec<_> = (classes.iter())
            .filter(|c| c.class != Class::Disjoint && !c.hidden)
            .collect();
        let why = format!("{what}: window {k} {win:?}");
        match win.outcome {
            Outcome::Decided(Rule::Empty) => assert!(live.is_empty(), "{why}"),
            Outcome::Decided(Rule::SinglePolygon) => {
                assert_eq!(live.len(), 1, "{why}");
                assert_ne!(live[0].class, Class::Surrounding, "{why}");
            }
            Outcome::Decided(Rule::SurrounderAlone) => {
                assert_eq!(live.len(), 1, "{why}");
                assert_eq!(live[0].class, Class::Surrounding, "{why}");
                assert!(classes.iter().all(|c| !c.hidden), "{why}");
            }
            Outcome::Decided(Rule::SurrounderInFront) => {
                assert_eq!(live.len(), 1, "{why}");
                assert_eq!(Some(live[0].triangle), win.front, "{why}");
                assert!(classes.iter().any(|c| c.hidden), "{why}");
            }
            Outcome::Decided(Rule::Sample) => {
                assert_eq!(win.look, Look::Sample, "{why}");
                assert!(live.len() >= 2, "{why}");
            }
            Outcome::Decided(Rule::PixelSubdivided) => panic!("{why}: pixel-centre mode"),
            Outcome::Cut => assert!(live.len() >= 2, "{why}"),
        }
        if let Some(f) = win.front {
            assert!(
                (classes.iter()).any(|c| c.triangle == f && c.class == Class::Surrounding),
                "{why}"
            );
        }
    }
    record
}

#[test]
fn recorded_classes_are_the_brute_force_classes() {
    let mut seen = [false; 4];
    let mut looks = std::collections::HashSet::new();
    let mut hidden = false;
    for (what, scene) in [
        ("intersecting", procedural::intersecting_pair()),
        ("cyclic", procedural::cyclic_triple()),
        ("soup", procedural::random_soup(30, 3)),
        ("cube", procedural::cube()),
    ] {
        for (w, h) in [(40, 24), (32, 32)] {
            let record = check(&screen(&scene, w, h), what);
            for c in &record.classes {
                seen[Class::ALL.iter().position(|&k| k == c.class).unwrap()] = true;
                hidden |= c.hidden;
            }
            looks.extend(record.windows.iter().map(|w| w.look));
        }
    }
    assert_eq!(seen, [true; 4], "every class occurs");
    assert!(hidden, "some polygon is culled behind a surrounder");
    assert_eq!(looks.len(), 4, "{looks:?}");
}

#[test]
fn the_record_is_off_by_default() {
    let s = screen(&procedural::intersecting_pair(), 32, 32);
    let mut warnock = Warnock::default();
    let mut frame = Frame::new(32, 32).unwrap();
    warnock.render(&s, &mut frame).unwrap();
    assert!(warnock.window_classes().windows.is_empty());
    assert!(warnock.window_classes().classes.is_empty());
}
