//! Appearance, in one place: materials' colours, lighting, textures and
//! the effect stages.
//!
//! Pixel-centre hiders only decide *which* primitive is visible; colour is
//! a separate pass over the id buffer ([`Shader`], or [`shade_frame`] for
//! flat colours), so every hider's picture is shaded the same way and
//! differences in the images are differences in visibility. Hiders that
//! resolve colour themselves (anti-aliasing, transparency) call the same
//! functions per fragment or sample: [`prim_color`] for a primitive's flat
//! colour and [`TextureSampler`] for its texture at a point.
//!
//! - [`stages`]: which effect stages run ([`Stages`]) and the colour pass
//!   over an id buffer ([`Shader`]);
//! - [`texture`]: decoding and sampling `map_Kd` images, decoded on first
//!   use ([`TextureRef`]), from the mip level that fits the pixel
//!   ([`mip`]), within the texture memory budget ([`budget`]);
//! - [`cutout`]: the alpha test of cut-out textures at pixel centres, for
//!   every single-sample hider;
//! - [`surface`]: perspective-correct texture coordinates at window points;
//! - [`prims`]: the per-primitive data shading reads, from a prepared scene
//!   or on demand from the world-space one.

use glam::DVec3;

pub mod budget;
pub mod cutout;
pub mod mip;
pub mod prims;
mod render;
pub mod setup;
pub mod stages;
pub mod surface;
pub mod texture;

pub use budget::{
    DEFAULT_TEXTURE_BUDGET, set_texture_budget, texture_budget, texture_bytes_in_use,
};
pub use prims::{Prims, ScenePrims};
pub use render::render_frame;
pub use setup::{SetupCache, SurfaceSetup};
pub use stages::{
    Shader, ShaderOptions, StageTrace, Stages, texture_failures, transparency_warning,
};
pub use surface::{Mapping, TextureOptions, TextureSampler};
pub use texture::{AlphaClass, Filter, MAX_TEXTURE_SIDE, Texture, TextureRef, TextureTransform};

use crate::error::{Error, Result};
use crate::frame::{BACKGROUND, Frame, NO_ID};
use crate::model::{Illumination, Light, Material};
use crate::prepare::ScreenScene;

/// How to colour visible primitives.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShadeMode {
    /// Flat Lambert shading of the material colour: from the scene's
    /// lights, or from a directional head light along the view axis when
    /// it has none. Two-sided.
    #[default]
    Lambert,
    /// A distinct false colour per primitive id.
    Ids,
}

/// The ambient light's intensity (the ambient term of the lighting
/// model), so faces turned away from every light still read as shapes.
pub const AMBIENT: f64 = 0.12;

/// The linear RGB colour of a primitive under `mode`, and its opacity: in
/// Lambert mode its flat colour ([`flat_color`]).
pub fn prim_color(scene: &ScreenScene, prim: u32, mode: ShadeMode) -> ([f32; 3], f32) {
    let material = scene.material(prim);
    match mode {
        ShadeMode::Ids => (id_color(prim), material.opacity),
        ShadeMode::Lambert => (
            flat_color(
                material,
                &scene.prims[prim as usize].camera,
                &scene.lights,
                scene.is_perspective(),
            ),
            material.opacity,
        ),
    }
}

/// The light a primitive receives under flat, two-sided Lambert shading,
/// ambient included, per linear RGB channel: from the scene's lights, or
/// from a directional head light along the view axis when it has none.
/// The diffuse colour (or texture) is multiplied by it.
pub fn lambert_light(scene: &ScreenScene, prim: u32) -> [f64; 3] {
    lambert_light_at(&scene.prims[prim as usize].camera, &scene.lights)
}

