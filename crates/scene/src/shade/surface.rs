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

use super::texture::{Filter, Texture};
use crate::model::Material;
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

/// Samples the diffuse textures of a frame's primitives at window points:
/// the camera rays of one view (the projection inverted once) and the
/// sampling options. Cheap to build; build one per frame.
///
/// Textures are the materials' own ([`crate::TextureRef`], decoded on first
/// use), so a sampler holds no texture and a scene needs no loading step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureSampler {
    rays: CameraRays,
    options: TextureOptions,
}

impl TextureSampler {
    /// A sampler for the frame `screen` was prepared for.
    pub fn new(screen: &ScreenScene, options: TextureOptions) -> Self {
        Self {
            rays: CameraRays::new(
                screen.projection_matrix,
                screen.viewport,
                screen.is_perspective(),
            ),
            options,
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
        }
    }

    /// The sampling options.
    pub fn options(&self) -> &TextureOptions {
        &self.options
    }

    /// The texture a primitive shows: its material's, when the primitive
    /// has texture coordinates and the texture loads (decoded now if this
    /// is its first use).
    #[inline]
    pub fn texture<'m>(&self, info: &PrimInfo, material: &'m Material) -> Option<&'m Texture> {
        info.uvs?;
        material.diffuse_texture.as_ref()?.get()
    }

    /// The texture coordinates of the primitive `info` seen at window point
    /// `(x, y)` (pixels, y down), or `None` without uvs or when the ray runs
    /// parallel to the primitive's plane.
    pub fn uv_at(&self, info: &PrimInfo, x: f64, y: f64) -> Option<DVec2> {
        let uv = info.uvs?.map(|t| t.as_dvec2());
        let c = info.camera;
        let b = match self.options.mapping {
            Mapping::PerspectiveCorrect => {
                let (o, d) = self.rays.ray(x, y);
                let n = (c[1] - c[0]).cross(c[2] - c[0]);
                let denom = n.dot(d);
                if denom == 0.0 {
                    return None;
                }
                let p = o + d * (n.dot(c[0] - o) / denom);
                barycentric3(c, n, p)
            }
            Mapping::Affine => {
                let w = c.map(|q| self.rays.window_of(q));
                barycentric2(w, DVec2::new(x, y))?
            }
        };
        Some(uv[0] * b[0] + uv[1] * b[1] + uv[2] * b[2])
    }

    /// `base` (a linear colour, usually the primitive's flat colour) times
    /// the primitive's texture at window point `(x, y)`; `base` itself when
    /// the primitive shows no texture.
    #[inline]
    pub fn rgb_at(
        &self,
        info: &PrimInfo,
        material: &Material,
        base: [f32; 3],
        x: f64,
        y: f64,
    ) -> [f32; 3] {
        let Some(texture) = self.texture(info, material) else {
            return base;
        };
        match self.uv_at(info, x, y) {
            Some(uv) => {
                let t = texture.sample(uv.x, uv.y, self.options.filter);
                [base[0] * t[0], base[1] * t[1], base[2] * t[2]]
            }
            None => base,
        }
    }
}

impl ScreenScene {
    /// `base` times primitive `prim`'s texture at window point `(x, y)`
    /// ([`TextureSampler::rgb_at`]): the surface colour a colour-resolving
    /// hider composites.
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
        sampler.rgb_at(info, &self.materials[info.material as usize], base, x, y)
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
struct CameraRays {
    inverse: DMat4,
    projection: DMat4,
    width: f64,
    height: f64,
    perspective: bool,
}

impl CameraRays {
    fn new(projection: DMat4, viewport: Viewport, perspective: bool) -> Self {
        Self {
            inverse: projection.inverse(),
            projection,
            width: f64::from(viewport.width),
            height: f64::from(viewport.height),
            perspective,
        }
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

    /// A camera-space point's window position (pixels, y down).
    fn window_of(&self, p: DVec3) -> DVec2 {
        let clip = self.projection * p.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        DVec2::new(
            (ndc.x + 1.0) * 0.5 * self.width,
            (1.0 - ndc.y) * 0.5 * self.height,
        )
    }
}
