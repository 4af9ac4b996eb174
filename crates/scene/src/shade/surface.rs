//! Surface colour at a point: what the hiders that resolve colour
//! themselves (the A-buffer, supersampling, anti-aliased Warnock) need of
//! the texture stage.
//!
//! Pixel-centre hiders only decide which primitive each pixel shows; the
//! colour pass over their id buffer samples textures at pixel centres.
//! Hiders that composite several surfaces in a pixel, or several samples,
//! must colour each fragment or sample themselves, so the same lookup is
//! offered here: a primitive's flat colour ([`crate::shade::prim_color`])
//! times its diffuse texture (`map_Kd`) at a window point, with
//! perspective-correct texture coordinates.
//!
//! Perspective-correct coordinates follow the perspective-correct
//! interpolation blog post and scratchapixel's depth-buffer lesson:
//! attributes are affine in camera space, not on the screen. The camera
//! ray through the window point is intersected with the primitive's
//! camera-space plane and the uvs are interpolated with the barycentrics
//! of that point, which also holds for the pieces of a triangle clipped by
//! the near plane (they keep their source primitive's uvs).
//!
//! Textures belong to the materials ([`crate::TextureRef`]): decoded on
//! first use, once per file, and shared by every copy of the material, so
//! nothing has to be loaded or bound before a frame.

use glam::{DMat4, DVec2, DVec3, DVec4};
use hider_geom::{Projection, Viewport};

use super::setup::{Footprint, SetupCache, SurfaceSetup, alpha_textures};
use super::texture::{Filter, TextureRef};
use crate::model::{Illumination, Light, Material};
use crate::prepare::{PrimInfo, ScreenScene};
use crate::view::View;

/// How texture coordinates are interpolated across a triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Mapping {
    /// Barycentrics of the camera-space point seen through the window
    /// point: correct under perspective (the default).
    #[default]
    PerspectiveCorrect,
    /// Barycentrics on the screen: *wrong* under perspective (straight
    /// texture lines bend at triangle edges); kept as a demonstration.
    Affine,
}

/// How textures are sampled. `Default` is the accurate choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct TextureOptions {
    /// Texture filter.
    pub filter: Filter,
    /// Texture coordinate interpolation.
    pub mapping: Mapping,
}

impl TextureOptions {
    /// Sets [`Self::filter`].
    pub fn with_filter(mut self, filter: Filter) -> Self {
        self.filter = filter;
        self
    }

    /// Sets [`Self::mapping`].
    pub fn with_mapping(mut self, mapping: Mapping) -> Self {
        self.mapping = mapping;
        self
    }
}

/// Shades a frame's primitives at window points: the camera rays of one
/// view (the projection inverted once), the texture sampling options, and
/// which stages run. Cheap to build; build one per frame.
///
/// A primitive whose colour varies across it (a texture, vertex normals
/// for smooth shading, highlights: [`Self::varies`]) is shaded per point
/// with [`super::shade_point`], its attributes interpolated with the
/// barycentrics of the camera-space point seen through the window point;
/// the others keep their flat colour ([`super::flat_color`]).
///
/// Textures are the materials' own ([`crate::TextureRef`], decoded on first
/// use), so a sampler holds no texture and a scene needs no loading step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureSampler {
    rays: CameraRays,
    options: TextureOptions,
    textures: bool,
    lighting: bool,
}

impl TextureSampler {
    /// A sampler for the frame `screen` was prepared for, every stage on.
    pub fn new(screen: &ScreenScene, options: TextureOptions) -> Self {
        Self {
            rays: CameraRays::new(
                screen.projection_matrix,
                screen.viewport,
                screen.is_perspective(),
            ),
            options,
            textures: true,
            lighting: true,
        }
    }

    /// A sampler for `view` (for passes that work from the world-space
    /// scene: the same rays as [`Self::new`] on the scene prepared for it).
    pub fn for_view(view: &View, options: TextureOptions) -> Self {
        let camera = view.camera;
        Self {
            rays: CameraRays::new(
                camera.projection_matrix(view.viewport.aspect()),
                view.viewport,
                matches!(camera.projection, Projection::Perspective { .. }),
            ),
            options,
            textures: true,
            lighting: true,
        }
    }

    /// This sampler with the texture and lighting stages on or off (off,
    /// textures are not sampled, and an unlit primitive shows its diffuse
    /// colour).
    pub fn with_stages(mut self, textures: bool, lighting: bool) -> Self {
        self.textures = textures;
        self.lighting = lighting;
        self
    }

    /// The sampling options.
    pub fn options(&self) -> &TextureOptions {
        &self.options
    }