/// [`lambert_light`] of a triangle with camera-space corners `c` under
/// camera-space `lights`: for front ends that keep no [`ScreenScene`].
pub fn lambert_light_at(c: &[DVec3; 3], lights: &[Light]) -> [f64; 3] {
    let n = (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero();
    let centroid = (c[0] + c[1] + c[2]) / 3.0;
    let diffuse = diffuse_light(n, centroid, lights);
    (DVec3::splat(AMBIENT) + diffuse * (1.0 - AMBIENT)).to_array()
}

/// The diffuse light at camera-space `point` with unit normal `n`,
/// two-sided (the cosine's magnitude), per channel.
fn diffuse_light(n: DVec3, point: DVec3, lights: &[Light]) -> DVec3 {
    if lights.is_empty() {
        // A directional head light along the view axis, not a point light
        // at the eye: with a point light each triangle of a flat face sees
        // the light at its own angle (from its own centroid), which draws a
        // seam across every flat quad; a direction gives every coplanar
        // triangle the same shade, as flat shading should.
        return DVec3::splat(n.z.abs());
    }
    lights.iter().fold(DVec3::ZERO, |acc, light| {
        let (to_light, color) = light_at(light, point);
        let k = n.dot(to_light).abs();
        acc + DVec3::new(color[0].into(), color[1].into(), color[2].into()) * k
    })
}

/// The unit direction from camera-space `point` to `light`, and its colour.
fn light_at(light: &Light, point: DVec3) -> (DVec3, [f32; 3]) {
    match *light {
        Light::Directional { direction, color } => (-direction.normalize_or_zero(), color),
        Light::Point { position, color } => ((position - point).normalize_or_zero(), color),
    }
}

/// What the shading model needs of one point of a surface, in camera
/// space: where it is, its normal, and its reflectances there (the
/// material's, times its textures and vertex colours).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position in camera space.
    pub position: DVec3,
    /// Unit normal (either side: lighting is two-sided).
    pub normal: DVec3,
    /// Diffuse reflectance (`Kd`, times `map_Kd` and vertex colours).
    pub diffuse: [f32; 3],
    /// Ambient reflectance (`Ka` times `map_Kd`), `None` for the diffuse
    /// one.
    pub ambient: Option<[f32; 3]>,
    /// Specular reflectance (`Ks` times `map_Ks`).
    pub specular: [f32; 3],
    /// Whether the camera is a perspective one (the view direction then
    /// runs from the point to the eye; else along +Z).
    pub perspective: bool,
}

/// The colour of a surface point under `material`'s illumination model
/// (the MTL specification's, see [`crate::Illumination`]) and `lights` (a
/// head light along the view axis when there are none):
/// `Ke + Ia Ka + (1 - Ia) Kd sum |N.L| C + Ks sum max(N.H, 0)^Ns C`, with
/// the ambient intensity `Ia` = [`AMBIENT`], two-sided diffuse light, and
/// Blinn-Phong highlights under `illum 2` (H halfway between the light and
/// the view direction, N turned towards the viewer). `illum 0` shows the
/// diffuse colour unlit.
pub fn shade_point(material: &Material, lights: &[Light], p: &SurfacePoint) -> [f32; 3] {
    let e = material.emission;
    if material.illumination == Illumination::Color {
        return std::array::from_fn(|k| p.diffuse[k] + e[k]);
    }
    let diffuse = diffuse_light(p.normal, p.position, lights) * (1.0 - AMBIENT);
    let mut c: [f64; 3] = match p.ambient {
        // The diffuse colour takes the ambient light too: the same
        // arithmetic as `lambert_light_at` times the colour, so flat
        // primitives keep their colour bit for bit.
        None => std::array::from_fn(|k| f64::from(p.diffuse[k]) * (AMBIENT + diffuse[k])),
        Some(ka) => std::array::from_fn(|k| {
            f64::from(ka[k]) * AMBIENT + f64::from(p.diffuse[k]) * diffuse[k]
        }),
    };
    if material.illumination == Illumination::Highlight && p.specular.iter().any(|&s| s > 0.0) {
        let view = if p.perspective {
            (-p.position).normalize_or_zero()
        } else {
            DVec3::Z
        };
        let n = if p.normal.dot(view) < 0.0 {
            -p.normal
        } else {
            p.normal
        };
        let head = [Light::Directional {
            direction: -DVec3::Z,
            color: [1.0; 3],
        }];
        let lights = if lights.is_empty() { &head[..] } else { lights };
        let exponent = f64::from(material.shininess.max(0.0));
        for light in lights {
            let (to_light, color) = light_at(light, p.position);
            if n.dot(to_light) <= 0.0 {
                continue;
            }
            let h = (to_light + view).normalize_or_zero();
            let k = n.dot(h).max(0.0).powf(exponent);
            for (ck, (sk, lk)) in c.iter_mut().zip(p.specular.iter().zip(color)) {
                *ck += f64::from(*sk) * f64::from(lk) * k;
            }
        }
    }
    std::array::from_fn(|k| (c[k] + f64::from(e[k])) as f32)
}

