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
//! Textures are decoded once per path and kept between frames in
//! [`SurfaceTextures`]; [`crate::prepare_into`] re-binds them to the new
//! frame's materials and camera without decoding anything.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use glam::{DMat4, DVec2, DVec3, DVec4};

use crate::prepare::ScreenScene;
use crate::texture::{Filter, Texture};

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

/// What [`SurfaceTextures::load`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TextureLoad {
    /// Textures decoded by this call (cached ones are not counted).
    pub loaded: u64,
    /// Textures that failed to load by this call, with the reason; their
    /// materials show their diffuse colour.
    pub failures: Vec<String>,
}

/// Decoded diffuse textures bound to a frame's materials, kept between
/// frames. Inactive (no texture applied) until [`Self::load`] runs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceTextures {
    options: TextureOptions,
    active: bool,
    /// Every path tried, with its texture or `None` when it failed.
    cache: HashMap<PathBuf, Option<Arc<Texture>>>,
    /// The texture of each material of the bound frame.
    bound: Vec<Option<Arc<Texture>>>,
    rays: Option<RayGen>,
}

impl SurfaceTextures {
    /// No textures yet, sampled with `options` once loaded.
    pub fn new(options: TextureOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The sampling options.
    pub fn options(&self) -> &TextureOptions {
        &self.options
    }

    /// Whether textures are applied (after [`Self::load`], until
    /// [`Self::deactivate`]).
    pub fn is_active(&self) -> bool {
        self.active
    }

    /// Stops applying textures (the decoded ones stay cached).
    pub fn deactivate(&mut self) {
        self.active = false;
        self.bound.clear();
        self.rays = None;
    }

    /// Decodes the diffuse textures of `scene`'s materials not decoded
    /// before, binds every material to its texture and the camera of
    /// `scene`, and activates texturing. A texture that fails to load is
    /// reported once and its material keeps its diffuse colour.
    pub fn load(&mut self, scene: &ScreenScene) -> TextureLoad {
        let mut report = TextureLoad::default();
        for path in scene
            .materials
            .iter()
            .filter_map(|m| m.diffuse_texture.as_ref())
        {
            if self.cache.contains_key(path) {
                continue;
            }
            let texture = match Texture::load(path) {
                Ok(t) => {
                    report.loaded += 1;
                    Some(Arc::new(t))
                }
                Err(e) => {
                    report.failures.push(e.to_string());
                    None
                }
            };
            self.cache.insert(path.clone(), texture);
        }
        self.active = true;
        self.rebind(scene);
        report
    }

    /// Binds the cached textures to `scene`'s materials and camera, without
    /// decoding; does nothing while inactive.
    pub fn rebind(&mut self, scene: &ScreenScene) {
        if !self.active {
            return;
        }
        let cache = &self.cache;
        self.bound.clear();
        self.bound.extend(scene.materials.iter().map(|m| {
            m.diffuse_texture
                .as_ref()
                .and_then(|path| cache.get(path).cloned().flatten())
        }));
        self.rays = Some(RayGen::new(scene));
    }

    /// The texture primitive `prim` of `scene` shows, if texturing is
    /// active and the primitive has texture coordinates.
    #[inline]
    pub fn texture(&self, scene: &ScreenScene, prim: u32) -> Option<&Texture> {
        if !self.active {
            return None;
        }
        let info = scene.prims.get(prim as usize)?;
        info.uvs?;
        self.bound.get(info.material as usize)?.as_deref()
    }

    /// The texture coordinates of primitive `prim` seen at window point
    /// `(x, y)` (pixels, y down), or `None` without uvs, while inactive, or
    /// when the ray runs parallel to the primitive's plane.
    pub fn uv_at(&self, scene: &ScreenScene, prim: u32, x: f64, y: f64) -> Option<DVec2> {
        let rays = self.rays.as_ref()?;
        let info = scene.prims.get(prim as usize)?;
        let uv = info.uvs?.map(|t| t.as_dvec2());
        let c = info.camera;
        let b = match self.options.mapping {
            Mapping::PerspectiveCorrect => {
                let (o, d) = rays.ray(x, y);
                let n = (c[1] - c[0]).cross(c[2] - c[0]);
                let denom = n.dot(d);
                if denom == 0.0 {
                    return None;
                }
                let p = o + d * (n.dot(c[0] - o) / denom);
                barycentric3(c, n, p)
            }
            Mapping::Affine => {
                let w = c.map(|q| rays.window_of(q));
                barycentric2(w, DVec2::new(x, y))?
            }
        };
        Some(uv[0] * b[0] + uv[1] * b[1] + uv[2] * b[2])
    }

    /// `base` (a linear colour, usually the primitive's flat colour) times
    /// primitive `prim`'s texture at window point `(x, y)`; `base` itself
    /// when the primitive shows no texture.
    #[inline]
    pub fn rgb_at(
        &self,
        scene: &ScreenScene,
        prim: u32,
        base: [f32; 3],
        x: f64,
        y: f64,
    ) -> [f32; 3] {
        let Some(texture) = self.texture(scene, prim) else {
            return base;
        };
        match self.uv_at(scene, prim, x, y) {
            Some(uv) => {
                let t = texture.sample(uv.x, uv.y, self.options.filter);
                [base[0] * t[0], base[1] * t[1], base[2] * t[2]]
            }
            None => base,
        }
    }

    /// Bytes held by the decoded textures.
    pub fn bytes(&self) -> usize {
        self.cache.values().flatten().map(|t| t.bytes()).sum()
    }
}

impl ScreenScene {
    /// Loads the diffuse textures of this frame's materials into
    /// [`ScreenScene::textures`] (decoding only those not cached) and turns
    /// texturing on for the hiders that resolve colour themselves.
    pub fn load_textures(&mut self, options: TextureOptions) -> TextureLoad {
        let mut textures = std::mem::take(&mut self.textures);
        if textures.options != options {
            textures.options = options;
        }
        let report = textures.load(self);
        self.textures = textures;
        report
    }

    /// `base` times primitive `prim`'s texture at window point `(x, y)`
    /// when textures are loaded ([`Self::load_textures`]), else `base`:
    /// the surface colour a colour-resolving hider composites.
    #[inline]
    pub fn surface_rgb(&self, prim: u32, base: [f32; 3], x: f64, y: f64) -> [f32; 3] {
        self.textures.rgb_at(self, prim, base, x, y)
    }

    /// Whether any primitive of this frame shows a texture.
    pub fn is_textured(&self) -> bool {
        self.textures.is_active() && self.textures.bound.iter().any(Option::is_some)
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
struct RayGen {
    inverse: DMat4,
    projection: DMat4,
    width: f64,
    height: f64,
    perspective: bool,
}

impl RayGen {
    fn new(scene: &ScreenScene) -> Self {
        Self {
            inverse: scene.projection_matrix.inverse(),
            projection: scene.projection_matrix,
            width: f64::from(scene.viewport.width),
            height: f64::from(scene.viewport.height),
            perspective: scene.is_perspective(),
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
