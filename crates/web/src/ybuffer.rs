//! The Y-buffer (tinyrenderer's 2D lesson): segments in a plane, seen
//! from one side, rendered to a 1-pixel-high image whose depth buffer is
//! the "y-buffer". The project's z-buffer draws it: each segment is a
//! quad extruded along the axis the image collapses (world Y), seen by
//! an orthographic camera looking across the plane, so one image row is
//! one depth test per column.

use glam::DVec3;
use hider_scene::geom::Camera;
use hider_scene::{Frame, Hider, Material, Mesh, PrepareOptions, Scene, View, prepare};
use hider_zbuffer::{ZBuffer, ZBufferOptions};
use wasm_bindgen::prelude::*;

use crate::{JsResult, js};

/// Widest image (columns); the plane is as deep as the image is wide.
pub const MAX_WIDTH: u32 = 1024;

/// The segments' colours, in order (the lesson's red, green and blue).
pub const COLOURS: [[u8; 3]; 3] = [[220, 40, 40], [40, 170, 60], [50, 90, 220]];

/// The eye's distance in front of the plane's near edge (`y = 0`).
const EYE: f64 = 1.0;
/// The orthographic camera's near clip distance.
const NEAR: f64 = 0.5;

/// The 3D scene of `segments` (`x0 y0 x1 y1` each, in a `width` x
/// `width` plane: `x` the image column, `y` the distance from the
/// viewer's side) and the camera that renders it `width` x 1: segment `k`
/// is mesh `k`, a quad from `(x, -1, -y)` to `(x, 1, -y)` along it, two
/// triangles, primitives `2k` and `2k + 1`.
pub fn scene(segments: &[f64], width: u32) -> Result<(Scene, Camera), String> {
    if !segments.len().is_multiple_of(4) || segments.len() / 4 > COLOURS.len() {
        return Err(format!(
            "{} numbers: the Y-buffer takes up to {} segments of 4 (x0 y0 x1 y1)",
            segments.len(),
            COLOURS.len()
        ));
    }
    if width == 0 || width > MAX_WIDTH {
        return Err(format!("Y-buffer width {width}: 1 to {MAX_WIDTH} columns"));
    }
    let side = f64::from(width);
    if let Some(v) = segments.iter().find(|v| !(0.0..=side).contains(*v)) {
        return Err(format!("segment end {v}: 0 to {side} (the plane)"));
    }
    let mut s = Scene::default();
    for (k, seg) in segments.chunks(4).enumerate() {
        let (a, b) = ((seg[0], seg[1]), (seg[2], seg[3]));
        let positions = vec![
            DVec3::new(a.0, -1.0, -a.1),
            DVec3::new(b.0, -1.0, -b.1),
            DVec3::new(b.0, 1.0, -b.1),
            DVec3::new(a.0, 1.0, -a.1),
        ];
        let material = Material {
            name: format!("segment_{k}"),
            diffuse: COLOURS[k].map(|c| f32::from(c) / 255.0),
            ..Material::default()
        };
        s.push_mesh(
            Mesh {
                name: format!("segment_{k}"),
                positions,
                indices: vec![[0, 1, 2], [0, 2, 3]],
                ..Mesh::default()
            },
            Some(material),
        );
    }
    // Half height 0.5 and aspect `width`: the view is `width` wide, one
    // unit per column, and the row's centres lie at world `y = 0`.
    let camera = Camera::orthographic(
        DVec3::new(0.5 * side, 0.0, EYE),
        DVec3::new(0.5 * side, 0.0, 0.0),
        0.5,
        NEAR,
        EYE + side + 1.0,
    );
    Ok((s, camera))
}

