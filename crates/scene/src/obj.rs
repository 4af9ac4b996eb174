//! OBJ + MTL loading through `tobj`, hardened for real-world files.
//!
//! Files are read as bytes and decoded leniently (stray non-UTF-8 bytes in
//! comments or names become U+FFFD; UTF-16 with a byte-order mark is
//! decoded), so files written by old exporters load the way Mesa- and
//! assimp-based tools load them. Before `tobj` parses the text, a
//! validation pass checks every `v`, `vt`, `vn` and `f` line so that a
//! malformed file is reported with its path and line number (tobj's own
//! errors name neither). Polygons are fan-split `(v0, vi, vi+1)` in file
//! order, which fixes the primitive ids the GL reference uses. Line (`l`)
//! and point (`p`) elements are skipped with a warning: they are not
//! surfaces.
//!
//! A missing MTL file, or a broken material in one, is a warning, not an
//! error: the faces get the default material, as GL viewers do.
//!
//! Plain files (`v`, `vt`, `vn`, `f`, `o`, `g`, `s`, `usemtl`, `mtllib`,
//! `l`, `p` and comments, numbers in the usual form) are read by a fast reader, in
//! parallel chunks, which builds the very scene tobj builds; anything else
//! goes to tobj, the loader of record ([`ObjParser`], `docs/loading.md`).

mod fast;
mod mtl;
mod statements;
mod text;
mod validate;

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec2, Vec3};

use crate::error::{Error, Result};
use crate::model::{Mesh, Scene};

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
    /// Which reader parses the file. Both give the same scene (and the same
    /// errors); the default, [`ObjParser::Fast`], is the quicker.
    pub parser: ObjParser,
}

impl Default for ObjOptions {
    fn default() -> Self {
        Self {
            max_triangles: MAX_TRIANGLES,
            max_file_bytes: MAX_FILE_BYTES,
            parser: ObjParser::default(),
        }
    }
}

/// The reader of an OBJ file's statements.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ObjParser {
    /// The fast reader, in parallel chunks (with the crate's `parallel`
    /// feature), for files made of `v`, `vt`, `vn`, `f`, `o`, `g`, `s`,
    /// `usemtl`, `mtllib`, `l`, `p` and comments; tobj for any other file (the
    /// reason is in [`ObjStats::fallback`]). The scene is the one tobj
    /// builds.
    #[default]
    Fast,
    /// tobj alone: the loader of record, kept to compare against.
    Tobj,
}

/// How an OBJ file was read.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ObjStats {
    /// Bytes of OBJ text read.
    pub bytes: u64,
    /// Whether the fast reader built the scene (otherwise tobj did).
    pub fast: bool,
    /// Why tobj read a file the fast reader was asked to read, naming the
    /// line (`"line 12: a 'l' statement ..."`).
    pub fallback: Option<String>,
    /// Chunks the fast reader cut the file into (read in parallel).
    pub chunks: usize,
}

/// Loads an OBJ file (and the MTL files it names) with default options.
pub fn load_obj(path: impl AsRef<Path>) -> Result<Scene> {
    load_obj_with(path.as_ref(), &ObjOptions::default())
}

/// Loads an OBJ file with the given options.
pub fn load_obj_with(path: &Path, options: &ObjOptions) -> Result<Scene> {
    load_obj_stats(path, options).map(|(scene, _)| scene)
}

/// Loads an OBJ file with the given options, saying how it was read.
pub fn load_obj_stats(path: &Path, options: &ObjOptions) -> Result<(Scene, ObjStats)> {
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
    load_obj_bytes_stats(&bytes, path, &base, options)
}

/// Loads OBJ text held in memory. `name` is used in error messages; MTL
/// files and textures are looked up relative to `base_dir`.
pub fn load_obj_bytes(
    bytes: &[u8],
    name: &Path,
    base_dir: &Path,
    options: &ObjOptions,
) -> Result<Scene> {
    load_obj_bytes_stats(bytes, name, base_dir, options).map(|(scene, _)| scene)
}

/// [`load_obj_bytes`], saying how the text was read.
pub fn load_obj_bytes_stats(
    bytes: &[u8],
    name: &Path,
    base_dir: &Path,
    options: &ObjOptions,
) -> Result<(Scene, ObjStats)> {
    let mut stats = ObjStats {
        bytes: bytes.len() as u64,
        ..ObjStats::default()
    };
    if options.parser == ObjParser::Fast {
        match load_fast(bytes, name, base_dir, options, fast::CHUNK_BYTES)? {
            Ok((scene, chunks)) => {
                stats.fast = true;
                stats.chunks = chunks;
                return Ok((scene, stats));
            }
            Err(reason) => stats.fallback = Some(reason),
        }
    }
    Ok((load_with_tobj(bytes, name, base_dir, options)?, stats))
}

