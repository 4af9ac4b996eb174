//! The benchmark matrix: scenes x resolutions x hiders (each registry entry
//! is one hider with one set of options), what a run selects from it, and
//! how it is split into shards.
//!
//! A *case* is one scene at one resolution; the oracle is evaluated once
//! per case and shared by every hider of the case, which is also why shards
//! split the matrix by case, never inside one.

use std::path::PathBuf;

use anyhow::{Result, bail};

use crate::scenes::{self, Group, Source};
use hider_plan::registry::{self, Entry};
use hider_scene::CameraOverrides;

/// The study a case belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Study {
    /// Real-size work: the bundled models and generated scenes at 1024 x
    /// 1024, timed over the whole pipeline (front end and render, the span
    /// a frame loop waits for) and scored against the oracle: the report's
    /// answer to what accuracy costs in time.
    RealSize,
    /// Two nearly coplanar surfaces per depth format: how often the
    /// farther one shows as their gap and the near/far ratio shrink.
    DepthPrecision,
    /// Small scenes scored against the oracle: what each hider gets wrong.
    Accuracy,
    /// Cost as the number of polygons grows (UV spheres, fixed resolution).
    Polygons,
    /// Cost as the resolution (every polygon's size in pixels) grows.
    Resolution,
    /// Cost as the depth complexity grows (stacked layers).
    DepthComplexity,
}

impl Study {
    /// Every study, in report order.
    pub const ALL: [Study; 6] = [
        Study::RealSize,
        Study::DepthPrecision,
        Study::Accuracy,
        Study::Polygons,
        Study::Resolution,
        Study::DepthComplexity,
    ];

    /// The scaling studies (time along one axis), in report order.
    pub const SCALING: [Study; 3] = [Study::Polygons, Study::Resolution, Study::DepthComplexity];

    /// Name used on the command line and in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Study::RealSize => "real-size",
            Study::DepthPrecision => "depth-precision",
            Study::Accuracy => "accuracy",
            Study::Polygons => "polygons",
            Study::Resolution => "resolution",
            Study::DepthComplexity => "depth-complexity",
        }
    }

    /// The study of this name.
    pub fn parse(name: &str) -> Option<Study> {
        Study::ALL.into_iter().find(|s| s.as_str() == name)
    }
}

/// One scene at one resolution.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The study it belongs to.
    pub study: Study,
    /// Scene name (file stem, hard-case name, `sphere_N`, `layers_K`).
    pub scene: String,
    /// Where the scene comes from.
    pub group: Group,
    /// How to build it.
    pub source: Source,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl Case {
    /// `scene@WxH`, unique within a matrix up to the study.
    pub fn label(&self) -> String {
        format!("{}@{}x{}", self.scene, self.width, self.height)
    }
}

