//! The scenes, camera and triangle lists of hider's tiled z-buffer
//! benchmark (`crates/bench/src/bin/fast_zbuffer_bench.rs`), built with
//! hider's own scene crate so every peer sees exactly what hider sees.
//!
//! - Scenes: the spider OBJ of the GL reference, UV spheres of 200 and 500
//!   segments, the random soup of 100,000 triangles (seed 1), under the
//!   benchmark's names (`spider`, `sphere 200`, `sphere 500`, `soup 100k`).
//! - Camera: [`View::for_scene`], i.e. the "fit" camera of
//!   `shared/gl-reference/README.md`; the matrix handed to a peer is
//!   `projection * view` computed in `f64` and rounded to `f32`, exactly as
//!   hider's GL-compatible front end (`PrepareOptions::gl_compatible`) does.
//! - Triangles: for each mesh, for each index triple, its three positions
//!   rounded to `f32`, in primitive order (a non-indexed triangle list).
//! - Coverage: the number of pixels hider's reference [`ZBuffer`] covers with
//!   the GL-compatible front end, which the peers' coverage is checked
//!   against.

use std::path::PathBuf;

use glam::Mat4;
use hider_scene::{
    Frame, Hider, NO_ID, PrepareOptions, Scene, View, load_obj, prepare, procedural,
};
use hider_zbuffer::ZBuffer;

/// A named scene of the benchmark.
pub struct NamedScene {
    /// The benchmark's name for it.
    pub name: &'static str,
    /// The scene itself.
    pub scene: Scene,
}

/// Where the spider OBJ of the GL reference lives (beside the project).
pub fn spider_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/gl-reference/models/spider.obj")
}

/// The benchmark's scenes, in its order. A spider that cannot be loaded is
/// left out with one line on standard error (when `quiet` is false); the
/// generated scenes cannot fail.
pub fn load_scenes(quiet: bool) -> Vec<NamedScene> {
    let mut scenes = Vec::new();
    let spider = spider_path();
    match load_obj(&spider) {
        Ok(scene) => scenes.push(NamedScene {
            name: "spider",
            scene,
        }),
        // hider's error names the file.
        Err(e) if !quiet => eprintln!("skipped the spider: {e}"),
        Err(_) => {}
    }
    scenes.push(NamedScene {
        name: "sphere 200",
        scene: procedural::uv_sphere(200),
    });
    scenes.push(NamedScene {
        name: "sphere 500",
        scene: procedural::uv_sphere(500),
    });
    scenes.push(NamedScene {
        name: "soup 100k",
        scene: procedural::random_soup(100_000, 1),
    });
    scenes
}

/// What a peer needs to draw one scene at one size.
pub struct Workload {
    /// The scene's name.
    pub name: &'static str,
    /// Image width and height in pixels.
    pub size: u32,
    /// `projection * view` of the fit camera, rounded to `f32`
    /// (column-major, as GL's `glLoadMatrixf` takes it).
    pub mvp: Mat4,
    /// Three positions per triangle, in primitive order.
    pub positions: Vec<[f32; 3]>,
}

impl Workload {
    /// The workload of `scene` at `size x size` with hider's camera.
    pub fn new(scene: &NamedScene, size: u32) -> Result<Self, String> {
        let view = View::for_scene(&scene.scene, size, size)
            .map_err(|e| format!("{} at {size}: {e}", scene.name))?;
        let view_matrix = view.camera.view_matrix();
        let projection = view.camera.projection_matrix(view.viewport.aspect());
        let mvp = (projection * view_matrix).as_mat4();
        let mut positions = Vec::with_capacity(scene.scene.triangle_count() * 3);
        for mesh in &scene.scene.meshes {
            for tri in &mesh.indices {
                for &i in tri {
                    positions.push(mesh.positions[i as usize].as_vec3().to_array());
                }
            }
        }
        Ok(Self {
            name: scene.name,
            size,
            mvp,
            positions,
        })
    }

    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.positions.len() / 3
    }
}

/// The number of pixels of a `size x size` image that hider's reference
/// z-buffer covers (GL-compatible `f32` front end, the one that reproduces
/// llvmpipe's coverage on the GL reference renders).
pub fn hider_coverage(scene: &NamedScene, size: u32) -> Result<u64, String> {
    let fail = |e: hider_scene::Error| format!("hider on {} at {size}: {e}", scene.name);
    let view = View::for_scene(&scene.scene, size, size).map_err(fail)?;
    let screen = prepare(&scene.scene, &view, &PrepareOptions::gl_compatible()).map_err(fail)?;
    let mut frame = Frame::new(size, size).map_err(fail)?;
    ZBuffer::default()
        .render(&screen, &mut frame)
        .map_err(fail)?;
    Ok(frame.ids.iter().filter(|&&id| id != NO_ID).count() as u64)
}

/// llvmpipe's 4x sample positions (Mesa's `lp_sample_pos_4x`, the
/// standard pattern of Direct3D and most GL drivers), in 1/256 pixel from
/// the pixel's top-left corner in hider's frame (y down: GL's offsets
/// from the bottom edge, flipped).
pub const MSAA_POSITIONS: [(i64, i64); 4] = [(96, 224), (224, 160), (32, 96), (160, 32)];

/// The samples covered at [`MSAA_POSITIONS`] by the triangles of hider's
/// GL-compatible front end, counted once per pixel and position whatever
/// the number of triangles covering it (the depth test decides colour,
/// not coverage): what a 4x multisampled llvmpipe frame covers, since it
/// snaps to the same 1/256 grid and uses the same fill rule.
pub fn hider_msaa_samples(scene: &NamedScene, size: u32) -> Result<u64, String> {
    let fail = |e: hider_scene::Error| format!("hider on {} at {size}: {e}", scene.name);
    let view = View::for_scene(&scene.scene, size, size).map_err(fail)?;
    let screen = prepare(&scene.scene, &view, &PrepareOptions::gl_compatible()).map_err(fail)?;
    let side = size as i64;
    let mut masks = vec![0u8; (side * side) as usize];
    for tri in &screen.tris {
        let edges = tri.edges();
        let xs = tri.v.map(|p| i64::from(p.x));
        let ys = tri.v.map(|p| i64::from(p.y));
        // Pixels whose samples may be inside: the box of the corners.
        let x0 = (xs.iter().min().unwrap_or(&0).div_euclid(256)).max(0);
        let x1 = (xs.iter().max().unwrap_or(&0).div_euclid(256)).min(side - 1);
        let y0 = (ys.iter().min().unwrap_or(&0).div_euclid(256)).max(0);
        let y1 = (ys.iter().max().unwrap_or(&0).div_euclid(256)).min(side - 1);
        for j in y0..=y1 {
            for (k, &(sx, sy)) in MSAA_POSITIONS.iter().enumerate() {
                // Edge values at the sample of the row's first pixel,
                // stepped by a whole pixel (exact integers).
                let y = j * 256 + sy;
                let mut e = edges.map(|f| f.eval(x0 * 256 + sx, y));
                let step = edges.map(|f| f.a * 256);
                for i in x0..=x1 {
                    if e.iter().all(|&v| v > 0) {
                        masks[(j * side + i) as usize] |= 1 << k;
                    }
                    for (v, s) in e.iter_mut().zip(&step) {
                        *v += s;
                    }
                }
            }
        }
    }
    Ok(masks.iter().map(|m| u64::from(m.count_ones())).sum())
}
