//! OBJ ingest: the fast reader against tobj (the loader of record) on
//! generated files of 10^4 to 10^7 tiny triangles, each load in a process
//! of its own so that its peak memory is its own; the two readers
//! alternate, so both see the same machine load. Optionally times
//! `hider render` of the largest file (`--render`, which needs the
//! release `hider` binary beside this one: `cargo build --release`).
//!
//! `cargo run --release -p hider-bench --bin obj_ingest -- [--sizes 10000,100000,1000000,10000000] [--runs 3] [--tobj-max 10000000] [--render]`
//!
//! The files are written to a fresh folder under the system's temporary
//! folder and deleted after use. Each is shaped like the file of issue
//! 40: all positions (`v x y z`, full-precision decimals, three per
//! triangle), then the faces (`f a b c`), about 227 bytes a triangle.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use hider_bench::programs::take_flag;

const USAGE: &str = "usage: obj_ingest [--sizes N,N,...] [--runs K] [--tobj-max N] [--render]
  --sizes     triangles of the generated files (default 10000,100000,1000000,10000000)
  --runs      loads of each file by each reader, alternating; the best is shown (default 3)
  --tobj-max  largest file also loaded by tobj (default: every size)
  --render    then time `hider render` of the largest file (needs the release hider binary)";
use hider_scene::obj::{ObjOptions, ObjParser, load_obj_stats};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("{USAGE}");
        return Ok(());
    }
    if let Some(path) = take_flag(&mut args, "--one")? {
        return one(Path::new(&path), args.first().map(String::as_str));
    }
    let sizes: Vec<u64> = take_flag(&mut args, "--sizes")?
        .unwrap_or_else(|| "10000,100000,1000000,10000000".into())
        .split(',')
        .map(|s| s.trim().parse())
        .collect::<Result<_, _>>()?;
    let runs: usize = take_flag(&mut args, "--runs")?.map_or(Ok(3), |r| r.parse())?;
    let tobj_max: u64 = take_flag(&mut args, "--tobj-max")?.map_or(Ok(u64::MAX), |r| r.parse())?;
    let render = args.iter().any(|a| a == "--render");
    let dir = std::env::temp_dir().join(format!("hider-obj-ingest-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let result = run(&dir, &sizes, runs, tobj_max, render);
    std::fs::remove_dir_all(&dir)?;
    result
}

/// One measurement: the file read by one reader, in this process.
/// Prints `seconds peak_bytes triangles fast`.
fn one(path: &Path, parser: Option<&str>) -> Result<(), Box<dyn std::error::Error>> {
    let options = ObjOptions {
        parser: match parser {
            Some("tobj") => ObjParser::Tobj,
            _ => ObjParser::Fast,
        },
        ..ObjOptions::default()
    };
    let start = Instant::now();
    let (scene, stats) = load_obj_stats(path, &options)?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(why) = &stats.fallback {
        eprintln!("obj_ingest: the fast reader gave the file to tobj: {why}");
    }
    println!(
        "{seconds} {} {} {} {}",
        cpu_seconds().unwrap_or(f64::NAN),
        hider_bench::machine::peak_resident_bytes().unwrap_or(0),
        scene.triangle_count(),
        stats.fast
    );
    Ok(())
}

/// The CPU time of the process so far (every thread, user and system),
/// in seconds: Linux's /proc/self/stat, in ticks of 1/100 s.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (which may hold spaces).
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 / 100.0)
}

/// A measured load: wall seconds, CPU seconds and peak bytes.
#[derive(Clone, Copy)]
struct Load {
    seconds: f64,
    cpu: f64,
    peak: u64,
}

