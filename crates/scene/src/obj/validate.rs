//! The validation pass over OBJ text: every statement tobj will parse is
//! checked first, so a malformed file is reported with its path and line
//! number (tobj's own errors name neither), and the statements tobj would
//! misread are found.

use std::borrow::Cow;
use std::path::Path;

use crate::error::{Error, Result};

/// A statement the loader leaves out of what tobj sees, or writes the
/// way tobj reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Skipped {
    /// `l`: a polyline.
    Line,
    /// `p`: points.
    Point,
    /// `usemtl` without a name.
    Usemtl,
    /// `vt u` with one coordinate (the format's `v` defaults to 0, tobj
    /// wants it written): given to tobj as `vt u 0`.
    Texcoord,
}

/// What the validation pass found in a valid file.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Checked {
    /// Triangles after fan-splitting the faces.
    pub(super) triangles: u64,
    /// The statements left out or rewritten, by 0-based line index.
    pub(super) skipped: Vec<(usize, Skipped)>,
    /// Statements read but not simulated (free-form geometry, render
    /// attributes): the first line of each keyword.
    pub(super) unsimulated: Vec<(usize, String)>,
    /// Faces (by 0-based line) where an object's faces change between
    /// having texture coordinates or normals and not, with the object's
    /// name: tobj is told a new object of the same name starts there, so
    /// that each part keeps what its faces have (one mesh holds an
    /// attribute for every vertex or for none).
    pub(super) splits: Vec<(usize, String)>,
}

impl Checked {
    fn skip(&mut self, line: usize, what: Skipped) {
        self.skipped.push((line, what));
    }

    /// The text tobj parses: `text` with the skipped statements replaced
    /// (line numbers kept), borrowed when nothing is skipped.
    pub(super) fn text_for_tobj<'a>(&self, text: &'a str) -> Cow<'a, str> {
        if self.skipped.is_empty() && self.splits.is_empty() {
            return Cow::Borrowed(text);
        }
        let mut lines: Vec<Cow<'_, str>> = text.split('\n').map(Cow::Borrowed).collect();
        for (k, object) in &self.splits {
            // The object statement shares the face's line, so every later
            // line keeps its number.
            lines[*k] = Cow::Owned(format!("o {object}\n{}", lines[*k]));
        }
        for &(k, what) in &self.skipped {
            lines[k] = match what {
                Skipped::Line | Skipped::Point => Cow::Borrowed(""),
                // A name no exporter writes, so the faces that follow get
                // the default material.
                Skipped::Usemtl => Cow::Borrowed("usemtl <no material>"),
                Skipped::Texcoord => Cow::Owned(format!("{} 0", lines[k].trim_end())),
            };
        }
        Cow::Owned(lines.join("\n"))
    }

    /// The warnings for the skipped statements, naming the file `name`.
    pub(super) fn warnings(&self, name: &Path) -> Vec<String> {
        let count = |what: Skipped| self.skipped.iter().filter(|s| s.1 == what).count();
        let mut warnings = Vec::new();
        warnings.extend(skipped_elements(
            count(Skipped::Line),
            count(Skipped::Point),
            name,
        ));
        for (k, keyword) in &self.unsimulated {
            warnings.push(format!(
                "{}:{}: '{keyword}' (free-form geometry or a render attribute) is read but not \
                 simulated",
                name.display(),
                k + 1
            ));
        }
        for &(k, what) in &self.skipped {
            if what == Skipped::Usemtl {
                warnings.push(format!(
                    "{}:{}: 'usemtl' without a name; the faces that follow get the default \
                     material",
                    name.display(),
                    k + 1
                ));
            }
        }
        warnings
    }
}

/// The warning for `lines` line elements (`l`) and `points` point
/// elements (`p`) skipped in the file `name`, when there are any.
pub(super) fn skipped_elements(lines: usize, points: usize, name: &Path) -> Option<String> {
    let elements = [(lines, "line", 'l'), (points, "point", 'p')]
        .iter()
        .filter(|e| e.0 > 0)
        .map(|&(n, what, key)| {
            let s = if n == 1 { "" } else { "s" };
            format!("{n} {what} element{s} ('{key}')")
        })
        .collect::<Vec<_>>();
    (!elements.is_empty()).then(|| {
        format!(
            "{}: skipped {}: only faces are rendered",
            name.display(),
            elements.join(" and ")
        )
    })
}

