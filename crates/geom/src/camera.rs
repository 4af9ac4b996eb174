//! Cameras: look-at view matrices and OpenGL-style projections.
//!
//! All matrices are `f64` ([`DMat4`]): the front end rounds to `f32` only
//! where it imitates a GL pipeline on purpose (see `hider-scene`'s
//! `TransformPrecision`). The conventions are OpenGL's: a right-handed world,
//! the camera looking down -Z, clip space with `-w <= z <= w`.
//!
//! A camera's [`Lens`] makes its frustum off-axis (`glFrustum` with
//! `left != -right`): the principal point of pinhole [`Intrinsics`] off the
//! image centre, or pixels taller than wide. It moves and stretches the
//! image in NDC only; the depth rows of the projection, and with them every
//! depth a hider computes, are those of the symmetric frustum.

use glam::{DMat4, DVec3};

pub use crate::lens::{Intrinsics, Lens};

/// The projection a camera uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Perspective projection (`gluPerspective`).
    Perspective {
        /// Vertical field of view in degrees.
        fovy_degrees: f64,
        /// Distance to the near plane (> 0).
        near: f64,
        /// Distance to the far plane (> near).
        far: f64,
    },
    /// Orthographic projection (`glOrtho` centred on the view axis).
    Orthographic {
        /// Half the height of the view volume in world units; the half width
        /// is this times the aspect ratio.
        half_height: f64,
        /// Distance to the near plane (may be negative).
        near: f64,
        /// Distance to the far plane (> near).
        far: f64,
    },
}

/// A camera: where the eye is, where it looks and how it projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Position of the eye in world space.
    pub eye: DVec3,
    /// Point the eye looks at.
    pub target: DVec3,
    /// Up direction (need not be orthogonal to the view direction).
    pub up: DVec3,
    /// The projection.
    pub projection: Projection,
    /// Where the view axis meets the image, and the pixels' shape:
    /// [`Lens::CENTRED`] for the symmetric frustum of `gluPerspective` and
    /// `glOrtho`.
    pub lens: Lens,
}

/// Why a camera cannot be used.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraError(pub String);

impl std::fmt::Display for CameraError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CameraError {}

impl Camera {
    /// The vertical field of view of [`Camera::perspective`]: 60 degrees.
    pub const DEFAULT_FOVY_DEGREES: f64 = 60.0;

    /// A perspective camera looking from `eye` at `target` with +Y up and a
    /// vertical field of view of [`Camera::DEFAULT_FOVY_DEGREES`], its clip
    /// planes `near` and `far` in front of the eye.
    ///
    /// ```
    /// use hider_geom::{Camera, Projection};
    /// use glam::DVec3;
    ///
    /// let camera = Camera::perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 0.5, 50.0);
    /// assert_eq!(camera.up, DVec3::Y);
    /// assert_eq!(
    ///     camera.projection,
    ///     Projection::Perspective { fovy_degrees: 60.0, near: 0.5, far: 50.0 }
    /// );
    /// assert!(camera.validate().is_ok());
    /// ```
    pub fn perspective(eye: DVec3, target: DVec3, near: f64, far: f64) -> Self {
        Self {
            eye,
            target,
            up: DVec3::Y,
            projection: Projection::Perspective {
                fovy_degrees: Self::DEFAULT_FOVY_DEGREES,
                near,
                far,
            },
            lens: Lens::CENTRED,
        }
    }

    /// An orthographic camera looking from `eye` at `target` with +Y up,
    /// its view volume `half_height` world units above and below the view
    /// axis and from `near` to `far` along it.
    ///
    /// ```
    /// use hider_geom::{Camera, Projection};
    /// use glam::DVec3;
    ///
    /// let camera = Camera::orthographic(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 1.4, 0.5, 10.0);
    /// assert_eq!(
    ///     camera.projection,
    ///     Projection::Orthographic { half_height: 1.4, near: 0.5, far: 10.0 }
    /// );
    /// ```
    pub fn orthographic(eye: DVec3, target: DVec3, half_height: f64, near: f64, far: f64) -> Self {
        Self {
            eye,
            target,
            up: DVec3::Y,
            projection: Projection::Orthographic {
                half_height,
                near,
                far,
            },
            lens: Lens::CENTRED,
        }
    }

    /// The same camera with `up` as its up direction.
    ///
    /// ```
    /// use hider_geom::Camera;
    /// use glam::DVec3;
    ///
    /// let camera = Camera::perspective(DVec3::Y * 5.0, DVec3::ZERO, 0.1, 10.0).with_up(DVec3::Z);
    /// assert!(camera.validate().is_ok());
    /// ```
    pub fn with_up(mut self, up: DVec3) -> Self {
        self.up = up;
        self
    }

