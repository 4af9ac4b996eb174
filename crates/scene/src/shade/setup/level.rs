//! One mip level per primitive where the footprint cannot change it.
//!
//! The level a point reads comes from its footprint, the change of the
//! texture coordinates one pixel right and one pixel down
//! ([`super::super::mip`]). With the `u/w`, `v/w` and `1/w` planes of
//! [`super::Planes`] (a coordinate is `t = T / D`, both planes), the step
//! right is `T(x + 1, y) / D(x + 1, y) - T / D`, whose numerator
//! `T_x D - D_x T` (subscripts: the planes' steps) is affine in `y` alone,
//! and the step down's, `T_y D - D_y T`, in `x` alone. Over a rectangle of
//! window points where `D` keeps its sign, the footprint is then bounded
//! by the numerators' extremes (at the rectangle's edges) over the
//! denominators' (at its corners). When the levels of both bounds agree,
//! every point of the rectangle reads that level: the level is a
//! non-decreasing function of the footprint ([`mip::level_for_squared`]).
//!
//! The bounds hold for the footprint as computed, not only as it is in
//! exact arithmetic: they are widened by a bound of the rounding of the
//! per-point computation (each plane evaluated to within a few units in
//! the last place of its terms' magnitudes, then two divisions and a
//! difference; [`LevelBounds::err`], taken 64 times over) and by a
//! relative `1e-9` (the bounds' own rounding and the squares'). A primitive
//! whose bounds straddle a level boundary, or whose corners are not all in
//! front of the eye, keeps the per-point footprint.

use glam::{DVec2, DVec3};

use super::super::mip;
use super::Plane;

/// Bounds of a primitive's footprint over the window points where its
/// colour is asked for (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub(super) struct LevelBounds {
    /// `x0, y0, x1, y1`: the points the bounds hold for.
    pub(super) rect: [f64; 4],
    /// `[lo, hi]` of the step right's numerator of `u` and of `v`, then
    /// the step down's (absolute values, rounding included).
    num: [[f64; 2]; 4],
    /// `[lo, hi]` of `|D|` over the rectangle grown by one pixel right and
    /// down (the steps' denominators).
    den: [f64; 2],
    /// Bound of the error of a computed step, in texture coordinates.
    err: f64,
}

/// `max |c + x X + y Y|`-style magnitude of a plane's terms over
/// `x in [0, xm]`, `y in [0, ym]` (absolute values): what its evaluation
/// rounds against.
fn terms(p: &Plane, xm: f64, ym: f64) -> f64 {
    p.c.abs() + xm * p.x.abs() + ym * p.y.abs()
}

/// `[min, max]` of `|a0 + a1 t|` for `t` in `[t0, t1]`, widened by `e`.
fn affine_abs(a0: f64, a1: f64, (t0, t1): (f64, f64), e: f64) -> [f64; 2] {
    let (p, q) = (a0 + a1 * t0, a0 + a1 * t1);
    let lo = if p.signum() != q.signum() {
        0.0
    } else {
        p.abs().min(q.abs())
    };
    [(lo - e).max(0.0), p.abs().max(q.abs()) + e]
}

