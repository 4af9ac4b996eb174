//! The repository as the docs check sees it: its files, its packages and
//! their targets, and the words that make a token a path.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Extensions that make a token a path even without a `/`.
pub(crate) const EXTENSIONS: &[&str] = &[
    ".rs", ".md", ".toml", ".obj", ".mtl", ".png", ".svg", ".py", ".sh",
];

/// Paths that are never checked: made by running something, or not in the
/// repository.
pub(crate) const EXEMPT_PREFIXES: &[&str] = &[
    // The benchmark's output folder and cargo's build folders.
    "bench-out/",
    "target/",
    "peers/target/",
    "fuzz/target/",
    // Folders the fuzzing and the benchmark write when run.
    "fuzz/artifacts/",
    "fuzz/corpus/",
    // The benchmark's shard example writes `out/1`, `out/2`, ...
    "out/",
];

/// Words in capitals that are file names, not placeholders.
pub(crate) const CAPITAL_NAMES: &[&str] = &["README", "LICENSE", "CHANGELOG", "CONTRIBUTING"];

/// Single tokens that look like paths and are not repository files: each is
/// explained. Keep this list small.
pub(crate) const ALLOWED: &[&str] = &[
    // Output names of the README's and the pages' example commands.
    "spider.png",
    "spider-aa.png",
    "spider-lines.svg",
    "cyclic.png",
    "cyclic.svg",
    "pieces.svg",
    "out.png",
    "sphere.png",
    "cube.png",
    "soup.png",
];

/// Flags whose value is a file the command writes (never checked).
pub(crate) const OUTPUT_FLAGS: &[&str] = &[
    "-o",
    "--out",
    "--output",
    "--svg",
    "--ids-out",
    "--depth-out",
    "--docs",
    "--out-dir",
    "--csv",
    "--json",
];

/// One package of the workspace: its folder and its targets.
#[derive(Debug, Default)]
pub(crate) struct Package {
    pub(crate) bins: BTreeSet<String>,
    pub(crate) examples: BTreeSet<String>,
    pub(crate) tests: BTreeSet<String>,
    /// The manifest's `default-run`: which binary a plain `cargo run`
    /// runs when the package has several.
    pub(crate) default_run: Option<String>,
}

/// What the checks compare against.
pub(crate) struct Repo {
    pub(crate) root: PathBuf,
    /// The name of the root package.
    pub(crate) root_package: String,
    pub(crate) packages: BTreeMap<String, Package>,
    /// Folders a path with a `/` may start from.
    pub(crate) bases: Vec<PathBuf>,
    /// Every file and folder name in the repository (not under `target/` or
    /// `.git/`).
    pub(crate) file_names: BTreeSet<String>,
    /// The names at the top of the repository and of a crate's folder (`src`,
    /// `tests`, `crates`, `docs`...): a path with a `/` starts with one.
    pub(crate) top_names: BTreeSet<String>,
}

