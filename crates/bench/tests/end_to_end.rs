//! End-to-end runs of tiny matrices: the CSV schema, every registered
//! hider present, the exact z-buffer agreeing with the oracle where the
//! linear-depth z-buffer does not, shards merging back into the full run,
//! the report and plots written, and an interrupted run keeping its CSV.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use hider_bench::cli::merge;
use hider_bench::matrix::{MatrixOptions, Shard, Study};
use hider_bench::record::{COLUMNS, Row, SCHEMA_VERSION, parse_csv, read_results, write_results};
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
    assert_eq!(json["schema"], SCHEMA_VERSION);
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
            real_size: (16, 16),
            real_spheres: vec![4],
            real_layers: vec![1],
            precision_gaps: vec![1e-2],
            precision_ratios: vec![1e-2],
            precision_size: 16,
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
    let key = |r: &Row| {
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

/// The Markdown table that follows `heading`: its lines of cells (header
/// and rule included), up to the first line that is not a table line.
fn table_after(report: &str, heading: &str) -> Vec<Vec<String>> {
    let start = report
        .find(heading)
        .unwrap_or_else(|| panic!("no '{heading}' in the report"));
    report[start..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            l.trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_owned())
                .collect()
        })
        .collect()
}

/// A number as the report writes it (`1.23`, `4.5e-4`, `12%`, `1,234`).
fn number(cell: &str) -> f64 {
    let t = cell.split_whitespace().next().unwrap_or("");
    let (t, scale) = match t.strip_suffix('%') {
        Some(p) => (p, 0.01),
        None => (t, 1.0),
    };
    t.replace(',', "")
        .parse::<f64>()
        .unwrap_or_else(|_| panic!("'{cell}' is not a number"))
        * scale
}

/// Whether `shown` is `value` written with the report's rounding (two
/// significant digits at worst).
fn same(shown: f64, value: f64) -> bool {
    (shown - value).abs() <= 0.051 * value.abs().max(1e-12) + 0.0005
}

fn geometric_mean(values: &[f64]) -> f64 {
    (values.iter().map(|v| v.ln()).sum::<f64>() / values.len() as f64).exp()
}

