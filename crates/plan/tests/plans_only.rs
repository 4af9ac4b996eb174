//! The plan crate plans and nothing else: no model loading, no shading or
//! texture code (they live in `hider-scene`), and no command-line flag in
//! a library error message (each front end words the typed errors itself).

use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, but the unit-test files (`tests.rs`),
/// which may exercise anything.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs")
            && path.file_name().is_some_and(|n| n != "tests.rs")
        {
            out.push(path);
        }
    }
}

/// What a file of the plan crate must not contain: the marks of loading,
/// decoding, shading and colour conversion.
const FORBIDDEN: &[&str] = &[
    "load_obj",
    "tobj::",
    "image::",
    "Texture::load",
    "TextureSampler",
    "to_srgb8",
    "lambert_light",
    "fn shade",
    "Shader",
    "frame.color",
];

/// The offences in `text` (one per line): a forbidden mark, or a `--flag`
/// inside an `#[error("...")]` message.
fn offences(name: &str, text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let code = line.trim_start();
        if code.starts_with("//") {
            continue;
        }
        for mark in FORBIDDEN {
            if code.contains(mark) {
                found.push(format!("{name}:{}: `{mark}` in `{}`", k + 1, code));
            }
        }
        if let Some(message) = code.strip_prefix("#[error(\"")
            && message.contains("--")
        {
            found.push(format!(
                "{name}:{}: a flag in an error message: {code}",
                k + 1
            ));
        }
    }
    found
}

#[test]
fn the_plan_crate_has_no_loading_shading_or_flags() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    assert!(files.len() > 10, "only {} files found", files.len());
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let name = file.strip_prefix(&src).unwrap().display().to_string();
        found.extend(offences(&name, &text));
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// The check finds what it looks for.
#[test]
fn the_check_catches_shading_and_flags() {
    let bad = "use hider_scene::shade::Shader;\n#[error(\"unknown --algo '{name}'\")]\n";
    assert_eq!(
        offences("bad.rs", bad).len(),
        2,
        "{:?}",
        offences("bad.rs", bad)
    );
    assert!(offences("ok.rs", "// a Shader in a comment\n").is_empty());
}
