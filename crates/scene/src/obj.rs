//! OBJ + MTL loading through `tobj`, hardened for real-world files.
//!
//! Files are read as bytes and decoded leniently (stray non-UTF-8 bytes in
//! comments or names become U+FFFD), so files written by old exporters load
//! the way Mesa- and assimp-based tools load them. Before `tobj` parses the
//! text, a validation pass checks every `v`, `vt`, `vn` and `f` line so that
//! a malformed file is reported with its path and line number (tobj's own
//! errors name neither). Polygons are fan-split `(v0, vi, vi+1)` in file
//! order, which fixes the primitive ids the GL reference uses.
//!
//! A missing or broken MTL file is a warning, not an error: the meshes get
//! the default material, as GL viewers do.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec2, Vec3};

use crate::error::{Error, Result};
use crate::model::{Material, Mesh, Scene};

/// Most triangles an OBJ file may produce before loading is refused (before
/// any mesh memory is allocated).
pub const MAX_TRIANGLES: u64 = 50_000_000;

/// Largest OBJ file read, in bytes (checked before reading it).
pub const MAX_FILE_BYTES: u64 = 4 << 30;

/// Options for [`load_obj_with`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjOptions {
    /// Most triangles accepted (after fan-splitting). Defaults to
    /// [`MAX_TRIANGLES`].
    pub max_triangles: u64,
    /// Largest file accepted, in bytes. Defaults to [`MAX_FILE_BYTES`].
    pub max_file_bytes: u64,
}

impl Default for ObjOptions {
    fn default() -> Self {
        Self {
            max_triangles: MAX_TRIANGLES,
            max_file_bytes: MAX_FILE_BYTES,
        }
    }
}

/// Loads an OBJ file (and the MTL files it names) with default options.
pub fn load_obj(path: impl AsRef<Path>) -> Result<Scene> {
    load_obj_with(path.as_ref(), &ObjOptions::default())
}

/// Loads an OBJ file with the given options.
pub fn load_obj_with(path: &Path, options: &ObjOptions) -> Result<Scene> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if meta.is_dir() {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: 0,
            message: "is a folder, not an OBJ file".into(),
        });
    }
    if meta.len() > options.max_file_bytes {
        return Err(Error::Limit {
            what: "OBJ file size in bytes",
            value: meta.len(),
            limit: options.max_file_bytes,
        });
    }
    let bytes = std::fs::read(path).map_err(io)?;
    let base = path.parent().unwrap_or(Path::new("")).to_path_buf();
    load_obj_bytes(&bytes, path, &base, options)
}

/// Loads OBJ text held in memory. `name` is used in error messages; MTL
/// files and textures are looked up relative to `base_dir`.
pub fn load_obj_bytes(
    bytes: &[u8],
    name: &Path,
    base_dir: &Path,
    options: &ObjOptions,
) -> Result<Scene> {
    let text = String::from_utf8_lossy(bytes);
    let triangles = validate_obj(&text, name)?;
    if triangles > options.max_triangles {
        return Err(Error::Limit {
            what: "triangle count",
            value: triangles,
            limit: options.max_triangles,
        });
    }
    let warnings = RefCell::new(Vec::new());
    let load_options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj splits lines itself; CR of CRLF files is whitespace to it.
    let mut reader = std::io::Cursor::new(text.as_bytes());
    let (models, materials) = tobj::load_obj_buf(&mut reader, &load_options, |mtl| {
        load_mtl(base_dir, mtl, &warnings)
    })
    .map_err(|e| Error::Parse {
        path: name.to_path_buf(),
        line: 0,
        message: format!("OBJ parser: {e}"),
    })?;
    let mut warnings = warnings.into_inner();
    let materials = materials.unwrap_or_else(|e| {
        warnings.push(format!(
            "materials unavailable ({e}); using the default material"
        ));
        Vec::new()
    });
    let mut scene = Scene {
        materials: materials
            .iter()
            .map(|m| convert_material(m, base_dir))
            .collect(),
        ..Scene::default()
    };
    for model in models {
        let mesh = mesh_from_tobj(model, scene.materials.len());
        scene.meshes.push(mesh);
    }
    if triangles == 0 {
        return Err(Error::Parse {
            path: name.to_path_buf(),
            line: 0,
            message: "contains no faces ('f' lines): nothing to render".into(),
        });
    }
    content_warnings(&scene, &mut warnings);
    scene.warnings = warnings;
    if scene.triangle_count() as u64 != triangles {
        // The validation pass and tobj disagree: a bug, but never a panic.
        return Err(Error::Parse {
            path: name.to_path_buf(),
            line: 0,
            message: format!(
                "expected {triangles} triangles after fan-splitting, the parser produced {}",
                scene.triangle_count()
            ),
        });
    }
    scene.validate()?;
    Ok(scene)
}

