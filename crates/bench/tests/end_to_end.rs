//! End-to-end runs of tiny matrices: the CSV schema, every registered
//! hider present, the exact z-buffer agreeing with the oracle where the
//! linear-depth z-buffer does not, shards merging back into the full run,
//! the report and plots written, and an interrupted run keeping its CSV.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use hider_bench::cli::merge;
use hider_bench::matrix::{MatrixOptions, Shard, Study};
use hider_bench::record::{COLUMNS, parse_csv, read_results, write_results};
use hider_bench::report::write_report;
use hider_bench::run::{RunOptions, run};
use hider_bench::scenes::linear_depth_probe;
use hider_plan::registry;
use hider_scene::timing::Timer;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-bench-e2e-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn quick_timing() -> Timer {
    Timer::new(2).with_warmup(1).with_max_seconds(0.5)
}

/// The two-triangle probe only, every registered hider, 24 x 24.
fn probe_options(out: PathBuf) -> RunOptions {
    RunOptions {
        matrix: MatrixOptions {
            assets_dir: "/nonexistent".into(),
            ..MatrixOptions::default()
        }
        .with_studies(vec![Study::Accuracy])
        .with_scenes(vec!["probe".into()])
        .with_scene("probe", linear_depth_probe())
        .with_sizes(vec![24]),
        timing: quick_timing(),
        contact_dir: Some(out.join("images")),
        out_dir: out,
        ..RunOptions::default()
    }
}

