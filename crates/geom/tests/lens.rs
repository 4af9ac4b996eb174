//! Off-axis cameras: a [`Lens`] projects as `glFrustum` and `glOrtho` do,
//! and pinhole [`Intrinsics`] put a world point at the pixel `K` gives it.

use glam::{DMat3, DMat4, DVec2, DVec3, DVec4};
use hider_geom::{Camera, Intrinsics, Lens, Projection, Viewport};

/// `glFrustum(left, right, bottom, top, near, far)`, as the OpenGL 2.1
/// reference pages write it.
fn gl_frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> DMat4 {
    DMat4::from_cols_array_2d(&[
        [2.0 * n / (r - l), 0.0, 0.0, 0.0],
        [0.0, 2.0 * n / (t - b), 0.0, 0.0],
        [
            (r + l) / (r - l),
            (t + b) / (t - b),
            -(f + n) / (f - n),
            -1.0,
        ],
        [0.0, 0.0, -2.0 * f * n / (f - n), 0.0],
    ])
}

/// `glOrtho(left, right, bottom, top, near, far)`.
fn gl_ortho(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> DMat4 {
    DMat4::from_cols_array_2d(&[
        [2.0 / (r - l), 0.0, 0.0, 0.0],
        [0.0, 2.0 / (t - b), 0.0, 0.0],
        [0.0, 0.0, -2.0 / (f - n), 0.0],
        [
            -(r + l) / (r - l),
            -(t + b) / (t - b),
            -(f + n) / (f - n),
            1.0,
        ],
    ])
}

/// Every entry of `a` within `rel` of `b`'s (relative to the largest
/// entry of its column, so that zeros compare with a scale).
fn assert_close(a: DMat4, b: DMat4, rel: f64) {
    for c in 0..4 {
        let scale = b.col(c).abs().max_element().max(1.0);
        let gap = (a.col(c) - b.col(c)).abs().max_element();
        assert!(
            gap <= rel * scale,
            "column {c}: {:?} vs {:?}",
            a.col(c),
            b.col(c)
        );
    }
}

/// The intrinsics of a few cameras: centred, off-centre both ways,
/// non-square pixels, a principal point outside the image.
const CASES: [(f64, f64, f64, f64, u32, u32); 5] = [
    (100.0, 100.0, 32.0, 24.0, 64, 48),
    (525.0, 525.0, 319.5, 239.5, 640, 480),
    (80.0, 80.0, 10.0, 40.0, 64, 48),
    (120.0, 90.0, 40.5, 17.25, 64, 48),
    (50.0, 60.0, -20.0, 70.0, 33, 17),
];

#[test]
fn a_perspective_lens_is_gl_frustum() {
    let (near, far) = (0.25, 40.0);
    for (fx, fy, cx, cy, width, height) in CASES {
        let k = Intrinsics {
            fx,
            fy,
            cx,
            cy,
            width,
            height,
        };
        let camera = Camera::perspective(DVec3::Z, DVec3::ZERO, near, far).with_intrinsics(&k);
        let (w, h) = (f64::from(width), f64::from(height));
        // The image plane at the near distance: pixel x in [0, w] is
        // camera x = (x - cx) near / fx, and image y (down) is -y.
        let (left, right) = (-cx * near / fx, (w - cx) * near / fx);
        let (bottom, top) = ((cy - h) * near / fy, cy * near / fy);
        let expected = gl_frustum(left, right, bottom, top, near, far);
        // A few roundings apart: the field of view goes through atan and
        // tan and degrees.
        assert_close(camera.projection_matrix(w / h), expected, 1e-13);
    }
}

#[test]
fn an_orthographic_lens_is_gl_ortho() {
    let camera =
        Camera::orthographic(DVec3::Z * 5.0, DVec3::ZERO, 2.0, -1.0, 9.0).with_lens(Lens {
            centre: DVec2::new(0.5, -0.25),
            x_scale: 2.0,
        });
    let aspect = 1.5;
    // Half width 3 / x_scale 2 = 1.5; the axis at NDC x 0.5 puts a
    // quarter of the width on its left: left = -1.5 (1 + 0.5), right =
    // 1.5 (1 - 0.5); in y, half height 2 and centre -0.25.
    let expected = gl_ortho(-2.25, 0.75, -1.5, 2.5, -1.0, 9.0);
    assert_close(camera.projection_matrix(aspect), expected, 1e-15);
}

#[test]
fn the_centred_lens_keeps_the_symmetric_matrices_bit_for_bit() {
    let p = Camera::perspective(DVec3::Z * 3.0, DVec3::ZERO, 0.5, 20.0);
    assert_eq!(p.lens, Lens::CENTRED);
    assert_eq!(
        p.projection_matrix(1.25),
        hider_geom::camera::perspective(60f64.to_radians(), 1.25, 0.5, 20.0)
    );
    let o = Camera::orthographic(DVec3::Z * 3.0, DVec3::ZERO, 1.5, 0.5, 20.0);
    assert_eq!(
        o.projection_matrix(2.0),
        hider_geom::camera::orthographic(3.0, 1.5, 0.5, 20.0)
    );
}

/// The window position (pixels, y down) and view depth of world point
/// `p` seen by `camera` in a `width x height` image, through the matrices
/// the front end uses.
fn project(camera: &Camera, width: u32, height: u32, p: DVec3) -> DVec3 {
    let vp = Viewport::new(width, height);
    let clip = camera.projection_matrix(vp.aspect()) * camera.view_matrix() * DVec4::from((p, 1.0));
    let ndc = clip.truncate() / clip.w;
    vp.ndc_to_window(ndc)
}

#[test]
fn intrinsics_put_a_world_point_where_k_puts_it() {
    // An OpenCV camera (x right, y down, z forward) at `eye`, turned by a
    // rotation with no special axis: its columns are the camera axes in
    // world space.
    let eye = DVec3::new(0.3, -1.2, 4.0);
    let rotation = DMat3::from_euler(glam::EulerRot::YXZ, 0.4, -0.3, 0.2);
    let (right, down, forward) = (rotation.x_axis, rotation.y_axis, rotation.z_axis);
    for (fx, fy, cx, cy, width, height) in CASES {
        let k = Intrinsics {
            fx,
            fy,
            cx,
            cy,
            width,
            height,
        };
        assert!(k.validate().is_ok());
        // The camera's -Z is OpenCV's +z, its +Y OpenCV's -y.
        let camera = Camera::perspective(eye, eye + forward, 0.1, 100.0)
            .with_up(-down)
            .with_intrinsics(&k);
        assert!(camera.validate().is_ok(), "{:?}", camera.validate());
        for local in [
            DVec3::new(0.0, 0.0, 3.0),
            DVec3::new(0.4, -0.2, 2.5),
            DVec3::new(-0.7, 0.5, 6.0),
        ] {
            let world = eye + right * local.x + down * local.y + forward * local.z;
            let expected = DVec2::new(fx * local.x / local.z + cx, fy * local.y / local.z + cy);
            let got = project(&camera, width, height, world);
            assert!(
                (got.truncate() - expected).abs().max_element() < 1e-9,
                "K {k:?}, point {local}: window {got} vs {expected}"
            );
        }
    }
}

#[test]
fn bad_lenses_and_intrinsics_are_refused_by_name() {
    let good = Camera::perspective(DVec3::Z * 5.0, DVec3::ZERO, 0.1, 100.0);
    for lens in [
        Lens {
            centre: DVec2::new(f64::NAN, 0.0),
            x_scale: 1.0,
        },
        Lens {
            centre: DVec2::ZERO,
            x_scale: 0.0,
        },
        Lens {
            centre: DVec2::ZERO,
            x_scale: f64::INFINITY,
        },
    ] {
        let e = good.with_lens(lens).validate().unwrap_err();
        assert!(e.0.contains("lens"), "{e}");
    }
    let k = Intrinsics {
        fx: 100.0,
        fy: 100.0,
        cx: 32.0,
        cy: 24.0,
        width: 64,
        height: 48,
    };
    assert!(
        Intrinsics { fx: -1.0, ..k }
            .validate()
            .unwrap_err()
            .0
            .contains("fx")
    );
    assert!(
        Intrinsics { fy: f64::NAN, ..k }
            .validate()
            .unwrap_err()
            .0
            .contains("fy")
    );
    assert!(
        Intrinsics {
            cy: f64::INFINITY,
            ..k
        }
        .validate()
        .unwrap_err()
        .0
        .contains("cy")
    );
    assert!(
        Intrinsics { width: 0, ..k }
            .validate()
            .unwrap_err()
            .0
            .contains("size")
    );
    // A lens never changes depth: the depth rows are the symmetric ones.
    let lens = good.with_intrinsics(&Intrinsics { cx: 5.0, ..k });
    let (a, b) = (
        lens.projection_matrix(4.0 / 3.0),
        good.projection_matrix(4.0 / 3.0),
    );
    assert_eq!((a.row(2), a.row(3)), (b.row(2), b.row(3)));
    assert!(matches!(lens.projection, Projection::Perspective { .. }));
}