/// One tobj model as a mesh; per-vertex normals and texture coordinates
/// are kept only when every vertex has one, a material index only when it
/// names one of the `material_count` materials.
fn mesh_from_tobj(model: tobj::Model, material_count: usize) -> Mesh {
    let m = model.mesh;
    let positions: Vec<DVec3> = m
        .positions
        .chunks_exact(3)
        .map(|p| DVec3::new(p[0], p[1], p[2]))
        .collect();
    let normals: Vec<Vec3> = m
        .normals
        .chunks_exact(3)
        .map(|n| Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32))
        .collect();
    let uvs: Vec<Vec2> = m
        .texcoords
        .chunks_exact(2)
        .map(|t| Vec2::new(t[0] as f32, t[1] as f32))
        .collect();
    let indices = m
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    let material = m.material_id.filter(|&k| k < material_count);
    Mesh {
        name: model.name,
        normals: if normals.len() == positions.len() {
            normals
        } else {
            Vec::new()
        },
        uvs: if uvs.len() == positions.len() {
            uvs
        } else {
            Vec::new()
        },
        positions,
        indices,
        material,
    }
}

/// Warnings about what the file holds rather than how it is written:
/// missing textures and degenerate triangles.
fn content_warnings(scene: &Scene, warnings: &mut Vec<String>) {
    for m in &scene.materials {
        if let Some(t) = &m.diffuse_texture
            && !t.is_file()
        {
            warnings.push(format!(
                "material '{}': texture {} not found; the material's diffuse colour is used",
                m.name,
                t.display()
            ));
        }
    }
    let degenerate = scene
        .triangles()
        .filter(|&(_, m, t)| {
            let [a, b, c] = scene.triangle_positions(m, t);
            (b - a).cross(c - a) == DVec3::ZERO
        })
        .count();
    if degenerate > 0 {
        warnings.push(format!(
            "{degenerate} degenerate triangles (repeated vertices or zero area): they cover \
         nothing and keep their primitive ids"
        ));
    }
}

