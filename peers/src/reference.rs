//! Reference renders for hider's GL agreement test: every case of a
//! manifest (`tests/data/gl/cases.txt`) drawn by llvmpipe, with the
//! visible triangle's index and GL's window depth per pixel written
//! losslessly as PNG.
//!
//! ```text
//! cargo run --release --manifest-path peers/Cargo.toml -- --reference tests/data/gl
//! ```
//!
//! Per case: the scene and camera are built with hider's own crate (the
//! manifest's syntax is documented in the data folder's README), the
//! matrix is `projection * view` in `f64` rounded to `f32` and loaded with
//! `glLoadMatrixf` (identity modelview), the triangles are drawn as one
//! `glDrawArrays(GL_TRIANGLES)` of `f32` positions in primitive order, each
//! with the flat colour `index + 1` as 24-bit RGB; depth test `GL_LESS`
//! against a 24-bit buffer cleared to 1.0, no culling, blending or
//! dithering, into a framebuffer object (`RGBA8` + `DEPTH_COMPONENT24`).
//! Read back with `glReadPixels` (colour as bytes, depth as `GL_FLOAT`),
//! rows flipped to top row first, and written as
//!
//! - `NAME.ids.png`: 24-bit RGB, `R + 256 G + 65536 B` = triangle index + 1,
//!   0 = background;
//! - `NAME.depth.png`: RGBA, the four little-endian bytes of the `f32`
//!   window depth (1.0 = background).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use glam::DVec3;
use hider_scene::geom::Camera;
use hider_scene::{Scene, View, load_obj, procedural};

use super::{
    GL_ARRAY_BUFFER, GL_BLEND, GL_COLOR_ATTACHMENT0, GL_COLOR_BUFFER_BIT, GL_CULL_FACE,
    GL_DEPTH_ATTACHMENT, GL_DEPTH_BUFFER_BIT, GL_DEPTH_COMPONENT24, GL_DEPTH_TEST, GL_DITHER,
    GL_FLAT, GL_FLOAT, GL_FRAMEBUFFER, GL_FRAMEBUFFER_COMPLETE, GL_LESS, GL_MODELVIEW,
    GL_PROJECTION, GL_RENDERBUFFER, GL_RGBA, GL_RGBA8, GL_TRIANGLES, GL_UNSIGNED_BYTE,
    GL_VERTEX_ARRAY, GLsizei, Llvmpipe,
};

const GL_COLOR_ARRAY: u32 = 0x8076;
const GL_DEPTH_COMPONENT: u32 = 0x1902;

/// One line of the manifest.
struct Case {
    name: String,
    size: u32,
    scene: String,
    camera: Vec<String>,
}

/// `--reference DIR` anywhere on the command line: renders every case of
/// `DIR/cases.txt` into `DIR` and returns the exit code; `None` without
/// that flag.
pub fn from_args() -> Option<ExitCode> {
    let args: Vec<String> = std::env::args().collect();
    let at = args.iter().position(|a| a == "--reference")?;
    let Some(dir) = args.get(at + 1) else {
        eprintln!("--reference needs a folder");
        return Some(ExitCode::from(2));
    };
    Some(match run(Path::new(dir)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    })
}

fn run(dir: &Path) -> Result<(), String> {
    let manifest = dir.join("cases.txt");
    let text =
        std::fs::read_to_string(&manifest).map_err(|e| format!("{}: {e}", manifest.display()))?;
    let cases = parse(&text).map_err(|e| format!("{}: {e}", manifest.display()))?;
    let mut gl = Llvmpipe::open()?;
    println!("{}", gl.describe());
    for case in &cases {
        let scene = load_scene(dir, &case.scene)?;
        let camera = match case.camera.first().map(String::as_str) {
            Some("fit") => None,
            _ => Some(look_at(&case.camera).map_err(|e| format!("{}: {e}", case.name))?),
        };
        let view = match camera {
            Some(c) => View::new(c, case.size, case.size),
            None => View::for_scene(&scene, case.size, case.size),
        }
        .map_err(|e| format!("{}: {e}", case.name))?;
        let (ids, depth) = draw(&mut gl, &scene, &view)?;
        let covered = ids.chunks(3).filter(|p| p != &[0, 0, 0]).count();
        write(dir, &case.name, case.size, ids, depth)?;
        println!(
            "{}: {} triangles at {}, {covered} pixels covered",
            case.name,
            scene.triangle_count(),
            case.size
        );
    }
    Ok(())
}

