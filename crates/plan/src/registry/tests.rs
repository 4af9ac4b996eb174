//! The registry's names, knobs and refusals.

use hider_zbuffer::{DepthFormat, DepthSource};

use super::*;
use crate::config::HiderConfig;

#[test]
fn names_are_unique_and_instances_carry_them() {
    let entries = all();
    for (i, a) in entries.iter().enumerate() {
        assert!(
            entries[i + 1..].iter().all(|b| b.name != a.name),
            "{}",
            a.name
        );
        assert_eq!(a.make().name(), a.name);
        assert_eq!(a.build(&HiderConfig::default()).unwrap().name(), a.name);
    }
    assert!(by_name("nope").is_none());
    assert!(!pixel_centre_hiders().is_empty());
}

#[test]
fn unknown_names_list_the_registered_ones() {
    let e = find("nonesuch").unwrap_err().to_string();
    assert!(
        e.starts_with("unknown --algo 'nonesuch' (one of: zbuffer, zbuffer-f64,"),
        "{e}"
    );
    assert!(e.ends_with("ssaa-sorted, oracle)"), "{e}");
}

#[test]
fn knobs_reach_the_hiders_that_have_them() {
    let format = HiderConfig::default().with_depth_format(DepthFormat::F64);
    let source = HiderConfig::default().with_depth_source(DepthSource::LinearViewZ);
    let both = format
        .with_depth_source(DepthSource::WindowZ)
        .with_threads(2);
    for name in ["zbuffer", "zbuffer-tiled"] {
        assert!(find(name).unwrap().build(&format).is_ok(), "{name}");
    }
    assert!(find("zbuffer").unwrap().build(&both).is_ok());
    let tiled = find("zbuffer-tiled").unwrap().build(&source);
    assert_eq!(
        tiled.err().unwrap().to_string(),
        "--depth-source applies to --algo zbuffer only (zbuffer-tiled compares window depth)"
    );
    for name in ["zbuffer-f64", "painter", "abuffer", "oracle"] {
        let e = find(name).unwrap().build(&format).err().unwrap();
        assert_eq!(
            e.to_string(),
            "--depth-format and --depth-source apply to --algo zbuffer and zbuffer-tiled only",
            "{name}"
        );
        assert!(
            matches!(e, PlanError::KnobNotApplicable { hider, knob: "--depth-format", .. } if hider == name)
        );
    }
    // Threads are never refused: they also drive the front end.
    let threads = HiderConfig::default().with_threads(4);
    assert!(all().iter().all(|e| e.build(&threads).is_ok()));
}

#[test]
fn vector_output_only_from_the_painters() {
    let svg = HiderConfig::default().with_vector_output(true);
    for e in all() {
        let built = e.build(&svg);
        if e.name.starts_with("painter") {
            assert!(built.is_ok(), "{}", e.name);
        } else {
            assert_eq!(
                built.err().unwrap().to_string(),
                "--svg needs --algo painter or painter-naive (vector output comes from the depth order)",
                "{}",
                e.name
            );
        }
    }
}