/// Loads `path` with `parser` in a child process.
fn measure(path: &Path, parser: &str, triangles: u64) -> Result<Load, Box<dyn std::error::Error>> {
    let out = Command::new(std::env::current_exe()?)
        .args(["--one", &path.display().to_string(), parser])
        .output()?;
    if !out.status.success() {
        return Err(format!(
            "loading {} with {parser} failed: {}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    let text = String::from_utf8(out.stdout)?;
    let fields: Vec<&str> = text.split_whitespace().collect();
    let [seconds, cpu, peak, loaded, fast] = fields[..] else {
        return Err(format!("unexpected output: {text}").into());
    };
    if loaded.parse::<u64>()? != triangles || (parser == "fast") != (fast == "true") {
        return Err(format!("{parser}: loaded {loaded} triangles (fast: {fast})").into());
    }
    Ok(Load {
        seconds: seconds.parse()?,
        cpu: cpu.parse()?,
        peak: peak.parse()?,
    })
}

fn run(
    dir: &Path,
    sizes: &[u64],
    runs: usize,
    tobj_max: u64,
    render: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "OBJ ingest, {threads} threads, best of {runs}: s = wall time of the load, cpu = CPU \
         time of the loading process (all threads), peak = its peak resident memory\n"
    );
    println!(
        "| triangles | file MB | fast s | fast cpu s | fast MB/s | fast peak / file | tobj s | \
         tobj cpu s | tobj MB/s | tobj peak / file | tobj s / fast s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let mut largest: Option<PathBuf> = None;
    for &n in sizes {
        let path = dir.join(format!("tiny-{n}.obj"));
        let bytes = generate(&path, n)?;
        let mb = bytes as f64 / 1e6;
        let (mut fast, mut tobj): (Option<Load>, Option<Load>) = (None, None);
        let best = |a: Option<Load>, b: Load| {
            Some(a.map_or(b, |a| Load {
                seconds: a.seconds.min(b.seconds),
                cpu: a.cpu.min(b.cpu),
                peak: a.peak.max(b.peak),
            }))
        };
        for _ in 0..runs {
            fast = best(fast, measure(&path, "fast", n)?);
            if n <= tobj_max {
                tobj = best(tobj, measure(&path, "tobj", n)?);
            }
        }
        let fast = fast.ok_or("no runs")?;
        let cell = |l: Option<Load>, f: &dyn Fn(Load) -> String| l.map_or("-".into(), f);
        println!(
            "| {n} | {mb:.1} | {:.3} | {:.2} | {:.0} | {:.2} | {} | {} | {} | {} | {} |",
            fast.seconds,
            fast.cpu,
            mb / fast.seconds,
            fast.peak as f64 / bytes as f64,
            cell(tobj, &|t| format!("{:.3}", t.seconds)),
            cell(tobj, &|t| format!("{:.2}", t.cpu)),
            cell(tobj, &|t| format!("{:.0}", mb / t.seconds)),
            cell(tobj, &|t| format!("{:.2}", t.peak as f64 / bytes as f64)),
            cell(tobj, &|t| format!("{:.1}x", t.seconds / fast.seconds)),
        );
        if let Some(previous) = largest.replace(path) {
            std::fs::remove_file(previous)?;
        }
    }
    if render && let Some(path) = &largest {
        render_time(path)?;
    }
    Ok(())
}

/// Times `hider render` of `path` (the tiled z-buffer at 64 x 64, the
/// command of issue 40), end to end.
fn render_time(path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let hider = std::env::current_exe()?.with_file_name("hider");
    if !hider.is_file() {
        return Err(format!(
            "{} not found: build it with `cargo build --release`",
            hider.display()
        )
        .into());
    }
    let png = path.with_extension("png");
    let start = Instant::now();
    let status = Command::new(&hider)
        .arg("render")
        .arg(path)
        .args(["--algo", "zbuffer", "--size", "64", "-o"])
        .arg(&png)
        .status()?;
    let seconds = start.elapsed().as_secs_f64();
    if !status.success() {
        return Err(format!("hider render failed ({status})").into());
    }
    println!(
        "\n`hider render {} --algo zbuffer --size 64`: {seconds:.2} s end to end",
        path.file_name().unwrap_or_default().to_string_lossy()
    );
    Ok(())
}

/// Writes `n` tiny triangles to `path`: every position first, at full
/// precision, then the faces; returns the file's size in bytes.
fn generate(path: &Path, n: u64) -> Result<u64, Box<dyn std::error::Error>> {
    let mut out = std::io::BufWriter::with_capacity(1 << 20, std::fs::File::create(path)?);
    // A fixed linear congruential sequence: the same file every run.
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut unit = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    writeln!(out, "# {n} tiny triangles, generated by obj_ingest")?;
    for _ in 0..n {
        let centre = [unit(), unit(), unit()];
        for _ in 0..3 {
            let [x, y, z] = centre.map(|c| c + 1e-3 * unit());
            writeln!(out, "v {x} {y} {z}")?;
        }
    }
    for t in 0..n {
        let a = 3 * t + 1;
        writeln!(out, "f {a} {} {}", a + 1, a + 2)?;
    }
    out.flush()?;
    Ok(std::fs::metadata(path)?.len())
}
