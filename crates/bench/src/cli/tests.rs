//! Tests of the benchmark's command line: parsing, checks and merging.

use super::*;
use crate::matrix::Study;
use crate::run::study_timing;
use clap::{CommandFactory, Parser};
use hider_geom::glam::DVec3;
use hider_scene::CameraOverrides;
use hider_scene::timing::Timer;

/// The arguments as the binary parses them.
#[derive(Parser, Debug)]
#[command(name = "hider-bench", allow_negative_numbers = true)]
struct Cli {
    #[command(flatten)]
    args: BenchArgs,
}

fn parse(args: &[&str]) -> std::result::Result<RunArgs, clap::Error> {
    Cli::try_parse_from(std::iter::once("hider-bench").chain(args.iter().copied()))
        .map(|c| c.args.run)
}

#[test]
fn sizes_take_squares_and_width_by_height() {
    let a = parse(&["--sizes", "64,800x600,3X2"]).unwrap();
    assert_eq!(a.sizes, vec![(64, 64), (800, 600), (3, 2)]);
    assert_eq!(a.options().matrix.sizes, vec![(64, 64), (800, 600), (3, 2)]);
    for bad in ["0", "8x", "x8", "-5", "big", "8x0", "1x2x3"] {
        assert!(parse(&["--sizes", bad]).is_err(), "{bad}");
    }
    // --quick's 32 px gives way to the sizes asked for.
    let q = parse(&["--quick", "--sizes", "40x30"]).unwrap();
    assert_eq!(q.options().matrix.sizes, vec![(40, 30)]);
    assert_eq!(
        parse(&[]).unwrap().options().matrix.sizes,
        vec![(64, 64), (256, 256)]
    );
}

#[test]
fn the_real_size_takes_width_by_height() {
    let a = parse(&["--real-size", "800x600"]).unwrap();
    assert_eq!(a.options().matrix.real_size, (800, 600));
    assert_eq!(
        parse(&["--real-size", "512"])
            .unwrap()
            .options()
            .matrix
            .real_size,
        (512, 512)
    );
    assert_eq!(parse(&[]).unwrap().options().matrix.real_size, (1024, 1024));
    assert!(parse(&["--real-size", "0x5"]).is_err());
}

#[test]
fn width_and_height_come_together_and_not_with_sizes() {
    let a = parse(&["--width", "80", "--height", "60"]).unwrap();
    assert_eq!(a.options().matrix.sizes, vec![(80, 60)]);
    assert!(parse(&["--width", "80"]).is_err());
    assert!(parse(&["--height", "60"]).is_err());
    assert!(parse(&["--width", "8", "--height", "6", "--sizes", "4"]).is_err());
}

#[test]
fn the_obj_camera_is_parsed_and_checked() {
    let a = parse(&[
        "--eye", "-3,2.5,5", "--target", "0,-1,0", "--up", "0,0,1", "--fovy", "40", "--near",
        "0.5", "--far", "90",
    ])
    .unwrap();
    let c = a.options().matrix.obj_camera;
    assert_eq!(c.eye, Some(DVec3::new(-3.0, 2.5, 5.0)));
    assert_eq!(c.target, Some(DVec3::new(0.0, -1.0, 0.0)));
    assert_eq!(c.up, Some(DVec3::Z));
    assert_eq!(c.fovy, Some(40.0));
    assert_eq!((c.near, c.far), (Some(0.5), Some(90.0)));
    assert_eq!(
        parse(&[]).unwrap().options().matrix.obj_camera,
        CameraOverrides::default()
    );
    for (flag, bad) in [
        ("--eye", "1,2"),
        ("--eye", "1,2,3,4"),
        ("--eye", "a,b,c"),
        ("--target", "1,inf,0"),
        ("--fovy", "0"),
        ("--near", "0"),
        ("--far", "-1"),
        ("--fovy", "180"),
        ("--fovy", "wide"),
    ] {
        assert!(parse(&[flag, bad]).is_err(), "{flag} {bad}");
    }
}

#[test]
fn threads_reach_the_run() {
    assert_eq!(
        parse(&["--threads", "2"]).unwrap().options().threads,
        Some(2)
    );
    assert_eq!(parse(&[]).unwrap().options().threads, None);
    assert!(parse(&["--threads", "0"]).is_err());
    // The most the parallel hiders take.
    assert!(parse(&["--threads", "256"]).is_ok());
    assert!(parse(&["--threads", "257"]).is_err());
}

#[test]
fn help_states_the_real_size_cap_and_what_the_camera_applies_to() {
    let help = Cli::command().render_long_help().to_string();
    let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
    for needle in [
        "Real-size jobs take at most 3",
        "set the camera of every --obj scene",
        "--threads",
        "WxH",
        "--eye",
        "--fovy",
    ] {
        assert!(flat.contains(needle), "{needle} in\n{help}");
    }
    // The cap stated is the cap applied.
    let t = study_timing(&Timer::new(10), Study::RealSize);
    assert_eq!(t.runs, 3);
}
