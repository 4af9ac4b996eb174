//! The fast reader: plain OBJ files (`v`, `vt`, `vn`, `f`, `o`, `g`, `s`,
//! `usemtl`, `mtllib`, comments, and the `l` and `p` elements the loader
//! of record skips) read in parallel chunks, producing
//! the meshes tobj produces for them, vertex for vertex.
//!
//! The file is cut into chunks at line ends. A first pass counts each
//! chunk's statements and triangles, so that the triangle limit is checked
//! and every array sized before anything is allocated; a second pass
//! parses each chunk into its slots of the file-wide position, texture
//! coordinate and normal arrays and lists its faces' corners and the
//! statements that shape meshes. The meshes are then built in file order
//! as tobj builds them: a new mesh at each `o`/`g` (after faces), at each
//! `usemtl` changing the material (after faces), where an object's faces
//! change between having texture coordinates or normals and not (the
//! split the validation pass asks tobj for), and one at the end; each
//! mesh's vertices are its distinct `(v, vt, vn)` corners in order of first
//! use.
//!
//! Whatever the reader does not fully handle — another statement, an
//! unusual number, a lone CR, a name after blanks, a bad index, too many
//! triangles — is a refusal: the file is then loaded by tobj, which gives
//! the same scene or the error with its line.

mod scan;

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::path::Path;

use glam::{DVec3, Vec2, Vec3};

use self::scan::{Counts, Event, NONE, Parsed, Refusal, Slots};
use super::{ObjOptions, Smoothing};
use crate::model::Mesh;

/// Chunks are about this many bytes (cut at the next line end): small
/// enough to share among threads evenly, large enough that each is
/// worth a task.
pub(super) const CHUNK_BYTES: usize = 1 << 20;

/// What the fast reader produced: everything the loader of record has
/// after tobj's parse.
pub(super) struct Loaded {
    /// The meshes, in file order (materials not yet checked against the
    /// final material count).
    pub meshes: Vec<Mesh>,
    /// The materials of the `mtllib` files, as tobj merges them.
    pub materials: Result<Vec<tobj::Material>, tobj::LoadError>,
    /// The warnings of the MTL files.
    pub warnings: Vec<String>,
    /// The MTL files read.
    pub mtl_files: Vec<std::path::PathBuf>,
    /// The `s` statements.
    pub smoothing: Smoothing,
    /// Triangles after fan-splitting.
    pub triangles: u64,
    /// The chunks read.
    pub chunks: usize,
    /// The `l` and `p` statements skipped.
    pub skipped: (usize, usize),
}

/// Reads `bytes` (an OBJ file) in chunks of about `chunk_bytes`, or says
/// why tobj must: the reason names the line.
pub(super) fn load(
    bytes: &[u8],
    base_dir: &Path,
    options: &ObjOptions,
    chunk_bytes: usize,
) -> std::result::Result<Loaded, String> {
    let bytes = match bytes {
        [0xEF, 0xBB, 0xBF, rest @ ..] => rest,
        [0xFF, 0xFE, ..] | [0xFE, 0xFF, ..] => return Err("UTF-16 text".to_owned()),
        _ => bytes,
    };
    let chunks = split(bytes, chunk_bytes.max(1));
    let at = |lines: &[usize], k: usize, r: Refusal| {
        format!(
            "line {}: {}",
            lines[..k].iter().sum::<usize>() + r.line + 1,
            r.why
        )
    };
    let counted = map(&chunks, scan::count);
    let mut counts = Vec::with_capacity(chunks.len());
    let mut lines = Vec::with_capacity(chunks.len());
    for (k, c) in counted.into_iter().enumerate() {
        // Every chunk before the first refusal was counted: its line is
        // known.
        let c = c.map_err(|r| at(&lines, k, r))?;
        lines.push(c.lines);
        counts.push(c);
    }
    let total = counts.iter().fold(Counts::default(), |a, &c| a.then(c));
    if total.triangles > options.max_triangles {
        return Err(format!(
            "{} triangles, over the limit of {}",
            total.triangles, options.max_triangles
        ));
    }
    if total.v >= NONE as usize || total.vt >= NONE as usize || total.vn >= NONE as usize {
        return Err("more than 2^32 - 1 vertices".to_owned());
    }
    let mut positions = vec![DVec3::ZERO; total.v];
    let mut uvs = vec![Vec2::ZERO; total.vt];
    let mut normals = vec![Vec3::ZERO; total.vn];
    let mut jobs = Vec::with_capacity(chunks.len());
    {
        let (mut p, mut t, mut n) = (&mut positions[..], &mut uvs[..], &mut normals[..]);
        let mut before = Counts::default();
        for (chunk, &c) in chunks.iter().zip(&counts) {
            let (ph, pt) = std::mem::take(&mut p).split_at_mut(c.v);
            let (th, tt) = std::mem::take(&mut t).split_at_mut(c.vt);
            let (nh, nt) = std::mem::take(&mut n).split_at_mut(c.vn);
            (p, t, n) = (pt, tt, nt);
            let slots = Slots {
                positions: ph,
                uvs: th,
                normals: nh,
            };
            jobs.push((*chunk, before, c.triangles, slots));
            before = before.then(c);
        }
    }
    let parsed = map_owned(jobs, |(chunk, before, triangles, slots)| {
        scan::parse(chunk, before, triangles, slots)
    });
    let mut chunks_parsed = Vec::with_capacity(parsed.len());
    for (k, p) in parsed.into_iter().enumerate() {
        chunks_parsed.push(p.map_err(|r| at(&lines, k, r))?);
    }
    let log = super::mtl::MtlLog::default();
    let mut groups = std::collections::HashSet::new();
    for p in &mut chunks_parsed {
        groups.extend(std::mem::take(&mut p.groups));
    }
    let (meshes, materials) = build(
        chunks_parsed,
        Arrays {
            positions,
            uvs: &uvs,
            normals: &normals,
        },
        base_dir,
        &log,
    );
    Ok(Loaded {
        meshes,
        materials,
        warnings: log.warnings.into_inner(),
        mtl_files: log.files.into_inner(),
        smoothing: Smoothing {
            on: !groups.is_empty(),
            groups: groups.len(),
        },
        triangles: total.triangles,
        chunks: chunks.len(),
        skipped: (total.l, total.p),
    })
}

