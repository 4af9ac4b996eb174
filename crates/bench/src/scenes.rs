//! Where the benchmark's scenes come from: the bundled assets, the hard-case
//! generators of [`hider_testkit::hard_cases`], any OBJ the user names, and
//! the generated families of the scaling study.
//!
//! The scaling families follow the three axes of Sutherland, Sproull &
//! Schumacker, "A Characterization of Ten Hidden-Surface Algorithms"
//! (Computing Surveys 6(1), 1974): the number of polygons, their size on
//! screen (here: the resolution, which scales every polygon's pixel count),
//! and the depth complexity (how many surfaces lie over a pixel).

use std::path::{Path, PathBuf};

use hider_geom::Camera;
use hider_geom::glam::DVec3;
use hider_scene::{Material, Mesh, Scene, load_obj, procedural};
use hider_testkit::hard_cases;

/// Seed of the hard-case instances: fixed so that every run, shard and
/// machine benchmarks the same scenes.
pub const HARD_CASE_SEED: u64 = 1;

/// Which part of the benchmark a scene belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Group {
    /// A bundled OBJ under `assets/`.
    Asset,
    /// A hard-case generator.
    HardCase,
    /// An OBJ the user named.
    Obj,
    /// A generated scene of the scaling study.
    Scaling,
}

impl Group {
    /// Name used in files and tables.
    pub fn as_str(self) -> &'static str {
        match self {
            Group::Asset => "asset",
            Group::HardCase => "hard-case",
            Group::Obj => "obj",
            Group::Scaling => "scaling",
        }
    }
}

/// How to build a scene: kept as a recipe (not the scene itself) so a
/// matrix can be listed, filtered and sharded without loading anything.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Load this OBJ file.
    Obj(PathBuf),
    /// The hard case of this name in [`hard_cases::all`].
    HardCase(String),
    /// `procedural::uv_sphere(n)`: `2n(n-1)` triangles, about a third of
    /// the frame, depth complexity 2: the polygon-count axis.
    Sphere(u32),
    /// [`layers`]`(k)`: `k` stacked screen-filling layers of small
    /// triangles: the depth-complexity axis.
    Layers(u32),
    /// [`crate::precision::near_coplanar`]: two parallel surfaces `gap`
    /// (relative to their distance) apart, the camera's near/far ratio
    /// `ratio`: the depth-precision study.
    NearCoplanar {
        /// Gap between the surfaces over their distance from the eye.
        gap: f64,
        /// Near plane over far plane.
        ratio: f64,
    },
    /// A scene built in memory (tests, library users).
    Scene(Box<Scene>),
}

impl Source {
    /// Builds the scene.
    pub fn load(&self) -> anyhow::Result<Scene> {
        use anyhow::Context;
        Ok(match self {
            Source::Obj(path) => {
                load_obj(path).with_context(|| format!("loading {}", path.display()))?
            }
            Source::HardCase(name) => hard_cases::all(HARD_CASE_SEED)
                .into_iter()
                .find(|(n, _)| n == name)
                .map(|(_, s)| s)
                .with_context(|| format!("no hard case named {name}"))?,
            Source::Sphere(n) => procedural::uv_sphere(*n),
            Source::Layers(k) => layers(*k),
            Source::NearCoplanar { gap, ratio } => crate::precision::near_coplanar(*gap, *ratio),
            Source::Scene(s) => (**s).clone(),
        })
    }
}

/// Quads per side of each layer of [`layers`] (8 x 8 quads, 128 triangles).
pub const LAYER_GRID: u32 = 8;

/// Half the side of each layer, in world units.
const HALF_SIDE: f64 = 2.0;

