//! The results: one [`Row`] per (case, hider) run, and their files,
//! `results.csv` (written row by row as runs finish, so an interrupted
//! sweep keeps what it measured) and `results.json` (with the machine
//! descriptions). The schema is documented in `docs/bench.md`; the columns
//! of the CSV are exactly the fields of [`Row`], in [`COLUMNS`] order.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{Context, Result, bail};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::machine::Machine;

/// Version of the result schema, stored in `results.json`.
pub const SCHEMA_VERSION: u32 = 3;

/// One run: one hider on one scene at one resolution.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Position of the case in the full matrix (shards keep it, so merged
    /// results sort back into matrix order).
    pub case: u32,
    /// Study: `accuracy`, `polygons`, `resolution`, `depth-complexity`.
    pub study: String,
    /// Scene name.
    pub scene: String,
    /// Scene group: `asset`, `hard-case`, `obj`, `scaling`.
    pub group: String,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Screen triangles after clipping.
    pub triangles: u64,
    /// Pixel centres covered by some triangle.
    pub covered_pixels: u64,
    /// Mean number of surfaces over a covered pixel centre.
    pub depth_complexity: f64,
    /// Registry name of the hider (with its options).
    pub hider: String,
    /// Registry kind: `ExactPixelCentre`, `ApproximatePixelCentre`,
    /// `MultiSample`, `Reference`.
    pub kind: String,
    /// `ok`, `error: MESSAGE` (the hider refused, e.g. a budget), or
    /// `skipped: REASON`.
    pub status: String,
    /// The effects the scene calls for that this hider does not simulate,
    /// joined by `;` (`transparency`: it draws translucent surfaces
    /// opaque); empty when it simulates them all. A run with an ignored
    /// effect is not exact for its scene, whatever its ids score.
    pub ignored_effects: String,
    /// Building or loading the scene, milliseconds (once per case).
    pub load_ms: f64,
    /// The shared front end `prepare()`, median milliseconds (once per case).
    pub prepare_ms: f64,
    /// Render time, median of the measured runs, milliseconds (in the
    /// real-size study the whole pipeline from the world-space scene: the
    /// front end too).
    pub render_ms: f64,
    /// Fastest measured run, milliseconds.
    pub render_min_ms: f64,
    /// Slowest measured run, milliseconds.
    pub render_max_ms: f64,
    /// Unmeasured warm-up runs.
    pub warmup: u32,
    /// Measured runs.
    pub runs: u32,
    /// Threads available to the hider.
    pub threads: u32,
    /// CPU model of the machine.
    pub cpu: String,
    /// `scored` (against the oracle or analytic coverage), `reference` (the
    /// oracle itself), or `skipped: REASON` (the oracle would be too slow).
    pub accuracy: String,
    /// Pixels covered in the hider's frame and not in the oracle's, or the
    /// reverse.
    pub coverage_mismatches: Option<u64>,
    /// Covered non-tie pixels whose id differs from the oracle's.
    pub wrong_ids: Option<u64>,
    /// `wrong_ids` over the covered non-tie pixels.
    pub wrong_fraction: Option<f64>,
    /// Covered pixels whose two nearest surfaces are within the tie
    /// tolerance (any id accepted).
    pub ties: Option<u64>,
    /// Ties where the hider chose another surface than the oracle.
    pub tie_differences: Option<u64>,
    /// Mean absolute window-depth difference to the oracle over pixels
    /// covered in both.
    pub depth_error_mean: Option<f64>,
    /// Largest absolute window-depth difference to the oracle.
    pub depth_error_max: Option<f64>,
    /// Depth-precision study: pixels showing the farther of the two
    /// surfaces.
    pub farther_pixels: Option<u64>,
    /// Multi-sample hiders: mean absolute difference between
    /// `Frame::coverage` and the analytic coverage, over all pixels.
    pub coverage_error: Option<f64>,
    /// Peak working memory the hider reported (`StatsTable::peak_bytes`).
    pub peak_bytes: u64,
    /// The hider's work counters, `name=value` joined by `;`.
    pub counters: String,
}

/// The CSV columns, in order: every field of [`Row`].
pub const COLUMNS: [&str; 34] = [
    "case",
    "study",
    "scene",
    "group",
    "width",
    "height",
    "triangles",
    "covered_pixels",
    "depth_complexity",
    "hider",
    "kind",
    "status",
    "ignored_effects",
    "load_ms",
    "prepare_ms",
    "render_ms",
    "render_min_ms",
    "render_max_ms",
    "warmup",
    "runs",
    "threads",
    "cpu",
    "accuracy",
    "coverage_mismatches",
    "wrong_ids",
    "wrong_fraction",
    "ties",
    "tie_differences",
    "depth_error_mean",
    "depth_error_max",
    "farther_pixels",
    "coverage_error",
    "peak_bytes",
    "counters",
];

/// Columns holding text (the others hold numbers or are empty).
const TEXT_COLUMNS: [&str; 10] = [
    "study",
    "scene",
    "group",
    "hider",
    "kind",
    "status",
    "ignored_effects",
    "cpu",
    "accuracy",
    "counters",
];

