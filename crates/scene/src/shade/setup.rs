//! Per-primitive shading setup: what [`TextureSampler::color_at`] needs of
//! a primitive that does not change across it, computed once, so that a
//! hider shading many fragments of one primitive pays per fragment only
//! for the point itself.
//!
//! **Barycentrics as ratios of planes.** Under a perspective camera every
//! camera ray starts at the eye and its direction `d` is affine in the
//! window point `(x, y)` (the inverse projection of `(ndc_x, ndc_y, -1,
//! 1)`, whose scale does not move the hit point). The point of the
//! primitive's plane (normal `n`, through corner `c0`) seen at `(x, y)` is
//! `p = d (n.c0) / (n.d)`, and its barycentrics `b_i = (n x e_i).(p - c_j)
//! / |n|^2` (the same formula as the per-point solve) are then ratios
//! `N_i(x, y) / D(x, y)` of two planes in window coordinates: the
//! screen-space planes of `u/w`, `v/w` and `1/w` of hardware rasterisers
//! (Heckbert and Moreton, "Interpolation for polygon texture mapping and
//! shading", 1991). One division per point gives the barycentrics; the
//! texture coordinates one pixel right and one pixel down (the mip level's
//! footprint, [`super::mip`]) cost two more divisions, not two ray solves.
//!
//! The arithmetic differs from a ray solve per point by rounding only: the
//! texture coordinates agree to about 1e-12 of their range, so a sample
//! differs from the solve's by at most one sRGB step, and reads another
//! mip level only where the footprint is within rounding of a level
//! boundary (tests below). Orthographic cameras and
//! [`Mapping::Affine`] keep the solve per point.
//!
//! The face normal, the texture's header (size, scale, levels) and the
//! decoded texture are also found once per primitive.

use std::sync::Arc;

use glam::{DVec2, DVec3};

use super::mip;
use super::surface::{Mapping, TextureSampler};
use super::texture::{Texture, TextureRef};
use crate::model::{Illumination, Light, Material};
use crate::prepare::PrimInfo;

/// `c + x X + y Y`: a function affine in the window point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Plane {
    c: f64,
    x: f64,
    y: f64,
}

impl Plane {
    /// The plane whose value at `(x, y)` is `f(D0 + x Dx + y Dy)` for a
    /// linear `f`, from `f` of the three ray terms.
    fn of(ray: &[DVec3; 3], f: impl Fn(DVec3) -> f64) -> Self {
        Self {
            c: f(ray[0]),
            x: f(ray[1]),
            y: f(ray[2]),
        }
    }

    #[inline]
    fn at(&self, x: f64, y: f64) -> f64 {
        self.c + x * self.x + y * self.y
    }
}

/// The barycentric planes of a primitive under a perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Planes {
    /// Ray direction at the window origin, and its change per pixel
    /// right and down.
    ray: [DVec3; 3],
    /// `(n.c0) |n|^2`: the point seen is `d (n.c0) / (n.d)`, the ray
    /// direction times this over the denominator.
    knn: f64,
    /// `|n|^2 (n.d)`: the barycentrics' denominator.
    den: Plane,
    /// Numerators of the first two barycentrics, over [`Self::den`].
    b0: Plane,
    b1: Plane,
    /// Numerators of the texture coordinates `u` and `v` over
    /// [`Self::den`] (the `u/w`, `v/w` planes), with uvs.
    uv: Option<[Plane; 2]>,
}

