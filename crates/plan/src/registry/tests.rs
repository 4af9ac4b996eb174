//! The registry's names, knobs and refusals.

use hider_zbuffer::{DepthFormat, DepthSource};

use super::*;
use crate::config::HiderConfig;
use crate::{AlgoName, Knob, PlanError};

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
    let e = find("nonesuch").unwrap_err();
    match &e {
        PlanError::UnknownHider { name, known } => {
            assert_eq!(name, "nonesuch");
            let known: Vec<&str> = known.iter().map(|a| a.as_str()).collect();
            assert_eq!(known, names());
        }
        other => panic!("{other:?}"),
    }
    // The library's message speaks of hiders, not of any front end's flags.
    let line = e.to_string();
    assert!(
        line.starts_with("no hider named 'nonesuch' (registered: zbuffer, zbuffer-f64,"),
        "{line}"
    );
    assert!(!line.contains("--"), "{line}");
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
    let tiled = find("zbuffer-tiled").unwrap().build(&source).err().unwrap();
    assert!(
        matches!(&tiled, PlanError::KnobNotApplicable { hider: AlgoName::ZbufferTiled, knob: Knob::DepthSource, takers } if takers == &[AlgoName::Zbuffer]),
        "{tiled:?}"
    );
    assert_eq!(
        tiled.to_string(),
        "the depth source applies to zbuffer only, not to zbuffer-tiled (zbuffer-tiled compares window depth)"
    );
    for name in ["zbuffer-f64", "painter", "abuffer", "oracle"] {
        let e = find(name).unwrap().build(&format).err().unwrap();
        assert!(
            matches!(&e, PlanError::KnobNotApplicable { hider, knob: Knob::DepthFormat, takers }
                if hider.as_str() == name && takers == &[AlgoName::Zbuffer, AlgoName::ZbufferTiled]),
            "{name}: {e:?}"
        );
        assert!(!e.to_string().contains("--"), "{e}");
    }
    // Threads are never refused: they also drive the front end; nor is
    // the shade mode (the colour pass applies it to the others).
    let threads = HiderConfig::default()
        .with_threads(4)
        .with_shade(hider_scene::ShadeMode::Ids);
    assert!(all().iter().all(|e| e.build(&threads).is_ok()));
}

#[test]
fn ordered_polygons_only_from_the_painters() {
    let svg = HiderConfig::default().with_ordered_polygons(true);
    for e in all() {
        let built = e.build(&svg);
        if e.name.starts_with("painter") {
            assert!(built.unwrap().ordered_polygons().is_some(), "{}", e.name);
        } else {
            let e = built.err().unwrap();
            assert!(
                matches!(&e, PlanError::KnobNotApplicable { knob: Knob::OrderedPolygons, takers, .. }
                    if takers == &[AlgoName::Painter, AlgoName::PainterNaive]),
                "{e:?}"
            );
        }
    }
}

/// The registry knows which hiders composite translucent surfaces: they,
/// and only they, are silent on a translucent scene.
#[test]
fn only_hiders_that_composite_are_silent_on_translucent_scenes() {
    use hider_scene::shade::{Stages, transparency_warning};
    let glass = Stages {
        transparency: true,
        ..Stages::default()
    };
    let mut compositing = Vec::new();
    for e in all() {
        let hider = e.make();
        if transparency_warning(hider.as_ref(), &glass).is_none() {
            compositing.push(e.name);
        }
        assert!(transparency_warning(hider.as_ref(), &Stages::default()).is_none());
    }
    assert_eq!(compositing, ["abuffer", "abuffer-carpenter", "ssaa-sorted"]);
    let line = transparency_warning(by_name("ssaa-8").unwrap().make().as_ref(), &glass).unwrap();
    assert!(
        line.contains("ssaa-8") && line.contains("abuffer"),
        "{line}"
    );
}

/// The registry and the names' type list the same hiders in the same
/// order, so every entry has its `AlgoName` and every name its entry.
#[test]
fn every_entry_has_its_algo_name() {
    let registered: Vec<&str> = AlgoName::REGISTERED.iter().map(|a| a.as_str()).collect();
    assert_eq!(registered, names());
    for e in all() {
        assert_eq!(e.algo().as_str(), e.name);
        assert_eq!(entry(e.algo()).unwrap().name, e.name);
    }
    assert!(entry(AlgoName::Auto).is_none());
    assert_eq!("auto".parse::<AlgoName>().unwrap(), AlgoName::Auto);
}
