//! Running the matrix: per case, load and prepare once, evaluate the
//! oracle once (and analytic coverage once, when a multi-sample hider is
//! selected), then render and score every selected hider on it once and
//! time them in rounds that alternate the hiders (see docs/bench.md).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result};
use hider_oracle::{
    CoverageReference, DEFAULT_TIE_TOLERANCE, RayCastOracle, Reference, analytic_coverage,
};
use hider_plan::HiderConfig;
use hider_plan::registry::{Entry, Kind};
use hider_scene::CameraOverrides;
use hider_scene::shade::cutout::cutout_stage;
use hider_scene::shade::transparency_warning;
use hider_scene::timing::{Summary, Timer};
use hider_scene::{
    DynHider, Frame, NO_ID, PrepareOptions, Scene, ScreenScene, ShadeMode, Stages, View, prepare,
    shade_frame,
};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::accuracy::{score_coverage, score_ids};
use crate::analysis::{SceneAnalysis, analyse};
use crate::contact::{ContactSheet, write_contact_sheet};
use crate::machine::Machine;
use crate::matrix::{Case, MatrixOptions, Shard, Study, build_cases, select_hiders};
use crate::record::{CsvSink, Results, Row, SCHEMA_VERSION};
use crate::rounds::{Contender, RenderInput, first_render, time_in_rounds};
use crate::scenes::Group;

/// The default time budget of one job's measured renders, in seconds: at
/// least one render is always measured, and slow hiders on large scaling
/// cases stop repeating after this long instead of dominating the sweep.
pub const MAX_SECONDS_PER_JOB: f64 = 2.0;

/// Everything a run needs. `Default` is the default `hider bench` run
/// (without output directories: set [`Self::out_dir`]).
#[derive(Clone, Debug, PartialEq)]
pub struct RunOptions {
    /// What to run.
    pub matrix: MatrixOptions,
    /// How often each job runs: warm-up renders, measured renders, and the
    /// seconds of measured renders after which a job stops repeating.
    pub timing: Timer,
    /// Which part of the matrix this process runs.
    pub shard: Shard,
    /// Where `results.csv` is written row by row.
    pub out_dir: PathBuf,
    /// Where contact sheets go (`bench-contact-SCENE.png`); `None` makes
    /// none.
    pub contact_dir: Option<PathBuf>,
    /// Relative gap under which two surfaces tie (the oracle's default).
    pub tie_tolerance: f64,
    /// Most (triangle, pixel) tests the oracle may spend on one case; above
    /// it the case is timed but not scored, and the row says so.
    pub oracle_budget: u64,
    /// Most (triangle, pixel) tests times depth complexity that analytic
    /// coverage (quadratic in the surfaces per pixel) may spend on a case.
    pub coverage_budget: u64,
    /// Draw a progress bar on the terminal.
    pub progress: bool,
    /// Worker threads of the run: a rayon pool of this many threads runs
    /// the matrix, and the hiders that take a thread count get it
    /// ([`HiderConfig::with_threads`]); `None` keeps rayon's default
    /// (`RAYON_NUM_THREADS`, else one per core) and every hider's own
    /// options.
    pub threads: Option<usize>,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            matrix: MatrixOptions::default(),
            timing: Timer::default().with_max_seconds(MAX_SECONDS_PER_JOB),
            shard: Shard::default(),
            out_dir: PathBuf::from("bench-out"),
            contact_dir: None,
            tie_tolerance: DEFAULT_TIE_TOLERANCE,
            oracle_budget: 200_000_000,
            coverage_budget: 200_000_000,
            progress: false,
            threads: None,
        }
    }
}

/// A prepared case with its references.
struct Prepared {
    /// What the real-size study times from: the world-space scene and its
    /// view (front end included).
    scene: Scene,
    view: View,
    screen: ScreenScene,
    analysis: SceneAnalysis,
    /// The effects the scene calls for (what a hider that ignores one is
    /// not exact for).
    stages: Stages,
    load: Summary,
    prepare: Summary,
    oracle: std::result::Result<Reference, String>,
    coverage: std::result::Result<CoverageReference, String>,
}

