//! Posters: every registered hider's time and peak memory on the spider
//! and the UV sphere of 500 segments at 1024, 2048, 4096 and 8192 pixels
//! (16384 on request), with the exponent of time in the pixel count, and
//! what writing the PNG of the tiled z-buffer's frame costs.
//!
//! Each measurement is a child process (this program re-executed with
//! `--child HIDER SCENE SIZE`), so its peak resident memory (`VmHWM` of
//! `/proc/self/status`) is its own: scene, front end, hider and frame.
//! The child renders one frame ([`DynHider::render_scene`](hider_scene::DynHider::render_scene), as `hider
//! render` does, colour stages left out) and reports its wall time; a
//! child still running after the budget is stopped and the hider skips
//! the larger sizes of that scene. The exponent is the slope of
//! log(time) over log(pixels) between the smallest and largest size
//! measured (1 = linear in the pixels; below 1, the scene's own cost
//! dominates).
//!
//! `cargo run --release -p hider-bench --bin posters -- [SIZES...] [--budget SECONDS] [--hiders A,B,..]`
//! (default sizes 1024 2048 4096 8192, budget 60 s, every hider).

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use hider_bench::programs;
use hider_plan::registry;
use hider_scene::{Frame, PrepareOptions, Scene, ScreenScene, View, procedural};

/// The scenes of the table.
const SCENES: [&str; 2] = ["spider", "sphere 500"];

fn scene(name: &str) -> Result<Scene, String> {
    match name {
        "spider" => programs::spider().map_err(|e| e.to_string()),
        "sphere 500" => Ok(procedural::uv_sphere(500)),
        other => Err(format!("unknown scene `{other}`")),
    }
}

/// The peak resident memory of this process in MB, where Linux reports
/// it.
fn peak_mb() -> Option<f64> {
    hider_bench::machine::peak_resident_bytes().map(|b| b as f64 / 1048576.0)
}

/// The child: one frame of `hider` on `scene` at `size`; prints
/// `ms peak_mb`, and with `png` the PNG's encoding ms, size in bytes and
/// the peak after it.
fn child(hider: &str, name: &str, size: u32, png: bool) -> Result<(), String> {
    let scene = scene(name)?;
    let view = View::for_scene(&scene, size, size).map_err(|e| e.to_string())?;
    let mut h = registry::find(hider).map_err(|e| e.to_string())?.make();
    let mut frame = Frame::new(size, size).map_err(|e| e.to_string())?;
    let mut screen = ScreenScene::empty(&view);
    let options = PrepareOptions::default();
    let t = Instant::now();
    h.render_scene(&scene, &view, &options, &mut screen, &mut frame)
        .map_err(|e| e.to_string())?;
    let ms = t.elapsed().as_secs_f64() * 1e3;
    print!("{ms:.1} {:.0}", peak_mb().unwrap_or(f64::NAN));
    if png {
        let path = std::env::temp_dir().join(format!("hider-poster-{}.png", std::process::id()));
        let t = Instant::now();
        frame.write_png(&path).map_err(|e| e.to_string())?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        let _ = std::fs::remove_file(&path);
        print!(" {ms:.1} {bytes} {:.0}", peak_mb().unwrap_or(f64::NAN));
    }
    println!();
    Ok(())
}

/// Runs one child within `budget`; its output's numbers, or why not.
fn measure(
    hider: &str,
    name: &str,
    size: u32,
    png: bool,
    budget: Duration,
) -> Result<Vec<f64>, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut cmd = Command::new(exe);
    cmd.args(["--child", hider, name, &size.to_string()]);
    if png {
        cmd.arg("--png");
    }
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| e.to_string())?;
    let start = Instant::now();
    loop {
        if child.try_wait().map_err(|e| e.to_string())?.is_some() {
            break;
        }
        if start.elapsed() > budget {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("> {} s", budget.as_secs()));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().map_err(|e| e.to_string())?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(err.lines().last().unwrap_or("failed").to_owned());
    }
    Ok(String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .filter_map(|v| v.parse().ok())
        .collect())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--child") {
        let size = args
            .get(3)
            .and_then(|s| s.parse().ok())
            .ok_or("--child HIDER SCENE SIZE")?;
        let png = args.iter().any(|a| a == "--png");
        return Ok(child(&args[1], &args[2], size, png)?);
    }
    let budget = programs::take_flag(&mut args, "--budget")?
        .map(|s| s.parse::<u64>().map_err(|e| format!("--budget: {e}")))
        .transpose()?
        .unwrap_or(60);
    let budget = Duration::from_secs(budget);
    let hiders: Vec<String> = match programs::take_flag(&mut args, "--hiders")? {
        Some(list) => list.split(',').map(str::to_owned).collect(),
        None => registry::names().into_iter().map(str::to_owned).collect(),
    };
    let mut sizes: Vec<u32> = args.iter().filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![1024, 2048, 4096, 8192];
    }
    println!(
        "one frame (render_scene, default options, all cores) per child process: wall ms / peak resident MB; budget {} s\n",
        budget.as_secs()
    );
    let head: Vec<String> = sizes.iter().map(|s| s.to_string()).collect();
    println!("| hider | scene | {} | exponent |", head.join(" | "));
    println!("|---|---|{}---|", "---|".repeat(sizes.len()));
    let mut pngs = Vec::new();
    for hider in &hiders {
        for name in SCENES {
            let mut cells = Vec::new();
            let mut points = Vec::new();
            let mut over = false;
            for &size in &sizes {
                if over {
                    cells.push("-".to_owned());
                    continue;
                }
                let png = hider == "zbuffer-tiled";
                match measure(hider, name, size, png, budget) {
                    Ok(v) if v.len() >= 2 => {
                        cells.push(format!("{:.1} / {:.0}", v[0], v[1]));
                        points.push((f64::from(size) * f64::from(size), v[0]));
                        if v.len() >= 5 {
                            pngs.push((name, size, v[0], v[2], v[3], v[1], v[4]));
                        }
                    }
                    Ok(_) => cells.push("?".to_owned()),
                    Err(e) => {
                        over = true;
                        cells.push(e);
                    }
                }
            }
            let exponent = match (points.first(), points.last()) {
                (Some(a), Some(b)) if b.0 > a.0 => {
                    format!("{:.2}", (b.1 / a.1).ln() / (b.0 / a.0).ln())
                }
                _ => "-".to_owned(),
            };
            println!("| {hider} | {name} | {} | {exponent} |", cells.join(" | "));
        }
    }
    if !pngs.is_empty() {
        println!(
            "\nPNG of the tiled z-buffer's frame (Frame::write_png):\n\n| scene | size | render ms | PNG ms | PNG bytes | peak MB before / after |"
        );
        println!("|---|---|---|---|---|---|");
        for (name, size, render, png, bytes, before, after) in pngs {
            println!(
                "| {name} | {size} | {render:.1} | {png:.1} | {bytes:.0} | {before:.0} / {after:.0} |"
            );
        }
    }
    Ok(())
}
