//! Bad options are a one-line error naming the option and the value, never
//! a panic; the SVG writers produce what the map holds.

use hider_scene::{ShadeMode, procedural};
use hider_testkit::screen;
use hider_vector::{VectorOptions, hidden_lines, lines_svg, regions_svg, visible_regions};

#[test]
fn bad_options_are_named_in_the_error() {
    let s = screen(&procedural::cube(), 32, 32);
    let cases = [
        (
            VectorOptions::default().with_crease_degrees(f64::NAN),
            "crease_degrees NaN",
        ),
        (
            VectorOptions::default().with_crease_degrees(190.0),
            "crease_degrees 190",
        ),
        (
            VectorOptions::default().with_stroke_width(0.0),
            "stroke_width 0",
        ),
        (
            VectorOptions::default().with_seam_stroke(-1.0),
            "seam_stroke -1",
        ),
        (
            VectorOptions::default().with_depth_tolerance(f64::INFINITY),
            "depth_tolerance inf",
        ),
        (
            VectorOptions::default().with_refine_bits(40),
            "refine_bits 40",
        ),
    ];
    for (options, expected) in cases {
        let err = visible_regions(&s, &options, ShadeMode::Lambert)
            .unwrap_err()
            .to_string();
        assert!(err.contains(expected), "{err:?} should name {expected:?}");
        assert!(!err.contains('\n'), "one line: {err:?}");
    }
}

#[test]
fn one_path_per_group_and_one_polyline_per_line() {
    let s = screen(&procedural::cube(), 64, 64);
    let options = VectorOptions::default();
    let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
    let svg = regions_svg(&s, &map, &options);
    assert_eq!(svg.matches("<path data-prim").count(), map.groups.len());
    // No background unless asked for.
    assert!(!svg.contains("<rect"));
    let white = options.clone().with_background(Some("white".into()));
    assert!(regions_svg(&s, &map, &white).contains(r#"<rect id="background""#));
    // Pixel coordinates, no scale transform.
    assert!(!svg.contains("transform"), "{svg}");
    // Two triangles of one cube face are one group, one path.
    assert!(
        map.groups.iter().all(|g| g.prims.len() == 2),
        "{:?}",
        map.groups
    );
    let drawing = hidden_lines(&s, &map, &options).unwrap();
    let lines = lines_svg(&s, &drawing, &options);
    assert_eq!(lines.matches("<polyline").count(), drawing.visible.len());
    assert!(
        drawing.hidden.is_empty(),
        "hidden parts only when asked for"
    );
}

#[test]
fn a_stopped_token_stops_the_regions_and_the_lines() {
    use hider_scene::{Cancel, Cancelled, Error};
    let s = screen(&procedural::cube(), 32, 32);
    let map = visible_regions(&s, &VectorOptions::default(), ShadeMode::Ids).unwrap();
    let token = Cancel::new();
    token.cancel();
    let stopped = VectorOptions::default().with_cancel(token);
    assert!(matches!(
        visible_regions(&s, &stopped, ShadeMode::Ids),
        Err(Error::Cancelled(Cancelled::Requested))
    ));
    assert!(matches!(
        hidden_lines(&s, &map, &stopped),
        Err(Error::Cancelled(Cancelled::Requested))
    ));
    let late = VectorOptions::default().with_cancel(Cancel::new().with_timeout(Default::default()));
    assert!(matches!(
        visible_regions(&s, &late, ShadeMode::Ids),
        Err(Error::Cancelled(Cancelled::TimedOut { .. }))
    ));
}
