//! Homogeneous clipping (Sutherland–Hodgman in clip space).
//!
//! Triangles are clipped against the near plane `z >= -w`, the far plane
//! `z <= w`, and four *guard-band* planes well outside the viewport. The
//! near plane keeps `w > 0` so the perspective divide is safe (a triangle
//! behind the eye disappears instead of wrapping around); the guard band
//! keeps snapped coordinates inside the range where integer edge functions
//! cannot overflow, while leaving triangles that merely poke out of the
//! image untouched (clipping them to the viewport would move their snapped
//! edges and change coverage). Clipping happens in `f64`; each output vertex
//! carries its barycentric coordinates in the source triangle so attributes
//! stay exact.

use glam::{DVec3, DVec4};

/// A vertex in clip space with its barycentric position in the source
/// triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVertex {
    /// Homogeneous clip-space position.
    pub pos: DVec4,
    /// Barycentric coordinates in the source triangle (sum to one).
    pub bary: DVec3,
}

impl ClipVertex {
    fn lerp(self, other: Self, t: f64) -> Self {
        Self {
            pos: self.pos + (other.pos - self.pos) * t,
            bary: self.bary + (other.bary - self.bary) * t,
        }
    }
}

/// The planes a triangle is clipped against, as `dot(plane, pos) >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVolume {
    /// Guard-band factor in x: vertices must satisfy `|x| <= gx * w`.
    pub guard_x: f64,
    /// Guard-band factor in y: vertices must satisfy `|y| <= gy * w`.
    pub guard_y: f64,
}

impl ClipVolume {
    /// The clip volume for a viewport of `width x height` pixels with
    /// `guard_pixels` of guard band on each side.
    pub fn for_viewport(width: u32, height: u32, guard_pixels: u32) -> Self {
        let g = f64::from(guard_pixels);
        Self {
            guard_x: 1.0 + 2.0 * g / f64::from(width.max(1)),
            guard_y: 1.0 + 2.0 * g / f64::from(height.max(1)),
        }
    }

    /// The outcode of a clip-space position (Cohen–Sutherland style):
    /// bits 0-3 say which side of the *viewport* it is beyond
    /// ([`OUTSIDE_VIEWPORT`]), bits 4-9 which clip plane it fails
    /// ([`OUTSIDE_PLANES`]). [`clip_triangle`] decides from these alone
    /// whether a triangle is culled, inside or to be cut, so a front end
    /// that caches them per vertex decides exactly as it does.
    #[inline]
    pub fn outcode(&self, p: DVec4) -> u32 {
        // The six plane tests `dot(plane, p) < 0` of `planes()`, written
        // out: the dot product's zero terms are exact zeros (p is finite)
        // and adding them leaves the other terms' sum unchanged, so each
        // sum here is the same rounded value (see `outcode_is_the_dot_products`).
        let (gx, gy) = (p.w * self.guard_x, p.w * self.guard_y);
        u32::from(p.x > p.w)
            | u32::from(p.x < -p.w) << 1
            | u32::from(p.y > p.w) << 2
            | u32::from(p.y < -p.w) << 3
            | u32::from(p.z + p.w < 0.0) << 4
            | u32::from(-p.z + p.w < 0.0) << 5
            | u32::from(p.x + gx < 0.0) << 6
            | u32::from(-p.x + gx < 0.0) << 7
            | u32::from(p.y + gy < 0.0) << 8
            | u32::from(-p.y + gy < 0.0) << 9
    }

    fn planes(&self) -> [DVec4; 6] {
        [
            DVec4::new(0.0, 0.0, 1.0, 1.0),  // near: z + w >= 0
            DVec4::new(0.0, 0.0, -1.0, 1.0), // far: w - z >= 0
            DVec4::new(1.0, 0.0, 0.0, self.guard_x),
            DVec4::new(-1.0, 0.0, 0.0, self.guard_x),
            DVec4::new(0.0, 1.0, 0.0, self.guard_y),
            DVec4::new(0.0, -1.0, 0.0, self.guard_y),
        ]
    }
}