    /// The diffuse texture a primitive shows: its material's, when the
    /// primitive has texture coordinates and textures are on (not decoded
    /// here).
    #[inline]
    pub fn texture<'m>(&self, info: &PrimInfo, material: &'m Material) -> Option<&'m TextureRef> {
        if !self.textures {
            return None;
        }
        info.uvs?;
        material.diffuse_texture.as_ref()
    }

    /// Whether the primitive's colour varies across it with the stages on:
    /// a texture to sample (with uvs), vertex colours or normals to
    /// interpolate, or highlights, which follow the view direction. Decides nothing by
    /// decoding a texture.
    pub fn varies(&self, info: &PrimInfo, material: &Material) -> bool {
        let textured = self.textures
            && info.uvs.is_some()
            && (material.diffuse_texture.is_some()
                || (self.lighting && material.specular_texture.is_some()));
        let lit = self.lighting && material.illumination != Illumination::Color;
        textured
            || info.colors.is_some()
            || (lit && (info.normals.is_some() || material.has_highlights()))
    }

    /// Barycentrics of the point of primitive `info` seen at window point
    /// `(x, y)`, and that point in camera space; `None` when the ray runs
    /// parallel to the primitive's plane or the primitive is degenerate.
    pub(super) fn barycentrics(
        &self,
        info: &PrimInfo,
        x: f64,
        y: f64,
    ) -> Option<([f64; 3], DVec3)> {
        let c = info.camera;
        match self.options.mapping {
            Mapping::PerspectiveCorrect => {
                let (o, d) = self.rays.ray(x, y);
                let n = (c[1] - c[0]).cross(c[2] - c[0]);
                let denom = n.dot(d);
                if denom == 0.0 || n == DVec3::ZERO {
                    return None;
                }
                let p = o + d * (n.dot(c[0] - o) / denom);
                Some((barycentric3(c, n, p), p))
            }
            Mapping::Affine => {
                let w = c.map(|q| self.rays.window_of(q));
                let b = barycentric2(w, DVec2::new(x, y))?;
                Some((b, c[0] * b[0] + c[1] * b[1] + c[2] * b[2]))
            }
        }
    }

    /// The texture coordinates of the primitive `info` seen at window point
    /// `(x, y)` (pixels, y down), or `None` without uvs or when the ray runs
    /// parallel to the primitive's plane.
    pub fn uv_at(&self, info: &PrimInfo, x: f64, y: f64) -> Option<DVec2> {
        let uv = info.uvs?.map(|t| t.as_dvec2());
        let (b, _) = self.barycentrics(info, x, y)?;
        Some(uv[0] * b[0] + uv[1] * b[1] + uv[2] * b[2])
    }

    /// The texture coordinates of `info` at window point `(x, y)` and their
    /// change one pixel right and one pixel down (the footprint the mip
    /// level is chosen from, [`super::mip`]), from barycentrics `b` at the
    /// point; the derivatives are zero where they cannot be found.
    pub(super) fn uv_footprint(
        &self,
        info: &PrimInfo,
        b: [f64; 3],
        x: f64,
        y: f64,
    ) -> Option<Footprint> {
        let t = info.uvs?.map(|t| t.as_dvec2());
        let at = |b: [f64; 3]| t[0] * b[0] + t[1] * b[1] + t[2] * b[2];
        let uv = at(b);
        let step = |bx: Option<([f64; 3], DVec3)>| bx.map_or(DVec2::ZERO, |(b, _)| at(b) - uv);
        let dx = step(self.barycentrics(info, x + 1.0, y));
        let dy = step(self.barycentrics(info, x, y + 1.0));
        Some(Footprint {
            uv,
            dx,
            dy,
            fixed: false,
        })
    }

    /// The texture alpha of primitive `info` at window point `(x, y)`: its
    /// diffuse texture's alpha times its dissolve texture's value (`map_d`,
    /// a mask); 1 for a texture that is missing, has no alpha channel or
    /// does not load, and without uvs: the value the alpha test compares
    /// with one half, sampled exactly as the colour is (same point, level
    /// and filter).
    ///
    /// A caller testing several points of one primitive builds its
    /// [`SurfaceSetup`] once instead ([`SurfaceSetup::alpha_at`]: the same
    /// values).
    pub fn alpha_at(&self, info: &PrimInfo, material: &Material, x: f64, y: f64) -> f32 {
        if !self.textures || info.uvs.is_none() || alpha_textures(material) == (None, None) {
            return 1.0;
        }
        SurfaceSetup::new(self, info).alpha_at(self, material, x, y)
    }

    /// The colour of primitive `info` (of `material`, under camera-space
    /// `lights`) at window point `(x, y)`, shaded at that point; `None`
    /// when its colour does not vary across it ([`Self::varies`]: the
    /// caller's flat colour is the answer) or the point cannot be found.
    /// A caller shading several points of one primitive builds its
    /// [`SurfaceSetup`] once instead (the same colours).
    pub fn color_at(
        &self,
        info: &PrimInfo,
        material: &Material,
        lights: &[Light],
        x: f64,
        y: f64,
    ) -> Option<[f32; 3]> {
        if !self.varies(info, material) {
            return None;
        }
        SurfaceSetup::new(self, info).color_at(self, material, lights, x, y)
    }

    /// The camera rays of the frame.
    pub(super) fn rays(&self) -> &CameraRays {
        &self.rays
    }

    /// Whether the texture stage is on.
    pub(super) fn textures_on(&self) -> bool {
        self.textures
    }

    /// Whether the lighting stage is on.
    pub(super) fn lighting_on(&self) -> bool {
        self.lighting
    }
}

