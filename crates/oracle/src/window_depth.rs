//! The textbook pixel-centre z-buffer, in `f64` on the snapped triangles'
//! window-depth planes: the plain brute force beside the ray cast.
//!
//! Where [`crate::RayCastOracle`] takes depth from camera-space planes, this
//! reference evaluates exactly the window-depth plane every pixel-centre
//! hider interpolates (`ScreenTri::depth` at `(i + 0.5, j + 0.5)`), so a
//! hider with `f64` depth must match its ids and depths bit for bit away
//! from ties. The window-depth gap to the runner-up tells ties apart.

use hider_scene::{NO_ID, ScreenScene};

use crate::nearest::{Candidate, EMPTY, Nearest};

/// Per pixel centre: the nearest primitive on the window-depth planes and
/// how far behind the runner-up is. Built by [`window_depth_reference`].
#[derive(Clone, Debug, PartialEq)]
pub struct WindowDepthReference {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The nearest primitive per pixel, row-major ([`NO_ID`] for
    /// background). At exactly equal depths the lower id wins: what a LESS
    /// z-buffer drawing in primitive order keeps.
    pub ids: Vec<u32>,
    /// The window depth of that primitive's plane at the pixel centre, in
    /// `f64` (1.0 for background).
    pub depth: Vec<f64>,
    /// Window depth of the nearest *other* primitive minus [`Self::depth`]
    /// (`f64::INFINITY` when fewer than two primitives cover the centre).
    /// Pieces of one clipped primitive share a plane and count once.
    pub gap: Vec<f64>,
}

impl WindowDepthReference {
    /// Whether pixel `k`'s two nearest primitives are less than
    /// `tolerance` apart in window depth (a covered pixel only).
    pub fn is_tie(&self, k: usize, tolerance: f64) -> bool {
        self.ids[k] != NO_ID && self.gap[k] < tolerance
    }

    /// The depths as a frame stores them (`f32`).
    pub fn depth_f32(&self) -> Vec<f32> {
        self.depth.iter().map(|&d| d as f32).collect()
    }

    /// Number of covered pixels.
    pub fn covered_count(&self) -> usize {
        self.ids.iter().filter(|&&id| id != NO_ID).count()
    }
}

/// The textbook z-buffer of `scene` at every pixel centre: coverage by the
/// shared exact edge functions, depth from each triangle's window-depth
/// plane in `f64`, the nearest kept (lower id on exact ties). See the
/// module documentation.
///
/// ```
/// use hider_oracle::{RayCastOracle, window_depth_reference};
/// use hider_scene::{PrepareOptions, View, prepare, procedural};
///
/// let scene = procedural::cube();
/// let screen = prepare(&scene, &View::for_scene(&scene, 24, 24)?, &PrepareOptions::default())?;
/// let brute = window_depth_reference(&screen);
/// assert_eq!(brute.ids, RayCastOracle::default().evaluate(&screen).ids);
/// # Ok::<(), hider_scene::Error>(())
/// ```
pub fn window_depth_reference(scene: &ScreenScene) -> WindowDepthReference {
    let vp = scene.viewport;
    let w = vp.width as usize;
    let mut nearest: Vec<Nearest> = vec![EMPTY; vp.pixel_count()];
    for tri in &scene.tris {
        tri.for_each_centre(vp, |i, j, covered| {
            if covered {
                let c = Candidate {
                    tri: 0,
                    prim: tri.prim,
                    key: tri.depth.at_pixel(i, j),
                };
                nearest[j as usize * w + i as usize].offer(c, |a, b| a.key.total_cmp(&b.key));
            }
        });
    }
    let ids = nearest.iter().map(|n| n.first.prim).collect();
    let depth = nearest
        .iter()
        .map(|n| {
            if n.first.prim == NO_ID {
                1.0
            } else {
                n.first.key
            }
        })
        .collect();
    let gap = nearest
        .iter()
        .map(|n| {
            if n.second.prim == NO_ID {
                f64::INFINITY
            } else {
                n.second.key - n.first.key
            }
        })
        .collect();
    WindowDepthReference {
        width: vp.width,
        height: vp.height,
        ids,
        depth,
        gap,
    }
}
