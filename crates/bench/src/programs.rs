//! What the timing and profiling programs of `src/bin` share (run as
//! `cargo run --release -p hider-bench --bin NAME -- ARGS`): the bundled
//! spider, the scenes of the llvmpipe comparison, the `peers` package's
//! timings, command-line flags and thread CPU time.

use std::path::PathBuf;
use std::process::{Command, Stdio};

use hider_scene::{Scene, load_obj, procedural};

/// The spider model bundled in `assets/spider/` (the same file as the GL
/// reference's `models/spider.obj`), found from this package's folder so
/// that the programs run from any directory.
pub fn spider_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/spider/spider.obj")
}

/// The bundled spider, loaded.
pub fn spider() -> hider_scene::Result<Scene> {
    load_obj(spider_path())
}

/// The scenes of the llvmpipe comparison, in its order and under the names
/// the `peers` package gives them: the spider, UV spheres of 200 and 500
/// segments, and the random soup of 100,000 triangles (seed 1). A spider
/// that cannot be loaded is left out with one line on standard error.
pub fn llvmpipe_scenes() -> Vec<(&'static str, Scene)> {
    let mut scenes = Vec::new();
    match spider() {
        Ok(s) => scenes.push(("spider", s)),
        // The error names the file.
        Err(e) => eprintln!("skipped the spider: {e}"),
    }
    scenes.push(("sphere 200", procedural::uv_sphere(200)));
    scenes.push(("sphere 500", procedural::uv_sphere(500)));
    scenes.push(("soup 100k", procedural::random_soup(100_000, 1)));
    scenes
}

/// Takes `--flag VALUE` out of `args`: the value, `None` without the flag,
/// an error when the flag ends the list.
pub fn take_flag(args: &mut Vec<String>, flag: &str) -> Result<Option<String>, String> {
    let Some(i) = args.iter().position(|a| a == flag) else {
        return Ok(None);
    };
    let value = args
        .get(i + 1)
        .cloned()
        .ok_or_else(|| format!("{flag} needs a value"))?;
    args.drain(i..i + 2);
    Ok(Some(value))
}

/// CPU time of the calling thread in seconds, where the platform gives it:
/// on a shared machine wall time measures the load too.
pub fn thread_cpu_seconds() -> Option<f64> {
    cpu_time::ThreadTime::try_now()
        .ok()
        .map(|t| t.as_duration().as_secs_f64())
}

/// One row of the `peers` package's JSON (its `--json FILE`).
#[derive(Debug, Clone, serde::Deserialize)]
pub struct PeerRow {
    /// The scene's name (see [`llvmpipe_scenes`]).
    pub scene: String,
    /// The image side in pixels.
    pub size: u32,
    /// The peer: `euc`, `llvmpipe`, `llvmpipe-msaa4`.
    pub peer: String,
    /// The threads it ran on.
    pub threads: u32,
    /// Its median frame time.
    pub median_ms: f64,
}

/// Runs the `peers` binary `bin` once (`--runs 5 --rounds 1`) on every
/// scene at `size`, with `extra` arguments first (which peers, MSAA), and
/// returns the rows it measured.
pub fn run_peers(bin: &str, extra: &[&str], size: u32) -> Result<Vec<PeerRow>, String> {
    let json = std::env::temp_dir().join(format!("hider-peers-{}.json", std::process::id()));
    let status = Command::new(bin)
        .args(extra)
        .args(["--runs", "5", "--rounds", "1", "--sizes", &size.to_string()])
        .arg("--json")
        .arg(&json)
        .stdout(Stdio::null())
        .status()
        .map_err(|e| format!("{bin}: {e}"))?;
    if !status.success() {
        return Err(format!("{bin} failed ({status})"));
    }
    let text = std::fs::read_to_string(&json).map_err(|e| format!("{}: {e}", json.display()));
    let _ = std::fs::remove_file(&json);
    serde_json::from_str(&text?).map_err(|e| format!("{}: {e}", json.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_come_out_with_their_values() {
        let mut args: Vec<String> = ["3", "--zbuffer-bin", "z", "512"].map(String::from).into();
        assert_eq!(
            take_flag(&mut args, "--zbuffer-bin").unwrap().as_deref(),
            Some("z")
        );
        assert_eq!(args, ["3", "512"]);
        assert_eq!(take_flag(&mut args, "--peers-bin"), Ok(None));
        args.push("--peers-bin".into());
        assert!(take_flag(&mut args, "--peers-bin").is_err());
    }

    #[test]
    fn the_bundled_spider_is_there() {
        assert!(spider_path().is_file(), "{}", spider_path().display());
    }
}