impl ScreenScene {
    /// The texture alpha of primitive `prim` at window point `(x, y)`
    /// ([`TextureSampler::alpha_at`]) when its material's alpha textures
    /// were decoded and hold partial alpha ([`super::AlphaClass::Partial`]:
    /// translucency, which compositing hiders multiply the opacity by);
    /// `None` otherwise (never decodes: the hider's alpha test decoded them
    /// when it met the primitive).
    pub fn partial_alpha_at(
        &self,
        sampler: &TextureSampler,
        prim: u32,
        x: f64,
        y: f64,
    ) -> Option<f32> {
        let info = &self.prims[prim as usize];
        let material = &self.materials[info.material as usize];
        info.uvs?;
        self.partial_alpha(material)
            .then(|| sampler.alpha_at(info, material, x, y))
    }

    /// [`Self::partial_alpha_at`] with the primitive's shading setup from
    /// `cache` (built there on first use): the same value, for a hider
    /// that tests many points of a primitive.
    pub fn partial_alpha_at_cached(
        &self,
        sampler: &TextureSampler,
        cache: &mut SetupCache,
        prim: u32,
        x: f64,
        y: f64,
    ) -> Option<f32> {
        let info = &self.prims[prim as usize];
        let material = &self.materials[info.material as usize];
        info.uvs?;
        // A material with partial alpha has an alpha texture, and the
        // setup answers 1 itself with textures off.
        self.partial_alpha(material).then(|| {
            let setup = cache.get_or_insert_with(prim, || SurfaceSetup::new(sampler, info));
            setup.alpha_at(sampler, material, x, y)
        })
    }

    /// Whether `material`'s alpha textures were decoded and hold partial
    /// alpha.
    fn partial_alpha(&self, material: &Material) -> bool {
        super::cutout::alpha_textures(material).any(|t| {
            t.may_have_alpha() && t.decoded_alpha_class() == Some(super::AlphaClass::Partial)
        })
    }

    /// [`Self::surface_rgb`] with the primitive's shading setup from
    /// `cache` (built there on first use): the same colour, for a hider
    /// that shades many points of a primitive.
    #[inline]
    pub fn surface_rgb_cached(
        &self,
        sampler: &TextureSampler,
        cache: &mut SetupCache,
        prim: u32,
        base: [f32; 3],
        x: f64,
        y: f64,
    ) -> [f32; 3] {
        let info = &self.prims[prim as usize];
        let material = &self.materials[info.material as usize];
        if !sampler.varies(info, material) {
            return base;
        }
        cache
            .get_or_insert_with(prim, || SurfaceSetup::new(sampler, info))
            .color_at(sampler, material, &self.lights, x, y)
            .unwrap_or(base)
    }

    /// The colour of primitive `prim` at window point `(x, y)`
    /// ([`TextureSampler::color_at`]), or `base`, its flat colour, when its
    /// colour does not vary: the surface colour a colour-resolving hider
    /// composites.
    #[inline]
    pub fn surface_rgb(
        &self,
        sampler: &TextureSampler,
        prim: u32,
        base: [f32; 3],
        x: f64,
        y: f64,
    ) -> [f32; 3] {
        let info = &self.prims[prim as usize];
        let material = &self.materials[info.material as usize];
        sampler
            .color_at(info, material, &self.lights, x, y)
            .unwrap_or(base)
    }

    /// Whether some primitive's colour varies across it under `sampler`'s
    /// stages ([`TextureSampler::varies`]): a frame a colour-resolving hider
    /// must shade per point.
    pub fn varies(&self, sampler: &TextureSampler) -> bool {
        self.prims
            .iter()
            .any(|p| sampler.varies(p, &self.materials[p.material as usize]))
    }
}