/// The flat colour of a triangle with camera-space corners `c` under
/// `material` and `lights`: the shading model ([`shade_point`]) at its
/// centroid, with its face normal and the material's own reflectances.
pub fn flat_color(
    material: &Material,
    c: &[DVec3; 3],
    lights: &[Light],
    perspective: bool,
) -> [f32; 3] {
    let point = SurfacePoint {
        position: (c[0] + c[1] + c[2]) / 3.0,
        normal: (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero(),
        diffuse: material.diffuse,
        ambient: material.ambient,
        specular: material.specular,
        perspective,
    };
    shade_point(material, lights, &point)
}

/// A well-spread false colour for an id (golden-ratio hue walk), linear RGB.
pub fn id_color(id: u32) -> [f32; 3] {
    let h = (f64::from(id) * 0.618_033_988_749_895).fract() * 6.0;
    let s = 0.65;
    let v = 0.55 + 0.4 * (f64::from(id.wrapping_mul(2_654_435_761) >> 28) / 15.0);
    let i = h.floor();
    let f = h - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let (r, g, b) = match i as u32 {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    [r as f32, g as f32, b as f32]
}

/// Linear [0, 1] to an sRGB byte.
pub fn to_srgb8(linear: f32) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// Fills `frame.color` from `frame.ids` with the flat colours of the
/// primitives of `scene` (the prepared scene the ids came from): each
/// covered pixel gets its primitive's colour, background pixels
/// [`BACKGROUND`]. Colours are computed once per visible primitive.
///
/// An id the scene does not hold is an error, never a background pixel:
/// it means the ids came from another scene, typically a hider with a
/// front end of its own (the tiled z-buffer, the A-buffer) that left
/// `scene` as it was; colour such a frame with [`Shader`] reading
/// [`Prims::Scene`] (the world-space scene), which needs no prepared one.
///
/// ```
/// use hider_scene::{Frame, PrepareOptions, ScreenScene, ShadeMode, View, prepare, procedural, shade_frame};
/// let scene = procedural::cube();
/// let view = View::for_scene(&scene, 16, 16)?;
/// let mut frame = Frame::new(16, 16)?;
/// frame.ids[0] = 3;
/// let empty = ScreenScene::empty(&view);
/// assert!(shade_frame(&empty, &mut frame, ShadeMode::Lambert).is_err());
/// let screen = prepare(&scene, &view, &PrepareOptions::default())?;
/// shade_frame(&screen, &mut frame, ShadeMode::Lambert)?;
/// # Ok::<(), hider_scene::Error>(())
/// ```
pub fn shade_frame(scene: &ScreenScene, frame: &mut Frame, mode: ShadeMode) -> Result<()> {
    if let Some(&id) = frame
        .ids
        .iter()
        .find(|&&id| id != NO_ID && id as usize >= scene.prims.len())
    {
        return Err(Error::InvalidScene(format!(
            "the frame shows primitive {id}, but the prepared scene holds {} primitives: \
             a hider with its own front end leaves the prepared scene as it was; colour its \
             frame with shade::Shader and Prims::Scene",
            scene.prims.len()
        )));
    }
    let mut cache: Vec<Option<[u8; 4]>> = vec![None; scene.prims.len()];
    for (id, out) in frame.ids.iter().zip(frame.color.iter_mut()) {
        if *id == NO_ID {
            *out = BACKGROUND;
            continue;
        }
        *out = *cache[*id as usize].get_or_insert_with(|| {
            let (rgb, _) = prim_color(scene, *id, mode);
            [to_srgb8(rgb[0]), to_srgb8(rgb[1]), to_srgb8(rgb[2]), 255]
        });
    }
    Ok(())
}

/// Fills `frame.color` with each id's false colour ([`id_color`]) and the
/// background elsewhere: [`ShadeMode::Ids`] without reading any
/// primitive, so it applies to any hider's ids.
pub fn id_frame(frame: &mut Frame) {
    let mut last: Option<(u32, [u8; 4])> = None;
    for (id, out) in frame.ids.iter().zip(frame.color.iter_mut()) {
        if *id == NO_ID {
            *out = BACKGROUND;
            continue;
        }
        *out = match last {
            Some((k, c)) if k == *id => c,
            _ => {
                let [r, g, b] = id_color(*id);
                let c = [to_srgb8(r), to_srgb8(g), to_srgb8(b), 255];
                last = Some((*id, c));
                c
            }
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_end_points() {
        assert_eq!(to_srgb8(0.0), 0);
        assert_eq!(to_srgb8(1.0), 255);
        assert_eq!(to_srgb8(2.0), 255);
        assert!(to_srgb8(0.5) > 180);
    }

    /// The two triangles of a flat quad seen off-axis through a perspective
    /// camera get one shade: the head light is a direction, not a point at
    /// the eye (which lit each triangle from its own centroid and drew a
    /// seam along the diagonal).
    #[test]
    fn a_flat_quad_gets_one_shade_under_the_head_light() {
        use crate::{Mesh, PrepareOptions, Scene, View, prepare};
        let mesh = Mesh {
            name: "quad".into(),
            positions: vec![
                DVec3::new(-1.0, -0.3, 0.5),
                DVec3::new(1.0, -0.3, 0.5),
                DVec3::new(1.0, 0.4, -1.5),
                DVec3::new(-1.0, 0.4, -1.5),
            ],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            ..Mesh::default()
        };
        let scene = Scene {
            meshes: vec![mesh],
            ..Scene::default()
        };
        let view = View::for_scene(&scene, 64, 64).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let (a, b) = (lambert_light(&screen, 0), lambert_light(&screen, 1));
        assert_eq!(a, b);
        assert!(a[0] > AMBIENT && a[0] < 1.0, "{a:?}");
    }

    /// The id pass is the ids mode of the prepared scene's pass.
    #[test]
    fn the_id_pass_equals_shading_in_ids_mode() {
        use crate::{PrepareOptions, View, prepare, procedural};
        let scene = procedural::uv_sphere(8);
        let view = View::for_scene(&scene, 24, 24).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let mut frame = Frame::new(24, 24).unwrap();
        for (k, id) in frame.ids.iter_mut().enumerate() {
            *id = if k % 5 == 0 {
                NO_ID
            } else {
                (k / 3) as u32 % 100
            };
        }
        let mut expected = frame.clone();
        shade_frame(&screen, &mut expected, ShadeMode::Ids).unwrap();
        id_frame(&mut frame);
        assert_eq!(frame.color, expected.color);
    }

    #[test]
    fn neighbouring_ids_get_different_colours() {
        for id in 0..100 {
            assert_ne!(id_color(id), id_color(id + 1));
        }
    }
}