/// What to put in the matrix. `Default` is the default matrix of
/// `hider bench`: the bundled models plus generated spheres and layers at
/// 1024 x 1024 (real size), the depth-precision sweep, every bundled asset
/// and hard case at 64 x 64 and 256 x 256 for accuracy, plus the three
/// scaling sweeps at 256 x 256 (and 64 to 1024 for resolution).
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixOptions {
    /// Folder of the bundled OBJ scenes.
    pub assets_dir: PathBuf,
    /// Further OBJ files to benchmark (accuracy study).
    pub objs: Vec<PathBuf>,
    /// Scenes built in memory, by name, benchmarked like user OBJs
    /// (accuracy study, group `obj`, always selected).
    pub extra_scenes: Vec<(String, hider_scene::Scene)>,
    /// Scene selectors (see [`matches()`]); empty selects every scene.
    pub scenes: Vec<String>,
    /// Hider selectors over registry names (see [`matches()`]); empty
    /// selects every registered hider.
    pub algos: Vec<String>,
    /// Studies to run.
    pub studies: Vec<Study>,
    /// Image size `(width, height)` of the real-size study.
    pub real_size: (u32, u32),
    /// UV sphere segment counts of the real-size study's generated spheres
    /// (`2n(n-1)` triangles: 64 gives 8,064; 200 is the 79,600-triangle
    /// sphere of the fast z-buffer's comparison with llvmpipe).
    pub real_spheres: Vec<u32>,
    /// Layer counts of the real-size study's stacked layers.
    pub real_layers: Vec<u32>,
    /// Gaps between the two surfaces of the depth-precision study,
    /// relative to their distance from the eye.
    pub precision_gaps: Vec<f64>,
    /// Near/far ratios of the depth-precision study's camera.
    pub precision_ratios: Vec<f64>,
    /// Square size of the depth-precision study.
    pub precision_size: u32,
    /// Image sizes `(width, height)` of the accuracy study.
    pub sizes: Vec<(u32, u32)>,
    /// The camera of the user's scenes ([`Group::Obj`]: `--obj` files and
    /// [`Self::extra_scenes`]) in every study; unset keeps each scene's
    /// own camera or the fit camera.
    pub obj_camera: CameraOverrides,
    /// UV sphere segment counts of the polygon study (`2n(n-1)` triangles).
    pub polygon_steps: Vec<u32>,
    /// Square sizes of the resolution study.
    pub resolution_steps: Vec<u32>,
    /// Segment count of the resolution study's sphere.
    pub resolution_sphere: u32,
    /// Layer counts of the depth-complexity study.
    pub depth_steps: Vec<u32>,
    /// Square size of the polygon and depth-complexity studies.
    pub scaling_size: u32,
}

impl Default for MatrixOptions {
    fn default() -> Self {
        Self {
            assets_dir: default_assets_dir(),
            objs: Vec::new(),
            extra_scenes: Vec::new(),
            scenes: Vec::new(),
            algos: Vec::new(),
            studies: Study::ALL.to_vec(),
            real_size: (1024, 1024),
            real_spheres: vec![64, 200],
            real_layers: vec![8],
            precision_gaps: vec![1e-2, 1e-3, 1e-4, 1e-5, 1e-6],
            precision_ratios: vec![1e-2, 1e-3, 1e-4, 1e-5],
            precision_size: 128,
            sizes: vec![(64, 64), (256, 256)],
            obj_camera: CameraOverrides::default(),
            polygon_steps: vec![8, 16, 32, 64, 128, 256],
            resolution_steps: vec![64, 128, 256, 512, 1024],
            resolution_sphere: 32,
            depth_steps: vec![1, 2, 4, 8, 16, 32],
            scaling_size: 256,
        }
    }
}

impl MatrixOptions {
    /// Sets [`Self::scenes`].
    pub fn with_scenes(mut self, scenes: Vec<String>) -> Self {
        self.scenes = scenes;
        self
    }

    /// Sets [`Self::algos`].
    pub fn with_algos(mut self, algos: Vec<String>) -> Self {
        self.algos = algos;
        self
    }

    /// Sets [`Self::studies`].
    pub fn with_studies(mut self, studies: Vec<Study>) -> Self {
        self.studies = studies;
        self
    }

    /// Sets [`Self::sizes`] to squares of these sides.
    pub fn with_sizes(mut self, sizes: Vec<u32>) -> Self {
        self.sizes = sizes.into_iter().map(|s| (s, s)).collect();
        self
    }

    /// Sets [`Self::sizes`] to these `(width, height)` pairs.
    pub fn with_image_sizes(mut self, sizes: Vec<(u32, u32)>) -> Self {
        self.sizes = sizes;
        self
    }

    /// Sets [`Self::obj_camera`].
    pub fn with_obj_camera(mut self, camera: CameraOverrides) -> Self {
        self.obj_camera = camera;
        self
    }

    /// The smallest accuracy size (by pixel count), where the hard cases'
    /// contact sheets are drawn.
    pub fn smallest_size(&self) -> Option<(u32, u32)> {
        self.sizes
            .iter()
            .copied()
            .min_by_key(|&(w, h)| u64::from(w) * u64::from(h))
    }