/// `k` parallel layers facing the camera, each an 8 x 8 grid of quads (128
/// triangles) filling the view, stacked from far to near in drawing order
/// (the worst case for a depth buffer: every layer overwrites the last).
/// Every pixel centre inside the frame is covered `k` times: depth
/// complexity exactly `k`, the third axis of Sutherland et al.
pub fn layers(k: u32) -> Scene {
    let k = k.max(1);
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    let g = LAYER_GRID;
    let step = 2.0 * HALF_SIDE / f64::from(g);
    for layer in 0..k {
        // Far (z = -1) to near (z = 0), all within the fit camera's range;
        // layers are slightly larger than the view so that every pixel
        // centre is covered by each.
        let z = -1.0 + f64::from(layer) / f64::from(k);
        let base = positions.len() as u32;
        for j in 0..=g {
            for i in 0..=g {
                positions.push(DVec3::new(
                    -HALF_SIDE + step * f64::from(i),
                    -HALF_SIDE + step * f64::from(j),
                    z,
                ));
            }
        }
        let at = |i: u32, j: u32| base + j * (g + 1) + i;
        for j in 0..g {
            for i in 0..g {
                indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            name: format!("layers_{k}"),
            positions,
            indices,
            ..Mesh::default()
        },
        Some(Material {
            name: "layers".into(),
            diffuse: [0.6, 0.7, 0.8],
            ..Material::default()
        }),
    );
    // A camera close enough that the layers fill the frame: from z = 0.5
    // at 60 degrees the farthest layer (1.5 away) shows a half-height of
    // 1.5 tan 30 = 0.87, so a half side of 2 covers aspect ratios up to 2.
    scene.camera = Some(Camera::perspective(
        DVec3::new(0.0, 0.0, 0.5),
        DVec3::new(0.0, 0.0, -1.0),
        0.05,
        10.0,
    ));
    scene
}

/// Two crossing triangles that tell a correct depth from a linearly
/// interpolated camera depth at any resolution: one recedes steeply (its
/// linearly interpolated depth lags behind the true `1/w`-correct one in
/// its interior), the other faces the camera (no interpolation error), and
/// they cross in the middle of the first. The smallest scene on which
/// interpolating camera depth linearly (the error scratchapixel's
/// depth-buffer lesson warns of) shows.
pub fn linear_depth_probe() -> Scene {
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            name: "linear_depth_probe".into(),
            positions: vec![
                DVec3::new(-1.0, -1.0, 1.5),
                DVec3::new(1.0, -1.0, 1.5),
                DVec3::new(0.0, 1.0, -1.5),
                DVec3::new(-1.2, -1.2, 0.0),
                DVec3::new(1.2, -1.2, 0.0),
                DVec3::new(0.0, 1.2, 0.0),
            ],
            indices: vec![[0, 1, 2], [3, 4, 5]],
            ..Mesh::default()
        },
        None,
    );
    scene
}

/// The bundled OBJ files in `dir` and in its subfolders one level down (a
/// model that ships with its textures, like `spider/spider.obj`), sorted
/// by name, as `(name, path)`.
pub fn bundled_assets(dir: &Path) -> Vec<(String, PathBuf)> {
    let obj_files = |dir: &Path| -> Vec<PathBuf> {
        std::fs::read_dir(dir)
            .map(|entries| entries.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default()
    };
    let is_obj = |p: &Path| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("obj"));
    let mut paths = Vec::new();
    for path in obj_files(dir) {
        if path.is_dir() {
            paths.extend(obj_files(&path).into_iter().filter(|p| is_obj(p)));
        } else if is_obj(&path) {
            paths.push(path);
        }
    }
    let mut found: Vec<(String, PathBuf)> = paths
        .into_iter()
        .filter_map(|p| Some((p.file_stem()?.to_string_lossy().into_owned(), p)))
        .collect();
    found.sort();
    found
}

/// The names of the hard cases, in the generators' order.
pub fn hard_case_names() -> Vec<&'static str> {
    hard_cases::all(HARD_CASE_SEED)
        .into_iter()
        .map(|(n, _)| n)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_testkit::screen;

    #[test]
    fn bundled_assets_include_models_in_their_own_folders() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
        let names: Vec<String> = bundled_assets(&dir).into_iter().map(|(n, _)| n).collect();
        for expected in ["cube", "sphere", "spider"] {
            assert!(
                names.iter().any(|n| n == expected),
                "{expected} in {names:?}"
            );
        }
        assert!(names.windows(2).all(|w| w[0] <= w[1]), "sorted: {names:?}");
    }

    #[test]
    fn layers_cover_every_pixel_k_times() {
        for k in [1, 3] {
            let scene = layers(k);
            assert_eq!(
                scene.triangle_count() as u32,
                k * 2 * LAYER_GRID * LAYER_GRID
            );
            let screen = screen(&scene, 24, 16);
            let a = crate::analysis::analyse(&screen);
            assert_eq!(a.covered_pixels, 24 * 16);
            assert_eq!(a.fragments, u64::from(k) * 24 * 16);
        }
    }

    #[test]
    fn sources_load_and_unknown_hard_cases_are_errors() {
        assert!(Source::HardCase("cube".into()).load().is_ok());
        assert!(Source::HardCase("nope".into()).load().is_err());
        assert!(Source::Obj("/nonexistent/x.obj".into()).load().is_err());
        assert_eq!(
            Source::Sphere(8).load().unwrap().triangle_count(),
            2 * 8 * 7
        );
        assert!(!hard_case_names().is_empty());
    }
}
