//! Arbitrary f32 triangles and cameras -> prepare -> every hider.
#![no_main]

mod common;

use hider::geom::glam::DVec3;
use hider::geom::{Camera, Projection};
use hider::scene::{Mesh, PrepareOptions, Scene, TransformPrecision, View, prepare};
use libfuzzer_sys::fuzz_target;

fn floats(data: &[u8]) -> Vec<f32> {
    data.chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 4 * 13 {
        return;
    }
    let f = floats(data);
    let v3 = |k: usize| DVec3::new(f[k].into(), f[k + 1].into(), f[k + 2].into());
    let camera = Camera {
        eye: v3(0),
        target: v3(3),
        up: v3(6),
        projection: if f[9].is_sign_negative() {
            Projection::Orthographic {
                half_height: f[10].abs().into(),
                near: f[11].into(),
                far: f[12].into(),
            }
        } else {
            Projection::Perspective {
                fovy_degrees: f[10].abs().into(),
                near: f[11].abs().into(),
                far: f[12].abs().into(),
            }
        },
    };
    let positions: Vec<DVec3> = f[13..].chunks_exact(3).take(16).map(|c| {
        DVec3::new(c[0].into(), c[1].into(), c[2].into())
    }).collect();
    let n = positions.len() as u32 / 3;
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            positions,
            indices: (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            ..Mesh::default()
        },
        None,
    );
    let (w, h) = (1 + data[0] as u32 % 16, 1 + data[1] as u32 % 16);
    let Ok(view) = View::new(camera, w, h) else {
        return;
    };
    let precision = if data[2] & 1 == 0 { TransformPrecision::F64 } else { TransformPrecision::F32 };
    let options = PrepareOptions::default().with_precision(precision);
    if let Ok(screen) = prepare(&scene, &view, &options) {
        common::render_all(&screen);
    }
});
