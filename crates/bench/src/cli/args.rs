//! The arguments of `hider bench` and what they mean as [`RunOptions`]:
//! the clap structures, the value parsers that check each flag, and the
//! matrix and timing a run's flags select.

use std::path::PathBuf;

use clap::{Args, Subcommand};
use hider_geom::glam::DVec3;
use hider_scene::CameraOverrides;
use hider_scene::timing::Timer;

use crate::matrix::{MatrixOptions, Shard, Study};
use crate::run::RunOptions;

/// Arguments of `hider bench`.
#[derive(Args, Debug, Clone, PartialEq)]
#[command(args_conflicts_with_subcommands = true)]
pub struct BenchArgs {
    /// `merge` or `report`; without one, run the matrix.
    #[command(subcommand)]
    pub action: Option<Action>,
    /// Options of a run.
    #[command(flatten)]
    pub run: RunArgs,
}

/// The steps besides running.
#[derive(Subcommand, Debug, Clone, PartialEq)]
pub enum Action {
    /// Combine the result folders of shards into one, with one report.
    Merge(MergeArgs),
    /// Regenerate the report and the plots from existing results.
    Report(ReportArgs),
}

/// Where the outputs go (shared by every action).
#[derive(Args, Debug, Clone, PartialEq)]
pub struct OutputArgs {
    /// Folder for results.csv, results.json, report.md and images/.
    #[arg(long, default_value = "bench-out")]
    pub out: PathBuf,
    /// Also write the report to DOCS/report.md with its plots and contact
    /// sheets in DOCS/images/ (the project's docs/ folder).
    #[arg(long)]
    pub docs: Option<PathBuf>,
}