impl LevelBounds {
    /// The bounds of the primitive with texture-coordinate planes `uv`
    /// and denominator `den`, over the window points within one pixel of
    /// its corners' window positions `corners` (which must all be in front
    /// of the eye) inside a `width x height` window grown by a pixel: every
    /// point of every pixel the primitive touches. `None` where `D` may
    /// vanish there or a bound is not finite.
    pub(super) fn new(
        uv: &[Plane; 2],
        den: &Plane,
        corners: [DVec2; 3],
        (width, height): (f64, f64),
    ) -> Option<Self> {
        let lo = corners[0].min(corners[1]).min(corners[2]) - DVec2::ONE;
        let hi = corners[0].max(corners[1]).max(corners[2]) + DVec2::ONE;
        let (x0, y0) = (lo.x.max(-1.0), lo.y.max(-1.0));
        let (x1, y1) = (hi.x.min(width + 1.0), hi.y.min(height + 1.0));
        if !(x0 <= x1 && y0 <= y1) {
            return None;
        }
        // The steps read D at the point and one pixel right or down.
        let ds = [
            (x0, y0),
            (x1 + 1.0, y0),
            (x0, y1 + 1.0),
            (x1 + 1.0, y1 + 1.0),
        ]
        .map(|(x, y)| den.at(x, y));
        let (dmin, dmax) = ds
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &d| {
                (a.min(d), b.max(d))
            });
        let (xm, ym) = (x0.abs().max(x1.abs() + 1.0), y0.abs().max(y1.abs() + 1.0));
        let dt = terms(den, xm, ym);
        // D's sign is the same at every point (a margin for its own
        // rounding): no step divides by zero or crosses the horizon.
        let d_err = 8.0 * f64::EPSILON * dt;
        let (dlo, dhi) = if dmin > d_err {
            (dmin - d_err, dmax + d_err)
        } else if dmax < -d_err {
            (-dmax - d_err, -dmin + d_err)
        } else {
            return None;
        };
        let eps = f64::EPSILON;
        let mut num = [[0.0; 2]; 4];
        let mut t_max = 0.0f64;
        for (k, p) in uv.iter().enumerate() {
            // Right: (T_x D_c - D_x T_c) + (T_x D_y - D_x T_y) y.
            let (a0, a1) = (p.x * den.c - den.x * p.c, p.x * den.y - den.x * p.y);
            let ea = 4.0 * eps * ((p.x * den.c).abs() + (den.x * p.c).abs())
                + 4.0 * eps * ym * ((p.x * den.y).abs() + (den.x * p.y).abs());
            num[k] = affine_abs(a0, a1, (y0, y1), ea);
            // Down: (T_y D_c - D_y T_c) + (T_y D_x - D_y T_x) x.
            let (b0, b1) = (p.y * den.c - den.y * p.c, p.y * den.x - den.y * p.x);
            let eb = 4.0 * eps * ((p.y * den.c).abs() + (den.y * p.c).abs())
                + 4.0 * eps * xm * ((p.y * den.x).abs() + (den.y * p.x).abs());
            num[2 + k] = affine_abs(b0, b1, (x0, x1), eb);
            t_max = t_max.max(terms(p, xm, ym) + p.x.abs().max(p.y.abs()));
        }
        // A coordinate T / D is off by its planes' rounding (a few units
        // in the last place of their terms) over D, plus the quotient's;
        // a step is two of them and their difference.
        let coordinate = t_max / dlo;
        let err = 64.0 * eps * (t_max / dlo + coordinate * dt / dlo + coordinate);
        let bounds = Self {
            rect: [x0, y0, x1, y1],
            num,
            den: [dlo, dhi],
            err,
        };
        let finite = bounds.num.iter().flatten().all(|v| v.is_finite())
            && dhi.is_finite()
            && err.is_finite();
        finite.then_some(bounds)
    }

    /// Whether `(x, y)` is a point the bounds hold for.
    #[inline]
    pub(super) fn holds_at(&self, x: f64, y: f64) -> bool {
        let [x0, y0, x1, y1] = self.rect;
        x >= x0 && x <= x1 && y >= y0 && y <= y1
    }

    /// The level every point of the rectangle reads from a chain of
    /// `levels` levels whose level-0 texels per unit of texture coordinate
    /// are `scale`, when the bounds give one level; `None` otherwise.
    pub(super) fn fixed_level(&self, scale: DVec2, levels: u32) -> Option<u32> {
        let s2 = scale * scale;
        let [dlo, dhi] = self.den;
        let (p_lo, p_hi) = ((dlo * dlo).powi(2), (dhi * dhi).powi(2));
        let sq = |[lo, hi]: [f64; 2]| DVec2::new(lo * lo, hi * hi);
        let bound = |u: DVec2, v: DVec2| (s2.x * u + s2.y * v) * DVec2::new(1.0 / p_hi, 1.0 / p_lo);
        let right = bound(sq(self.num[0]), sq(self.num[1]));
        let down = bound(sq(self.num[2]), sq(self.num[3]));
        let rho = DVec2::new(right.x.max(down.x), right.y.max(down.y)).map(f64::sqrt);
        let margin = 2.0 * self.err * scale.x.abs().max(scale.y.abs());
        let lo = (rho.x * (1.0 - 1e-9) - margin).max(0.0);
        let hi = rho.y * (1.0 + 1e-9) + margin;
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        let (a, b) = (
            mip::level_for_squared(lo * lo * (1.0 - 1e-9), levels),
            mip::level_for_squared(hi * hi * (1.0 + 1e-9), levels),
        );
        (a == b).then_some(a)
    }
}

/// The window positions of camera-space `corners`, when all are in front
/// of the eye (`to_window` gives `None` for one that is not).
pub(super) fn window_corners(
    corners: [DVec3; 3],
    to_window: impl Fn(DVec3) -> Option<DVec2>,
) -> Option<[DVec2; 3]> {
    let [a, b, c] = corners.map(to_window);
    Some([a?, b?, c?])
}