/// The manifest: one case per line, `NAME SIZE SCENE CAMERA...`; `#`
/// starts a comment.
fn parse(text: &str) -> Result<Vec<Case>, String> {
    let mut cases = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.len() < 4 {
            return Err(format!("line {}: expected NAME SIZE SCENE CAMERA", n + 1));
        }
        let size = words[1]
            .parse()
            .map_err(|_| format!("line {}: size `{}` is not a number", n + 1, words[1]))?;
        cases.push(Case {
            name: words[0].to_owned(),
            size,
            scene: words[2].to_owned(),
            camera: words[3..].iter().map(|w| (*w).to_owned()).collect(),
        });
    }
    Ok(cases)
}

/// `obj:FILE` (beside the manifest) or `sphere:N` (hider's UV sphere).
fn load_scene(dir: &Path, spec: &str) -> Result<Scene, String> {
    if let Some(file) = spec.strip_prefix("obj:") {
        let path: PathBuf = dir.join(file);
        return load_obj(&path).map_err(|e| e.to_string());
    }
    if let Some(n) = spec.strip_prefix("sphere:") {
        let n = n
            .parse()
            .map_err(|_| format!("scene `{spec}`: segments not a number"))?;
        return Ok(procedural::uv_sphere(n));
    }
    Err(format!("scene `{spec}` is neither obj:FILE nor sphere:N"))
}

/// `look EYE TARGET NEAR FAR`, points as `x,y,z`: a perspective camera
/// with +Y up and hider's default field of view.
fn look_at(words: &[String]) -> Result<Camera, String> {
    let point = |w: &str| -> Result<DVec3, String> {
        let v: Vec<f64> = w
            .split(',')
            .map(|c| c.parse().map_err(|_| format!("`{w}` is not x,y,z")))
            .collect::<Result<_, _>>()?;
        match v[..] {
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            _ => Err(format!("`{w}` is not x,y,z")),
        }
    };
    let number = |w: &str| {
        w.parse::<f64>()
            .map_err(|_| format!("`{w}` is not a number"))
    };
    match words {
        [look, eye, target, near, far] if look == "look" => Ok(Camera::perspective(
            point(eye)?,
            point(target)?,
            number(near)?,
            number(far)?,
        )),
        _ => Err(format!(
            "camera `{}` is neither fit nor look EYE TARGET NEAR FAR",
            words.join(" ")
        )),
    }
}