    /// The same camera with a perspective projection of `fovy_degrees`
    /// vertical field of view; an orthographic camera is returned as it
    /// was.
    ///
    /// ```
    /// use hider_geom::{Camera, Projection};
    /// use glam::DVec3;
    ///
    /// let camera = Camera::perspective(DVec3::Z * 3.0, DVec3::ZERO, 0.5, 20.0).with_fovy_degrees(90.0);
    /// assert!(matches!(camera.projection, Projection::Perspective { fovy_degrees: 90.0, .. }));
    /// ```
    pub fn with_fovy_degrees(mut self, fovy_degrees: f64) -> Self {
        if let Projection::Perspective {
            fovy_degrees: ref mut f,
            ..
        } = self.projection
        {
            *f = fovy_degrees;
        }
        self
    }

    /// The same camera with `lens`.
    ///
    /// ```
    /// use hider_geom::{Camera, Lens};
    /// use glam::{DVec2, DVec3};
    ///
    /// let lens = Lens { centre: DVec2::new(0.25, 0.0), x_scale: 1.0 };
    /// let camera = Camera::perspective(DVec3::Z * 3.0, DVec3::ZERO, 0.5, 20.0).with_lens(lens);
    /// // The view axis (the target) lands a quarter of the way right of centre.
    /// let clip = camera.projection_matrix(1.0) * camera.view_matrix() * DVec3::ZERO.extend(1.0);
    /// assert!((clip.x / clip.w - 0.25).abs() < 1e-15);
    /// ```
    pub fn with_lens(mut self, lens: Lens) -> Self {
        self.lens = lens;
        self
    }

    /// The same camera with the field of view and lens of pinhole
    /// `intrinsics` (a perspective camera; an orthographic one gets the
    /// lens only). Rendered at the intrinsics' image size, a world point
    /// lands at the pixel position `K` gives it (see [`Intrinsics`]).
    pub fn with_intrinsics(self, intrinsics: &Intrinsics) -> Self {
        self.with_fovy_degrees(intrinsics.fovy_degrees())
            .with_lens(intrinsics.lens())
    }

    /// The view matrix (world to camera space).
    pub fn view_matrix(&self) -> DMat4 {
        look_at(self.eye, self.target, self.up)
    }

    /// The projection matrix for an image of the given aspect ratio
    /// (width / height): the symmetric frustum's, then the [`Lens`]. With
    /// a lens a perspective camera's matrix is `glFrustum`'s, for
    /// `right - left = 2 near tan(fovy / 2) aspect / x_scale` and
    /// `(right + left) / (right - left) = -centre.x` (and the same in y
    /// with a scale of 1): the lens's entries go where `glFrustum` has
    /// them, and the depth rows are untouched.
    pub fn projection_matrix(&self, aspect: f64) -> DMat4 {
        let mut m = self.symmetric_projection_matrix(aspect);
        if self.lens != Lens::CENTRED {
            let Lens { centre, x_scale } = self.lens;
            // Premultiplying by the NDC map [[sx, 0, 0, cx], [0, 1, 0, cy],
            // [0, 0, 1, 0], [0, 0, 0, 1]]: row x scales and gains cx times
            // row w, row y gains cy times row w. Row w of either projection
            // is a unit vector (-z or the constant 1), so the lens's entries
            // are exact and the x scale adds one rounding.
            m.x_axis.x *= x_scale;
            let w_row = m.row(3);
            for c in 0..4 {
                let col = m.col_mut(c);
                col.x += centre.x * w_row[c];
                col.y += centre.y * w_row[c];
            }
        }
        m
    }

    /// The projection of the symmetric frustum, without the lens.
    fn symmetric_projection_matrix(&self, aspect: f64) -> DMat4 {
        match self.projection {
            Projection::Perspective {
                fovy_degrees,
                near,
                far,
            } => perspective(fovy_degrees.to_radians(), aspect, near, far),
            Projection::Orthographic {
                half_height,
                near,
                far,
            } => orthographic(half_height * aspect, half_height, near, far),
        }
    }