/// Arguments of a run.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct RunArgs {
    /// Outputs.
    #[command(flatten)]
    pub output: OutputArgs,
    /// Scenes: names, groups (asset, hard-case, obj, scaling) or patterns
    /// with `*`; comma-separated. Default: all.
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Hiders from the registry (`hider list`): names or patterns with `*`;
    /// comma-separated. Default: all.
    #[arg(long, value_delimiter = ',')]
    pub algos: Vec<String>,
    /// Studies: real-size, depth-precision, accuracy, polygons, resolution,
    /// depth-complexity.
    #[arg(long, value_delimiter = ',', value_parser = parse_study)]
    pub studies: Vec<Study>,
    /// Image sizes of the accuracy study: `N` (N x N) or `WxH`;
    /// comma-separated (default 64,256). Example: --sizes 64,800x600.
    #[arg(long, value_delimiter = ',', value_parser = parse_size)]
    pub sizes: Vec<(u32, u32)>,
    /// Image width of the accuracy study (with --height; the same as
    /// --sizes WxH).
    #[arg(long, requires = "height", conflicts_with = "sizes")]
    pub width: Option<u32>,
    /// Image height of the accuracy study (with --width).
    #[arg(long, requires = "width", conflicts_with = "sizes")]
    pub height: Option<u32>,
    /// Image size of the real-size study: `N` (N x N) or `WxH` (default
    /// 1024).
    #[arg(long, value_parser = parse_size)]
    pub real_size: Option<(u32, u32)>,
    /// Extra OBJ files to benchmark (accuracy and real-size studies);
    /// repeatable. Each gets a contact sheet. --eye, --target, --up and
    /// --fovy set the camera of every --obj scene.
    #[arg(long = "obj")]
    pub objs: Vec<PathBuf>,
    /// Eye position `X,Y,Z` of every --obj scene's camera (default: the
    /// fit camera's, on +Z of the scene's centre). Near and far planes not
    /// given are fitted around the scene as seen from there.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<DVec3>,
    /// Point `X,Y,Z` every --obj scene's camera looks at (default: the
    /// centre of the scene's bounding box).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<DVec3>,
    /// Up direction `X,Y,Z` of every --obj scene's camera (default 0,1,0).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: Option<DVec3>,
    /// Vertical field of view in degrees of every --obj scene's camera
    /// (default 60).
    #[arg(long, value_parser = parse_fovy)]
    pub fovy: Option<f64>,
    /// Near clip distance of every --obj scene's camera (default: fitted
    /// around the scene).
    #[arg(long, value_parser = parse_distance)]
    pub near: Option<f64>,
    /// Far clip distance of every --obj scene's camera (default: fitted
    /// around the scene).
    #[arg(long, value_parser = parse_distance)]
    pub far: Option<f64>,
    /// Folder of the bundled scenes (default: ./assets).
    #[arg(long)]
    pub assets: Option<PathBuf>,
    /// UV sphere segment counts of the polygon study.
    #[arg(long, value_delimiter = ',')]
    pub polygon_steps: Vec<u32>,
    /// Square sizes of the resolution study.
    #[arg(long, value_delimiter = ',')]
    pub resolution_steps: Vec<u32>,
    /// Layer counts of the depth-complexity study.
    #[arg(long, value_delimiter = ',')]
    pub depth_steps: Vec<u32>,
    /// Square size of the polygon and depth-complexity studies.
    #[arg(long)]
    pub scaling_size: Option<u32>,
    /// Unmeasured warm-up renders per job.
    #[arg(long, default_value_t = RunOptions::default().timing.warmup)]
    pub warmup: u32,
    /// Measured renders per job (at least 1). Real-size jobs take at most
    /// 3 and stop repeating after 1 s (or --max-seconds if less);
    /// depth-precision jobs render once.
    #[arg(long, default_value_t = RunOptions::default().timing.runs)]
    pub repeats: u32,
    /// Stop repeating a job after this many seconds of measured renders.
    #[arg(long, default_value_t = RunOptions::default().timing.max_seconds)]
    pub max_seconds: f64,
    /// Run only shard i of n (1 <= i <= n), splitting by case; combine
    /// the shards' folders with `hider bench merge`.
    #[arg(long, default_value = "1/1")]
    pub shard: Shard,
    /// Most (triangle, pixel) tests the oracle may spend on one case;
    /// larger cases are timed but not scored.
    #[arg(long, default_value_t = RunOptions::default().oracle_budget)]
    pub oracle_budget: u64,
    /// Worker threads, 1 to 256: the run happens in a pool of N threads
    /// and the hiders that render in parallel use N (default:
    /// RAYON_NUM_THREADS, else one per core).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=256))]
    pub threads: Option<u32>,
    /// A small matrix for a smoke test (32 px, 2 repeats, short sweeps).
    #[arg(long)]
    pub quick: bool,
    /// List the cases and hiders the options select, and exit.
    #[arg(long)]
    pub dry_run: bool,
    /// No progress bar.
    #[arg(long)]
    pub no_progress: bool,
}

/// Arguments of `hider bench merge`.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct MergeArgs {
    /// The shards' output folders.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Outputs.
    #[command(flatten)]
    pub output: OutputArgs,
}

/// Arguments of `hider bench report`.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct ReportArgs {
    /// Folder holding results.json (or results.csv).
    #[arg(long, default_value = "bench-out")]
    pub from: PathBuf,
    /// Outputs (`--out` defaults to the `--from` folder's parent layout:
    /// report.md and images/ are written into `--out`).
    #[command(flatten)]
    pub output: OutputArgs,
}

/// `N` (a square) or `WxH`.
fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let side = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| format!("bad image size '{s}' (expected N or WxH, e.g. 256 or 800x600)"))
    };
    match s.split_once(['x', 'X']) {
        Some((w, h)) => Ok((side(w)?, side(h)?)),
        None => side(s).map(|n| (n, n)),
    }
}

