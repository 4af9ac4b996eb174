//! Diffuse textures (`map_Kd`): loading with the `image` crate and
//! sampling, nearest or bilinear, with repeat wrapping.
//!
//! Without the crate's `image` feature no image file is read: every
//! texture file is not loaded, with an error saying so ([`probe`],
//! [`Texture::load`], [`TextureRef::problem`]); textures built from bytes
//! ([`Texture::from_srgb8`]) still sample.
//!
//! Texels are kept in linear light so that bilinear filtering averages
//! light, not sRGB codes. Texture coordinates follow OBJ: `(0, 0)` is the
//! *bottom*-left of the image, `v` grows upward (tinyrenderer's z-buffer
//! lesson, lesson 3, reads `vt` the same way).
//!
//! The size is read from the file header and checked against
//! [`MAX_TEXTURE_SIDE`] before any pixel is decoded.
//!
//! A material names its texture with a [`TextureRef`]: the path, and the
//! texture decoded on first use. Decoding is lazy so that a texture that
//! no visible pixel samples costs nothing, and it is shared: clones of a
//! material (every front end copies the scene's materials) and materials
//! naming the same file share one decode.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use crate::{Error, Result};

/// Largest texture side accepted, in texels (checked before decoding).
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// How a texture is sampled between texel centres.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// The texel containing the point.
    Nearest,
    /// The weighted mean of the four nearest texels (the accurate default).
    #[default]
    Bilinear,
}

/// An RGB texture in linear light.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    /// sRGB bytes, 3 per texel, top row first, converted to linear light
    /// as they are sampled: a quarter of the memory of linear `f32`
    /// texels, the same values.
    texels: Vec<u8>,
    /// Whether the image had texels that are not fully opaque (an alpha
    /// cut-out or a translucent texture): the alpha is not simulated.
    alpha: bool,
}

/// The error of every texture file in a build without the `image` feature.
#[cfg(not(feature = "image"))]
fn without_image(path: &Path) -> Error {
    Error::Image {
        path: path.to_path_buf(),
        message: "texture not loaded: hider-scene was built without its `image` feature".into(),
    }
}

/// Reads an image file's size from its header, checking the limit; this is
/// what "the texture loads" means to the analysis, without decoding it.
///
/// Without the `image` feature: an error naming the file and the feature.
#[cfg(not(feature = "image"))]
pub fn probe(path: &Path) -> Result<(u32, u32)> {
    Err(without_image(path))
}

/// Reads an image file's size from its header, checking the limit; this is
/// what "the texture loads" means to the analysis, without decoding it.
#[cfg(feature = "image")]
pub fn probe(path: &Path) -> Result<(u32, u32)> {
    let image_error = |e: image::ImageError| Error::Image {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    crate::input::check_regular(
        path,
        "texture file size in bytes",
        crate::input::MAX_TEXTURE_FILE_BYTES,
    )?;
    let reader = image::ImageReader::open(path)
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?
        .with_guessed_format()
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    let (w, h) = reader.into_dimensions().map_err(image_error)?;
    for (what, v) in [("texture width", w), ("texture height", h)] {
        if v > MAX_TEXTURE_SIDE {
            return Err(Error::Limit {
                what,
                value: v.into(),
                limit: MAX_TEXTURE_SIDE.into(),
            });
        }
    }
    if w == 0 || h == 0 {
        return Err(Error::Image {
            path: path.to_path_buf(),
            message: "image has no pixels".into(),
        });
    }
    Ok((w, h))
}

/// An sRGB texel in linear light, through a table of
/// [`srgb_to_linear`]'s 256 values (the same numbers, without a `powf`
/// per channel).
#[inline]
fn linear(texel: [u8; 3]) -> [f32; 3] {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| std::array::from_fn(|c| srgb_to_linear(c as u8)));
    texel.map(|c| table[usize::from(c)])
}