/// Real-size, depth-precision and accuracy studies at small sizes through
/// every hider: the report's answer section is read back and every number
/// in its tables is checked against the results files of the same run.
#[test]
fn the_reports_numbers_are_the_results_files_numbers() {
    let dir = temp_dir("answer");
    let options = RunOptions {
        matrix: MatrixOptions {
            assets_dir: "/nonexistent".into(),
            real_size: (40, 40),
            real_spheres: vec![6],
            real_layers: vec![2],
            precision_gaps: vec![1e-2, 1e-6],
            precision_ratios: vec![1e-4],
            precision_size: 24,
            ..MatrixOptions::default()
        }
        .with_studies(vec![
            Study::RealSize,
            Study::DepthPrecision,
            Study::Accuracy,
        ])
        .with_scenes(vec![
            "probe".into(),
            "scaling".into(),
            "intersecting_pairs".into(),
        ])
        .with_scene("probe", linear_depth_probe())
        .with_sizes(vec![24]),
        timing: quick_timing(),
        out_dir: dir.clone(),
        ..RunOptions::default()
    };
    let out = run(&options, &AtomicBool::new(false), "test").unwrap();
    write_results(&dir, &out.results).unwrap();
    write_report(
        &out.results,
        &dir.join("report.md"),
        &dir.join("images"),
        "test",
    )
    .unwrap();
    let rows = read_results(&dir).unwrap().rows;
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let scenes = check_exact(&report, &rows);
    check_aa(&report, &rows);
    check_shortcuts(&report, &rows);
    check_precision(&report, &rows);
    check_summary(&report, &rows, &scenes);
    // The folder reads on its own: the interpretation page beside the
    // report, every linked file present.
    assert!(dir.join("bench.md").is_file());
    for link in report.split("](").skip(1) {
        let target = link.split(')').next().unwrap();
        assert!(dir.join(target).is_file(), "broken link {target}");
    }
    assert!(!report.contains("ExactPixelCentre") && !report.contains("0.00e0"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The row of `hider` on `scene` in `study`.
fn find<'a>(rows: &'a [Row], study: &str, scene: &str, hider: &str) -> &'a Row {
    rows.iter()
        .find(|r| r.study == study && r.scene == scene && r.hider == hider)
        .unwrap_or_else(|| panic!("no {study} {scene} {hider}"))
}

/// Checks the exact hiders' table against the rows; returns its scenes.
fn check_exact(report: &str, rows: &[Row]) -> Vec<String> {
    // (a) Exact hiders per real-size scene, and their geometric means.
    let exact = table_after(report, "### Exact visibility at pixel centres");
    let hiders = exact[0][1..].to_vec();
    assert!(
        hiders.contains(&"zbuffer-tiled".to_owned()) && hiders.contains(&"scanline".to_owned())
    );
    let scenes: Vec<String> = exact[2..]
        .iter()
        .filter(|l| !l[0].starts_with("**") && !l[0].starts_with("relative"))
        .map(|l| l[0].split(" (").next().unwrap().to_owned())
        .collect();
    assert_eq!(scenes, ["probe", "sphere_6", "layers_2"]);
    for line in &exact[2..2 + scenes.len()] {
        let scene = line[0].split(" (").next().unwrap();
        for (h, cell) in hiders.iter().zip(&line[1..]) {
            let r = find(rows, "real-size", scene, h);
            assert!(
                same(number(cell), r.render_ms),
                "{scene} {h}: {cell} vs {}",
                r.render_ms
            );
        }
    }
    let means = &exact[2 + scenes.len()];
    for (h, cell) in hiders.iter().zip(&means[1..]) {
        let times: Vec<f64> = scenes
            .iter()
            .map(|s| find(rows, "real-size", s, h).render_ms)
            .collect();
        assert!(same(number(cell), geometric_mean(&times)), "{h} mean");
    }

    scenes
}

/// Checks the anti-aliasing table against the rows.
fn check_aa(report: &str, rows: &[Row]) {
    // (b) Coverage error and time of the anti-aliasing hiders.
    let aa = table_after(report, "### Anti-aliasing: coverage error against time");
    assert!(aa.len() > 4);
    for line in &aa[2..] {
        let h = &line[0];
        let with: Vec<&Row> = rows
            .iter()
            .filter(|r| r.study == "real-size" && &r.hider == h && r.coverage_error.is_some())
            .collect();
        let error = with.iter().map(|r| r.coverage_error.unwrap()).sum::<f64>() / with.len() as f64;
        let times: Vec<f64> = with.iter().map(|r| r.render_ms).collect();
        assert!(same(number(&line[1]), error), "{h}: {} vs {error}", line[1]);
        assert!(same(number(&line[2]), geometric_mean(&times)), "{h} time");
    }
}

/// Checks the shortcuts' wrong pixels against the rows.
fn check_shortcuts(report: &str, rows: &[Row]) {
    // (c) Wrong pixels of each shortcut at real size.
    let shortcuts = table_after(report, "### What each shortcut costs");
    for line in &shortcuts[2..] {
        let h = line[0].split(' ').next().unwrap();
        let wrong: u64 = rows
            .iter()
            .filter(|r| r.study == "real-size" && r.hider == h)
            .map(|r| r.wrong_ids.unwrap() + r.coverage_mismatches.unwrap())
            .sum();
        assert_eq!(number(&line[2]) as u64, wrong, "{h}");
    }
}

/// Checks the depth-precision table against the rows.
fn check_precision(report: &str, rows: &[Row]) {
    // (d) Share of pixels showing the farther surface.
    let precision = table_after(report, "### Depth precision");
    for line in &precision[2..] {
        let h = line[0].split('`').nth(1).unwrap();
        for (k, gap) in ["1e-2", "1e-6"].iter().enumerate() {
            let r = find(rows, "depth-precision", &format!("gap_{gap}_nf_1e-4"), h);
            let share = r.farther_pixels.unwrap() as f64 / r.covered_pixels as f64;
            assert!(same(number(&line[2 + k]), share), "{h} {gap}");
        }
    }
    // The coarsest format loses the hair's gap, f64 keeps it.
    let share = |h: &str| {
        find(rows, "depth-precision", "gap_1e-6_nf_1e-4", h)
            .farther_pixels
            .unwrap()
    };
    assert!(share("zbuffer-fixed16") > 0);
    assert_eq!(share("zbuffer-f64"), 0);
}

/// Checks that the summary and the conclusions order the tiled and the
/// plain z-buffer as the rows do.
fn check_summary(report: &str, rows: &[Row], scenes: &[String]) {
    // The summary orders the tiled and the plain z-buffer as the data does,
    // and the conclusions say the same.
    let summary = table_after(report, "## Summary per hider");
    let time_in_summary = |h: &str| number(&summary.iter().find(|l| l[0] == h).unwrap()[2]);
    let data = |h: &str| {
        let t: Vec<f64> = scenes
            .iter()
            .map(|s| find(rows, "real-size", s, h).render_ms)
            .collect();
        geometric_mean(&t)
    };
    let faster = data("zbuffer-tiled") < data("zbuffer");
    assert_eq!(
        time_in_summary("zbuffer-tiled") < time_in_summary("zbuffer"),
        faster
    );
    let (t, z) = (data("zbuffer-tiled"), data("zbuffer"));
    let same = t.max(z) / t.min(z) - 1.0 < 0.05;
    assert!(report.contains(if same {
        "the same speed (within the 5% the report treats as noise) on the same scenes"
    } else if faster {
        "x faster on the same scenes"
    } else {
        "x slower on the same scenes"
    }));
    assert!(report.contains("repeat noise: the measured renders of a job lie"));
}

/// A quad of glass in front of an opaque quad.
fn glass_scene() -> hider_scene::Scene {
    use hider_scene::glam::DVec3;
    use hider_scene::{Material, Mesh, Scene};
    let quad = |z: f64, half: f64| Mesh {
        positions: vec![
            DVec3::new(-half, -half, z),
            DVec3::new(half, -half, z),
            DVec3::new(half, half, z),
            DVec3::new(-half, half, z),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    };
    let mut scene = Scene::default();
    scene.push_mesh(quad(0.0, 1.0), None);
    let glass = Material {
        name: "glass".into(),
        opacity: 0.4,
        ..Material::default()
    };
    scene.push_mesh(quad(0.5, 0.6), Some(glass));
    scene
}

/// The check: on a scene with glass the z-buffers are marked as
/// ignoring transparency (not exact there), the A-buffer is not, the
/// conclusions leave the marked hiders out of "the fastest exact hider",
/// and an anti-aliasing recommendation is always given (here from the
/// measured A-buffer and supersampling; without any anti-aliasing hider,
/// the reason there is none).
#[test]
fn a_scene_with_glass_marks_the_hiders_that_draw_it_opaque() {
    let dir = temp_dir("glass");
    let options = |algos: Vec<String>| RunOptions {
        matrix: MatrixOptions {
            assets_dir: "/nonexistent".into(),
            real_size: (32, 24),
            real_spheres: vec![],
            real_layers: vec![],
            ..MatrixOptions::default()
        }
        .with_studies(vec![Study::RealSize, Study::Accuracy])
        .with_scenes(vec!["glass".into()])
        .with_scene("glass", glass_scene())
        .with_algos(algos)
        .with_sizes(vec![24]),
        timing: quick_timing(),
        out_dir: dir.clone(),
        ..RunOptions::default()
    };
    let algos = ["zbuffer", "zbuffer-tiled", "painter", "abuffer", "ssaa-4"];
    let out = run(
        &options(algos.iter().map(|s| (*s).to_owned()).collect()),
        &AtomicBool::new(false),
        "test",
    )
    .unwrap();
    let rows = &out.results.rows;
    for r in rows {
        assert!(r.is_ok(), "{} {}: {}", r.study, r.hider, r.status);
        let opaque_only = !matches!(r.hider.as_str(), "abuffer");
        assert_eq!(
            r.ignored_effects,
            if opaque_only { "transparency" } else { "" },
            "{} {}",
            r.study,
            r.hider
        );
    }
    write_results(&dir, &out.results).unwrap();
    write_report(
        &out.results,
        &dir.join("report.md"),
        &dir.join("images"),
        "test",
    )
    .unwrap();
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let exact = table_after(&report, "### Exact visibility at pixel centres");
    let glass_line = exact.iter().find(|l| l[0].starts_with("glass")).unwrap();
    assert!(
        glass_line[1..]
            .iter()
            .all(|c| c.contains("*ignores transparency*")),
        "{glass_line:?}"
    );
    assert!(report.contains("Left out as not exact on these scenes"));
    assert!(!report.contains("the fastest exact hider is"));
    let accuracy = table_after(&report, "## Accuracy: wrong pixels per scene");
    let z = accuracy[0].iter().position(|c| c == "zbuffer").unwrap();
    let a = accuracy[0].iter().position(|c| c == "abuffer").unwrap();
    assert!(
        accuracy[2][z].contains("*ignores transparency*"),
        "{:?}",
        accuracy[2]
    );
    assert!(!accuracy[2][a].contains("ignores"), "{:?}", accuracy[2]);
    // Only the A-buffer composites the glass, so it is the one recommended.
    assert!(
        report.contains("Anti-aliasing recommendation: `abuffer`"),
        "{report}"
    );
    let summary = table_after(&report, "## Summary per hider");
    let line = |h: &str| summary.iter().find(|l| l[0] == h).unwrap().clone();
    assert_eq!(line("zbuffer")[4], "0/1 (ignores an effect on 1)");
    assert_eq!(line("abuffer")[4], "1/1");

    // Without an anti-aliasing hider the report says why it recommends none.
    let out = run(
        &options(vec!["zbuffer".into()]),
        &AtomicBool::new(false),
        "test",
    )
    .unwrap();
    write_report(
        &out.results,
        &dir.join("report.md"),
        &dir.join("images"),
        "test",
    )
    .unwrap();
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(
        report.contains("Anti-aliasing recommendation: none from this run"),
        "{report}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