    /// Checks that the camera describes a usable view: finite values, a view
    /// direction, an up vector not parallel to it, and sane clip distances.
    pub fn validate(&self) -> Result<(), CameraError> {
        let finite = self.eye.is_finite() && self.target.is_finite() && self.up.is_finite();
        if !finite {
            return Err(CameraError(format!(
                "camera has a non-finite value (eye {}, target {}, up {})",
                short3(self.eye),
                short3(self.target),
                short3(self.up)
            )));
        }
        let dir = self.target - self.eye;
        if !dir.is_finite() {
            return Err(CameraError(format!(
                "camera eye {} and target {} are too far apart",
                short3(self.eye),
                short3(self.target)
            )));
        }
        if dir == DVec3::ZERO {
            return Err(CameraError(format!(
                "camera eye and target are the same point {}",
                short3(self.eye)
            )));
        }
        // Rescaled, so that a direction of any finite length (1e200 as well
        // as 1e-200) squares without overflow or underflow.
        let (d, up) = (rescaled(dir).normalize(), rescaled(self.up));
        if up == DVec3::ZERO || d.cross(up.normalize()).length_squared() <= 1e-24 {
            return Err(CameraError(format!(
                "camera up {} is parallel to the view direction {}",
                short3(self.up),
                short3(dir)
            )));
        }
        let Lens { centre, x_scale } = self.lens;
        if !(centre.is_finite() && x_scale > 0.0 && x_scale.is_finite()) {
            return Err(CameraError(format!(
                "camera lens centre [{}, {}] must be finite and its x scale {} finite and > 0",
                short(centre.x),
                short(centre.y),
                short(x_scale)
            )));
        }
        match self.projection {
            Projection::Perspective {
                fovy_degrees,
                near,
                far,
            } => {
                if !(fovy_degrees > 0.0 && fovy_degrees < 180.0) {
                    return Err(CameraError(format!(
                        "fovy {} is not between 0 and 180 degrees",
                        short(fovy_degrees)
                    )));
                }
                if !(near > 0.0 && near.is_finite()) {
                    return Err(CameraError(format!("near {} must be > 0", short(near))));
                }
                if !(far > near && far.is_finite()) {
                    return Err(CameraError(format!(
                        "far {} must be finite and > near {}",
                        short(far),
                        short(near)
                    )));
                }
            }
            Projection::Orthographic {
                half_height,
                near,
                far,
            } => {
                if !(half_height > 0.0 && half_height.is_finite()) {
                    return Err(CameraError(format!(
                        "orthographic half height {} must be > 0",
                        short(half_height)
                    )));
                }
                if !(far > near && far.is_finite() && near.is_finite()) {
                    return Err(CameraError(format!(
                        "far {} must be finite and > near {}",
                        short(far),
                        short(near)
                    )));
                }
            }
        }
        Ok(())
    }
}

/// Right-handed look-at matrix (`gluLookAt`): the eye ends at the origin
/// looking down -Z with `up` projected to +Y. The direction and `up` are
/// rescaled by powers of two before they are normalised, so that a camera
/// 1e200 from its target gets the same rotation as one 1 away (for lengths
/// that square without overflow the result is bit for bit glam's
/// `look_at_rh`: scaling by a power of two is exact).
pub fn look_at(eye: DVec3, target: DVec3, up: DVec3) -> DMat4 {
    DMat4::look_to_rh(eye, rescaled(target - eye).normalize(), rescaled(up))
}

/// `v` times the power of two that brings its largest component into
/// [1, 2) (`v` itself when it is zero or not finite). Exact, so the
/// direction is kept, and the result squares without overflow or
/// underflow.
pub fn rescaled(v: DVec3) -> DVec3 {
    v * power_of_two_scale(v.abs().max_element())
}

/// The power of two that brings `m` (not negative) into [1, 2); 1 when
/// `m` is zero or not finite.
fn power_of_two_scale(m: f64) -> f64 {
    if !(m > 0.0 && m.is_finite()) {
        return 1.0;
    }
    // The exponent of a normal m, clamped so that the scale is a normal
    // number: subnormals get 2^1022 (they stay small but non-zero, and
    // overflow nothing), the top binade 2^-1022 (it lands in [2, 4)).
    let e = ((m.to_bits() >> 52) as i32 - 1023).clamp(-1022, 1022);
    f64::from_bits(((1023 - e) as u64) << 52)
}

/// The Euclidean length of `v` without overflow or underflow: equal to
/// `v.length()` wherever that is finite and its squares are normal
/// numbers (scaling by a power of two is exact), finite for every finite
/// `v` whose length is below the largest `f64`.
pub fn length(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if !(m > 0.0 && m.is_finite()) {
        return v.length();
    }
    let r = rescaled(v);
    // The scale rescaled applied, recovered exactly from one component.
    let scale = r.abs().max_element() / m;
    r.length() / scale
}

/// OpenGL perspective projection (`gluPerspective`), `fovy` in radians.
///
/// Maps camera-space depth `-near` to NDC z = -1 and `-far` to +1; clip w is
/// `-z_camera`, the distance in front of the eye.
pub fn perspective(fovy: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    // glam's perspective_rh_gl is exactly gluPerspective's matrix, but its
    // `2 near far` overflows for distances near 1e200. Computed on near and
    // far rescaled by a power of two and the one entry that scales with
    // them scaled back: every operation commutes with the exact scaling,
    // so the bits are glam's wherever glam's products do not overflow.
    let s = power_of_two_scale(far.abs().max(near.abs()));
    let mut m = DMat4::perspective_rh_gl(fovy, aspect, near * s, far * s);
    m.w_axis.z /= s;
    m
}