/// Draws `scene` through `view`; returns the id image (RGB bytes) and the
/// depth image (RGBA bytes of the f32), top row first.
fn draw(gl: &mut Llvmpipe, scene: &Scene, view: &View) -> Result<(Vec<u8>, Vec<u8>), String> {
    let size = view.viewport.width;
    let side = size as GLsizei;
    gl.bind_window(size)?;
    let mvp = (view.camera.projection_matrix(view.viewport.aspect()) * view.camera.view_matrix())
        .as_mat4();
    let (positions, colours) = triangle_list(scene);
    let n = size as usize * size as usize;
    let (mut rgba, mut depth) = (vec![0u8; 4 * n], vec![0f32; n]);
    let (mut fbo, mut rbs) = (0, [0; 2]);
    let g = &gl.gl;
    // SAFETY: the context is current on this thread; every pointer handed
    // to GL points to live memory of the size given (`positions` and
    // `colours` hold one entry per vertex drawn, `rgba` and `depth` one
    // pixel each of side x side), and stays alive until glFinish returns
    // and the read-backs are done.
    unsafe {
        (g.glGenRenderbuffers)(2, rbs.as_mut_ptr());
        (g.glBindRenderbuffer)(GL_RENDERBUFFER, rbs[0]);
        (g.glRenderbufferStorage)(GL_RENDERBUFFER, GL_RGBA8, side, side);
        (g.glBindRenderbuffer)(GL_RENDERBUFFER, rbs[1]);
        (g.glRenderbufferStorage)(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, side, side);
        (g.glGenFramebuffers)(1, &mut fbo);
        (g.glBindFramebuffer)(GL_FRAMEBUFFER, fbo);
        (g.glFramebufferRenderbuffer)(
            GL_FRAMEBUFFER,
            GL_COLOR_ATTACHMENT0,
            GL_RENDERBUFFER,
            rbs[0],
        );
        (g.glFramebufferRenderbuffer)(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rbs[1]);
        let status = (g.glCheckFramebufferStatus)(GL_FRAMEBUFFER);
        if status != GL_FRAMEBUFFER_COMPLETE {
            return Err(format!("framebuffer incomplete: 0x{status:04x}"));
        }
        (g.glViewport)(0, 0, side, side);
        (g.glMatrixMode)(GL_PROJECTION);
        (g.glLoadMatrixf)(mvp.to_cols_array().as_ptr());
        (g.glMatrixMode)(GL_MODELVIEW);
        (g.glLoadIdentity)();
        (g.glEnable)(GL_DEPTH_TEST);
        (g.glDepthFunc)(GL_LESS);
        (g.glDisable)(GL_CULL_FACE);
        (g.glDisable)(GL_BLEND);
        (g.glDisable)(GL_DITHER);
        (g.glShadeModel)(GL_FLAT);
        (g.glClearColor)(0.0, 0.0, 0.0, 0.0);
        (g.glClearDepth)(1.0);
        (g.glClear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        (g.glBindBuffer)(GL_ARRAY_BUFFER, 0);
        (g.glVertexPointer)(3, GL_FLOAT, 0, positions.as_ptr().cast());
        (g.glColorPointer)(3, GL_UNSIGNED_BYTE, 0, colours.as_ptr().cast());
        (g.glEnableClientState)(GL_VERTEX_ARRAY);
        (g.glEnableClientState)(GL_COLOR_ARRAY);
        (g.glDrawArrays)(GL_TRIANGLES, 0, positions.len() as GLsizei);
        (g.glFinish)();
        (g.glReadPixels)(
            0,
            0,
            side,
            side,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            rgba.as_mut_ptr().cast(),
        );
        (g.glReadPixels)(
            0,
            0,
            side,
            side,
            GL_DEPTH_COMPONENT,
            GL_FLOAT,
            depth.as_mut_ptr().cast(),
        );
        (g.glDisableClientState)(GL_COLOR_ARRAY);
        (g.glDisableClientState)(GL_VERTEX_ARRAY);
        (g.glBindFramebuffer)(GL_FRAMEBUFFER, 0);
        (g.glDeleteFramebuffers)(1, &fbo);
        (g.glDeleteRenderbuffers)(2, rbs.as_ptr());
    }
    gl.check("reference render")?;
    Ok(top_row_first(size as usize, &rgba, &depth))
}

/// Three `f32` positions per triangle in primitive order, each with the
/// flat colour `index + 1` as RGB bytes.
fn triangle_list(scene: &Scene) -> (Vec<[f32; 3]>, Vec<[u8; 3]>) {
    let mut positions = Vec::with_capacity(scene.triangle_count() * 3);
    let mut colours = Vec::with_capacity(scene.triangle_count() * 3);
    for (prim, m, t) in scene.triangles() {
        let mesh = &scene.meshes[m];
        let [r, g, b, _] = (prim + 1).to_le_bytes();
        for &i in &mesh.indices[t] {
            positions.push(mesh.positions[i as usize].as_vec3().to_array());
            colours.push([r, g, b]);
        }
    }
    (positions, colours)
}

/// GL's bottom-up rows, top row first: the ids as RGB bytes (alpha
/// dropped) and the depths as their little-endian bytes.
fn top_row_first(row: usize, rgba: &[u8], depth: &[f32]) -> (Vec<u8>, Vec<u8>) {
    let mut ids = Vec::with_capacity(3 * depth.len());
    let mut depth_bytes = Vec::with_capacity(4 * depth.len());
    for r in (0..row).rev() {
        for p in rgba[4 * r * row..4 * (r + 1) * row].chunks_exact(4) {
            ids.extend_from_slice(&p[..3]);
        }
        for d in &depth[r * row..(r + 1) * row] {
            depth_bytes.extend_from_slice(&d.to_le_bytes());
        }
    }
    (ids, depth_bytes)
}

/// Writes `NAME.ids.png` and `NAME.depth.png`.
fn write(dir: &Path, name: &str, size: u32, ids: Vec<u8>, depth: Vec<u8>) -> Result<(), String> {
    let fail = |p: &Path, e: image::ImageError| format!("{}: {e}", p.display());
    let path = dir.join(format!("{name}.ids.png"));
    image::RgbImage::from_raw(size, size, ids)
        .ok_or("id image of the wrong size")?
        .save(&path)
        .map_err(|e| fail(&path, e))?;
    let path = dir.join(format!("{name}.depth.png"));
    image::RgbaImage::from_raw(size, size, depth)
        .ok_or("depth image of the wrong size")?
        .save(&path)
        .map_err(|e| fail(&path, e))
}