impl Row {
    /// Whether the run finished.
    pub fn is_ok(&self) -> bool {
        self.status == "ok"
    }

    /// Whether the hider simulates every effect the scene calls for (see
    /// [`Self::ignored_effects`]).
    pub fn simulates_all_effects(&self) -> bool {
        self.ignored_effects.is_empty()
    }

    /// The one error number the plots put against time: for multi-sample
    /// hiders the coverage error; for the others the wrong pixels
    /// (non-tie wrong ids plus coverage mismatches) over the covered pixels.
    /// `None` when not scored.
    pub fn error(&self) -> Option<f64> {
        if self.kind == "MultiSample" {
            return self.coverage_error;
        }
        let wrong = self.wrong_ids? + self.coverage_mismatches?;
        Some(wrong as f64 / self.covered_pixels.max(1) as f64)
    }

    /// The row's CSV fields, in [`COLUMNS`] order.
    pub fn csv_fields(&self) -> Vec<String> {
        let Ok(Value::Object(map)) = serde_json::to_value(self) else {
            unreachable!("a Row always serialises to an object");
        };
        COLUMNS
            .iter()
            .map(|c| match map.get(*c) {
                None | Some(Value::Null) => String::new(),
                Some(Value::String(s)) => s.clone(),
                Some(v) => v.to_string(),
            })
            .collect()
    }

    /// A row from CSV fields in [`COLUMNS`] order.
    pub fn from_csv_fields(fields: &[String]) -> Result<Row> {
        if fields.len() != COLUMNS.len() {
            bail!("expected {} fields, found {}", COLUMNS.len(), fields.len());
        }
        let mut map = Map::new();
        for (c, f) in COLUMNS.iter().zip(fields) {
            let v = if TEXT_COLUMNS.contains(c) {
                Value::String(f.clone())
            } else if f.is_empty() {
                Value::Null
            } else {
                serde_json::from_str(f)
                    .with_context(|| format!("column {c}: '{f}' is not a number"))?
            };
            map.insert((*c).to_owned(), v);
        }
        Ok(serde_json::from_value(Value::Object(map))?)
    }
}

/// Quotes a CSV field when it holds a comma, quote or line break.
fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

/// One CSV line (with its line break) for `row`.
pub fn csv_line(row: &Row) -> String {
    let fields: Vec<String> = row.csv_fields().iter().map(|f| quote(f)).collect();
    format!("{}\n", fields.join(","))
}

/// The CSV header line.
pub fn csv_header() -> String {
    format!("{}\n", COLUMNS.join(","))
}

/// Parses CSV text written by [`csv_line`] (RFC 4180 quoting) into rows,
/// checking the header.
pub fn parse_csv(text: &str) -> Result<Vec<Row>> {
    let records = split_records(text)?;
    let Some((header, body)) = records.split_first() else {
        bail!("empty CSV");
    };
    if header.iter().map(String::as_str).ne(COLUMNS) {
        bail!("CSV header does not match the schema: {}", header.join(","));
    }
    body.iter()
        .enumerate()
        .map(|(k, r)| Row::from_csv_fields(r).with_context(|| format!("CSV record {}", k + 2)))
        .collect()
}

fn split_records(text: &str) -> Result<Vec<Vec<String>>> {
    let mut records = Vec::new();
    let mut record = Vec::new();
    let mut field = String::new();
    let mut chars = text.chars().peekable();
    let mut in_quotes = false;
    let mut any = false;
    while let Some(c) = chars.next() {
        any = true;
        match (in_quotes, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => in_quotes = false,
            (true, c) => field.push(c),
            (false, '"') => in_quotes = true,
            (false, ',') => record.push(std::mem::take(&mut field)),
            (false, '\r') => {}
            (false, '\n') => {
                record.push(std::mem::take(&mut field));
                records.push(std::mem::take(&mut record));
                any = false;
            }
            (false, c) => field.push(c),
        }
    }
    if in_quotes {
        bail!("unterminated quoted CSV field");
    }
    if any {
        record.push(field);
        records.push(record);
    }
    Ok(records)
}

/// `results.csv` being written while the sweep runs: the header first,
/// then each row as soon as it is finished, flushed, so that Ctrl-C (or a
/// crash) leaves every finished row on disk.
pub struct CsvSink {
    out: BufWriter<File>,
}

impl CsvSink {
    /// Creates (truncates) `path` and writes the header.
    pub fn create(path: &Path) -> Result<Self> {
        let file = File::create(path).with_context(|| format!("creating {}", path.display()))?;
        let mut out = BufWriter::new(file);
        out.write_all(csv_header().as_bytes())?;
        out.flush()?;
        Ok(Self { out })
    }

    /// Appends one row and flushes it to the file.
    pub fn push(&mut self, row: &Row) -> Result<()> {
        self.out.write_all(csv_line(row).as_bytes())?;
        self.out.flush()?;
        Ok(())
    }
}

/// The contents of `results.json`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// [`SCHEMA_VERSION`].
    pub schema: u32,
    /// The machines the rows were measured on (one per shard machine).
    pub machines: Vec<Machine>,
    /// The command lines that produced the rows.
    pub commands: Vec<String>,
    /// Whether every selected job ran (false after Ctrl-C).
    pub complete: bool,
    /// The rows, in matrix order.
    pub rows: Vec<Row>,
}