/// sRGB byte to linear light.
pub fn srgb_to_linear(c: u8) -> f32 {
    let s = f32::from(c) / 255.0;
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

impl Texture {
    /// Loads an image file (PNG or JPEG), size checked first.
    ///
    /// Without the `image` feature: an error naming the file and the
    /// feature.
    #[cfg(not(feature = "image"))]
    pub fn load(path: &Path) -> Result<Self> {
        Err(without_image(path))
    }

    /// Loads an image file (PNG or JPEG), size checked first.
    #[cfg(feature = "image")]
    pub fn load(path: &Path) -> Result<Self> {
        probe(path)?;
        let img = image::open(path).map_err(|e| Error::Image {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        // The alpha is read where it is (8-bit RGBA, the common case)
        // rather than from a converted copy of the image.
        let alpha = match &img {
            image::DynamicImage::ImageRgba8(rgba) => rgba.pixels().any(|p| p.0[3] < 255),
            other => other.color().has_alpha() && other.to_rgba8().pixels().any(|p| p.0[3] < 255),
        };
        // An RGB image's buffer becomes the texels without a copy.
        let rgb = img.into_rgb8();
        let (width, height) = (rgb.width(), rgb.height());
        let mut texture = Self::from_srgb8_vec(width, height, rgb.into_raw())?;
        texture.alpha = alpha;
        Ok(texture)
    }

    /// A texture from sRGB bytes, 3 per texel, top row first.
    pub fn from_srgb8(width: u32, height: u32, bytes: &[u8]) -> Result<Self> {
        Self::from_srgb8_vec(width, height, bytes.to_vec())
    }

    /// [`Self::from_srgb8`], taking the bytes without copying them.
    pub fn from_srgb8_vec(width: u32, height: u32, bytes: Vec<u8>) -> Result<Self> {
        for (what, v) in [("texture width", width), ("texture height", height)] {
            if v == 0 || v > MAX_TEXTURE_SIDE {
                return Err(Error::OutOfRange {
                    what,
                    expected: "1 to 8192 texels",
                    value: v.to_string(),
                });
            }
        }
        let n = width as usize * height as usize;
        if bytes.len() != 3 * n {
            return Err(Error::OutOfRange {
                what: "texture data",
                expected: "3 bytes per texel",
                value: format!("{} bytes for {width}x{height}", bytes.len()),
            });
        }
        Ok(Self {
            width,
            height,
            texels: bytes,
            alpha: false,
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Whether the image had texels that are not fully opaque; their alpha
    /// is not simulated (the texture is drawn opaque).
    pub fn has_alpha(&self) -> bool {
        self.alpha
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.texels.len()
    }

    fn texel(&self, x: i64, y: i64, clamp: bool) -> [f32; 3] {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let (x, y) = if clamp {
            (x.clamp(0, w - 1) as usize, y.clamp(0, h - 1) as usize)
        } else {
            (x.rem_euclid(w) as usize, y.rem_euclid(h) as usize)
        };
        let k = 3 * (y * self.width as usize + x);
        linear([self.texels[k], self.texels[k + 1], self.texels[k + 2]])
    }

    /// The linear colour at texture coordinates `(u, v)` (OBJ convention,
    /// repeat wrapping). Non-finite coordinates give the first texel.
    pub fn sample(&self, u: f64, v: f64, filter: Filter) -> [f32; 3] {
        self.sample_wrapped(u, v, filter, false)
    }

    /// [`Self::sample`], with coordinates outside [0, 1] clamped to the
    /// image's edge texels when `clamp` (MTL's `-clamp on`) instead of
    /// repeating.
    pub fn sample_wrapped(&self, u: f64, v: f64, filter: Filter, clamp: bool) -> [f32; 3] {
        if !(u.is_finite() && v.is_finite()) {
            return linear([self.texels[0], self.texels[1], self.texels[2]]);
        }
        // Texel space: x right, y down from the top row; centres at +0.5.
        let (u, v) = if clamp {
            (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
        } else {
            (u.rem_euclid(1.0), v.rem_euclid(1.0))
        };
        let x = u * f64::from(self.width);
        let y = (1.0 - v) * f64::from(self.height);
        let texel = |x: i64, y: i64| self.texel(x, y, clamp);
        match filter {
            // Clamped, u = 1 is the last texel's far edge (the texel look-up
            // clamps it); repeating, it is the next repeat's start.
            Filter::Nearest => texel(x.floor() as i64, y.floor() as i64),
            Filter::Bilinear => {
                let (fx, fy) = (x - 0.5, y - 0.5);
                let (x0, y0) = (fx.floor(), fy.floor());
                let (tx, ty) = ((fx - x0) as f32, (fy - y0) as f32);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let [a, b, c, d] = [
                    texel(x0, y0),
                    texel(x0 + 1, y0),
                    texel(x0, y0 + 1),
                    texel(x0 + 1, y0 + 1),
                ];
                std::array::from_fn(|k| {
                    let top = a[k] + (b[k] - a[k]) * tx;
                    let bottom = c[k] + (d[k] - c[k]) * tx;
                    top + (bottom - top) * ty
                })
            }
        }
    }
}

/// A material's diffuse texture (`map_Kd`): its path, and the texture
/// decoded the first time a sample needs it ([`Self::get`]).
///
/// Clones share the decode. Two references are equal when they name the
/// same path with the same [`TextureTransform`].
///
/// ```
/// use hider_scene::TextureRef;
/// let missing = TextureRef::new("/no/such/texture.png");
/// assert!(!missing.is_decoded());
/// assert!(missing.get().is_none());
/// assert!(missing.error().unwrap().contains("/no/such/texture.png"));
/// ```
#[derive(Clone, Debug)]
pub struct TextureRef {
    path: PathBuf,
    decoded: Arc<OnceLock<std::result::Result<Arc<Texture>, String>>>,
    /// The statement's options that change where the image is sampled.
    pub transform: TextureTransform,
}

/// Where a texture statement samples its image: the MTL options `-s`
/// (scale), `-o` (offset) and `-clamp`, applied to the texture coordinates
/// as the MTL specification says (`uv * s + o`, then repeat, or clamp to
/// the image's edge with `-clamp on`). `Default` is the identity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureTransform {
    /// `-s u v`: the coordinates are multiplied by it (the image repeats
    /// `s` times).
    pub scale: [f64; 2],
    /// `-o u v`: added after the scale.
    pub offset: [f64; 2],
    /// `-clamp on`: coordinates outside [0, 1] take the edge texel instead
    /// of repeating.
    pub clamp: bool,
}

impl Default for TextureTransform {
    fn default() -> Self {
        Self {
            scale: [1.0, 1.0],
            offset: [0.0, 0.0],
            clamp: false,
        }
    }
}

impl TextureTransform {
    /// `(u, v)` moved as the options say.
    pub fn apply(&self, u: f64, v: f64) -> (f64, f64) {
        (
            u * self.scale[0] + self.offset[0],
            v * self.scale[1] + self.offset[1],
        )
    }
}

impl TextureRef {
    /// A reference to the image at `path`, not decoded yet.
    pub fn new(path: impl Into<PathBuf>) -> Self {
        Self {
            path: path.into(),
            decoded: Arc::new(OnceLock::new()),
            transform: TextureTransform::default(),
        }
    }

    /// This reference sampled through `transform`.
    pub fn with_transform(mut self, transform: TextureTransform) -> Self {
        self.transform = transform;
        self
    }

    /// The linear colour at texture coordinates `(u, v)` through
    /// [`Self::transform`], decoding the image on first use; `None` when it
    /// does not load.
    pub fn sample(&self, u: f64, v: f64, filter: Filter) -> Option<[f32; 3]> {
        let texture = self.get()?;
        let (u, v) = self.transform.apply(u, v);
        Some(texture.sample_wrapped(u, v, filter, self.transform.clamp))
    }

    /// A reference to an already decoded texture (for scenes built in
    /// memory); `path` names it in messages.
    pub fn from_texture(path: impl Into<PathBuf>, texture: Texture) -> Self {
        let r = Self::new(path);
        let _ = r.decoded.set(Ok(Arc::new(texture)));
        r
    }

    /// The image file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The texture, decoded now if this is the first use; `None` when it
    /// cannot be loaded ([`Self::error`] says why).
    pub fn get(&self) -> Option<&Texture> {
        self.decoded
            .get_or_init(|| {
                Texture::load(&self.path)
                    .map(Arc::new)
                    .map_err(|e| e.to_string())
            })
            .as_ref()
            .ok()
            .map(Arc::as_ref)
    }

    /// Whether a decode was attempted (successful or not).
    pub fn is_decoded(&self) -> bool {
        self.decoded.get().is_some()
    }

    /// Why the texture could not be loaded, decoding it if that was not
    /// tried yet; `None` when it loads.
    pub fn error(&self) -> Option<&str> {
        self.get();
        self.decoded.get()?.as_ref().err().map(String::as_str)
    }

    /// Why the texture could not be loaded, only if a decode was already
    /// attempted (never decodes).
    pub fn failure(&self) -> Option<&str> {
        self.decoded.get()?.as_ref().err().map(String::as_str)
    }

    /// Why the texture cannot be used, without decoding it: the decode's
    /// error if one was tried, else what reading the image's header finds
    /// (a missing or undecodable file, a size over [`MAX_TEXTURE_SIDE`]).
    pub fn problem(&self) -> Option<String> {
        match self.decoded.get() {
            Some(Ok(_)) => None,
            Some(Err(why)) => Some(why.clone()),
            None => probe(&self.path).err().map(|e| e.to_string()),
        }
    }

    /// Whether the texture was decoded and its image has texels that are
    /// not fully opaque (never decodes).
    pub fn decoded_with_alpha(&self) -> bool {
        matches!(self.decoded.get(), Some(Ok(t)) if t.has_alpha())
    }

    /// Bytes held by the decoded texels (0 before decoding).
    pub fn bytes(&self) -> usize {
        match self.decoded.get() {
            Some(Ok(t)) => t.bytes(),
            _ => 0,
        }
    }

    /// Makes references to the same path share one decode: the second and
    /// later references of a path in `refs` take the first one's.
    pub fn share<'a>(refs: impl IntoIterator<Item = &'a mut TextureRef>) {
        type Slot = Arc<OnceLock<std::result::Result<Arc<Texture>, String>>>;
        let mut seen: HashMap<PathBuf, Slot> = HashMap::new();
        for r in refs {
            let shared = seen
                .entry(r.path.clone())
                .or_insert_with(|| r.decoded.clone());
            r.decoded = shared.clone();
        }
    }
}

impl PartialEq for TextureRef {
    fn eq(&self, other: &Self) -> bool {
        self.path == other.path && self.transform == other.transform
    }
}

impl From<PathBuf> for TextureRef {
    fn from(path: PathBuf) -> Self {
        Self::new(path)
    }
}

impl From<&Path> for TextureRef {
    fn from(path: &Path) -> Self {
        Self::new(path)
    }
}

/// A checkerboard image: `squares x squares` squares of `square` texels,
/// alternating `a` and `b` (sRGB bytes, 3 per texel, top row first), `a`
/// in the top-left corner.
pub fn checkerboard(squares: u32, square: u32, a: [u8; 3], b: [u8; 3]) -> (u32, Vec<u8>) {
    let side = squares * square;
    let mut bytes = Vec::with_capacity(side as usize * side as usize * 3);
    for y in 0..side {
        for x in 0..side {
            let odd = (x / square + y / square) % 2 == 1;
            bytes.extend_from_slice(if odd { &b } else { &a });
        }
    }
    (side, bytes)
}

/// Name of the bundled checkerboard texture (`assets/checker.png`).
pub const CHECKER_PNG: &str = "checker.png";

/// The bundled checkerboard: 8 x 8 squares of 32 texels, light and dark.
pub fn checker_texture() -> (u32, Vec<u8>) {
    checkerboard(8, 32, [230, 230, 230], [40, 40, 40])
}

/// The OBJ and MTL text of the bundled textured asset
/// (`assets/checker_plane.obj`): one quad (two triangles) of 2 x 2 units,
/// tilted 14 degrees out of the XZ plane (`y = -z / 4`) so that the fit
/// camera sees it at a grazing angle, with uvs spanning the texture once
/// and a material whose `map_Kd` is `texture` (white `Kd`, so the texture
/// shows as it is).
pub fn checker_plane_text(mtl_name: &str, texture: &str) -> (String, String) {
    let obj = format!(
        "# written by hider: a checkerboard plane for perspective-correct texturing\n\
         mtllib {mtl_name}\n\
         o checker_plane\n\
         v -1 -0.25 1\nv 1 -0.25 1\nv 1 0.25 -1\nv -1 0.25 -1\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         usemtl checker\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    );
    let mtl = format!("newmtl checker\nKd 1 1 1\nd 1\nmap_Kd {texture}\n");
    (obj, mtl)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_and_bilinear_sampling_with_obj_orientation() {
        // 2 x 2: top row black, white; bottom row white, black.
        let t =
            Texture::from_srgb8(2, 2, &[0, 0, 0, 255, 255, 255, 255, 255, 255, 0, 0, 0]).unwrap();
        // v = 0.75 is the top row in OBJ convention.
        assert_eq!(t.sample(0.25, 0.75, Filter::Nearest), [0.0; 3]);
        assert_eq!(t.sample(0.75, 0.75, Filter::Nearest), [1.0; 3]);
        assert_eq!(t.sample(0.25, 0.25, Filter::Nearest), [1.0; 3]);
        // Repeat wrapping.
        assert_eq!(t.sample(1.25, -0.25, Filter::Nearest), [0.0; 3]);
        // At texel centres bilinear equals nearest; halfway it averages.
        assert_eq!(t.sample(0.25, 0.75, Filter::Bilinear), [0.0; 3]);
        let mid = t.sample(0.5, 0.75, Filter::Bilinear);
        assert!((mid[0] - 0.5).abs() < 1e-6, "{mid:?}");
        assert_eq!(t.sample(f64::NAN, 0.0, Filter::Bilinear), [0.0; 3]);
    }

    #[test]
    fn bad_sizes_and_files_are_errors() {
        assert!(Texture::from_srgb8(0, 1, &[]).is_err());
        assert!(Texture::from_srgb8(2, 2, &[0; 11]).is_err());
        let e = probe(Path::new("/no/such/texture.png"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("/no/such/texture.png"), "{e}");
        let dir = std::env::temp_dir().join(format!("hider-tex-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("bad.png");
        std::fs::write(&bad, b"not a png at all").unwrap();
        assert!(Texture::load(&bad).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn checkerboard_alternates() {
        let (side, bytes) = checkerboard(2, 3, [1, 1, 1], [2, 2, 2]);
        assert_eq!(side, 6);
        assert_eq!(bytes[0], 1);
        assert_eq!(bytes[3 * 3], 2); // x = 3, second square
        assert_eq!(bytes[3 * (3 * 6 + 3)], 1); // x = 3, y = 3
    }
}
