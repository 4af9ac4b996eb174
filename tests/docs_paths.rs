//! Every path and command that `README.md` and the pages under `docs/` name
//! exists.
//!
//! - Paths: the text of every inline code span (and every word of a code
//!   block) that is one token looking like a path, and every markdown link
//!   or image target that is not a URL. A token looks like a path when it
//!   ends in `.rs`, `.md`, `.toml`, `.obj`, `.mtl`, `.png`, `.svg`, `.py` or
//!   `.sh`, or when it has a `/` and either ends with `/` or starts with a
//!   name at the top of the repository (`crates/hider`, `src/tiled`), so that
//!   prose such as `z/w` or `OBJ/MTL` is not taken for a path. Names with a
//!   placeholder in capitals (`OUT/report.md`, `NAME.ids.png`) are patterns,
//!   not paths, and are skipped. A path with a
//!   `/` must exist from the repository root, or from a crate's folder
//!   (`crates/NAME/`, its `src/`, `tests/` or `examples/`: the algorithm
//!   pages name their own sources that way, as in `simd/coverage.rs`); a
//!   bare file name (`raster.rs`) must be some file of the repository;
//!   `../shared/...` is looked up beside the repository; a link is resolved
//!   from the page that holds it, as a markdown viewer does.
//! - Commands: every `cargo run`, `cargo build` and `cargo test` names
//!   workspace packages (`-p`), and the `--bin`, `--example` and `--test`
//!   targets it names exist in that package (the root package when there is
//!   no `-p`); `--manifest-path` files exist; a built binary named as
//!   `target/release/NAME` or `target/release/examples/NAME` is a binary or
//!   an example of some package.
//!
//! `docs/notes/` is skipped: its files are dated records of past runs, kept
//! verbatim, and name the examples, files and commands of their day (many
//! of them since renamed or removed). The generated `docs/report.md` is
//! checked like any page.
//!
//! A failure lists every bad reference as `file:line: what`.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Extensions that make a token a path even without a `/`.
const EXTENSIONS: &[&str] = &[
    ".rs", ".md", ".toml", ".obj", ".mtl", ".png", ".svg", ".py", ".sh",
];