/// Loads and prepares a case (both timed), measures its size, and
/// evaluates the references the selected hiders are scored against, within
/// their budgets (a reference over budget is a reason, not a value).
fn prepare_case(case: &Case, options: &RunOptions, need_coverage: bool) -> Result<Prepared> {
    let mut scene = None;
    let load = Timer::new(1).with_warmup(0).try_time(&|| false, || {
        scene = Some(case.source.load()?);
        Ok::<(), anyhow::Error>(())
    })?;
    let mut scene = scene.context("load never ran")?;
    // The user's camera applies to the user's scenes, in every study.
    if case.group == Group::Obj && options.matrix.obj_camera != CameraOverrides::default() {
        scene.camera = Some(options.matrix.obj_camera.apply(&scene));
    }
    let view = View::for_scene(&scene, case.width, case.height)?;
    let prepare_options = PrepareOptions::default();
    let mut screen = None;
    let prepare_time = options
        .timing
        .try_time(&|| false, || {
            screen = Some(prepare(&scene, &view, &prepare_options)?);
            Ok::<(), hider_scene::Error>(())
        })
        .with_context(|| format!("preparing {}", case.label()))?;
    let screen = screen.context("prepare never ran")?;
    let analysis = analyse(&screen);
    let oracle = if analysis.pixel_tests > options.oracle_budget {
        Err(format!(
            "skipped: oracle would cost {} pixel tests (budget {})",
            analysis.pixel_tests, options.oracle_budget
        ))
    } else {
        Ok(RayCastOracle::default().evaluate(&screen))
    };
    let coverage_cost = analysis.pixel_tests as f64 * analysis.depth_complexity().max(1.0);
    let coverage = if !need_coverage {
        Err("skipped: no multi-sample hider selected".to_owned())
    } else if !matches!(case.study, Study::Accuracy | Study::RealSize) {
        // Scaling rows measure time; their multi-sample accuracy is the
        // business of the accuracy and real-size studies.
        Err("not computed in this study".to_owned())
    } else if coverage_cost > options.coverage_budget as f64 {
        Err(format!(
            "skipped: analytic coverage would cost about {coverage_cost:.0} clip steps (budget {})",
            options.coverage_budget
        ))
    } else {
        Ok(analytic_coverage(&screen))
    };
    Ok(Prepared {
        stages: Stages::for_scene(&scene, true),
        scene,
        view,
        screen,
        analysis,
        load,
        prepare: prepare_time,
        oracle,
        coverage,
    })
}

/// The row of one job with everything known before it runs: the case, the
/// scene's size, the hider, the load and prepare times and the machine.
fn base_row(index: usize, case: &Case, p: &Prepared, entry: &Entry, machine: &Machine) -> Row {
    Row {
        case: index as u32,
        study: case.study.as_str().into(),
        scene: case.scene.clone(),
        group: case.group.as_str().into(),
        width: case.width,
        height: case.height,
        triangles: p.analysis.triangles,
        covered_pixels: p.analysis.covered_pixels,
        depth_complexity: p.analysis.depth_complexity(),
        hider: entry.name.into(),
        kind: format!("{:?}", entry.kind),
        load_ms: p.load.median_ms,
        prepare_ms: p.prepare.median_ms,
        threads: machine.threads,
        cpu: machine.cpu.clone(),
        ..Row::default()
    }
}

/// What a study's renders start from: the real-size study times what a
/// frame loop waits for, the front end too (the tiled z-buffer brings a
/// lean one of its own); the others time the render of the prepared scene.
fn render_input(p: &Prepared, study: Study) -> RenderInput<'_> {
    RenderInput {
        scene: &p.scene,
        view: &p.view,
        screen: &p.screen,
        whole: study == Study::RealSize,
    }
}