pub(crate) fn repo() -> Repo {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let manifest = fs::read_to_string(root.join("Cargo.toml")).expect("root Cargo.toml");
    let mut packages = BTreeMap::new();
    let (root_package, root_targets) = package(&root, &manifest);
    let root_package = root_package.expect("the root Cargo.toml has a [package]");
    packages.insert(root_package.clone(), root_targets);
    let mut bases = vec![root.clone()];
    for member in members(&manifest) {
        let dir = root.join(&member);
        let text = fs::read_to_string(dir.join("Cargo.toml"))
            .unwrap_or_else(|e| panic!("{member}/Cargo.toml: {e}"));
        let (name, targets) = package(&dir, &text);
        packages.insert(name.unwrap_or_else(|| panic!("{member}: no name")), targets);
    }
    // Crate folders, members or not (fuzz/ and peers/ are workspaces of their
    // own), are where the pages' source paths start.
    let mut crates: Vec<PathBuf> = fs::read_dir(root.join("crates"))
        .expect("crates/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    crates.sort();
    crates.push(root.join("fuzz"));
    crates.push(root.join("peers"));
    for dir in crates {
        for sub in ["", "src", "tests", "examples"] {
            bases.push(if sub.is_empty() {
                dir.clone()
            } else {
                dir.join(sub)
            });
        }
    }
    let mut file_names = BTreeSet::new();
    walk(&root, &mut |p| {
        for name in p
            .strip_prefix(&root)
            .unwrap_or(p)
            .iter()
            .filter_map(|n| n.to_str())
        {
            file_names.insert(name.to_string());
        }
    });
    let mut top_names: BTreeSet<String> = [".."].iter().map(|s| s.to_string()).collect();
    for base in &bases {
        for entry in fs::read_dir(base).into_iter().flatten().flatten() {
            top_names.insert(entry.file_name().to_string_lossy().into_owned());
        }
    }
    for prefix in EXEMPT_PREFIXES {
        top_names.insert(prefix.split('/').next().unwrap_or("").to_string());
    }
    Repo {
        root,
        root_package,
        packages,
        bases,
        file_names,
        top_names,
    }
}

/// Calls `f` on every file under `dir`, skipping build output and VCS data.
pub(crate) fn walk(dir: &Path, f: &mut dyn FnMut(&Path)) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            if name != "target" && name != ".git" && name != "bench-out" {
                walk(&path, f);
            }
        } else {
            f(&path);
        }
    }
}

/// The workspace's `members` of a root manifest.
pub(crate) fn members(manifest: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with("members") && line.contains('[') {
            inside = true;
        }
        if inside {
            out.extend(quoted(line));
            if line.contains(']') {
                break;
            }
        }
    }
    out
}

/// Every double-quoted string of a line.
pub(crate) fn quoted(line: &str) -> Vec<String> {
    line.split('"')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

/// A package's name and targets, from its manifest and its folders (cargo's
/// automatic targets plus the manifest's `[[bin]]`, `[[example]]` and
/// `[[test]]` sections).
pub(crate) fn package(dir: &Path, manifest: &str) -> (Option<String>, Package) {
    let mut name = None;
    let mut targets = Package::default();
    let mut section = String::new();
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            section = line.to_string();
            continue;
        }
        if section == "[package]"
            && let Some(run) = line
                .strip_prefix("default-run")
                .map(str::trim_start)
                .and_then(|l| l.strip_prefix('='))
                .and_then(|l| quoted(l).into_iter().next())
        {
            targets.default_run = Some(run);
            continue;
        }
        let Some(value) = line
            .strip_prefix("name")
            .map(str::trim_start)
            .and_then(|l| l.strip_prefix('='))
            .and_then(|l| quoted(l).into_iter().next())
        else {
            continue;
        };
        match section.as_str() {
            "[package]" => name = Some(value),
            "[[bin]]" => {
                targets.bins.insert(value);
            }
            "[[example]]" => {
                targets.examples.insert(value);
            }
            "[[test]]" => {
                targets.tests.insert(value);
            }
            _ => {}
        }
    }
    // src/main.rs is the package's own binary, unless a [[bin]] section
    // already names it (the root package's binary is `hider`).
    let main_named = manifest.contains("path = \"src/main.rs\"");
    if let Some(name) = &name
        && dir.join("src/main.rs").is_file()
        && !main_named
    {
        targets.bins.insert(name.clone());
    }
    for (sub, set) in [
        ("src/bin", &mut targets.bins),
        ("examples", &mut targets.examples),
        ("tests", &mut targets.tests),
    ] {
        let Ok(entries) = fs::read_dir(dir.join(sub)) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
            if path.extension().is_some_and(|e| e == "rs")
                || (path.is_dir() && path.join("main.rs").is_file())
            {
                set.insert(stem.to_string());
            }
        }
    }
    (name, targets)
}