    /// Adds a scene built in memory (see [`Self::extra_scenes`]).
    pub fn with_scene(mut self, name: &str, scene: hider_scene::Scene) -> Self {
        self.extra_scenes.push((name.to_owned(), scene));
        self
    }

    /// Sets [`Self::objs`].
    pub fn with_objs(mut self, objs: Vec<PathBuf>) -> Self {
        self.objs = objs;
        self
    }
}

/// `assets/` of the current folder when there is one (a checkout's root),
/// else the workspace's own `assets/` this crate was built from.
pub fn default_assets_dir() -> PathBuf {
    let here = PathBuf::from("assets");
    if here.is_dir() {
        here
    } else {
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets"))
    }
}

/// Whether `name` (in `group`) is picked by `selector`: the exact name, a
/// group name (`asset`, `hard-case`, `obj`, `scaling`), or a pattern with
/// `*` wildcards (`zbuffer*`, `*fan`).
pub fn matches(selector: &str, name: &str, group: Option<&str>) -> bool {
    if Some(selector) == group {
        return true;
    }
    let parts: Vec<&str> = selector.split('*').collect();
    if parts.len() == 1 {
        return selector == name;
    }
    let mut rest = name;
    for (k, part) in parts.iter().enumerate() {
        if k == 0 {
            let Some(r) = rest.strip_prefix(part) else {
                return false;
            };
            rest = r;
        } else if k == parts.len() - 1 {
            return rest.ends_with(part);
        } else if let Some(at) = rest.find(part) {
            rest = &rest[at + part.len()..];
        } else {
            return false;
        }
    }
    true
}

fn selected(selectors: &[String], name: &str, group: Option<&str>) -> bool {
    selectors.is_empty() || selectors.iter().any(|s| matches(s, name, group))
}

/// The registry entries the options select, in registry order. Errors if
/// a selector picks nothing (a typo should not silently shrink a sweep).
pub fn select_hiders(options: &MatrixOptions) -> Result<Vec<Entry>> {
    let all = registry::all();
    for s in &options.algos {
        if !all.iter().any(|e| matches(s, e.name, None)) {
            let names: Vec<&str> = all.iter().map(|e| e.name).collect();
            bail!("no hider matches '{s}' (registered: {})", names.join(", "));
        }
    }
    Ok(all
        .into_iter()
        .filter(|e| selected(&options.algos, e.name, None))
        .collect())
}

/// The cases the options select, in a fixed order (study, then scene, then
/// size) so that shards of the same matrix agree on indices.
pub fn build_cases(options: &MatrixOptions) -> Result<Vec<Case>> {
    let mut all = Vec::new();
    for &study in &options.studies {
        let s = options.scaling_size;
        match study {
            Study::RealSize => real_size_cases(options, &mut all),
            Study::DepthPrecision => {
                for &gap in &options.precision_gaps {
                    for &ratio in &options.precision_ratios {
                        let source = Source::NearCoplanar { gap, ratio };
                        let size = options.precision_size;
                        let scene = crate::precision::scene_name(gap, ratio);
                        all.push(square(study, scene, Group::Scaling, source, size));
                    }
                }
            }
            Study::Accuracy => {
                for (name, group, source) in accuracy_scenes(options) {
                    for &size in &options.sizes {
                        all.push(sized(study, name.clone(), group, source.clone(), size));
                    }
                }
            }
            Study::Polygons => {
                for &n in &options.polygon_steps {
                    let scene = format!("sphere_{n}");
                    all.push(square(study, scene, Group::Scaling, Source::Sphere(n), s));
                }
            }
            Study::Resolution => {
                let n = options.resolution_sphere;
                for &s in &options.resolution_steps {
                    let scene = format!("sphere_{n}");
                    all.push(square(study, scene, Group::Scaling, Source::Sphere(n), s));
                }
            }
            Study::DepthComplexity => {
                for &k in &options.depth_steps {
                    let scene = format!("layers_{k}");
                    all.push(square(study, scene, Group::Scaling, Source::Layers(k), s));
                }
            }
        }
    }
    // User OBJs are always kept: naming one is selecting it.
    let cases: Vec<Case> = all
        .into_iter()
        .filter(|c| {
            c.group == Group::Obj || selected(&options.scenes, &c.scene, Some(c.group.as_str()))
        })
        .collect();
    for s in &options.scenes {
        if !cases
            .iter()
            .any(|c| matches(s, &c.scene, Some(c.group.as_str())))
        {
            bail!("no scene matches '{s}' in the selected studies");
        }
    }
    for c in &cases {
        hider_scene::view::check_image_size(c.width, c.height)?;
    }
    Ok(cases)
}