#[test]
fn two_triangles_every_hider_and_the_csv_schema() {
    let dir = temp_dir("probe");
    let out = run(&probe_options(dir.clone()), &AtomicBool::new(false), "test").unwrap();
    assert!(out.results.complete);
    let rows = &out.results.rows;
    // Every registered hider appears, once, in registry order.
    let names: Vec<&str> = rows.iter().map(|r| r.hider.as_str()).collect();
    let registered: Vec<&str> = registry::all().iter().map(|e| e.name).collect();
    assert_eq!(names, registered);
    for r in rows {
        assert!(r.is_ok(), "{}: {}", r.hider, r.status);
        assert!(
            r.render_ms > 0.0 && r.render_min_ms <= r.render_ms && r.render_ms <= r.render_max_ms
        );
        assert!(r.runs >= 1 && r.warmup == 1 && r.threads >= 1);
        assert_eq!((r.width, r.height, r.triangles), (24, 24, 2));
    }
    let row = |name: &str| rows.iter().find(|r| r.hider == name).unwrap();
    let exact = row("zbuffer");
    assert_eq!(
        (exact.wrong_ids, exact.coverage_mismatches),
        (Some(0), Some(0))
    );
    assert_eq!(exact.error(), Some(0.0));
    let linear = row("zbuffer-linear-z");
    assert!(
        linear.wrong_ids.unwrap() > 0,
        "the linear-depth z-buffer must get the crossing wrong"
    );
    assert!(linear.wrong_fraction.unwrap() > 0.0);
    assert!(linear.depth_error_max.unwrap() > exact.depth_error_max.unwrap());
    // The oracle row is the reference, not scored against itself.
    assert_eq!(row("oracle").accuracy, "reference");
    // Every exact pixel-centre hider agrees with the oracle.
    for e in registry::all()
        .iter()
        .filter(|e| e.kind == registry::Kind::ExactPixelCentre)
    {
        assert_eq!(row(e.name).wrong_ids, Some(0), "{}", e.name);
    }
    // Multi-sample hiders carry a coverage error (when they write coverage).
    for e in registry::all()
        .iter()
        .filter(|e| e.kind == registry::Kind::MultiSample)
    {
        let r = row(e.name);
        assert!(
            r.coverage_error.is_some() || r.accuracy.contains("no coverage"),
            "{}",
            e.name
        );
    }

    // The CSV written row by row has the schema's header and every row.
    let text = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert_eq!(text.lines().next().unwrap(), COLUMNS.join(","));
    assert_eq!(parse_csv(&text).unwrap().len(), rows.len());

    // Final files, report and plots.
    write_results(&dir, &out.results).unwrap();
    assert_eq!(read_results(&dir).unwrap(), out.results);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    assert_eq!(json["schema"], 1);
    assert!(json["machines"][0]["cpu"].is_string());
    let first = json["rows"][0].as_object().unwrap();
    assert_eq!(first.len(), COLUMNS.len());
    write_report(
        &out.results,
        &dir.join("report.md"),
        &dir.join("images"),
        "test",
    )
    .unwrap();
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("zbuffer-linear-z") && report.contains("images/bench-pareto-all.svg"));
    assert!(dir.join("images/bench-pareto-all.png").is_file());
    assert!(dir.join("images/bench-pareto-probe-24.svg").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shards_merge_into_the_full_run() {
    let dir = temp_dir("shards");
    let options = |out: PathBuf, shard: Shard| RunOptions {
        matrix: MatrixOptions {
            assets_dir: "/nonexistent".into(),
            polygon_steps: vec![4, 8],
            depth_steps: vec![1, 2],
            resolution_steps: vec![16],
            scaling_size: 16,
            ..MatrixOptions::default()
        }
        .with_scenes(vec!["cube".into(), "fan".into(), "scaling".into()])
        .with_sizes(vec![16])
        .with_algos(vec!["zbuffer".into(), "zbuffer-f64".into()]),
        timing: Timer::new(1).with_warmup(0).with_max_seconds(0.1),
        shard,
        out_dir: out,
        ..RunOptions::default()
    };
    let stop = AtomicBool::new(false);
    let full = run(&options(dir.join("full"), Shard::default()), &stop, "full").unwrap();
    let mut parts = Vec::new();
    for index in 1..=3 {
        let part_dir = dir.join(format!("part{index}"));
        let part = run(
            &options(part_dir.clone(), Shard { index, count: 3 }),
            &stop,
            "part",
        )
        .unwrap();
        assert!(part.results.rows.len() < full.results.rows.len());
        write_results(&part_dir, &part.results).unwrap();
        parts.push(part_dir);
    }
    let merged = merge(&parts).unwrap();
    let key = |r: &hider_bench::record::Row| {
        (
            r.case,
            r.study.clone(),
            r.scene.clone(),
            r.width,
            r.hider.clone(),
            r.wrong_ids,
        )
    };
    assert_eq!(
        merged.rows.iter().map(key).collect::<Vec<_>>(),
        full.results.rows.iter().map(key).collect::<Vec<_>>()
    );
    assert!(merged.complete);
    assert_eq!(merged.commands.len(), 3);
    // Every study of the matrix made it through.
    for study in Study::ALL {
        assert!(
            merged.rows.iter().any(|r| r.study == study.as_str()),
            "{study:?}"
        );
    }
    // A shard given twice is refused.
    assert!(merge(&[parts[0].clone(), parts[0].clone()]).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_interrupted_run_keeps_its_csv_and_says_so() {
    let dir = temp_dir("stop");
    let out = run(&probe_options(dir.clone()), &AtomicBool::new(true), "test").unwrap();
    assert!(!out.results.complete);
    assert!(out.results.rows.is_empty());
    let text = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert_eq!(parse_csv(&text).unwrap().len(), 0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_selections_are_errors_not_empty_sweeps() {
    let dir = temp_dir("bad");
    let mut o = probe_options(dir.clone());
    o.matrix.algos = vec!["no-such-hider".into()];
    assert!(run(&o, &AtomicBool::new(false), "t").is_err());
    let mut o = probe_options(dir.clone());
    o.matrix.objs = vec!["/nonexistent/model.obj".into()];
    o.matrix.scenes = vec!["model.obj".into()];
    let e = run(&o, &AtomicBool::new(false), "t").unwrap_err();
    assert!(format!("{e:#}").contains("model.obj"), "{e:#}");
    std::fs::remove_dir_all(&dir).unwrap();
}