/// Checks one face line's vertices: at least three, one `v/vt/vn` layout
/// for all of them, and every index (negative ones counting back) naming
/// one of the `counts` = (positions, texture coordinates, normals) defined
/// so far, as the OBJ format requires.
fn check_face(values: &[&str], counts: [i64; 3], err: &dyn Fn(String) -> Error) -> Result<()> {
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

fn load_mtl(base: &Path, mtl: &Path, warnings: &RefCell<Vec<String>>) -> tobj::MTLLoadResult {
    let path = base.join(normalize_separators(&mtl.to_string_lossy()));
    let fail = |why: String| {
        warnings.borrow_mut().push(format!(
            "{}: {why}; using the default material",
            path.display()
        ));
        Err(tobj::LoadError::OpenFileFailed)
    };
    match std::fs::read(&path) {
        Ok(bytes) => {
            let text = String::from_utf8_lossy(&bytes);
            let mut reader = std::io::Cursor::new(text.as_bytes());
            match tobj::load_mtl_buf(&mut reader) {
                Ok(r) => Ok(r),
                Err(e) => fail(format!("cannot parse MTL ({e})")),
            }
        }
        Err(e) => fail(format!("cannot read MTL ({e})")),
    }
}

fn normalize_separators(p: &str) -> String {
    let p = p.trim().replace('\\', "/");
    p.strip_prefix("./").map(str::to_owned).unwrap_or(p)
}

fn convert_material(m: &tobj::Material, base: &Path) -> Material {
    let diffuse = m
        .diffuse
        .map(|d| d.map(|c| (c as f32).clamp(0.0, 1.0)))
        .unwrap_or(Material::default().diffuse);
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
    Material {
        name: m.name.clone(),
        diffuse,
        opacity,
        diffuse_texture: m
            .diffuse_texture
            .as_deref()
            .filter(|t| !t.trim().is_empty())
            .map(|t| base.join(PathBuf::from(normalize_separators(t)))),
    }
}

/// Checks the lines tobj will parse, reporting the first problem with its
/// line number, and returns the number of triangles after fan-splitting.
fn validate_obj(text: &str, name: &Path) -> Result<u64> {
    let (mut nv, mut nvt, mut nvn) = (0i64, 0i64, 0i64);
    let mut triangles = 0u64;
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
        let values: Vec<&str> = words.collect();
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
                nvt += 1;
            }
            "vn" => {
                floats(3, "vn")?;
                nvn += 1;
            }
            "f" => {
                check_face(&values, [nv, nvt, nvn], &err)?;
                triangles += values.len() as u64 - 2;
            }
            _ => {}
        }
    }
    Ok(triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &str) -> Result<Scene> {
        load_obj_bytes(
            text.as_bytes(),
            Path::new("test.obj"),
            Path::new("/nonexistent"),
            &ObjOptions::default(),
        )
    }

    #[test]
    fn quad_is_fan_split_in_file_order() {
        let s = load("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n").unwrap();
        assert_eq!(s.triangle_count(), 3);
        let tris: Vec<_> = s
            .triangles()
            .map(|(_, m, t)| s.triangle_positions(m, t))
            .collect();
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        assert_eq!(tris[0], [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
        assert_eq!(tris[1], [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]);
    }

    #[test]
    fn crlf_tabs_and_stray_bytes_load() {
        let mut bytes = b"# caf\xe9 \xff comment\r\nv\t0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\no na\xefme\r\nf 1//\t2// 3//\r\n".to_vec();
        // The face above uses "1//" without normals; make it plain indices.
        bytes = String::from_utf8_lossy(&bytes)
            .replace("1//\t2// 3//", "1\t2 3")
            .into_bytes();
        bytes.extend_from_slice(b"f -3 -2 -1\r\n");
        let s = load_obj_bytes(
            &bytes,
            Path::new("x.obj"),
            Path::new("."),
            &ObjOptions::default(),
        )
        .unwrap();
        assert_eq!(s.triangle_count(), 2);
    }

    #[test]
    fn missing_mtl_is_a_warning() {
        let s = load("mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n").unwrap();
        assert_eq!(s.triangle_count(), 1);
        assert!(
            s.warnings.iter().any(|w| w.contains("nothere.mtl")),
            "{:?}",
            s.warnings
        );
        assert_eq!(s.meshes[0].material, None);
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("test.obj:4:") && e.contains("index 4"), "{e}");
        let e = load("v 0 0 0\nv 1 nan 0\n").unwrap_err().to_string();
        assert!(e.starts_with("test.obj:2:") && e.contains("NaN"), "{e}");
        let e = load("v 0 0 0\nv 1 zero 0\n").unwrap_err().to_string();
        assert!(e.contains(":2:") && e.contains("'zero'"), "{e}");
        let e = load("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err().to_string();
        assert!(e.contains(":3:") && e.contains("2 vertices"), "{e}");
        let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains(":4:") && e.contains("index 0"), "{e}");
        let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains(":4:") && e.contains("-4"), "{e}");
    }

    #[test]
    fn triangle_limit_is_checked_before_loading() {
        let opts = ObjOptions {
            max_triangles: 1,
            ..ObjOptions::default()
        };
        let e = load_obj_bytes(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\n",
            Path::new("big.obj"),
            Path::new("."),
            &opts,
        )
        .unwrap_err();
        assert!(matches!(
            e,
            Error::Limit {
                value: 2,
                limit: 1,
                ..
            }
        ));
    }

    #[test]
    fn mtl_with_windows_texture_path_and_opacity() {
        let dir = std::env::temp_dir().join(format!("hider-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("m.mtl"),
            "newmtl glass\r\nKd 0.1 0.2 0.3\r\nd 0.25\r\nmap_Kd .\\tex\\a.jpg\r\nnewmtl tr\nTr 0.75\n",
        )
        .unwrap();
        std::fs::write(
            dir.join("m.obj"),
            "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\nusemtl tr\nf 1 3 2\n",
        )
        .unwrap();
        let s = load_obj(dir.join("m.obj")).unwrap();
        let glass = &s.materials[s.meshes[0].material.unwrap()];
        assert_eq!(glass.diffuse, [0.1, 0.2, 0.3]);
        assert_eq!(glass.opacity, 0.25);
        assert_eq!(glass.diffuse_texture, Some(dir.join("tex/a.jpg")));
        assert!(
            s.warnings
                .iter()
                .any(|w| w.contains("tex/a.jpg") && w.contains("glass")),
            "{:?}",
            s.warnings
        );
        let tr = &s.materials[s.meshes[1].material.unwrap()];
        assert_eq!(tr.opacity, 0.25);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn degenerate_faces_and_missing_textures_are_warnings() {
        let s = load("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 4\nf 1 2 4\n").unwrap();
        assert_eq!(s.triangle_count(), 3, "degenerate triangles keep their ids");
        assert!(
            s.warnings.iter().any(|w| w.starts_with("2 degenerate")),
            "{:?}",
            s.warnings
        );
        let e = load("v 0 0 0\nv 1 0 0\n").unwrap_err().to_string();
        assert!(e.contains("no faces"), "{e}");
    }

    #[test]
    fn file_size_limit_is_checked_before_reading() {
        let dir = std::env::temp_dir().join(format!("hider-objsize-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("big.obj");
        std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let opts = ObjOptions {
            max_file_bytes: 10,
            ..ObjOptions::default()
        };
        let e = load_obj_with(&p, &opts).unwrap_err();
        assert!(matches!(e, Error::Limit { limit: 10, .. }), "{e}");
        let e = load_obj(&dir).unwrap_err().to_string();
        assert!(e.contains("folder"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn missing_file_names_the_path() {
        let e = load_obj("/definitely/not/here.obj")
            .unwrap_err()
            .to_string();
        assert!(e.contains("/definitely/not/here.obj"), "{e}");
    }
}