/// Bundled assets with fewer triangles than this are demonstrations of one
/// hard case (two crossing triangles, a cycle of three), not models: the
/// real-size study leaves them to the accuracy study, where they are.
pub const REAL_MODEL_TRIANGLES: usize = 100;

/// Whether a bundled asset is a model for the real-size study: at least
/// [`REAL_MODEL_TRIANGLES`] triangles (an asset that does not load is
/// kept, so that its run reports the error).
fn is_real_model(source: &Source) -> bool {
    source
        .load()
        .map_or(true, |scene| scene.triangle_count() >= REAL_MODEL_TRIANGLES)
}

/// The real-size cases: the bundled models and every user OBJ, then the
/// generated spheres and layers, at the real size.
fn real_size_cases(options: &MatrixOptions, all: &mut Vec<Case>) {
    let (study, s) = (Study::RealSize, options.real_size);
    for (name, group, source) in accuracy_scenes(options) {
        let keep = match group {
            Group::HardCase => false,
            Group::Asset => is_real_model(&source),
            Group::Obj | Group::Scaling => true,
        };
        if keep {
            all.push(sized(study, name, group, source, s));
        }
    }
    for &n in &options.real_spheres {
        let scene = format!("sphere_{n}");
        all.push(sized(study, scene, Group::Scaling, Source::Sphere(n), s));
    }
    for &k in &options.real_layers {
        let scene = format!("layers_{k}");
        all.push(sized(study, scene, Group::Scaling, Source::Layers(k), s));
    }
}

/// A case of `size` x `size` pixels.
fn square(study: Study, scene: String, group: Group, source: Source, size: u32) -> Case {
    sized(study, scene, group, source, (size, size))
}

/// A case of `width` x `height` pixels.
fn sized(study: Study, scene: String, group: Group, source: Source, size: (u32, u32)) -> Case {
    Case {
        study,
        scene,
        group,
        source,
        width: size.0,
        height: size.1,
    }
}

/// The scenes of the accuracy study, as `(name, group, source)`: bundled
/// assets, hard cases, the user's OBJ files, then the scenes built in
/// memory.
fn accuracy_scenes(options: &MatrixOptions) -> Vec<(String, Group, Source)> {
    let mut scenes: Vec<(String, Group, Source)> = Vec::new();
    // Files keep their extension in the name (`cube.obj`), so they never
    // clash with a generator of the same name.
    for (name, path) in scenes::bundled_assets(&options.assets_dir) {
        scenes.push((format!("{name}.obj"), Group::Asset, Source::Obj(path)));
    }
    for name in scenes::hard_case_names() {
        scenes.push((name.into(), Group::HardCase, Source::HardCase(name.into())));
    }
    for path in &options.objs {
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into(),
        );
        scenes.push((name, Group::Obj, Source::Obj(path.clone())));
    }
    for (name, scene) in &options.extra_scenes {
        scenes.push((
            name.clone(),
            Group::Obj,
            Source::Scene(Box::new(scene.clone())),
        ));
    }
    scenes
}

/// One part of a sweep split across machines: shard `index` (1-based) of
/// `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, 1 to `count`.
    pub index: u32,
    /// How many shards.
    pub count: u32,
}