/// `bytes` cut into pieces of about `size` bytes, each ending at a line
/// end (or the end of the file).
fn split(bytes: &[u8], size: usize) -> Vec<&[u8]> {
    let mut out = Vec::with_capacity(bytes.len() / size + 1);
    let mut rest = bytes;
    while !rest.is_empty() {
        let end = match rest
            .get(size..)
            .and_then(|tail| memchr::memchr(b'\n', tail))
        {
            Some(k) => size + k + 1,
            None => rest.len(),
        };
        let (head, tail) = rest.split_at(end);
        out.push(head);
        rest = tail;
    }
    out
}

/// `f` over the chunks, in parallel where the crate may use threads.
fn map<T: Send>(chunks: &[&[u8]], f: impl Fn(&[u8]) -> T + Sync) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        chunks.par_iter().map(|c| f(c)).collect()
    }
    #[cfg(not(feature = "parallel"))]
    chunks.iter().map(|c| f(c)).collect()
}

/// `f` over owned jobs, in parallel where the crate may use threads.
fn map_owned<J: Send, T: Send>(jobs: Vec<J>, f: impl Fn(J) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        jobs.into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    jobs.into_iter().map(f).collect()
}

/// The file-wide arrays the corners index.
struct Arrays<'a> {
    positions: Vec<DVec3>,
    uvs: &'a [Vec2],
    normals: &'a [Vec3],
}

/// The meshes and materials of the parsed chunks, as tobj builds them
/// from the same statements.
fn build(
    chunks: Vec<Parsed>,
    arrays: Arrays<'_>,
    base_dir: &Path,
    log: &super::mtl::MtlLog,
) -> (Vec<Mesh>, Result<Vec<tobj::Material>, tobj::LoadError>) {
    let mut meshes = Vec::new();
    let mut builder = Builder::new(arrays.positions, arrays.uvs, arrays.normals);
    let mut materials = Materials::default();
    // tobj's current object and material; the validation pass's layout of
    // the object's last face.
    let mut name = "unnamed_object".to_owned();
    let mut material: Option<usize> = None;
    let mut layout: Option<(bool, bool)> = None;
    for chunk in chunks {
        let mut next = 0;
        for (at, event) in &chunk.events {
            builder.triangles(&chunk.corners[3 * next..3 * at]);
            next = *at;
            match event {
                Event::Object(object) => {
                    if builder.has_faces() {
                        meshes.push(builder.take(&name, material));
                    }
                    name.clone_from(object);
                    layout = None;
                }
                Event::Material(m) => {
                    let new = materials.map.get(m).copied();
                    if material != new && builder.has_faces() {
                        meshes.push(builder.take(&name, material));
                    }
                    material = new;
                }
                Event::Library(file) => {
                    materials.merge(super::mtl::load_mtl(base_dir, Path::new(file), log));
                }
                &Event::Layout(vt, vn) => {
                    // The validation pass starts an object of the same
                    // name here.
                    if layout.is_some_and(|l| l != (vt, vn)) && builder.has_faces() {
                        meshes.push(builder.take(&name, material));
                    }
                    layout = Some((vt, vn));
                }
            }
        }
        builder.triangles(&chunk.corners[3 * next..]);
    }
    meshes.push(builder.take_last(&name, material));
    let materials = materials.into_materials();
    let count = materials.as_ref().map_or(0, Vec::len);
    for mesh in &mut meshes {
        mesh.material = mesh.material.filter(|&k| k < count);
    }
    (meshes, materials)
}

/// tobj's merge of the material files an OBJ file names: later names
/// shadow earlier ones; an error is kept only when no file loads.
#[derive(Default)]
struct Materials {
    list: Vec<tobj::Material>,
    map: HashMap<String, usize>,
    error: Option<tobj::LoadError>,
}

