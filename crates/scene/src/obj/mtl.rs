//! MTL files: loaded through `tobj`, with a broken material treated like a
//! missing one. tobj stops at the first bad statement of an MTL file
//! without saying where; here the statement is found (the shortest prefix
//! of the file that fails), reported with its file and line, and only the
//! material it belongs to is dropped, so its faces get the default
//! material while the rest of the file loads.

use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::text::decode;
use crate::model::{Illumination, Material};

/// Most broken materials reported and dropped in one MTL file before the
/// whole file is given up.
const MAX_BROKEN_MATERIALS: usize = 64;

/// What the MTL loader reports besides materials: warnings, and the MTL
/// files it read (so that a caller can refuse to overwrite them).
#[derive(Default)]
pub(super) struct MtlLog {
    /// Non-fatal problems, in the order found.
    pub warnings: RefCell<Vec<String>>,
    /// Every MTL file read, as resolved against the OBJ's folder.
    pub files: RefCell<Vec<PathBuf>>,
}

/// The MTL loader handed to `tobj`: never an error, a warning instead (the
/// default material is used for what could not be loaded).
pub(super) fn load_mtl(base: &Path, mtl: &Path, log: &MtlLog) -> tobj::MTLLoadResult {
    let path = base.join(normalize_separators(&mtl.to_string_lossy()));
    let warn = |message: String| log.warnings.borrow_mut().push(message);
    let none = || Ok((Vec::new(), HashMap::new()));
    let bytes = match crate::input::read_regular(
        &path,
        "MTL file size in bytes",
        crate::input::MAX_MTL_BYTES,
    ) {
        Ok(bytes) => {
            log.files.borrow_mut().push(path.clone());
            bytes
        }
        Err(e) => {
            warn(format!("cannot read MTL ({e}); using the default material"));
            return none();
        }
    };
    let text = match decode(&bytes, &path) {
        Ok(text) => text,
        Err(e) => {
            warn(format!("{e}; using the default material"));
            return none();
        }
    };
    let mut lines: Vec<&str> = text.split('\n').collect();
    for w in super::statements::warnings(&lines, &path.display().to_string()) {
        warn(w);
    }
    for _ in 0..MAX_BROKEN_MATERIALS {
        let error = match parse(&lines) {
            Ok(loaded) => return Ok(loaded),
            Err(e) => e,
        };
        let bad = first_failing_line(&lines);
        let (start, end, name) = material_block(&lines, bad);
        let at = format!("{}:{}", path.display(), bad + 1);
        warn(match name {
            // Nothing can select a material without a name.
            None => format!("{at}: 'newmtl' without a name: its statements are skipped"),
            Some(name) => format!(
                "{at}: {error} in '{}': {name} gets the default material",
                lines[bad].trim()
            ),
        });
        lines[start..end].fill("");
    }
    warn(format!(
        "{}: more than {MAX_BROKEN_MATERIALS} broken materials; using the default material",
        path.display()
    ));
    none()
}

/// tobj's parse of the given lines, after the statements it cannot take:
/// tobj panics on a colour (`Ka`, `Kd`, `Ks`, `Ke`) of fewer than three
/// numbers, so one number is written three times (the format's grey, `Kd
/// r` meaning `Kd r r r`) and none or two is refused here; `d -halo X` is
/// read as `d X` (tobj refuses the option, which dropped the material).
fn parse(lines: &[&str]) -> tobj::MTLLoadResult {
    let mut text = String::new();
    for line in lines {
        if let Some(plain) = super::statements::without_halo(line) {
            text.push_str(&plain);
            text.push('\n');
            continue;
        }
        let mut words = line.split_whitespace();
        let key = words.next();
        let values: Vec<&str> = words.collect();
        match (key, values.as_slice()) {
            (Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")), [grey]) => {
                text.push_str(&format!("{key} {grey} {grey} {grey}"));
            }
            (Some("Ka" | "Kd" | "Ks" | "Ke"), [] | [_, _]) => {
                return Err(tobj::LoadError::MaterialParseError);
            }
            _ => text.push_str(line),
        }
        text.push('\n');
    }
    tobj::load_mtl_buf(&mut std::io::Cursor::new(text.as_bytes()))
}