impl Planes {
    fn new(ray: [DVec3; 3], c: [DVec3; 3], n: DVec3, uvs: Option<[DVec2; 3]>) -> Self {
        let k = n.dot(c[0]);
        let nn = n.length_squared();
        // b0 = m0.(p - c1) with p = d k / (n.d): over |n|^2 (n.d), the
        // numerator k m0.d - (m0.c1) n.d is linear in d.
        let numerator = |m: DVec3, corner: DVec3| {
            let mc = m.dot(corner);
            Plane::of(&ray, |d| k * m.dot(d) - mc * n.dot(d))
        };
        let den = Plane::of(&ray, |d| nn * n.dot(d));
        let (b0, b1) = (
            numerator(n.cross(c[2] - c[1]), c[1]),
            numerator(n.cross(c[0] - c[2]), c[2]),
        );
        // u = sum t_i b_i with b2 = 1 - b0 - b1: over `den`, the plane
        // t2 den + (t0 - t2) N0 + (t1 - t2) N1.
        let uv = uvs.map(|t| {
            let (a, b) = (t[0] - t[2], t[1] - t[2]);
            let plane = |k: usize| Plane {
                c: t[2][k] * den.c + a[k] * b0.c + b[k] * b1.c,
                x: t[2][k] * den.x + a[k] * b0.x + b[k] * b1.x,
                y: t[2][k] * den.y + a[k] * b0.y + b[k] * b1.y,
            };
            [plane(0), plane(1)]
        });
        Self {
            ray,
            knn: k * nn,
            den,
            b0,
            b1,
            uv,
        }
    }

    /// Barycentrics at `(x, y)`, the denominator there and its inverse;
    /// `None` where the ray runs parallel to the plane.
    #[inline]
    fn barycentrics(&self, x: f64, y: f64) -> Option<([f64; 3], Den)> {
        let den = self.den.at(x, y);
        if den == 0.0 {
            return None;
        }
        let inv = 1.0 / den;
        let (b0, b1) = (self.b0.at(x, y) * inv, self.b1.at(x, y) * inv);
        Some(([b0, b1, 1.0 - b0 - b1], Den { den, inv }))
    }

    /// The camera-space point at `(x, y)`, where the denominator's
    /// inverse is `inv`.
    #[inline]
    fn position(&self, x: f64, y: f64, inv: f64) -> DVec3 {
        let d = self.ray[0] + self.ray[1] * x + self.ray[2] * y;
        d * (self.knn * inv)
    }

    /// The texture coordinates at `(x, y)`, where the denominator is
    /// `den`, and one pixel right and down (from the planes' steps: one
    /// division each, no barycentrics) unless the point's levels are
    /// `fixed` (then the steps are left zero: nothing reads them); `None`
    /// without uvs.
    #[inline]
    fn footprint(&self, x: f64, y: f64, Den { den, inv }: Den, fixed: bool) -> Option<Footprint> {
        let [pu, pv] = self.uv.as_ref()?;
        let top = DVec2::new(pu.at(x, y), pv.at(x, y));
        let uv = top * inv;
        if fixed {
            return Some(Footprint {
                uv,
                dx: DVec2::ZERO,
                dy: DVec2::ZERO,
                fixed,
            });
        }
        let step = |top: DVec2, den: f64| {
            if den == 0.0 {
                DVec2::ZERO
            } else {
                top / den - uv
            }
        };
        Some(Footprint {
            uv,
            dx: step(top + DVec2::new(pu.x, pv.x), den + self.den.x),
            dy: step(top + DVec2::new(pu.y, pv.y), den + self.den.y),
            fixed,
        })
    }
}

/// The barycentrics' denominator at a point and its inverse.
#[derive(Clone, Copy, Debug, Default)]
struct Den {
    den: f64,
    inv: f64,
}

/// A texture's sampling setup for one primitive: its footprint scale and
/// chain length (from the header), the level every point of the
/// primitive reads when its footprint cannot change it
/// ([`level::LevelBounds`]), and the decoded texture once sampled.
#[derive(Clone, Debug)]
struct TexSetup {
    /// Level-0 texels per unit of texture coordinate, `-s` included.
    scale: DVec2,
    levels: u32,
    fixed: Option<u32>,
    held: Option<Arc<Texture>>,
}

impl TexSetup {
    fn new(texture: &TextureRef, bounds: Option<&LevelBounds>) -> Option<Self> {
        let (size, levels) = texture.footprint_scale()?;
        let scale = DVec2::from(size) * DVec2::from(texture.transform.scale);
        Some(Self {
            scale,
            levels,
            fixed: bounds.and_then(|b| b.fixed_level(scale, levels)),
            held: None,
        })
    }

    /// [`TextureRef::sample_footprint`] with this setup, inlined with
    /// the whole fetch (its helpers and closures are forced inline too:
    /// with this alone they were left as calls, 8 M instructions more on
    /// the textured spider's frame).
    #[inline(always)]
    fn sample(
        &mut self,
        texture: &TextureRef,
        f: &Footprint,
        filter: super::Filter,
    ) -> Option<([f32; 3], f32)> {
        let (t, level, u, v) = self.at(texture, f)?;
        Some(t.sample_level(u, v, filter, texture.transform.clamp, level))
    }

