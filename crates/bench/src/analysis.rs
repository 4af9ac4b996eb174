//! What a prepared scene asks of a hider: its triangle count, how many
//! pixels it covers and how many surfaces lie over each (depth complexity),
//! the quantities Sutherland, Sproull & Schumacker (1974) express costs in.

use glam::DVec3;
use hider_scene::procedural::SplitMix64;
use hider_scene::{Mesh, Scene, ScreenScene};

/// `count` random triangles overlapping in the cube `[-1, 1]^3`: each has
/// a centre uniform in the cube and corners `centre + reach (q - centre)`
/// for points `q` uniform in the cube. With `reach = 1` the corners are
/// uniform in the cube (the second outside tester's "random triangles in
/// a cube", where most pairs overlap on screen and a good share cross);
/// with `reach = k / sqrt(count)` the triangles shrink as they multiply,
/// so the pairs that overlap on screen grow linearly with `count` (the
/// family on which the analysis's work must grow linearly too).
pub fn overlapping_triangles(count: u32, reach: f64, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut point = || {
        DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        )
    };
    let mut positions = Vec::with_capacity(count as usize * 3);
    for _ in 0..count {
        let centre = point();
        for _ in 0..3 {
            positions.push(centre + (point() - centre) * reach);
        }
    }
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            name: format!("overlapping_{count}_{reach}"),
            positions,
            indices: (0..count).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            ..Mesh::default()
        },
        None,
    );
    scene
}

/// A star of `count` triangles around one vertex: the unit disk's fan
/// around the origin in the plane z = 0 (`lift = 0`, a cylinder cap), or a
/// cone with its apex at z = `lift` (the pole of a UV sphere). Every
/// triangle contains the centre, so bins at the centre list them all (the
/// family of docs/notes/2026-11-28-fan-pairs.md).
pub fn star_fan(count: u32, lift: f64) -> Scene {
    let mut scene = Scene::default();
    scene.push_mesh(hider_testkit::sheets::fan(count, lift), None);
    scene
}

/// A fan of `count` triangles around the origin whose rim alternates
/// between `z = pleat` and `z = -pleat`: steep pleats, whose triangles'
/// sectors overlap in every projection but the axis's.
pub fn pleated_fan(count: u32, pleat: f64) -> Scene {
    let mut mesh = hider_testkit::sheets::fan(count, 0.0);
    for (k, p) in mesh.positions.iter_mut().enumerate().skip(1) {
        p.z = if k % 2 == 0 { pleat } else { -pleat };
    }
    let mut scene = Scene::default();
    scene.push_mesh(mesh, None);
    scene
}

/// A book: `count` pages (triangles) sharing the spine from `(0, -1, 0)`
/// to `(0, 1, 0)`, their third corners at unit distance spread over a half
/// turn around it.
pub fn book(count: u32) -> Scene {
    let n = count.max(1);
    let mut positions = vec![DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)];
    positions.extend((0..n).map(|k| {
        let a = std::f64::consts::PI * (f64::from(k) + 0.5) / f64::from(n);
        DVec3::new(a.cos(), 0.0, a.sin())
    }));
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            name: "book".into(),
            positions,
            indices: (0..n).map(|k| [0, 1, 2 + k]).collect(),
            ..Mesh::default()
        },
        None,
    );
    scene
}

/// The size of the visibility problem a [`ScreenScene`] poses.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SceneAnalysis {
    /// Screen triangles after clipping.
    pub triangles: u64,
    /// Pixel centres covered by at least one triangle.
    pub covered_pixels: u64,
    /// (triangle, pixel centre) pairs with the centre covered: the
    /// fragments a depth buffer resolves.
    pub fragments: u64,
    /// (triangle, pixel) pairs in the triangles' pixel bounds: what a
    /// bounding-box rasteriser and the oracle test.
    pub pixel_tests: u64,
}

impl SceneAnalysis {
    /// Mean number of surfaces over a covered pixel centre (0 for an empty
    /// frame).
    pub fn depth_complexity(&self) -> f64 {
        if self.covered_pixels == 0 {
            0.0
        } else {
            self.fragments as f64 / self.covered_pixels as f64
        }
    }
}

/// Counts coverage with the shared exact edge functions (the same decision
/// every hider makes), so the numbers are the scene's, not an estimate.
/// Cost: one edge test per pixel of each triangle's bounds.
pub fn analyse(scene: &ScreenScene) -> SceneAnalysis {
    let vp = scene.viewport;
    let width = vp.width as usize;
    let mut count = vec![0u32; width * vp.height as usize];
    let mut a = SceneAnalysis {
        triangles: scene.tris.len() as u64,
        ..SceneAnalysis::default()
    };
    for tri in &scene.tris {
        tri.for_each_centre(vp, |i, j, covered| {
            a.pixel_tests += 1;
            if covered {
                count[j as usize * width + i as usize] += 1;
                a.fragments += 1;
            }
        });
    }
    a.covered_pixels = count.iter().filter(|&&c| c > 0).count() as u64;
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_plan::{AnalysisWork, RenderOptions, analyze};
    use hider_scene::procedural;
    use hider_testkit::screen;

    /// The analysis's pair work on `overlapping_triangles(count, reach)`
    /// at 256 x 256.
    fn work(count: u32, reach: f64) -> AnalysisWork {
        let scene = overlapping_triangles(count, reach, 7);
        let options = RenderOptions::default().with_size(256, 256);
        let fx = analyze(&scene, &options).unwrap();
        assert!(fx.intersections.certain && fx.cyclic_overlap.certain);
        fx.work
    }

    #[test]
    fn analysis_work_grows_linearly_when_the_overlaps_do() {
        // Triangles shrinking as 1/sqrt(N): overlapping pairs grow as N,
        // and so must the pairs the searches list and test (a return to
        // all pairs, or to bins each listing most of the scene, at least
        // quadruples per doubling).
        let w: Vec<AnalysisWork> = [500, 1000, 2000, 4000]
            .iter()
            .map(|&n| work(n, 3.0 / f64::from(n).sqrt()))
            .collect();
        for pair in w.windows(2) {
            let growth = pair[1].total() as f64 / pair[0].total() as f64;
            assert!(
                growth < 3.0,
                "doubling N multiplied the pair work by {growth:.2}: {:?} -> {:?}",
                pair[0],
                pair[1]
            );
        }
        assert!(w[0].overlap_tests > 500, "the family overlaps: {:?}", w[0]);
    }

    #[test]
    fn bins_list_few_pairs_beyond_those_whose_boxes_meet() {
        // Corners uniform in the cube: nearly every pair's boxes meet.
        // Bins of about one triangle each made every large triangle sit in
        // hundreds of them, listing each pair hundreds of times (work
        // growing as N^3: 2,000 such triangles took 5 s); coarser bins
        // list each pair a few times at most.
        for n in [200, 400] {
            let w = work(n, 1.0);
            let all = u64::from(n) * u64::from(n - 1) / 2;
            assert!(
                w.intersection_candidates <= 8 * all && w.overlap_candidates <= 8 * all,
                "{n} triangles, {all} pairs: {w:?}"
            );
        }
    }

    #[test]
    fn a_convex_closed_mesh_has_depth_complexity_two() {
        let scene = procedural::cube();
        let screen = screen(&scene, 48, 48);
        let a = analyse(&screen);
        assert_eq!(a.triangles, 12);
        assert!(a.covered_pixels > 100);
        // Every covered centre meets one front and one back face.
        assert_eq!(a.fragments, 2 * a.covered_pixels);
        assert_eq!(a.depth_complexity(), 2.0);
        assert!(a.pixel_tests >= a.fragments);
    }
}