impl Results {
    /// Sorts rows into matrix order (case, then registry order as given by
    /// `hider_rank`), keeping equal rows' order.
    pub fn sort(&mut self, hider_rank: impl Fn(&str) -> usize) {
        self.rows
            .sort_by_key(|r| (r.case, r.study.clone(), hider_rank(&r.hider)));
    }
}

/// Writes `text` to `path` atomically (temporary file, then rename).
pub fn write_text_atomic(path: &Path, text: &str) -> Result<()> {
    hider_scene::atomic::write_atomic(path, |w| {
        w.write_all(text.as_bytes())
            .map_err(|source| hider_scene::Error::Io {
                path: path.to_path_buf(),
                source,
            })
    })
    .with_context(|| format!("writing {}", path.display()))
}

/// Writes `results.csv` and `results.json` into `dir`, atomically.
pub fn write_results(dir: &Path, results: &Results) -> Result<()> {
    let mut csv = csv_header();
    for row in &results.rows {
        csv.push_str(&csv_line(row));
    }
    write_text_atomic(&dir.join("results.csv"), &csv)?;
    let json = serde_json::to_string_pretty(results)?;
    write_text_atomic(&dir.join("results.json"), &json)
}

/// Reads the results of a run directory: `results.json`, or, for a run cut
/// short before it was written, the rows of `results.csv`.
pub fn read_results(dir: &Path) -> Result<Results> {
    let json = dir.join("results.json");
    if json.is_file() {
        let text = std::fs::read_to_string(&json)
            .with_context(|| format!("reading {}", json.display()))?;
        let r: Results =
            serde_json::from_str(&text).with_context(|| format!("parsing {}", json.display()))?;
        if r.schema != SCHEMA_VERSION {
            bail!(
                "{}: schema {} (this build reads {SCHEMA_VERSION})",
                json.display(),
                r.schema
            );
        }
        return Ok(r);
    }
    let csv = dir.join("results.csv");
    let text = std::fs::read_to_string(&csv)
        .with_context(|| format!("reading {} (no results.json either)", csv.display()))?;
    Ok(Results {
        schema: SCHEMA_VERSION,
        rows: parse_csv(&text).with_context(|| format!("parsing {}", csv.display()))?,
        ..Results::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn sample_row() -> Row {
        Row {
            case: 3,
            study: "accuracy".into(),
            scene: "odd, \"name\"".into(),
            group: "obj".into(),
            width: 64,
            height: 48,
            triangles: 12,
            covered_pixels: 900,
            depth_complexity: 1.75,
            hider: "zbuffer".into(),
            kind: "ExactPixelCentre".into(),
            status: "ok".into(),
            render_ms: 0.125,
            wrong_ids: Some(2),
            coverage_mismatches: Some(0),
            wrong_fraction: Some(2.0 / 880.0),
            ties: Some(20),
            depth_error_max: Some(1e-7),
            counters: "fragments=10;tests=20".into(),
            ..Row::default()
        }
    }

    #[test]
    fn columns_are_exactly_the_fields() {
        let Value::Object(map) = serde_json::to_value(Row::default()).unwrap() else {
            panic!()
        };
        let mut keys: Vec<&str> = map.keys().map(String::as_str).collect();
        let mut cols = COLUMNS.to_vec();
        keys.sort_unstable();
        cols.sort_unstable();
        assert_eq!(keys, cols);
    }

    #[test]
    fn csv_round_trips_with_quoting_and_empty_options() {
        let row = sample_row();
        let text = format!(
            "{}{}{}",
            csv_header(),
            csv_line(&row),
            csv_line(&Row::default())
        );
        let back = parse_csv(&text).unwrap();
        assert_eq!(back, vec![row.clone(), Row::default()]);
        assert!(parse_csv("a,b\n1,2\n").is_err());
        assert!(parse_csv(&format!("{}\"open", csv_header())).is_err());
        assert_eq!(row.error(), Some(2.0 / 900.0));
        assert_eq!(Row::default().error(), None);
    }

    #[test]
    fn results_files_round_trip_and_csv_is_the_fallback() {
        let dir = std::env::temp_dir().join(format!("hider-bench-record-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let results = Results {
            schema: SCHEMA_VERSION,
            machines: vec![Machine::detect()],
            commands: vec!["hider bench".into()],
            complete: true,
            rows: vec![sample_row()],
        };
        write_results(&dir, &results).unwrap();
        assert_eq!(read_results(&dir).unwrap(), results);
        std::fs::remove_file(dir.join("results.json")).unwrap();
        let from_csv = read_results(&dir).unwrap();
        assert_eq!(from_csv.rows, results.rows);
        assert!(!from_csv.complete);
        let mut sink = CsvSink::create(&dir.join("results.csv")).unwrap();
        sink.push(&sample_row()).unwrap();
        // Flushed: readable while the sink is still open.
        assert_eq!(read_results(&dir).unwrap().rows.len(), 1);
        drop(sink);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