/// The fast reader with chunks of about `chunk_bytes`: the scene and the
/// chunk count, or why tobj must read the file.
fn load_fast(
    bytes: &[u8],
    name: &Path,
    base_dir: &Path,
    options: &ObjOptions,
    chunk_bytes: usize,
) -> Result<std::result::Result<(Scene, usize), String>> {
    let loaded = match fast::load(bytes, base_dir, options, chunk_bytes) {
        Ok(loaded) => loaded,
        Err(reason) => return Ok(Err(reason)),
    };
    // The validation pass's warnings come before those of the MTL files.
    let (lines, points) = loaded.skipped;
    let mut warnings: Vec<String> = validate::skipped_elements(lines, points, name)
        .into_iter()
        .chain(loaded.warnings)
        .collect();
    let materials = materials_or_default(loaded.materials, &mut warnings);
    let scene = finish(
        materials,
        loaded.meshes,
        (warnings, loaded.mtl_files),
        &loaded.smoothing,
        loaded.triangles,
        name,
        base_dir,
    )?;
    Ok(Ok((scene, loaded.chunks)))
}

/// The loader of record: the validation pass, then tobj.
fn load_with_tobj(
    bytes: &[u8],
    name: &Path,
    base_dir: &Path,
    options: &ObjOptions,
) -> Result<Scene> {
    let text = text::decode(bytes, name)?;
    let checked = validate::validate_obj(&text, name)?;
    let smoothing = smoothing_groups(&text);
    let triangles = checked.triangles;
    if triangles > options.max_triangles {
        return Err(Error::Limit {
            what: "triangle count",
            value: triangles,
            limit: options.max_triangles,
        });
    }
    let log = mtl::MtlLog {
        warnings: RefCell::new(checked.warnings(name)),
        ..mtl::MtlLog::default()
    };
    let text = checked.text_for_tobj(&text);
    let load_options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj splits lines itself; CR of CRLF files is whitespace to it.
    let mut reader = std::io::Cursor::new(text.as_bytes());
    let (models, materials) = tobj::load_obj_buf(&mut reader, &load_options, |mtl| {
        mtl::load_mtl(base_dir, mtl, &log)
    })
    .map_err(|e| Error::Parse {
        path: name.to_path_buf(),
        line: 0,
        message: format!("OBJ parser: {e}"),
    })?;
    let mut warnings = log.warnings.into_inner();
    let materials = materials_or_default(materials, &mut warnings);
    let meshes = models
        .into_iter()
        .map(|model| mesh_from_tobj(model, materials.len(), &mut warnings))
        .collect();
    finish(
        materials,
        meshes,
        (warnings, log.files.into_inner()),
        &smoothing,
        triangles,
        name,
        base_dir,
    )
}

/// The materials of the MTL files, or none with a warning.
fn materials_or_default(
    materials: std::result::Result<Vec<tobj::Material>, tobj::LoadError>,
    warnings: &mut Vec<String>,
) -> Vec<tobj::Material> {
    materials.unwrap_or_else(|e| {
        warnings.push(format!(
            "materials unavailable ({e}); using the default material"
        ));
        Vec::new()
    })
}

