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

mod checks;
mod repo;

use std::fs;
use std::path::{Path, PathBuf};

use repo::{repo, walk};

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