impl Default for Shard {
    fn default() -> Self {
        Self { index: 1, count: 1 }
    }
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// Parses `i/n` with `1 <= i <= n`.
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("shard '{s}' is not of the form i/n"))?;
        let index: u32 = i
            .trim()
            .parse()
            .map_err(|_| format!("shard index '{i}' is not a number"))?;
        let count: u32 = n
            .trim()
            .parse()
            .map_err(|_| format!("shard count '{n}' is not a number"))?;
        if count == 0 || index == 0 || index > count {
            return Err(format!("shard {index}/{count}: need 1 <= i <= n"));
        }
        Ok(Self { index, count })
    }
}

impl Shard {
    /// Whether case number `case` (its position in [`build_cases`]) is in
    /// this shard: round-robin, so every shard gets a mix of small and
    /// large cases.
    pub fn contains(&self, case: usize) -> bool {
        case % self.count as usize == (self.index - 1) as usize
    }

    /// The cases of this shard, with their matrix positions.
    pub fn select(&self, cases: &[Case]) -> Vec<(usize, Case)> {
        cases
            .iter()
            .enumerate()
            .filter(|(k, _)| self.contains(*k))
            .map(|(k, c)| (k, c.clone()))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn selectors_match_names_groups_and_wildcards() {
        assert!(matches("zbuffer", "zbuffer", None));
        assert!(!matches("zbuffer", "zbuffer-f64", None));
        assert!(matches("zbuffer*", "zbuffer-f64", None));
        assert!(matches("*fan", "near_degenerate_fan", None));
        assert!(matches("*coplanar*", "near_coplanar_far", None));
        assert!(!matches("*coplanar*", "cube", None));
        assert!(matches("hard-case", "cube", Some("hard-case")));
        assert!(!matches("asset", "cube", Some("hard-case")));
    }

    #[test]
    fn selection_filters_and_typos_are_errors() {
        let o = MatrixOptions {
            assets_dir: "/nonexistent".into(),
            ..MatrixOptions::default()
        }
        .with_studies(vec![Study::Accuracy])
        .with_scenes(vec!["cube".into(), "*fan".into()])
        .with_sizes(vec![16, 32]);
        let cases = build_cases(&o).unwrap();
        let names: Vec<String> = cases.iter().map(Case::label).collect();
        assert_eq!(
            names,
            // Generator order, then size.
            [
                "near_degenerate_fan@16x16",
                "near_degenerate_fan@32x32",
                "fan@16x16",
                "fan@32x32",
                "cube@16x16",
                "cube@32x32",
            ]
        );
        assert!(build_cases(&o.clone().with_scenes(vec!["nope".into()])).is_err());
        assert!(build_cases(&o.clone().with_sizes(vec![0])).is_err());
        let hiders = select_hiders(&o.clone().with_algos(vec!["zbuffer*".into()])).unwrap();
        assert!(!hiders.is_empty() && hiders.iter().all(|e| e.name.starts_with("zbuffer")));
        assert_eq!(select_hiders(&o).unwrap().len(), registry::all().len());
        assert!(select_hiders(&o.with_algos(vec!["zbufer".into()])).is_err());
    }

    #[test]
    fn default_matrix_has_every_study_and_hard_case() {
        let cases = build_cases(&MatrixOptions::default()).unwrap();
        for study in Study::ALL {
            assert!(cases.iter().any(|c| c.study == study), "{study:?}");
        }
        for name in scenes::hard_case_names() {
            assert!(cases.iter().any(|c| c.scene == name), "{name}");
        }
    }

    #[test]
    fn shards_partition_the_cases() {
        let cases = build_cases(&MatrixOptions::default()).unwrap();
        for n in 1..=4u32 {
            let mut seen: Vec<usize> = (1..=n)
                .flat_map(|i| Shard { index: i, count: n }.select(&cases))
                .map(|(k, _)| k)
                .collect();
            seen.sort_unstable();
            assert_eq!(seen, (0..cases.len()).collect::<Vec<_>>());
        }
        assert_eq!("2/3".parse::<Shard>(), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/3", "4/3", "1/0", "x/2", "3"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