/// The scene of the meshes and materials either reader produced: smoothing
/// where asked, the warnings about the file's content, the checks.
fn finish(
    materials: Vec<tobj::Material>,
    meshes: Vec<Mesh>,
    (mut warnings, mtl_files): (Vec<String>, Vec<PathBuf>),
    smoothing: &Smoothing,
    triangles: u64,
    name: &Path,
    base_dir: &Path,
) -> Result<Scene> {
    let mut scene = Scene {
        materials: materials
            .iter()
            .map(|m| mtl::convert_material(m, base_dir))
            .collect(),
        source_files: std::iter::once(name.to_path_buf())
            .chain(mtl_files)
            .collect(),
        ..Scene::default()
    };
    // Materials naming one file share one (lazy) decode.
    crate::shade::TextureRef::share(
        scene
            .materials
            .iter_mut()
            .flat_map(|m| [m.diffuse_texture.as_mut(), m.alpha_texture.as_mut()])
            .flatten(),
    );
    let mut smoothed = false;
    for mut mesh in meshes {
        if smoothing.on && mesh.normals.is_empty() {
            mesh.normals = smooth_normals(&mesh);
            smoothed = true;
        }
        scene.meshes.push(mesh);
    }
    // With vn the groups change nothing: only smoothing done here is named.
    if smoothed && smoothing.groups > 1 {
        warnings.push(format!(
            "{}: {} smoothing groups ('s' statements): each object is smoothed as one group \
             (give faces meant to meet at a hard edge their own object, or write vn)",
            name.display(),
            smoothing.groups
        ));
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

/// One tobj model as a mesh; per-vertex normals, texture coordinates and
/// colours are kept only when every vertex has one (a warning names what
/// is dropped), a material index only when it names one of the
/// `material_count` materials.
fn mesh_from_tobj(model: tobj::Model, material_count: usize, warnings: &mut Vec<String>) -> Mesh {
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
    let colors: Vec<[f32; 3]> = m
        .vertex_color
        .chunks_exact(3)
        .map(|c| {
            // A colour that is not a number is black; out of range, clamped.
            let channel = |x: f64| {
                if x.is_finite() {
                    x.clamp(0.0, 1.0) as f32
                } else {
                    0.0
                }
            };
            [channel(c[0]), channel(c[1]), channel(c[2])]
        })
        .collect();
    let material = m.material_id.filter(|&k| k < material_count);
    let n = positions.len();
    let mut whole = |what: &str, len: usize| {
        if len != 0 && len != n {
            warnings.push(format!(
                "object '{}': some faces have {what} and some do not; the {what} of the whole \
                 object are dropped (split it into objects that have them and objects that do not)",
                model.name
            ));
        }
        len == n
    };
    Mesh {
        name: model.name.clone(),
        normals: if whole("normals (vn)", normals.len()) {
            normals
        } else {
            Vec::new()
        },
        uvs: if whole("texture coordinates (vt)", uvs.len()) {
            uvs
        } else {
            Vec::new()
        },
        colors: if whole("vertex colours", colors.len()) {
            colors
        } else {
            Vec::new()
        },
        positions,
        indices,
        material,
        ..Mesh::default()
    }
}

/// What an OBJ file's smoothing-group statements (`s N`, `s off`) ask for.
struct Smoothing {
    /// Whether some statement turns smoothing on.
    on: bool,
    /// How many distinct groups are named.
    groups: usize,
}

/// The smoothing groups of OBJ text: `s 0` and `s off` turn smoothing off,
/// any other value names a group.
fn smoothing_groups(text: &str) -> Smoothing {
    let mut groups: Vec<&str> = Vec::new();
    for line in text.lines() {
        // Most lines are not `s` statements: the first character says so.
        if !line.trim_start().starts_with('s') {
            continue;
        }
        let mut words = line.split_whitespace();
        if words.next() != Some("s") {
            continue;
        }
        match words.next() {
            None | Some("off" | "0") => {}
            Some(group) => {
                if !groups.contains(&group) {
                    groups.push(group);
                }
            }
        }
    }
    Smoothing {
        on: !groups.is_empty(),
        groups: groups.len(),
    }
}

/// Vertex normals for a mesh without them whose file asks for smoothing:
/// at each vertex the sum of its triangles' normals weighted by their area
/// (the cross product's length), normalised, as OBJ viewers smooth a
/// smoothing group. Vertices the loader split (at a texture seam) are
/// smoothed apart.
fn smooth_normals(mesh: &Mesh) -> Vec<Vec3> {
    let mut sums = vec![DVec3::ZERO; mesh.positions.len()];
    for tri in &mesh.indices {
        let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a);
        if !n.is_finite() {
            continue;
        }
        for &i in tri {
            sums[i as usize] += n;
        }
    }
    sums.into_iter()
        .map(|n| n.normalize_or_zero().as_vec3())
        .collect()
}

/// Warnings about what the file holds rather than how it is written:
/// missing textures and degenerate triangles.
fn content_warnings(scene: &Scene, warnings: &mut Vec<String>) {
    for m in &scene.materials {
        let maps = [
            (&m.diffuse_texture, "map_Kd", "diffuse colour (Kd)"),
            (&m.specular_texture, "map_Ks", "specular colour (Ks)"),
            (&m.alpha_texture, "map_d", "opacity (d)"),
        ];
        for (texture, statement, fallback) in maps {
            if let Some(t) = texture
                && !t.path().is_file()
                && !crate::memory_files::holds(t.path())
            {
                warnings.push(format!(
                    "material '{}': texture {} ({statement}) not found; the material's \
                     {fallback} is used",
                    m.name,
                    t.path().display()
                ));
            }
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

#[cfg(test)]
mod tests;
