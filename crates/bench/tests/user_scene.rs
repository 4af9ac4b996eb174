//! The bench on the user's own scene (`--obj`): its camera (`--eye`,
//! `--target`, `--up`, `--fovy`), a non-square size (`--sizes WxH`), a
//! thread count (`--threads`) and its contact sheet, through the library
//! and through the binary, on the bundled cube at a tiny size.

use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::AtomicBool;

use hider_bench::matrix::{MatrixOptions, Study};
use hider_bench::run::{RunOptions, run};
use hider_geom::glam::DVec3;
use hider_scene::CameraOverrides;
use hider_scene::timing::Timer;

fn cube() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/cube.obj"
    ))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-bench-user-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn options(out: PathBuf, camera: CameraOverrides, threads: Option<usize>) -> RunOptions {
    RunOptions {
        matrix: MatrixOptions {
            assets_dir: "/nonexistent".into(),
            ..MatrixOptions::default()
        }
        .with_studies(vec![Study::Accuracy])
        .with_scenes(vec!["obj".into()])
        .with_objs(vec![cube()])
        .with_image_sizes(vec![(24, 16)])
        .with_algos(vec![
            "zbuffer".into(),
            "zbuffer-tiled".into(),
            "painter".into(),
        ])
        .with_obj_camera(camera),
        timing: Timer::new(1).with_warmup(0).with_max_seconds(0.5),
        contact_dir: Some(out.join("images")),
        out_dir: out,
        threads,
        ..RunOptions::default()
    }
}

#[test]
fn the_users_camera_size_threads_and_contact_sheet() {
    let dir = temp_dir("lib");
    let fit = run(
        &options(dir.join("fit"), CameraOverrides::default(), None),
        &AtomicBool::new(false),
        "test",
    )
    .unwrap();
    // On the diagonal through a corner, narrow: the cube fills the frame.
    let close = CameraOverrides {
        eye: Some(DVec3::new(2.5, 2.5, 2.5)),
        target: Some(DVec3::ZERO),
        up: None,
        fovy: Some(30.0),
        ..CameraOverrides::default()
    };
    let out = run(
        &options(dir.join("close"), close, Some(1)),
        &AtomicBool::new(false),
        "test",
    )
    .unwrap();
    assert_eq!(out.results.rows.len(), 3);
    assert_eq!(out.results.machines[0].threads, 1);
    for r in &out.results.rows {
        assert!(r.is_ok(), "{}: {}", r.hider, r.status);
        assert_eq!((r.group.as_str(), r.width, r.height), ("obj", 24, 16));
        assert_eq!(r.wrong_ids, Some(0), "{}", r.hider);
    }
    let covered = |o: &hider_bench::run::RunOutput| o.results.rows[0].covered_pixels;
    assert!(
        covered(&out) > covered(&fit),
        "the camera applies: {} px covered, {} with the fit camera",
        covered(&out),
        covered(&fit)
    );
    // A contact sheet for the user's scene: the oracle and three hiders.
    let sheet = dir.join("close/images/bench-contact-cube.obj.png");
    assert_eq!(out.contact_sheets, vec![sheet.clone()]);
    // Four 24 x 16 tiles in a row, each scaled 5 times (to 120 x 80).
    let img = image::open(&sheet).unwrap();
    assert!(
        img.width() > 4 * 120 && img.height() > 80,
        "{}x{}",
        img.width(),
        img.height()
    );
    assert!(img.width() < 5 * 120, "one row of four: {}", img.width());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_thread_count_reaches_the_hiders() {
    // One more than the A-buffer takes: refused by it, by name, so the
    // count got there; the z-buffer, which takes no thread count, runs.
    let dir = temp_dir("threads");
    let mut o = options(dir.clone(), CameraOverrides::default(), Some(257));
    o.matrix.algos = vec!["abuffer".into(), "zbuffer".into()];
    let out = run(&o, &AtomicBool::new(false), "test").unwrap();
    let status = |name: &str| {
        let row = out.results.rows.iter().find(|r| r.hider == name).unwrap();
        row.status.clone()
    };
    assert_eq!(status("zbuffer"), "ok");
    let refused = status("abuffer");
    assert!(
        refused.starts_with("error") && refused.contains("threads"),
        "{refused}"
    );
    assert_eq!(out.results.machines[0].threads, 257);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_real_size_only_run_still_draws_the_users_scene() {
    let dir = temp_dir("real");
    let mut o = options(dir.clone(), CameraOverrides::default(), None);
    o.matrix.studies = vec![Study::RealSize];
    o.matrix.real_size = (20, 14);
    let out = run(&o, &AtomicBool::new(false), "test").unwrap();
    assert!(
        out.results
            .rows
            .iter()
            .all(|r| (r.study.as_str(), r.width, r.height) == ("real-size", 20, 14))
    );
    assert_eq!(
        out.contact_sheets,
        vec![dir.join("images/bench-contact-cube.obj.png")]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_binary_takes_the_users_camera_size_and_threads() {
    let dir = temp_dir("bin");
    let out = Command::new(env!("CARGO_BIN_EXE_hider-bench"))
        .args(["--obj", cube().to_str().unwrap()])
        .args(["--assets", "/nonexistent", "--scenes", "obj"])
        .args(["--studies", "accuracy", "--sizes", "20x12"])
        .args(["--eye", "-2,1.5,2.5", "--target", "0,0,0", "--up", "0,1,0"])
        .args(["--fovy", "50", "--threads", "1", "--algos", "zbuffer"])
        .args(["--repeats", "1", "--warmup", "0", "--no-progress"])
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert!(csv.lines().nth(1).is_some_and(|l| l.contains("cube.obj")));
    assert!(dir.join("images/bench-contact-cube.obj.png").is_file());
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("bench-contact-cube.obj.png"), "{report}");
    let _ = std::fs::remove_dir_all(&dir);
}