    /// [`Self::sample`]'s alpha alone.
    #[inline]
    fn sample_alpha(
        &mut self,
        texture: &TextureRef,
        f: &Footprint,
        filter: super::Filter,
    ) -> Option<f32> {
        let (t, level, u, v) = self.at(texture, f)?;
        Some(t.sample_level_alpha(u, v, filter, texture.transform.clamp, level))
    }

    /// The texture holding the level footprint `f` reads (decoded now if
    /// it is not held), that level and the point's coordinates through the
    /// texture's transform.
    #[inline(always)]
    fn at(&mut self, texture: &TextureRef, f: &Footprint) -> Option<(&Texture, u32, f64, f64)> {
        let level = match self.fixed {
            Some(level) if f.fixed => level,
            _ => {
                debug_assert!(!f.fixed, "a footprint without steps for a level not fixed");
                let rho2 = (f.dx * self.scale)
                    .length_squared()
                    .max((f.dy * self.scale).length_squared());
                mip::level_for_squared(rho2, self.levels)
            }
        };
        if self.held.as_ref().is_none_or(|t| t.base_level() > level) {
            self.held = Some(texture.get_level(level)?);
        }
        let (u, v) = texture.transform.apply(f.uv.x, f.uv.y);
        Some((self.held.as_deref()?, level, u, v))
    }
}

/// The colour of `texture` (with its setup in `slot`, made by
/// [`SurfaceSetup::levels_fixed`]) at footprint `f`; `None` without a
/// texture, a footprint, or when the texture does not load.
#[inline(always)]
fn map_texel(
    slot: &mut Option<Option<TexSetup>>,
    texture: Option<&TextureRef>,
    f: Option<&Footprint>,
    filter: super::Filter,
) -> Option<[f32; 3]> {
    let texture = texture?;
    let setup = slot.as_mut()?.as_mut()?;
    Some(setup.sample(texture, f?, filter)?.0)
}

/// The textures whose alpha make up `material`'s texture alpha, where
/// their headers declare one: `map_Kd` (its alpha channel) and `map_d` (a
/// mask).
pub(super) fn alpha_textures(material: &Material) -> (Option<&TextureRef>, Option<&TextureRef>) {
    fn with_alpha(t: &Option<TextureRef>) -> Option<&TextureRef> {
        t.as_ref().filter(|t| t.may_have_alpha())
    }
    (
        with_alpha(&material.diffuse_texture),
        with_alpha(&material.alpha_texture),
    )
}

/// Texture coordinates at a point and their change one pixel right (`dx`)
/// and down (`dy`); `fixed` when the point is one where every texture
/// sampled has its level fixed (then the steps were not computed).
pub(super) struct Footprint {
    pub(super) uv: DVec2,
    pub(super) dx: DVec2,
    pub(super) dy: DVec2,
    pub(super) fixed: bool,
}

/// What shading a primitive per point reads that does not change across
/// it (see the module documentation): build one per primitive (and
/// frame), then [`Self::color_at`] for each of its points. The colours
/// are the same, bit for bit, as [`TextureSampler::color_at`]'s, which
/// builds one per call.
#[derive(Clone, Debug)]
pub struct SurfaceSetup {
    info: PrimInfo,
    planes: Option<Planes>,
    /// The footprint's bounds when every texture the colour reads has a
    /// fixed level where they hold, found with the textures' setups on
    /// the first textured point (`Some(None)`: nowhere).
    fixed: Option<Option<LevelBounds>>,
    /// Unit face normal (zero for a degenerate primitive).
    face: DVec3,
    /// The diffuse, specular and dissolve (`map_d`) textures' setups,
    /// made on first sample (`Some(None)`: no texture, or its header does
    /// not read).
    diffuse: Option<Option<TexSetup>>,
    specular: Option<Option<TexSetup>>,
    dissolve: Option<Option<TexSetup>>,
}

