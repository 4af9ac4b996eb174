//! The checks of one reference: a path, a cargo command, a built binary,
//! and the walk over a page's markdown and prose that finds them.

use std::path::Path;

use crate::repo::*;

impl Repo {
    /// Whether a token looks like a repository path (see the top of the file).
    pub(crate) fn looks_like_path(&self, token: &str) -> bool {
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
    pub(crate) fn check_path(&self, page: &Path, token: &str, link: bool) -> Option<String> {
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
    pub(crate) fn check_command(&self, command: &str) -> Vec<String> {
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
    pub(crate) fn check_built(&self, token: &str) -> Option<String> {
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
    pub(crate) fn check_markdown(&self, page: &Path, text: &str) -> Vec<String> {
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
    pub(crate) fn check_prose(
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
            if chars[i] == ']'
                && chars.get(i + 1) == Some(&'(')
                && let Some(len) = chars[i + 2..].iter().position(|c| *c == ')')
            {
                let target: String = chars[i + 2..i + 2 + len].iter().collect();
                let target = target.split_whitespace().next().unwrap_or("");
                if let Some(p) = self.check_path(page, target, true) {
                    report(origin[i], p);
                }
                i += 2 + len;
                continue;
            }
            i += 1;
        }
    }
}