/// Builds one hider for a prepared case, renders it once (the warm-up, or
/// the first measured render when the timer asks for no warm-up) and
/// scores that frame, which stays in `frame` for the contact sheet. The
/// contender for the timed rounds, or `None` with the row saying why.
fn first_job(
    entry: &Entry,
    study: Study,
    p: &Prepared,
    options: &RunOptions,
    row: &mut Row,
    row_index: usize,
    frame: &mut Frame,
) -> Option<Contender> {
    if entry.kind == Kind::Reference
        && let Err(reason) = &p.oracle
    {
        row.status = reason.clone();
        return None;
    }
    let mut hider = match options.threads {
        None => entry.make(),
        Some(n) => match entry.build(&HiderConfig::default().with_threads(n)) {
            Ok(h) => h,
            Err(e) => {
                row.status = format!("error: {e}");
                return None;
            }
        },
    };
    row.ignored_effects = ignored_effects(hider.as_ref(), &p.stages);
    let timing = study_timing(&options.timing, study);
    let input = render_input(p, study);
    let (took, mut stats) = match first_render(hider.as_mut(), &input, frame) {
        Ok(done) => done,
        Err(status) => {
            row.status = status;
            return None;
        }
    };
    // The alpha test of cut-outs belongs to the frame that is scored (the
    // oracle applies it too); the timed renders are the hider's alone.
    if p.stages.cutout
        && let Err(e) = cutout_stage(
            hider.as_ref(),
            &p.scene,
            &p.view,
            &PrepareOptions::default(),
            frame,
            &mut stats,
        )
    {
        row.status = format!("error: {e}");
        return None;
    }
    row.status = "ok".into();
    row.warmup = timing.warmup;
    row.peak_bytes = stats.peak_bytes;
    row.counters = stats
        .counters
        .iter()
        .map(|(n, v)| format!("{n}={v}"))
        .collect::<Vec<_>>()
        .join(";");
    if !hider.resolves_color()
        && let Err(e) = shade_frame(&p.screen, frame, ShadeMode::Lambert)
    {
        row.status = format!("error: {e}");
        return None;
    }
    score(entry.kind, p, options, row, frame);
    if study == Study::DepthPrecision {
        row.farther_pixels = Some(crate::precision::farther_pixels(frame));
    }
    Some(Contender::new(
        hider,
        row_index,
        &input,
        took,
        timing.warmup == 0,
    ))
}

/// Times the case's contenders in alternating rounds and writes each one's
/// times (or why it stopped) into its row.
fn time_contenders(
    contenders: &mut [Contender],
    study: Study,
    p: &Prepared,
    options: &RunOptions,
    stop: &AtomicBool,
    rows: &mut [Row],
    frame: &mut Frame,
) {
    let timing = study_timing(&options.timing, study);
    time_in_rounds(contenders, &render_input(p, study), &timing, stop, frame);
    for c in contenders.iter() {
        let row = &mut rows[c.row];
        let summary = c.summary();
        if let Some(failure) = &c.failure {
            row.status = failure.clone();
        } else if summary.runs == 0 {
            row.status = "skipped: interrupted".into();
        }
        row.render_ms = summary.median_ms;
        row.render_min_ms = summary.min_ms;
        row.render_max_ms = summary.max_ms;
        row.runs = summary.runs;
    }
}

/// The effects `stages` calls for that `hider` does not simulate, as the
/// row's `ignored_effects` (the same rule as the render's warning:
/// [`transparency_warning`]). Cut-outs are simulated by every hider: the
/// single-sample ones through the cut-out stage, the ones that resolve
/// colour at their own samples.
fn ignored_effects(hider: &dyn DynHider, stages: &Stages) -> String {
    let mut ignored = Vec::new();
    if transparency_warning(hider, stages).is_some() {
        ignored.push("transparency");
    }
    ignored.join(";")
}