/// Index of the line tobj fails on: the end of the shortest failing
/// prefix (parsing is sequential, so every longer prefix fails too).
fn first_failing_line(lines: &[&str]) -> usize {
    let (mut ok, mut failing) = (0, lines.len());
    while failing - ok > 1 {
        let mid = ok + (failing - ok) / 2;
        if parse(&lines[..mid]).is_ok() {
            ok = mid;
        } else {
            failing = mid;
        }
    }
    failing - 1
}

/// The lines `start..end` of the material that line `bad` belongs to (from
/// its `newmtl` to the next one), and the material as the warning names it
/// (`None` when its `newmtl` has no name).
fn material_block(lines: &[&str], bad: usize) -> (usize, usize, Option<Cow<'static, str>>) {
    let is_newmtl = |l: &&str| l.split_whitespace().next() == Some("newmtl");
    let start = (0..=bad).rev().find(|&i| is_newmtl(&lines[i]));
    let end = lines[bad + 1..]
        .iter()
        .position(is_newmtl)
        .map_or(lines.len(), |k| bad + 1 + k);
    let name = match start {
        None => Some(Cow::Borrowed("what comes before the first material")),
        Some(i) => match lines[i].trim()["newmtl".len()..].trim() {
            "" => None,
            n => Some(Cow::Owned(format!("material '{n}'"))),
        },
    };
    (start.unwrap_or(0), end, name)
}

/// A material file name or texture path as written on Windows (`.\a.jpg`)
/// made portable.
pub(super) fn normalize_separators(p: &str) -> String {
    let p = p.trim().replace('\\', "/");
    p.strip_prefix("./").map(str::to_owned).unwrap_or(p)
}

/// A tobj material as the scene's, `Tr` (transparency) read when `d`
/// (dissolve) is absent, texture statements split into their options and
/// their file (relative to `base`), values clamped to their ranges.
pub(super) fn convert_material(m: &tobj::Material, base: &Path) -> Material {
    let color =
        |c: Option<[f64; 3]>| c.map(|d| d.map(|c| finite_or(c as f32, 0.0).clamp(0.0, 1.0)));
    let diffuse = color(m.diffuse).unwrap_or(Material::default().diffuse);
    let from_tr = m
        .unknown_param
        .get("Tr")
        .and_then(|t| t.trim().parse::<f32>().ok())
        .map(|tr| 1.0 - tr);
    let opacity = m
        .dissolve
        .map(|d| d as f32)
        .or(from_tr)
        .filter(|o| o.is_finite())
        .unwrap_or(1.0)
        .clamp(0.0, 1.0);
    let texture = |statement: &Option<String>| {
        statement
            .as_deref()
            .filter(|t| !t.trim().is_empty())
            .map(|t| {
                let parsed = super::statements::texture_statement(t);
                crate::shade::TextureRef::new(
                    base.join(PathBuf::from(normalize_separators(&parsed.file))),
                )
                .with_transform(parsed.transform)
            })
            .filter(|t| !t.path().as_os_str().is_empty())
    };
    Material {
        name: m.name.clone(),
        diffuse,
        ambient: color(m.ambient),
        specular: color(m.specular).unwrap_or([0.0; 3]),
        shininess: m
            .shininess
            .map_or(0.0, |n| finite_or(n as f32, 0.0).clamp(0.0, 1000.0)),
        emission: color(m.emissive).unwrap_or([0.0; 3]),
        illumination: match m.illumination_model {
            Some(0) => Illumination::Color,
            Some(1) => Illumination::Diffuse,
            _ => Illumination::Highlight,
        },
        opacity,
        diffuse_texture: texture(&m.diffuse_texture),
        specular_texture: texture(&m.specular_texture),
        alpha_texture: texture(&m.dissolve_texture).map(crate::shade::TextureRef::as_mask),
    }
}

/// `x`, or `default` when it is not finite.
fn finite_or(x: f32, default: f32) -> f32 {
    if x.is_finite() { x } else { default }
}