impl SurfaceSetup {
    /// The setup of the primitive with data `info` for `sampler`'s frame.
    pub fn new(sampler: &TextureSampler, info: &PrimInfo) -> Self {
        let c = info.camera;
        let n = (c[1] - c[0]).cross(c[2] - c[0]);
        let planes = match (sampler.options().mapping, sampler.rays().affine_ray()) {
            (Mapping::PerspectiveCorrect, Some(ray)) if n != DVec3::ZERO => Some(Planes::new(
                ray,
                c,
                n,
                info.uvs.map(|t| t.map(|t| t.as_dvec2())),
            )),
            _ => None,
        };
        Self {
            info: *info,
            planes,
            fixed: None,
            face: n.normalize_or_zero(),
            diffuse: None,
            specular: None,
            dissolve: None,
        }
    }

    /// The primitive's data.
    pub fn info(&self) -> &PrimInfo {
        &self.info
    }

    /// Barycentrics of the point seen at `(x, y)`, that point in camera
    /// space, and the planes' denominator there (zero without planes).
    #[inline(always)]
    fn point(&self, sampler: &TextureSampler, x: f64, y: f64) -> Option<([f64; 3], DVec3, Den)> {
        match &self.planes {
            Some(p) => {
                let (b, den) = p.barycentrics(x, y)?;
                Some((b, p.position(x, y, den.inv), den))
            }
            None => {
                let (b, position) = sampler.barycentrics(&self.info, x, y)?;
                Some((b, position, Den::default()))
            }
        }
    }

    /// The texture coordinates at the point with barycentrics `b` seen at
    /// `(x, y)` (where the planes' denominator is `den`), and their change
    /// one pixel right and down (zero where it cannot be found).
    #[inline]
    fn footprint(
        &self,
        sampler: &TextureSampler,
        b: [f64; 3],
        den: Den,
        x: f64,
        y: f64,
        fixed: bool,
    ) -> Option<Footprint> {
        if let Some(p) = &self.planes {
            return p.footprint(x, y, den, fixed);
        }
        sampler.uv_footprint(&self.info, b, x, y)
    }

    /// Whether each of the textures `diffuse` and `specular` reads a
    /// fixed level at `(x, y)` ([`level::LevelBounds`]): then the point's
    /// footprint needs no steps. The first call makes their setups and
    /// the bounds (the textures a primitive's colour reads are the same
    /// at every point: its material's, under the frame's sampler); the
    /// others cost four comparisons.
    #[inline]
    fn levels_fixed(
        &mut self,
        sampler: &TextureSampler,
        diffuse: Option<&TextureRef>,
        specular: Option<&TextureRef>,
        x: f64,
        y: f64,
    ) -> bool {
        let bounds = match &self.fixed {
            Some(bounds) => bounds,
            None => {
                let bounds = self.make_texture_setups(sampler, diffuse, specular);
                self.fixed.insert(bounds)
            }
        };
        bounds.as_ref().is_some_and(|b| b.holds_at(x, y))
    }

    /// Makes the setups of `diffuse` and `specular` with the footprint's
    /// bounds, and gives the bounds when both read a fixed level where
    /// they hold.
    #[cold]
    fn make_texture_setups(
        &mut self,
        sampler: &TextureSampler,
        diffuse: Option<&TextureRef>,
        specular: Option<&TextureRef>,
    ) -> Option<LevelBounds> {
        let (planes, info) = (&self.planes, &self.info);
        let bounds = planes.as_ref().and_then(|p| {
            let corners =
                level::window_corners(info.camera, |c| sampler.rays().window_in_front(c))?;
            LevelBounds::new(p.uv.as_ref()?, &p.den, corners, sampler.rays().size())
        });
        let mut fixed = bounds.is_some();
        for (slot, texture) in [(&mut self.diffuse, diffuse), (&mut self.specular, specular)] {
            if let Some(t) = texture {
                let setup = slot.get_or_insert_with(|| TexSetup::new(t, bounds.as_ref()));
                fixed &= setup.as_ref().is_none_or(|s| s.fixed.is_some());
            }
        }
        bounds.filter(|_| fixed)
    }