/// How a study's jobs are timed: as asked, except that a real-size job
/// takes at most 3 measured renders and stops repeating after a second
/// (its frames take milliseconds to a second, and the default run should
/// stay short), and a depth-precision job renders once (it is scored, not
/// timed).
pub fn study_timing(timing: &Timer, study: Study) -> Timer {
    match study {
        Study::RealSize => (*timing)
            .with_runs(timing.runs.min(3))
            .with_max_seconds(timing.max_seconds.min(1.0)),
        Study::DepthPrecision => (*timing).with_runs(1).with_warmup(0),
        _ => *timing,
    }
}

/// Scores the frame against the case's references: ids and depth against
/// the oracle, and coverage for multi-sample hiders.
fn score(kind: Kind, p: &Prepared, options: &RunOptions, row: &mut Row, frame: &Frame) {
    match (&p.oracle, kind) {
        (Err(reason), _) => row.accuracy = reason.clone(),
        (Ok(_), Kind::Reference) => row.accuracy = "reference".into(),
        (Ok(reference), kind) => {
            let s = score_ids(reference, frame, options.tie_tolerance);
            row.accuracy = "scored".into();
            row.coverage_mismatches = Some(s.coverage_mismatches);
            row.wrong_ids = Some(s.wrong_ids);
            row.wrong_fraction = Some(s.wrong_fraction);
            row.ties = Some(s.ties);
            row.tie_differences = Some(s.tie_differences);
            row.depth_error_mean = Some(s.depth_error_mean);
            row.depth_error_max = Some(s.depth_error_max);
            if kind != Kind::MultiSample {
                // One sample per pixel: coverage 0 or 1 at the centre, the
                // first point of the anti-aliasing curve.
                if let Ok(c) = &p.coverage {
                    let binary: Vec<f32> = frame
                        .ids
                        .iter()
                        .map(|&id| if id == NO_ID { 0.0 } else { 1.0 })
                        .collect();
                    row.coverage_error = Some(c.mean_coverage_error(&binary));
                }
            } else {
                match &p.coverage {
                    Ok(c) => match score_coverage(c, frame) {
                        Some(e) => row.coverage_error = Some(e),
                        None => {
                            row.accuracy = "scored: ids only (the hider wrote no coverage)".into()
                        }
                    },
                    Err(reason) => row.accuracy = format!("scored: ids only, coverage {reason}"),
                }
            }
        }
    }
}

/// A progress bar of `len` jobs, drawn on the terminal when `visible`.
fn progress_bar(len: u64, visible: bool) -> ProgressBar {
    let bar = if visible {
        ProgressBar::new(len)
    } else {
        ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden())
    };
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg} (eta {eta})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar
}

/// Whether the case gets a contact sheet: every hard case and every user
/// scene ([`Group::Obj`]) at the smallest accuracy size (tiles are scaled
/// up; larger sizes would only make larger files), and a user scene at the
/// real size when the run has no accuracy study.
fn wants_sheet(case: &Case, options: &RunOptions) -> bool {
    let m = &options.matrix;
    let smallest = Some((case.width, case.height)) == m.smallest_size();
    match (case.group, case.study) {
        (Group::HardCase | Group::Obj, Study::Accuracy) => smallest,
        (Group::Obj, Study::RealSize) => !m.studies.contains(&Study::Accuracy),
        _ => false,
    }
}

/// What a run produced.
#[derive(Debug)]
pub struct RunOutput {
    /// The rows and machine, in matrix order.
    pub results: Results,
    /// Contact sheets written.
    pub contact_sheets: Vec<PathBuf>,
}

/// Runs the selected matrix (this process's shard of it), writing
/// `results.csv` in `options.out_dir` row by row. Polls `stop` between
/// runs: when set, finishes the run in progress and returns what is done
/// with `complete = false`. Writing `results.json` and the report is the
/// caller's ([`crate::record::write_results`], [`crate::report`]).
///
/// With [`RunOptions::threads`] the whole run happens in a rayon pool of
/// that many threads.
pub fn run(options: &RunOptions, stop: &AtomicBool, command: &str) -> Result<RunOutput> {
    match options.threads {
        None => run_here(options, stop, command),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .with_context(|| format!("starting a pool of {n} threads"))?;
            pool.install(|| run_here(options, stop, command))
        }
    }
}