/// Barycentrics of `p` (on the plane of `c` with normal `n`).
fn barycentric3(c: [DVec3; 3], n: DVec3, p: DVec3) -> [f64; 3] {
    let nn = n.length_squared();
    let b0 = n.dot((c[2] - c[1]).cross(p - c[1])) / nn;
    let b1 = n.dot((c[0] - c[2]).cross(p - c[2])) / nn;
    [b0, b1, 1.0 - b0 - b1]
}

/// Barycentrics of `p` in the 2D triangle `w`.
fn barycentric2(w: [DVec2; 3], p: DVec2) -> Option<[f64; 3]> {
    let area = (w[1] - w[0]).perp_dot(w[2] - w[0]);
    if area == 0.0 {
        return None;
    }
    let b0 = (w[2] - w[1]).perp_dot(p - w[1]) / area;
    let b1 = (w[0] - w[2]).perp_dot(p - w[2]) / area;
    Some([b0, b1, 1.0 - b0 - b1])
}

/// Camera-space rays through window points, with the projection inverted
/// once per frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct CameraRays {
    inverse: DMat4,
    projection: DMat4,
    width: f64,
    height: f64,
    pub(super) perspective: bool,
    /// [`Self::affine_ray`], found once (every primitive's setup reads it).
    affine: Option<[DVec3; 3]>,
}

impl CameraRays {
    fn new(projection: DMat4, viewport: Viewport, perspective: bool) -> Self {
        let mut rays = Self {
            inverse: projection.inverse(),
            projection,
            width: f64::from(viewport.width),
            height: f64::from(viewport.height),
            perspective,
            affine: None,
        };
        rays.affine = rays.solve_affine_ray();
        rays
    }

    /// `(origin, direction)` as [`ScreenScene::camera_ray`] gives them.
    fn ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let ndc_x = 2.0 * x / self.width - 1.0;
        let ndc_y = 1.0 - 2.0 * y / self.height;
        let near = self.inverse * DVec4::new(ndc_x, ndc_y, -1.0, 1.0);
        let near = near.truncate() / near.w;
        if self.perspective {
            (DVec3::ZERO, near)
        } else {
            let far = self.inverse * DVec4::new(ndc_x, ndc_y, 1.0, 1.0);
            (near, far.truncate() / far.w - near)
        }
    }

    /// Under a perspective camera, the direction of the ray through the
    /// window origin and its change one pixel right and one pixel down:
    /// the ray through `(x, y)` runs from the eye along `d0 + x dx + y dy`
    /// ([`Self::ray`]'s direction up to a positive or negative scale,
    /// which does not move the point it meets a plane at). `None` for an
    /// orthographic camera, whose rays do not share an origin.
    #[inline]
    pub(super) fn affine_ray(&self) -> Option<[DVec3; 3]> {
        self.affine
    }

    /// [`Self::affine_ray`] from the inverse projection.
    fn solve_affine_ray(&self) -> Option<[DVec3; 3]> {
        if !self.perspective {
            return None;
        }
        // The homogeneous inverse image of (ndc_x, ndc_y, -1, 1) is
        // affine in the window point; its division by w only scales it.
        let at = |v: DVec4| (self.inverse * v).truncate();
        Some([
            at(DVec4::new(-1.0, 1.0, -1.0, 1.0)),
            at(DVec4::new(2.0 / self.width, 0.0, 0.0, 0.0)),
            at(DVec4::new(0.0, -2.0 / self.height, 0.0, 0.0)),
        ])
    }

    /// A camera-space point's window position (pixels, y down), when it
    /// is in front of the eye (clip `w` positive) under a perspective
    /// camera.
    pub(super) fn window_in_front(&self, p: DVec3) -> Option<DVec2> {
        let clip = self.projection * p.extend(1.0);
        (self.perspective && clip.w > 0.0).then(|| self.window_of_clip(clip))
    }

    /// The window's width and height in pixels.
    pub(super) fn size(&self) -> (f64, f64) {
        (self.width, self.height)
    }

    /// A camera-space point's window position (pixels, y down).
    pub(super) fn window_of(&self, p: DVec3) -> DVec2 {
        self.window_of_clip(self.projection * p.extend(1.0))
    }

    /// The window position of clip-space point `clip`.
    fn window_of_clip(&self, clip: DVec4) -> DVec2 {
        let ndc = clip.truncate() / clip.w;
        DVec2::new(
            (ndc.x + 1.0) * 0.5 * self.width,
            (1.0 - ndc.y) * 0.5 * self.height,
        )
    }
}