/// Outcode bits of a position beyond one side of the viewport.
pub const OUTSIDE_VIEWPORT: u32 = 0b1111;
/// Outcode bits of a position failing one of the six clip planes.
pub const OUTSIDE_PLANES: u32 = 0b11_1111 << 4;

/// What clipping did to a triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClipOutcome {
    /// Entirely inside: the polygon is the triangle itself.
    Inside,
    /// Entirely outside one plane, or outside the viewport: nothing left.
    Culled,
    /// Cut by one or more planes: the polygon has the pieces left.
    Clipped,
}

/// Clips a triangle to the clip volume and also culls triangles that lie
/// entirely outside the viewport (`|x| > w` or `|y| > w` for all vertices).
///
/// `out` receives the convex polygon left (3 to 9 vertices), in the
/// triangle's winding. `scratch` is reused storage.
pub fn clip_triangle(
    tri: [DVec4; 3],
    volume: &ClipVolume,
    out: &mut Vec<ClipVertex>,
    scratch: &mut Vec<ClipVertex>,
) -> ClipOutcome {
    out.clear();
    if tri.iter().any(|p| !p.is_finite()) {
        return ClipOutcome::Culled;
    }
    let planes = volume.planes();
    let codes = tri.map(|p| volume.outcode(p));
    // All three beyond one side of the image (or one clip plane): no pixel
    // centre can be covered.
    if codes[0] & codes[1] & codes[2] != 0 {
        return ClipOutcome::Culled;
    }
    let bary = [DVec3::X, DVec3::Y, DVec3::Z];
    out.extend((0..3).map(|i| ClipVertex {
        pos: tri[i],
        bary: bary[i],
    }));
    let failing = (codes[0] | codes[1] | codes[2]) & OUTSIDE_PLANES;
    if failing == 0 {
        return ClipOutcome::Inside;
    }
    let mut clipped = false;
    for (k, plane) in planes.into_iter().enumerate() {
        if failing & (1 << (4 + k)) == 0 {
            continue;
        }
        let all_in = out.iter().all(|v| plane.dot(v.pos) >= 0.0);
        if all_in {
            continue;
        }
        clipped = true;
        scratch.clear();
        let n = out.len();
        for i in 0..n {
            let a = out[i];
            let b = out[(i + 1) % n];
            let da = plane.dot(a.pos);
            let db = plane.dot(b.pos);
            if da >= 0.0 {
                scratch.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                // Interpolate from the inside vertex so the result does not
                // depend on which way round the edge is traversed.
                let v = if da >= 0.0 {
                    a.lerp(b, da / (da - db))
                } else {
                    b.lerp(a, db / (db - da))
                };
                scratch.push(v);
            }
        }
        std::mem::swap(out, scratch);
        if out.len() < 3 {
            out.clear();
            return ClipOutcome::Culled;
        }
    }
    if clipped {
        ClipOutcome::Clipped
    } else {
        ClipOutcome::Inside
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// The written-out outcode equals the six dot products bit for bit.
        #[test]
        fn outcode_is_the_dot_products(
            p in proptest::array::uniform4(proptest::prop_oneof![
                -1e30f64..1e30, -10.0f64..10.0, proptest::strategy::Just(0.0), proptest::strategy::Just(-0.0)
            ]),
            w in 1u32..20000,
            h in 1u32..20000,
            guard in 0u32..20000,
        ) {
            let p = DVec4::from_array(p);
            let v = ClipVolume::for_viewport(w, h, guard);
            let mut code = u32::from(p.x > p.w)
                | u32::from(p.x < -p.w) << 1
                | u32::from(p.y > p.w) << 2
                | u32::from(p.y < -p.w) << 3;
            for (k, plane) in v.planes().iter().enumerate() {
                code |= u32::from(plane.dot(p) < 0.0) << (4 + k);
            }
            proptest::prop_assert_eq!(v.outcode(p), code);
        }
    }

    fn vol() -> ClipVolume {
        ClipVolume::for_viewport(100, 100, 100)
    }

    fn run(tri: [DVec4; 3]) -> (ClipOutcome, Vec<ClipVertex>) {
        let mut out = Vec::new();
        let mut scratch = Vec::new();
        let o = clip_triangle(tri, &vol(), &mut out, &mut scratch);
        (o, out)
    }

    #[test]
    fn inside_triangle_is_untouched() {
        let t = [
            DVec4::new(-0.5, -0.5, 0.0, 1.0),
            DVec4::new(0.5, -0.5, 0.0, 1.0),
            DVec4::new(0.0, 0.5, 0.0, 1.0),
        ];
        let (o, out) = run(t);
        assert_eq!(o, ClipOutcome::Inside);
        assert_eq!(out.len(), 3);
        assert_eq!(out[1].bary, DVec3::Y);
    }

    #[test]
    fn triangle_crossing_near_plane_is_cut_and_keeps_w_positive() {
        // One vertex behind the eye (w < 0), as a perspective projection
        // produces for a point behind the camera.
        let t = [
            DVec4::new(0.0, 0.0, 0.5, 1.0),
            DVec4::new(0.2, 0.0, 0.5, 1.0),
            DVec4::new(0.0, 0.5, -3.0, -1.0),
        ];
        let (o, out) = run(t);
        assert_eq!(o, ClipOutcome::Clipped);
        assert_eq!(out.len(), 4);
        for v in &out {
            assert!(v.pos.z + v.pos.w >= -1e-12);
            assert!(v.pos.w > 0.0);
            assert!((v.bary.x + v.bary.y + v.bary.z - 1.0).abs() < 1e-12);
            // The clip position is the barycentric blend of the source.
            let blend = t[0] * v.bary.x + t[1] * v.bary.y + t[2] * v.bary.z;
            assert!((blend - v.pos).length() < 1e-12);
        }
    }

    #[test]
    fn triangle_behind_the_eye_is_culled() {
        let t = [
            DVec4::new(0.0, 0.0, -3.0, -1.0),
            DVec4::new(0.2, 0.0, -3.0, -1.0),
            DVec4::new(0.0, 0.5, -3.0, -2.0),
        ];
        assert_eq!(run(t).0, ClipOutcome::Culled);
    }

    #[test]
    fn triangle_off_screen_is_culled_and_huge_one_is_guard_clipped() {
        let off = [
            DVec4::new(2.0, 0.0, 0.0, 1.0),
            DVec4::new(3.0, 0.0, 0.0, 1.0),
            DVec4::new(2.0, 1.0, 0.0, 1.0),
        ];
        assert_eq!(run(off).0, ClipOutcome::Culled);
        let huge = [
            DVec4::new(-1e6, -1e6, 0.0, 1.0),
            DVec4::new(1e6, -1e6, 0.0, 1.0),
            DVec4::new(0.0, 1e6, 0.0, 1.0),
        ];
        let (o, out) = run(huge);
        assert_eq!(o, ClipOutcome::Clipped);
        let g = vol().guard_x;
        for v in &out {
            assert!(v.pos.x.abs() <= g * v.pos.w * (1.0 + 1e-12));
            assert!(v.pos.y.abs() <= g * v.pos.w * (1.0 + 1e-12));
        }
    }

    #[test]
    fn non_finite_input_is_culled() {
        let t = [
            DVec4::new(f64::NAN, 0.0, 0.0, 1.0),
            DVec4::new(0.5, 0.0, 0.0, 1.0),
            DVec4::new(0.0, 0.5, 0.0, 1.0),
        ];
        assert_eq!(run(t).0, ClipOutcome::Culled);
    }
}
