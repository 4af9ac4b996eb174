//! What a prepared scene asks of a hider: its triangle count, how many
//! pixels it covers and how many surfaces lie over each (depth complexity),
//! the quantities Sutherland, Sproull & Schumacker (1974) express costs in.

use hider_scene::ScreenScene;

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
    use hider_scene::procedural;
    use hider_testkit::screen;

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