/// `X,Y,Z`, three finite numbers.
fn parse_vec3(s: &str) -> std::result::Result<DVec3, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|c| c.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| format!("bad vector '{s}' (expected X,Y,Z, e.g. 0,5,10)"))?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(x, y, z)),
        _ => Err(format!("bad vector '{s}' (expected X,Y,Z, e.g. 0,5,10)")),
    }
}

/// A field of view strictly between 0 and 180 degrees.
fn parse_fovy(s: &str) -> std::result::Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|f| *f > 0.0 && *f < 180.0)
        .ok_or_else(|| format!("bad field of view '{s}' (expected degrees, 0 < fovy < 180)"))
}

/// A clip distance: finite and positive.
fn parse_distance(s: &str) -> std::result::Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|d| *d > 0.0 && d.is_finite())
        .ok_or_else(|| format!("bad clip distance '{s}' (expected a positive number)"))
}

fn parse_study(s: &str) -> std::result::Result<Study, String> {
    Study::parse(s).ok_or_else(|| {
        let names: Vec<&str> = Study::ALL.iter().map(|s| s.as_str()).collect();
        format!("unknown study '{s}' (expected one of {})", names.join(", "))
    })
}

impl RunArgs {
    /// The run these arguments describe, writing into `out`.
    pub fn options(&self) -> RunOptions {
        let mut m = MatrixOptions::default();
        let mut timing = Timer::new(self.repeats.max(1))
            .with_warmup(self.warmup)
            .with_max_seconds(self.max_seconds);
        if self.quick {
            m.sizes = vec![(32, 32)];
            m.real_size = (128, 128);
            m.real_spheres = vec![32];
            m.real_layers = vec![2];
            m.precision_gaps = vec![1e-2, 1e-4, 1e-6];
            m.precision_ratios = vec![1e-2, 1e-4];
            m.precision_size = 32;
            m.polygon_steps = vec![8, 16, 32];
            m.resolution_steps = vec![32, 64, 128];
            m.resolution_sphere = 16;
            m.depth_steps = vec![1, 2, 4];
            m.scaling_size = 64;
            timing = timing.with_runs(timing.runs.min(2));
        }
        let set = |v: &Vec<u32>, dst: &mut Vec<u32>| {
            if !v.is_empty() {
                dst.clone_from(v);
            }
        };
        if !self.sizes.is_empty() {
            m.sizes.clone_from(&self.sizes);
        }
        if let (Some(w), Some(h)) = (self.width, self.height) {
            m.sizes = vec![(w, h)];
        }
        m.obj_camera = CameraOverrides {
            eye: self.eye,
            target: self.target,
            up: self.up,
            fovy: self.fovy,
            near: self.near,
            far: self.far,
        };
        set(&self.polygon_steps, &mut m.polygon_steps);
        set(&self.resolution_steps, &mut m.resolution_steps);
        set(&self.depth_steps, &mut m.depth_steps);
        if let Some(s) = self.real_size {
            m.real_size = s;
        }
        if let Some(s) = self.scaling_size {
            m.scaling_size = s;
        }
        if let Some(a) = &self.assets {
            m.assets_dir = a.clone();
        }
        if !self.studies.is_empty() {
            m.studies = self.studies.clone();
        }
        m.scenes.clone_from(&self.scenes);
        m.algos.clone_from(&self.algos);
        m.objs.clone_from(&self.objs);
        RunOptions {
            matrix: m,
            timing,
            shard: self.shard,
            out_dir: self.output.out.clone(),
            contact_dir: Some(image_dir(&self.output)),
            oracle_budget: self.oracle_budget,
            progress: !self.no_progress,
            threads: self.threads.map(|n| n as usize),
            ..RunOptions::default()
        }
    }
}

/// Where images go: `DOCS/images` with `--docs`, else `OUT/images`.
pub(super) fn image_dir(output: &OutputArgs) -> PathBuf {
    output
        .docs
        .as_ref()
        .map_or_else(|| output.out.join("images"), |d| d.join("images"))
}