/// OpenGL orthographic projection symmetric about the view axis (`glOrtho`
/// with left = -half_width, bottom = -half_height).
pub fn orthographic(half_width: f64, half_height: f64, near: f64, far: f64) -> DMat4 {
    DMat4::orthographic_rh_gl(
        -half_width,
        half_width,
        -half_height,
        half_height,
        near,
        far,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec4;

    #[test]
    fn perspective_maps_near_and_far_to_ndc_bounds() {
        let p = perspective(60f64.to_radians(), 1.0, 0.5, 20.0);
        let near = p * DVec4::new(0.0, 0.0, -0.5, 1.0);
        let far = p * DVec4::new(0.0, 0.0, -20.0, 1.0);
        assert!((near.z / near.w + 1.0).abs() < 1e-12);
        assert!((far.z / far.w - 1.0).abs() < 1e-12);
        assert!((near.w - 0.5).abs() < 1e-12, "clip w is the distance");
    }

    #[test]
    fn look_at_puts_target_on_negative_z() {
        let v = look_at(
            DVec3::new(1.0, 2.0, 10.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::Y,
        );
        let t = v.transform_point3(DVec3::new(1.0, 2.0, 0.0));
        assert!((t - DVec3::new(0.0, 0.0, -10.0)).length() < 1e-12);
    }

    #[test]
    fn huge_and_tiny_distances_keep_their_rotation() {
        let base = look_at(
            DVec3::new(1.0, 2.0, 10.0),
            DVec3::new(3.0, -1.0, 0.0),
            DVec3::Y,
        );
        // 2^664 (about 1.9e200): every product of the rotation would
        // overflow before the direction is rescaled.
        let k = 2f64.powi(664);
        let huge = look_at(
            DVec3::new(1.0, 2.0, 10.0) * k,
            DVec3::new(3.0, -1.0, 0.0) * k,
            DVec3::Y * k,
        );
        for c in 0..3 {
            assert_eq!(huge.col(c), base.col(c), "column {c}");
        }
        let camera = Camera::perspective(DVec3::Z * k, DVec3::ZERO, 0.1 * k, 10.0 * k);
        assert!(camera.validate().is_ok(), "{:?}", camera.validate());
        assert_eq!(length(DVec3::new(3.0, 4.0, 0.0) * k), 5.0 * k);
        assert_eq!(length(DVec3::new(3.0, 4.0, 12.0)), 13.0);
        assert_eq!(length(DVec3::ZERO), 0.0);
        let tiny = 2f64.powi(-600);
        assert_eq!(length(DVec3::new(3.0, 4.0, 0.0) * tiny), 5.0 * tiny);
    }

    #[test]
    fn validate_rejects_bad_cameras() {
        let good = Camera::perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 0.1, 100.0);
        assert!(good.validate().is_ok());
        let mut c = good;
        c.up = DVec3::Z;
        assert!(c.validate().unwrap_err().0.contains("parallel"));
        let mut c = good;
        c.target = c.eye;
        assert!(c.validate().is_err());
        let mut c = good;
        c.projection = Projection::Perspective {
            fovy_degrees: 60.0,
            near: 0.0,
            far: 1.0,
        };
        assert!(c.validate().unwrap_err().0.contains("near"));
        let mut c = good;
        c.eye.x = f64::NAN;
        assert!(c.validate().unwrap_err().0.contains("non-finite"));
    }
}

#[cfg(test)]
mod short_tests {
    use super::*;

    #[test]
    fn huge_numbers_print_short() {
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(1e308), "1e308");
        assert_eq!(short(-1.2345678e200), "-1.23457e200");
        assert_eq!(
            short3(DVec3::new(5e307, 0.0, f64::INFINITY)),
            "[5e307, 0, inf]"
        );
    }
}

/// A number for a message: as Rust prints it when that is short, else in
/// scientific notation with 6 significant digits (`1e308` prints 309 digits
/// in full).
pub fn short(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 16 {
        plain
    } else {
        let sci = format!("{x:.5e}");
        // Trailing zeros of the mantissa say nothing.
        match sci.split_once('e') {
            Some((mantissa, exponent)) if mantissa.contains('.') => {
                let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
                format!("{mantissa}e{exponent}")
            }
            _ => sci,
        }
    }
}

/// A vector for a message, each coordinate [`short`].
pub fn short3(v: DVec3) -> String {
    format!("[{}, {}, {}]", short(v.x), short(v.y), short(v.z))
}
