//! The outputs people read: the terminal table, the plots and the Markdown
//! report (`docs/report.md`), all generated from [`Results`] alone, so a
//! merged set of shards gives the same report as one run.
//!
//! One file per part: [`terminal_table`] and [`exponent_table`] for the
//! terminal, [`write_plots`] for the figures, and [`markdown`], which
//! assembles the report from its sections (header, summary per hider,
//! tables per scene, scaling, contact sheets and problems).

mod answer;
mod conclusions;
mod figures;
mod format;
mod markdown;
mod noise;
mod options;
mod rows;
mod scaling_tables;
mod scene_tables;
mod summary;
mod terminal;

use std::path::Path;

use anyhow::Result;

use crate::record::{Results, write_text_atomic};

pub use figures::write_plots;
pub use markdown::markdown;
pub use options::ReportOptions;
pub use rows::{hider_order, kind_label};
pub use terminal::{exponent_table, terminal_table};

/// The report's conclusions, one sentence each, every number from
/// `results` (what the terminal prints after its table).
pub fn conclusions(results: &Results) -> Vec<String> {
    let rows = &results.rows;
    conclusions::sentences(rows, &hider_order(rows))
}

/// The interpretation page, written beside every report it is not
/// already beside, so that the report's folder reads on its own.
const INTERPRETATION: &str = include_str!("../../../../docs/bench.md");

/// Writes the plots into `image_dir`, the interpretation page `bench.md`
/// beside the report (unless the folder already holds one) and the report
/// to `report_path`.
pub fn write_report(
    results: &Results,
    report_path: &Path,
    image_dir: &Path,
    command: &str,
) -> Result<()> {
    write_plots(results, image_dir)?;
    let report_dir = report_path.parent().unwrap_or(Path::new(""));
    let interpretation = report_dir.join("bench.md");
    if !interpretation.is_file() || is_generated_copy(&interpretation) {
        write_text_atomic(&interpretation, &copy_note(INTERPRETATION))?;
    }
    let prefix = match image_dir.strip_prefix(report_dir) {
        Ok(rel) if rel.as_os_str().is_empty() => String::new(),
        Ok(rel) => format!("{}/", rel.display()),
        Err(_) => format!("{}/", image_dir.display()),
    };
    let md = markdown(
        results,
        &ReportOptions {
            image_prefix: prefix,
            image_dir: image_dir.to_path_buf(),
            command: command.to_owned(),
            report_dir: report_dir.to_path_buf(),
        },
    );
    write_text_atomic(report_path, &md)
}

/// The first line of a copy of the interpretation page: a page that
/// starts with it was written here and may be replaced by a newer copy;
/// any other `bench.md` (the docs folder's own) is left alone.
const COPY_MARK: &str =
    "<!-- copied by hider-bench beside the report; the source is docs/bench.md -->";

fn copy_note(page: &str) -> String {
    format!("{COPY_MARK}\n{page}")
}

fn is_generated_copy(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| t.starts_with(COPY_MARK))
}