    /// [`TextureSampler::alpha_at`] of this primitive (of `material`, the
    /// one `info` names) at window point `(x, y)`: its diffuse texture's
    /// alpha times its dissolve texture's value, sampled as the colour is
    /// (same point, footprint, level and filter).
    pub fn alpha_at(
        &mut self,
        sampler: &TextureSampler,
        material: &Material,
        x: f64,
        y: f64,
    ) -> f32 {
        if !sampler.textures_on() || self.info.uvs.is_none() {
            return 1.0;
        }
        let (kd, d) = alpha_textures(material);
        if kd.is_none() && d.is_none() {
            return 1.0;
        }
        let Some(f) = self
            .point(sampler, x, y)
            .and_then(|(b, _, den)| self.footprint(sampler, b, den, x, y, false))
        else {
            return 1.0;
        };
        let filter = sampler.options().filter;
        let alpha = |slot: &mut Option<Option<TexSetup>>, texture: Option<&TextureRef>| {
            texture
                .and_then(|t| {
                    let setup = slot
                        .get_or_insert_with(|| TexSetup::new(t, None))
                        .as_mut()?;
                    setup.sample_alpha(t, &f, filter)
                })
                .unwrap_or(1.0)
        };
        alpha(&mut self.diffuse, kd) * alpha(&mut self.dissolve, d)
    }

    /// [`TextureSampler::color_at`] of this primitive (of `material`, the
    /// one `info` names, under camera-space `lights`) at window point
    /// `(x, y)`.
    pub fn color_at(
        &mut self,
        sampler: &TextureSampler,
        material: &Material,
        lights: &[Light],
        x: f64,
        y: f64,
    ) -> Option<[f32; 3]> {
        if !sampler.varies(&self.info, material) {
            return None;
        }
        let (b, position, den) = self.point(sampler, x, y)?;
        let textures = sampler.textures_on();
        let filter = sampler.options().filter;
        let highlights = sampler.lighting_on() && material.has_highlights();
        let diffuse_map = material.diffuse_texture.as_ref().filter(|_| textures);
        let specular_map = (material.specular_texture.as_ref()).filter(|_| textures && highlights);
        // The footprint is the same for both textures: found once, into a
        // local (not built on first use inside a closure: that cost three
        // trips through memory on the way to the mip level).
        let footprint = if diffuse_map.is_some() || specular_map.is_some() {
            let fixed = self.levels_fixed(sampler, diffuse_map, specular_map, x, y);
            self.footprint(sampler, b, den, x, y, fixed)
        } else {
            None
        };
        let f = footprint.as_ref();
        let times = |c: [f32; 3], t: Option<[f32; 3]>| match t {
            Some(t) => [c[0] * t[0], c[1] * t[1], c[2] * t[2]],
            None => c,
        };
        let texel = map_texel(&mut self.diffuse, diffuse_map, f, filter);
        let specular_texel =
            highlights.then(|| map_texel(&mut self.specular, specular_map, f, filter));
        let info = &self.info;
        let base = match info.colors {
            Some(c) => std::array::from_fn(|k| {
                (f64::from(c[0][k]) * b[0] + f64::from(c[1][k]) * b[1] + f64::from(c[2][k]) * b[2])
                    as f32
            }),
            None => material.diffuse,
        };
        let diffuse = times(base, texel);
        if !sampler.lighting_on() {
            return Some(diffuse);
        }
        let face = self.face;
        let normal = match info.normals {
            Some(n) if material.illumination != Illumination::Color => {
                let n = n.map(|n| n.as_dvec3());
                let smooth = (n[0] * b[0] + n[1] * b[1] + n[2] * b[2]).normalize_or_zero();
                // A zero normal (opposite normals at the corners) falls back
                // to the face's.
                if smooth == DVec3::ZERO { face } else { smooth }
            }
            _ => face,
        };
        let specular = match specular_texel {
            Some(t) => times(material.specular, t),
            None => [0.0; 3],
        };
        let point = super::SurfacePoint {
            position,
            normal,
            diffuse,
            ambient: material.ambient.map(|a| times(a, texel)),
            specular,
            perspective: sampler.rays().perspective,
        };
        Some(super::shade_point(material, lights, &point))
    }
}

mod cache;
mod level;
pub use cache::SetupCache;
use level::LevelBounds;

#[cfg(all(test, feature = "obj", feature = "image"))]
mod tests;