/// Checks the lines tobj will parse, reporting the first problem with its
/// line number, and counts what the file holds.
pub(super) fn validate_obj(text: &str, name: &Path) -> Result<Checked> {
    let (mut nv, mut nvt, mut nvn) = (0i64, 0i64, 0i64);
    let mut checked = Checked::default();
    // The current object's name (tobj's default before any `o` or `g`) and
    // the layout (has vt, has vn) of its last face.
    let mut object = String::from("unnamed_object");
    let mut layout: Option<(bool, bool)> = None;
    // One buffer for every line's words (a file has millions of lines).
    let mut values: Vec<&str> = Vec::new();
    for (k, raw) in text.split('\n').enumerate() {
        let line_no = k + 1;
        let err = |message: String| Error::Parse {
            path: name.to_path_buf(),
            line: line_no,
            message,
        };
        let line = raw.trim_end_matches('\r');
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        values.clear();
        values.extend(words);
        let values = &values;
        let floats = |want: usize, what: &str| -> Result<()> {
            if values.len() < want {
                return Err(err(format!(
                    "'{what}' needs {want} numbers, found {}: '{}'",
                    values.len(),
                    line.trim()
                )));
            }
            for v in &values[..want] {
                match v.parse::<f64>() {
                    Ok(x) if x.is_finite() => {}
                    Ok(x) => return Err(err(format!("'{what}' has a non-finite value {x}"))),
                    Err(_) => return Err(err(format!("'{what}' has a bad number '{v}'"))),
                }
            }
            Ok(())
        };
        match keyword {
            "v" => {
                floats(3, "v")?;
                if values.len() == 4 {
                    match values[3].parse::<f64>() {
                        Ok(w) if w.is_finite() && w != 0.0 => {}
                        _ => return Err(err(format!("'v' has a bad w '{}'", values[3]))),
                    }
                }
                nv += 1;
            }
            "vt" => {
                floats(1, "vt")?;
                if values.len() == 1 {
                    checked.skip(k, Skipped::Texcoord);
                }
                nvt += 1;
            }
            "vn" => {
                floats(3, "vn")?;
                nvn += 1;
            }
            "f" => {
                check_face(values, [nv, nvt, nvn], &err)?;
                checked.triangles += values.len() as u64 - 2;
                let mut parts = values[0].split('/');
                parts.next();
                let face = (
                    parts.next().is_some_and(|t| !t.is_empty()),
                    parts.next().is_some_and(|n| !n.is_empty()),
                );
                if layout.is_some_and(|l| l != face) {
                    checked.splits.push((k, object.clone()));
                }
                layout = Some(face);
            }
            "o" | "g" => {
                let name = line.trim_start()[1..].trim();
                object = if name.is_empty() {
                    "unnamed_object".to_owned()
                } else {
                    name.to_owned()
                };
                layout = None;
            }
            // tobj reads a polyline of three or more vertices as a face;
            // lines and points are not surfaces, so they are skipped.
            "l" => checked.skip(k, Skipped::Line),
            "p" => checked.skip(k, Skipped::Point),
            // tobj refuses a `usemtl` without a name; it selects no
            // material, as a name no MTL defines does.
            "usemtl" if values.is_empty() => checked.skip(k, Skipped::Usemtl),
            // Free-form geometry and the display and render attributes of
            // the OBJ specification: read by no loader here, so named.
            "vp" | "cstype" | "deg" | "bmat" | "step" | "curv" | "curv2" | "surf" | "parm"
            | "trim" | "hole" | "scrv" | "sp" | "end" | "con" | "bevel" | "c_interp"
            | "d_interp" | "lod" | "shadow_obj" | "trace_obj" | "ctech" | "stech"
                if !checked.unsimulated.iter().any(|(_, w)| *w == keyword) =>
            {
                checked.unsimulated.push((k, keyword.to_owned()));
            }
            _ => {}
        }
    }
    Ok(checked)
}

/// Checks one face line's vertices: at least three, one `v/vt/vn` layout
/// for all of them, and every index (negative ones counting back) naming
/// one of the `counts` = (positions, texture coordinates, normals) defined
/// so far, as the OBJ format requires.
pub(super) fn check_face(
    values: &[&str],
    counts: [i64; 3],
    err: &dyn Fn(String) -> Error,
) -> Result<()> {
    if values.len() < 3 {
        return Err(err(format!(
            "face has {} vertices, needs at least 3",
            values.len()
        )));
    }
    let mut layout = None;
    for v in values {
        let parts: Vec<&str> = v.split('/').collect();
        if parts.len() > 3 {
            return Err(err(format!("bad face vertex '{v}'")));
        }
        let this_layout = (
            parts.len(),
            parts.get(1).is_some_and(|s| !s.is_empty()),
            parts.get(2).is_some_and(|s| !s.is_empty()),
        );
        if *layout.get_or_insert(this_layout) != this_layout {
            return Err(err(format!(
                "face mixes vertex formats ('{}' and '{v}')",
                values[0]
            )));
        }
        for (slot, count, what) in [
            (0, counts[0], "vertex"),
            (1, counts[1], "texture"),
            (2, counts[2], "normal"),
        ] {
            let Some(s) = parts.get(slot).filter(|s| !s.is_empty()) else {
                if slot == 0 {
                    return Err(err(format!("face vertex '{v}' has no position index")));
                }
                continue;
            };
            let i: i64 = s
                .parse()
                .map_err(|_| err(format!("bad {what} index '{s}' in '{v}'")))?;
            let resolved = if i < 0 { count + i + 1 } else { i };
            if i == 0 || resolved < 1 || resolved > count {
                return Err(err(format!(
                    "{what} index {i} out of range (1..={count} defined so far)"
                )));
            }
        }
    }
    Ok(())
}