fn run_here(options: &RunOptions, stop: &AtomicBool, command: &str) -> Result<RunOutput> {
    let hiders = select_hiders(&options.matrix)?;
    let cases = options.shard.select(&build_cases(&options.matrix)?);
    std::fs::create_dir_all(&options.out_dir)
        .with_context(|| format!("creating {}", options.out_dir.display()))?;
    if let Some(dir) = &options.contact_dir {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    let mut sink = CsvSink::create(&options.out_dir.join("results.csv"))?;
    let mut machine = Machine::detect();
    if let Some(n) = options.threads {
        machine.threads = u32::try_from(n).unwrap_or(u32::MAX);
    }
    let need_coverage = hiders.iter().any(|e| e.kind == Kind::MultiSample);
    let bar = progress_bar((cases.len() * hiders.len()) as u64, options.progress);
    let mut rows = Vec::new();
    let mut contact_sheets = Vec::new();
    let mut complete = true;
    for (index, case) in &cases {
        bar.set_message(format!("{} preparing", case.label()));
        let p = prepare_case(case, options, need_coverage)?;
        let sheet_wanted =
            options.contact_dir.is_some() && p.oracle.is_ok() && wants_sheet(case, options);
        let mut sheet = ContactSheet::default();
        let mut frame = Frame::new(case.width, case.height)?;
        let mut case_rows = Vec::new();
        let mut contenders = Vec::new();
        for entry in &hiders {
            if stop.load(Ordering::Relaxed) {
                complete = false;
                break;
            }
            // The oracle's time is the accuracy study's business: in the
            // studies that only use it as a reference, it is not timed.
            if entry.kind == Kind::Reference
                && matches!(case.study, Study::RealSize | Study::DepthPrecision)
            {
                bar.inc(1);
                continue;
            }
            bar.set_message(format!("{} {}", case.label(), entry.name));
            let mut row = base_row(*index, case, &p, entry, &machine);
            frame.clear();
            let contender = first_job(
                entry,
                case.study,
                &p,
                options,
                &mut row,
                case_rows.len(),
                &mut frame,
            );
            if sheet_wanted && row.is_ok() && entry.kind != Kind::Reference {
                sheet.tiles.push((entry.name.to_owned(), frame.clone()));
            }
            contenders.extend(contender);
            case_rows.push(row);
            bar.inc(1);
        }
        bar.set_message(format!("{} timing in rounds", case.label()));
        time_contenders(
            &mut contenders,
            case.study,
            &p,
            options,
            stop,
            &mut case_rows,
            &mut frame,
        );
        drop(contenders);
        for row in case_rows {
            sink.push(&row)?;
            rows.push(row);
        }
        if stop.load(Ordering::Relaxed) {
            complete = false;
        }
        if let (true, Some(dir), Ok(reference)) = (sheet_wanted, &options.contact_dir, &p.oracle) {
            let path = dir.join(format!("bench-contact-{}.png", case.scene));
            write_contact_sheet(&path, &p.screen, reference, &sheet, options.tie_tolerance)?;
            contact_sheets.push(path);
        }
        if !complete {
            break;
        }
    }
    bar.finish_and_clear();
    let mut results = Results {
        schema: SCHEMA_VERSION,
        machines: vec![machine],
        commands: vec![command.to_owned()],
        complete,
        rows,
    };
    let order: Vec<&str> = hiders.iter().map(|e| e.name).collect();
    results.sort(|h| order.iter().position(|n| *n == h).unwrap_or(usize::MAX));
    Ok(RunOutput {
        results,
        contact_sheets,
    })
}