/// The 1-pixel-high image of `segments` ([`scene`]) by the z-buffer:
/// per column the segment in front (`-1` for none) and its distance `y`
/// in the plane (the y-buffer, from the z-buffer's window depth; `-1`
/// for none).
pub fn render(segments: &[f64], width: u32) -> Result<(Vec<i32>, Vec<f64>), String> {
    let (scene, camera) = scene(segments, width)?;
    let view = View::new(camera, width, 1).map_err(|e| e.to_string())?;
    let screen = prepare(&scene, &view, &PrepareOptions::default()).map_err(|e| e.to_string())?;
    let mut frame = Frame::new(width, 1).map_err(|e| e.to_string())?;
    ZBuffer::new(ZBufferOptions::default())
        .render(&screen, &mut frame)
        .map_err(|e| e.to_string())?;
    let far = EYE + f64::from(width) + 1.0;
    let mut ids = Vec::with_capacity(width as usize);
    let mut ys = Vec::with_capacity(width as usize);
    for (&id, &z) in frame.ids.iter().zip(&frame.depth) {
        if id == hider_scene::NO_ID {
            ids.push(-1);
            ys.push(-1.0);
        } else {
            ids.push((id / 2) as i32);
            // Orthographic window depth is linear in the distance.
            ys.push(NEAR + f64::from(z) * (far - NEAR) - EYE);
        }
    }
    Ok((ids, ys))
}

/// The page's Y-buffer view (`new YBuffer()`, then `render`).
#[wasm_bindgen]
#[derive(Default)]
pub struct YBuffer {
    ids: Vec<i32>,
    ys: Vec<f64>,
}

#[wasm_bindgen]
impl YBuffer {
    /// Nothing rendered yet.
    #[wasm_bindgen(constructor)]
    pub fn new() -> YBuffer {
        YBuffer::default()
    }

    /// Segment `k`'s colour, RGB bytes.
    pub fn colour(k: usize) -> Vec<u8> {
        COLOURS.get(k).map(|c| c.to_vec()).unwrap_or_default()
    }

    /// Renders `segments` (`x0 y0 x1 y1` each, up to three, in a `width`
    /// x `width` plane) to `width` x 1 with the z-buffer.
    pub fn render(&mut self, segments: Vec<f64>, width: u32) -> JsResult<()> {
        (self.ids, self.ys) = render(&segments, width).map_err(js)?;
        Ok(())
    }

    /// Per column, the segment in front, -1 for none.
    pub fn segments(&self) -> Vec<i32> {
        self.ids.clone()
    }

    /// Per column, the y-buffer: the front segment's distance from the
    /// viewer's side, -1 for none.
    pub fn ybuffer(&self) -> Vec<f64> {
        self.ys.clone()
    }

    /// The image, RGBA bytes (black where no segment is seen).
    pub fn rgba(&self) -> Vec<u8> {
        self.ids
            .iter()
            .flat_map(|&id| {
                let c = usize::try_from(id).map_or([0, 0, 0], |k| COLOURS[k]);
                [c[0], c[1], c[2], 255]
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lesson's layout: each column shows the segment nearest the
    /// viewer there (worked out here from the segments' lines), and the
    /// y-buffer holds its distance.
    #[test]
    fn each_column_shows_the_nearest_segment() {
        let w = 64;
        // A slope from far-left to near-right, a flat one in front of it
        // on the left, and one on the right that crosses it.
        let segs = [
            4.0, 50.0, 60.0, 10.0, 2.0, 30.0, 28.0, 30.0, 36.0, 20.0, 62.0, 20.0,
        ];
        let (ids, ys) = render(&segs, w).unwrap();
        let mut seen = [0; 3];
        for x in 0..w as usize {
            let cx = x as f64 + 0.5;
            let mut best: Option<(f64, usize)> = None;
            for (k, s) in segs.chunks(4).enumerate() {
                let (lo, hi) = (s[0].min(s[2]), s[0].max(s[2]));
                if cx > lo && cx < hi {
                    let y = s[1] + (s[3] - s[1]) * (cx - s[0]) / (s[2] - s[0]);
                    if best.is_none_or(|b| y < b.0) {
                        best = Some((y, k));
                    }
                }
            }
            match best {
                Some((y, k)) => {
                    assert_eq!(ids[x], k as i32, "column {x}");
                    assert!((ys[x] - y).abs() < 1e-3, "column {x}: {} for {y}", ys[x]);
                    seen[k] += 1;
                }
                None => assert_eq!((ids[x], ys[x]), (-1, -1.0), "column {x}"),
            }
        }
        assert!(seen.iter().all(|&n| n > 3), "{seen:?}");
        let (scene, _) = scene(&segs, w).unwrap();
        assert_eq!(scene.triangle_count(), 6);
        assert!(render(&segs[..5], w).is_err());
        assert!(
            render(&[0.0, 0.0, 100.0, 0.0], w)
                .unwrap_err()
                .contains("100")
        );
    }
}