impl Materials {
    fn merge(&mut self, loaded: tobj::MTLLoadResult) {
        match loaded {
            Ok((mut list, map)) => {
                let offset = self.list.len();
                self.list.append(&mut list);
                for (name, k) in map {
                    self.map.insert(name, k + offset);
                }
            }
            Err(e) => self.error = Some(e),
        }
    }

    fn into_materials(self) -> Result<Vec<tobj::Material>, tobj::LoadError> {
        match self.error {
            Some(e) if self.list.is_empty() => Err(e),
            _ => Ok(self.list),
        }
    }
}

/// A hasher for corner keys (three small integers): the keys are not
/// chosen by an adversary who could profit from collisions, and SipHash
/// cost tobj 7.5% of a load.
#[derive(Default)]
struct CornerHasher(u64);

impl Hasher for CornerHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.0 = (self.0.rotate_left(5) ^ u64::from_le_bytes(word))
                .wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// The mesh being built: its vertices are the distinct corners of its
/// triangles in order of first use (tobj's `single_index` meshes).
struct Builder<'a> {
    positions: Vec<DVec3>,
    uvs: &'a [Vec2],
    normals: &'a [Vec3],
    /// Per file-wide position, 1 + the mesh vertex of the first corner
    /// using it (0 when none does yet: the array starts as zeroed pages).
    first: Vec<u32>,
    /// The mesh vertices of the other corners sharing a position with an
    /// earlier one (texture seams, hard edges).
    others: HashMap<[u32; 3], u32, BuildHasherDefault<CornerHasher>>,
    /// Each mesh vertex's corner; the mesh's attributes are gathered from
    /// them when it is taken, into arrays of their final size.
    corners: Vec<[u32; 3]>,
    indices: Vec<[u32; 3]>,
}

impl<'a> Builder<'a> {
    fn new(positions: Vec<DVec3>, uvs: &'a [Vec2], normals: &'a [Vec3]) -> Self {
        Self {
            first: vec![0; positions.len()],
            positions,
            uvs,
            normals,
            others: HashMap::default(),
            corners: Vec::new(),
            indices: Vec::new(),
        }
    }

    fn has_faces(&self) -> bool {
        !self.indices.is_empty()
    }

    /// Adds the triangles of `corners` (three per triangle).
    fn triangles(&mut self, corners: &[[u32; 3]]) {
        self.indices.reserve(corners.len() / 3);
        for t in corners.chunks_exact(3) {
            let tri = [self.vertex(t[0]), self.vertex(t[1]), self.vertex(t[2])];
            self.indices.push(tri);
        }
    }

    /// The mesh vertex of `corner`, added when new.
    #[inline]
    fn vertex(&mut self, corner: [u32; 3]) -> u32 {
        let v = corner[0] as usize;
        let first = self.first[v];
        if first != 0 {
            if self.corners[first as usize - 1] == corner {
                return first - 1;
            }
            if let Some(&k) = self.others.get(&corner) {
                return k;
            }
        }
        let k = self.corners.len() as u32;
        if first == 0 {
            self.first[v] = k + 1;
        } else {
            self.others.insert(corner, k);
        }
        self.corners.push(corner);
        k
    }

    /// The mesh built so far, named `name` with `material`; the builder
    /// starts the next one.
    fn take(&mut self, name: &str, material: Option<usize>) -> Mesh {
        self.take_with(name, material, None)
    }

    /// [`Self::take`], with `positions` as the mesh's positions when given.
    fn take_with(
        &mut self,
        name: &str,
        material: Option<usize>,
        positions: Option<Vec<DVec3>>,
    ) -> Mesh {
        let corners = std::mem::take(&mut self.corners);
        for c in &corners {
            self.first[c[0] as usize] = 0;
        }
        self.others.clear();
        let with = |slot: usize| corners.first().is_some_and(|c| c[slot] != NONE);
        Mesh {
            name: name.to_owned(),
            positions: positions.unwrap_or_else(|| {
                corners
                    .iter()
                    .map(|c| self.positions[c[0] as usize])
                    .collect()
            }),
            normals: match with(2) {
                true => corners
                    .iter()
                    .map(|c| self.normals[c[2] as usize])
                    .collect(),
                false => Vec::new(),
            },
            uvs: match with(1) {
                true => corners.iter().map(|c| self.uvs[c[1] as usize]).collect(),
                false => Vec::new(),
            },
            colors: Vec::new(),
            indices: std::mem::take(&mut self.indices),
            material,
            triangle_materials: Vec::new(),
        }
    }

    /// The last mesh ([`Self::take`]), given the file-wide positions
    /// themselves when it uses each once, in file order (a single-object
    /// file written vertex by vertex, as scanners and converters write).
    fn take_last(mut self, name: &str, material: Option<usize>) -> Mesh {
        let in_order = self.corners.len() == self.positions.len()
            && self
                .corners
                .iter()
                .enumerate()
                .all(|(k, c)| c[0] as usize == k);
        if !in_order {
            return self.take(name, material);
        }
        let positions = std::mem::take(&mut self.positions);
        self.take_with(name, material, Some(positions))
    }
}