/// Paths that are never checked: made by running something, or not in the
/// repository.
const EXEMPT_PREFIXES: &[&str] = &[
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
const CAPITAL_NAMES: &[&str] = &["README", "LICENSE", "CHANGELOG", "CONTRIBUTING"];

/// Single tokens that look like paths and are not repository files: each is
/// explained. Keep this list small.
const ALLOWED: &[&str] = &[
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
const OUTPUT_FLAGS: &[&str] = &[
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
struct Package {
    bins: BTreeSet<String>,
    examples: BTreeSet<String>,
    tests: BTreeSet<String>,
    /// The manifest's `default-run`: which binary a plain `cargo run`
    /// runs when the package has several.
    default_run: Option<String>,
}

/// What the checks compare against.
struct Repo {
    root: PathBuf,
    /// The name of the root package.
    root_package: String,
    packages: BTreeMap<String, Package>,
    /// Folders a path with a `/` may start from.
    bases: Vec<PathBuf>,
    /// Every file and folder name in the repository (not under `target/` or
    /// `.git/`).
    file_names: BTreeSet<String>,
    /// The names at the top of the repository and of a crate's folder (`src`,
    /// `tests`, `crates`, `docs`...): a path with a `/` starts with one.
    top_names: BTreeSet<String>,
}

fn repo() -> Repo {
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
fn walk(dir: &Path, f: &mut dyn FnMut(&Path)) {
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
fn members(manifest: &str) -> Vec<String> {
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
fn quoted(line: &str) -> Vec<String> {
    line.split('"')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

/// A package's name and targets, from its manifest and its folders (cargo's
/// automatic targets plus the manifest's `[[bin]]`, `[[example]]` and
/// `[[test]]` sections).
fn package(dir: &Path, manifest: &str) -> (Option<String>, Package) {
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

impl Repo {
    /// Whether a token looks like a repository path (see the top of the file).
    fn looks_like_path(&self, token: &str) -> bool {
        if token.is_empty()
            || !token
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "_.-/".contains(c))
        {
            return false;
        }
        let placeholder = token.split(['/', '.', '-', '_']).any(|w| {
            w.len() >= 2 && w.chars().all(|c| c.is_ascii_uppercase()) && !CAPITAL_NAMES.contains(&w)
        });
        if placeholder {
            return false;
        }
        if EXTENSIONS
            .iter()
            .any(|e| token.ends_with(e) && token.len() > e.len())
        {
            return true;
        }
        let first = token.split('/').next().unwrap_or("");
        token.contains('/')
            && token
                .split('/')
                .any(|s| s.chars().any(|c| c.is_ascii_alphabetic()))
            && (token.ends_with('/') || self.top_names.contains(first))
    }

    /// `None` when the path exists, else what is wrong.
    fn check_path(&self, page: &Path, token: &str, link: bool) -> Option<String> {
        let token = token.split('#').next().unwrap_or("");
        if token.is_empty()
            || token.contains("://")
            || token.starts_with("mailto:")
            || token.starts_with('/')
            || token.starts_with('~')
            || ALLOWED.contains(&token)
            || EXEMPT_PREFIXES.iter().any(|p| token.starts_with(p))
        {
            return None;
        }
        if link {
            let base = page.parent().unwrap_or(&self.root);
            return (!base.join(token).exists()).then(|| format!("link to missing `{token}`"));
        }
        if let Some(rest) = token.strip_prefix("../shared/") {
            // The shared folder beside the repository (CI provides it).
            let shared = self.root.join("../shared");
            return (shared.is_dir() && !shared.join(rest).exists())
                .then(|| format!("missing `{token}` (beside the repository)"));
        }
        let trimmed = token.trim_end_matches('/');
        let found = if token.contains('/') {
            self.bases.iter().any(|b| b.join(trimmed).exists())
        } else {
            self.file_names.contains(trimmed) || self.root.join(trimmed).exists()
        };
        (!found).then(|| format!("missing path `{token}`"))
    }

    /// Every problem with one `cargo` command line (already joined).
    fn check_command(&self, command: &str) -> Vec<String> {
        let mut problems = Vec::new();
        let tokens: Vec<&str> = command
            .split('#')
            .next()
            .unwrap_or("")
            .split_whitespace()
            .collect();
        let Some(start) = tokens.iter().position(|t| *t == "cargo") else {
            return problems;
        };
        let tokens = &tokens[start + 1..];
        let Some(sub) = tokens.first() else {
            return problems;
        };
        if !["run", "build", "test", "bench", "rustc", "check"].contains(sub) {
            return problems;
        }
        let mut packages = Vec::new();
        let mut wanted: Vec<(&str, String)> = Vec::new();
        let mut manifest = None;
        let mut workspace = false;
        let mut i = 1;
        let mut program_args = &tokens[tokens.len()..];
        while i < tokens.len() {
            let t = tokens[i];
            let value = tokens.get(i + 1).map(|v| v.trim_matches(['[', ']']));
            match t {
                "--" => {
                    program_args = &tokens[i + 1..];
                    break;
                }
                "-p" | "--package" => packages.extend(value.map(str::to_string)),
                "--bin" | "--example" | "--test" => {
                    if let Some(v) = value {
                        wanted.push((t, v.to_string()));
                    }
                }
                "--manifest-path" => manifest = value,
                "--workspace" | "--all" => workspace = true,
                _ => {
                    if let Some(v) = t.strip_prefix("--package=").or(t.strip_prefix("-p=")) {
                        packages.push(v.to_string());
                    }
                    i += 1;
                    continue;
                }
            }
            i += 2;
        }
        if let Some(m) = manifest {
            if !self.root.join(m).is_file() {
                problems.push(format!("`--manifest-path {m}`: no such file"));
            }
            // Another workspace (peers/, fuzz/): its targets are its own.
            return problems;
        }
        for p in &packages {
            if !self.packages.contains_key(p) {
                problems.push(format!("`-p {p}`: no such workspace package"));
            }
        }
        if !workspace {
            let in_packages: Vec<&str> = if packages.is_empty() {
                vec![self.root_package.as_str()]
            } else {
                packages.iter().map(String::as_str).collect()
            };
            // A plain `cargo run` must know which binary: one, or the
            // package's default-run (the README's main command broke when
            // the timing programs joined the benchmark's package).
            let target_named = wanted
                .iter()
                .any(|(f, _)| *f == "--bin" || *f == "--example");
            if *sub == "run" && !target_named {
                for p in &in_packages {
                    if let Some(pkg) = self.packages.get(*p)
                        && pkg.bins.len() > 1
                        && pkg.default_run.is_none()
                    {
                        problems.push(format!(
                            "`cargo run -p {p}`: {p} has {} binaries and no default-run",
                            pkg.bins.len()
                        ));
                    }
                }
            }
            for (flag, name) in &wanted {
                let exists = in_packages.iter().any(|p| {
                    self.packages.get(*p).is_some_and(|pkg| match *flag {
                        "--bin" => pkg.bins.contains(name),
                        "--example" => pkg.examples.contains(name),
                        _ => pkg.tests.contains(name),
                    })
                });
                if !exists {
                    problems.push(format!(
                        "`{flag} {name}`: not a target of {}",
                        in_packages.join(", ")
                    ));
                }
            }
        }
        // The program's own arguments: input paths must exist, built
        // binaries must be targets; outputs are not checked.
        let mut previous = "";
        for arg in program_args {
            if !OUTPUT_FLAGS.contains(&previous) {
                if let Some(p) = self.check_built(arg) {
                    problems.push(p);
                } else if self.looks_like_path(arg)
                    && let Some(p) = self.check_path(&self.root, arg, false)
                {
                    problems.push(p);
                }
            }
            previous = arg;
        }
        problems
    }

    /// A built binary `target/release/NAME` or `target/release/examples/NAME`
    /// (also under `target/debug/`) must be a target of some package.
    fn check_built(&self, token: &str) -> Option<String> {
        let rest = token
            .strip_prefix("target/release/")
            .or_else(|| token.strip_prefix("target/debug/"))?;
        let (examples, name) = match rest.strip_prefix("examples/") {
            Some(name) => (true, name),
            None => (false, rest),
        };
        if name.is_empty() || name.contains('/') || name.contains('.') {
            return None;
        }
        let exists = self.packages.values().any(|p| {
            if examples {
                p.examples.contains(name)
            } else {
                p.bins.contains(name)
            }
        });
        (!exists).then(|| format!("`{token}`: no package builds that binary"))
    }

    /// Every problem of one markdown text, as `file:line: what`.
    fn check_markdown(&self, page: &Path, text: &str) -> Vec<String> {
        let shown = page
            .strip_prefix(&self.root)
            .unwrap_or(page)
            .display()
            .to_string();
        let mut problems = Vec::new();
        let mut report =
            |line: usize, what: String| problems.push(format!("{shown}:{line}: {what}"));
        let lines: Vec<&str> = text.lines().collect();
        // Prose (outside code fences) is gathered into paragraphs, so that an
        // inline code span or a link broken over two lines is seen whole;
        // each paragraph remembers the line each of its characters came from.
        let mut paragraph = String::new();
        let mut origin: Vec<usize> = Vec::new();
        let mut fence: Option<&str> = None;
        let mut i = 0;
        while i < lines.len() {
            let line = lines[i];
            let trimmed = line.trim_start();
            if let Some(marker) = fence {
                if trimmed.starts_with(marker) {
                    fence = None;
                    i += 1;
                    continue;
                }
                // A code block: whole commands (with `\` continuations), and
                // every path-like word of a line that is not a command.
                let number = i + 1;
                let mut joined = line.to_string();
                while joined.trim_end().ends_with('\\') && i + 1 < lines.len() {
                    joined = format!(
                        "{} {}",
                        joined.trim_end().trim_end_matches('\\'),
                        lines[i + 1]
                    );
                    i += 1;
                }
                if joined.contains("cargo ") {
                    for p in self.check_command(&joined) {
                        report(number, p);
                    }
                    // Paths before `cargo` (none) and after `--` are handled
                    // there.
                } else if !joined.trim_start().starts_with("//") {
                    let words: Vec<&str> = joined
                        .split('#')
                        .next()
                        .unwrap_or("")
                        .split_whitespace()
                        .collect();
                    let mut previous = "";
                    for word in words {
                        let word = word.trim_matches(|c: char| "`'\",;()[]".contains(c));
                        if !OUTPUT_FLAGS.contains(&previous) && self.looks_like_path(word) {
                            if let Some(p) = self.check_built(word) {
                                report(number, p);
                            } else if let Some(p) = self.check_path(page, word, false) {
                                report(number, p);
                            }
                        }
                        previous = word;
                    }
                }
                i += 1;
                continue;
            }
            if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
                self.check_prose(page, &paragraph, &origin, &mut report);
                paragraph.clear();
                origin.clear();
                fence = Some(if trimmed.starts_with("```") {
                    "```"
                } else {
                    "~~~"
                });
                i += 1;
                continue;
            }
            if trimmed.is_empty() {
                self.check_prose(page, &paragraph, &origin, &mut report);
                paragraph.clear();
                origin.clear();
            } else {
                for c in line.chars().chain(std::iter::once(' ')) {
                    paragraph.push(c);
                    origin.push(i + 1);
                }
            }
            i += 1;
        }
        self.check_prose(page, &paragraph, &origin, &mut report);
        problems
    }

    /// Inline code spans and link targets of one paragraph.
    fn check_prose(
        &self,
        page: &Path,
        paragraph: &str,
        origin: &[usize],
        report: &mut dyn FnMut(usize, String),
    ) {
        let chars: Vec<char> = paragraph.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            if chars[i] == '`' {
                let run = chars[i..].iter().take_while(|c| **c == '`').count();
                let start = i + run;
                let mut j = start;
                let mut end = None;
                while j < chars.len() {
                    if chars[j] == '`' {
                        let r = chars[j..].iter().take_while(|c| **c == '`').count();
                        if r == run {
                            end = Some(j);
                            break;
                        }
                        j += r;
                    } else {
                        j += 1;
                    }
                }
                let Some(end) = end else {
                    i = start;
                    continue;
                };
                let span: String = chars[start..end].iter().collect();
                let span = span.trim();
                let line = origin[i];
                if span.starts_with("cargo ") || span.contains(" cargo ") {
                    for p in self.check_command(span) {
                        report(line, p);
                    }
                } else if self.looks_like_path(span) {
                    if let Some(p) = self.check_built(span) {
                        report(line, p);
                    } else if let Some(p) = self.check_path(page, span, false) {
                        report(line, p);
                    }
                }
                i = end + run;
                continue;
            }
            if chars[i] == ']' && chars.get(i + 1) == Some(&'(') {
                if let Some(len) = chars[i + 2..].iter().position(|c| *c == ')') {
                    let target: String = chars[i + 2..i + 2 + len].iter().collect();
                    let target = target.split_whitespace().next().unwrap_or("");
                    if let Some(p) = self.check_path(page, target, true) {
                        report(origin[i], p);
                    }
                    i += 2 + len;
                    continue;
                }
            }
            i += 1;
        }
    }
}

/// `README.md` and every page under `docs/` but `docs/notes/`.
fn pages(root: &Path) -> Vec<PathBuf> {
    let mut out = vec![root.join("README.md")];
    walk(&root.join("docs"), &mut |p| {
        if p.extension().is_some_and(|e| e == "md") && !p.starts_with(root.join("docs/notes")) {
            out.push(p.to_path_buf());
        }
    });
    out.sort();
    out
}

#[test]
fn every_path_and_command_in_the_docs_exists() {
    let repo = repo();
    let mut problems = Vec::new();
    for page in pages(&repo.root) {
        let text = fs::read_to_string(&page).unwrap_or_else(|e| panic!("{}: {e}", page.display()));
        problems.extend(repo.check_markdown(&page, &text));
    }
    assert!(
        problems.is_empty(),
        "{} bad reference(s) in README.md and docs/:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

/// The checker itself: wrong paths and targets are caught, with their lines,
/// and right ones pass.
#[test]
fn the_checker_catches_wrong_references() {
    let repo = repo();
    let page = repo.root.join("docs/sample.md");
    let good = "See `crates/zbuffer/Cargo.toml`, [conventions](conventions.md) and\n\
                `cargo test -p hider-zbuffer`; outputs go to `bench-out/`; `z/w`,\n\
                `OBJ/MTL` and `OUT/report.md` are not paths; `src/tiled/` is.\n\n\
                ```sh\ncargo run --release -- render assets/cube.obj -o new.png\n```\n";
    assert_eq!(repo.check_markdown(&page, good), Vec::<String>::new());
    let bad = "A wrong path `crates/zbuffer/tests/no_such_test.rs` and a\n\
               wrong [link](no-such-page.md).\n\n\
               ```sh\ncargo run --release -p hider-nothing\n\
               cargo run --release -p hider-zbuffer --example \\\n    no_such_example -- assets/no_such.obj\n\
               cargo test -p hider-zbuffer --test no_such_test\n```\n\
               A span broken over lines: `cargo run -p hider-zbuffer --bin\nno_such_bin`.\n\
               Folders: `crates/no_such_crate` and `src/no_such_module/`.\n";
    let found = repo.check_markdown(&page, bad);
    let expected = [
        "docs/sample.md:1: missing path `crates/zbuffer/tests/no_such_test.rs`",
        "docs/sample.md:2: link to missing `no-such-page.md`",
        "docs/sample.md:5: `-p hider-nothing`: no such workspace package",
        "docs/sample.md:6: `--example no_such_example`: not a target of hider-zbuffer",
        "docs/sample.md:6: missing path `assets/no_such.obj`",
        "docs/sample.md:8: `--test no_such_test`: not a target of hider-zbuffer",
        "docs/sample.md:10: `--bin no_such_bin`: not a target of hider-zbuffer",
        "docs/sample.md:12: missing path `crates/no_such_crate`",
        "docs/sample.md:12: missing path `src/no_such_module/`",
    ];
    assert_eq!(found, expected);
}
