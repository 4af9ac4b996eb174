//! A material's reference to a texture file, decoded on first use down to
//! the mip level its samples need.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock, RwLock};

use super::super::mip;
use super::decode::{Header, header, load_level};
use super::{AlphaClass, Filter, Texture};

/// A decode's outcome: the texture, or why it did not load.
type Decoded = Option<Result<Arc<Texture>, String>>;

/// What every copy of a reference shares.
#[derive(Debug, Default)]
struct Slot {
    header: OnceLock<Result<Header, String>>,
    decoded: RwLock<Decoded>,
    /// Why a finer level than the one held was not decoded (the budget):
    /// samples then read the coarser level.
    coarser: Mutex<Option<String>>,
}

/// A material's texture (`map_Kd`, `map_Ks`): its path, and the texture
/// decoded the first time a sample needs it, down to the mip level that
/// sample needs ([`Self::sample_footprint`]); a later sample that needs a
/// finer level decodes the file again down to it.
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
    slot: Arc<Slot>,
    /// The statement's options that change where the image is sampled.
    pub transform: TextureTransform,
    /// Whether the image is a mask (`map_d`): its first channel is the
    /// alpha ([`Self::as_mask`]).
    mask: bool,
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
            slot: Arc::default(),
            transform: TextureTransform::default(),
            mask: false,
        }
    }

    /// This reference read as a mask, as MTL's `map_d` (the dissolve
    /// texture, a scalar) is: the alpha is the image's first channel (the
    /// grey of a greyscale image, the red of a colour one, as assimp and
    /// Blender's importer read it), a plain number in [0, 1] (not
    /// sRGB-decoded); the image's own alpha channel is not read. Samples'
    /// alpha ([`Self::sample_footprint`]) is that value.
    pub fn as_mask(mut self) -> Self {
        self.mask = true;
        self
    }

    /// Whether this reference reads its image as a mask ([`Self::as_mask`]).
    pub fn is_mask(&self) -> bool {
        self.mask
    }

    /// This reference sampled through `transform`.
    pub fn with_transform(mut self, transform: TextureTransform) -> Self {
        self.transform = transform;
        self
    }

    /// A reference to an already decoded texture (for scenes built in
    /// memory); `path` names it in messages.
    pub fn from_texture(path: impl Into<PathBuf>, texture: Texture) -> Self {
        let r = Self::new(path);
        let header = Header {
            width: texture.width(),
            height: texture.height(),
            alpha: texture.levels[0].alpha.is_some(),
        };
        let _ = r.slot.header.set(Ok(header));
        *write(&r.slot.decoded) = Some(Ok(Arc::new(texture)));
        r
    }

    /// The image file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The file's header, read once.
    fn header(&self) -> Result<Header, String> {
        self.slot
            .header
            .get_or_init(|| header(&self.path).map_err(|e| e.to_string()))
            .clone()
            .map(|h| Header {
                alpha: h.alpha || self.mask,
                ..h
            })
    }

    /// The texture holding mip level `level` or a finer one, decoded now
    /// (again, finer) when the one held is coarser; `None` when it cannot
    /// be loaded ([`Self::error`] says why). When the budget refuses the
    /// finer decode, the coarser texture is kept ([`Self::coarser`] says
    /// why).
    pub fn get_level(&self, level: u32) -> Option<Arc<Texture>> {
        let fits = |d: &Decoded| match d {
            Some(Ok(t)) if t.base_level() <= level => Some(Some(t.clone())),
            Some(Err(_)) => Some(None),
            _ => None,
        };
        if let Some(answer) = fits(&read(&self.slot.decoded)) {
            return answer;
        }
        let mut decoded = write(&self.slot.decoded);
        if let Some(answer) = fits(&decoded) {
            return answer;
        }
        let held = decoded.as_ref().and_then(|d| d.as_ref().ok().cloned());
        if held.is_some() && lock(&self.slot.coarser).is_some() {
            return held;
        }
        match load_level(&self.path, level, self.mask) {
            Ok(t) => {
                let t = Arc::new(t);
                *decoded = Some(Ok(t.clone()));
                Some(t)
            }
            Err(e) if held.is_some() => {
                *lock(&self.slot.coarser) = Some(e.to_string());
                held
            }
            Err(e) => {
                *decoded = Some(Err(e.to_string()));
                None
            }
        }
    }

    /// The texture at full resolution (level 0), decoded now if it is not
    /// held at that level; `None` when it cannot be loaded
    /// ([`Self::error`] says why).
    pub fn get(&self) -> Option<Arc<Texture>> {
        self.get_level(0)
    }

    /// The linear colour at texture coordinates `(u, v)` through
    /// [`Self::transform`], at full resolution, decoding the image on
    /// first use; `None` when it does not load.
    pub fn sample(&self, u: f64, v: f64, filter: Filter) -> Option<[f32; 3]> {
        let texture = self.get()?;
        let (u, v) = self.transform.apply(u, v);
        Some(texture.sample_wrapped(u, v, filter, self.transform.clamp))
    }

    /// The linear colour and alpha at texture coordinates `uv` through
    /// [`Self::transform`], from the mip level that fits a pixel whose
    /// texture coordinates change by `dx` and `dy` (before the transform)
    /// one pixel right and one pixel down (see [`crate::shade::mip`]);
    /// `None` when the texture does not load. Decodes on first use, down
    /// to the level needed.
    pub fn sample_footprint(
        &self,
        uv: [f64; 2],
        dx: [f64; 2],
        dy: [f64; 2],
        filter: Filter,
    ) -> Option<([f32; 3], f32)> {
        let header = self.header().ok()?;
        let [su, sv] = self.transform.scale;
        let (w, h) = (f64::from(header.width), f64::from(header.height));
        let length = |d: [f64; 2]| (d[0] * su * w).hypot(d[1] * sv * h);
        let rho = length(dx).max(length(dy));
        let level = mip::level_for(rho, mip::level_count(header.width, header.height));
        let texture = self.get_level(level)?;
        let (u, v) = self.transform.apply(uv[0], uv[1]);
        Some(texture.sample_level(u, v, filter, self.transform.clamp, level))
    }

    /// Level 0's size in texels and the chain's number of levels, from
    /// the header (read once, never decodes); `None` when it does not
    /// read: what [`Self::sample_footprint`] scales a footprint by.
    pub(crate) fn footprint_scale(&self) -> Option<([f64; 2], u32)> {
        let h = self
            .slot
            .header
            .get_or_init(|| header(&self.path).map_err(|e| e.to_string()));
        let h = h.as_ref().ok()?;
        Some((
            [f64::from(h.width), f64::from(h.height)],
            mip::level_count(h.width, h.height),
        ))
    }

    /// Whether a decode was attempted (successful or not).
    pub fn is_decoded(&self) -> bool {
        read(&self.slot.decoded).is_some()
    }

    /// Why the texture could not be loaded, decoding it if that was not
    /// tried yet (at its coarsest level: the cheapest decode that tells);
    /// `None` when it loads.
    pub fn error(&self) -> Option<String> {
        if !self.is_decoded() {
            self.get_level(u32::MAX);
        }
        self.failure()
    }

    /// Why the texture could not be loaded, only if a decode was already
    /// attempted (never decodes).
    pub fn failure(&self) -> Option<String> {
        read(&self.slot.decoded).as_ref()?.as_ref().err().cloned()
    }

    /// Why a finer mip level than the one held was not decoded (the
    /// texture budget), if that happened: the texture is then drawn from a
    /// coarser, blurrier level.
    pub fn coarser(&self) -> Option<String> {
        lock(&self.slot.coarser).clone()
    }

    /// Why the texture cannot be used, without decoding it: the decode's
    /// error if one was tried, else what reading the image's header finds
    /// (a missing or undecodable file, a size over
    /// [`super::MAX_TEXTURE_SIDE`]).
    pub fn problem(&self) -> Option<String> {
        match &*read(&self.slot.decoded) {
            Some(Ok(_)) => None,
            Some(Err(why)) => Some(why.clone()),
            None => self.header().err(),
        }
    }

    /// Whether the image's header declares an alpha channel (reads the
    /// header, never decodes): the texture may be a cut-out.
    pub fn may_have_alpha(&self) -> bool {
        // Without the clone `header` makes: colour-resolving hiders ask
        // this per fragment.
        self.slot
            .header
            .get_or_init(|| header(&self.path).map_err(|e| e.to_string()))
            .as_ref()
            .is_ok_and(|h| h.alpha || self.mask)
    }

    /// What the alpha channel holds, if the texture was decoded (never
    /// decodes).
    pub fn decoded_alpha_class(&self) -> Option<AlphaClass> {
        match &*read(&self.slot.decoded) {
            Some(Ok(t)) => Some(t.alpha_class()),
            _ => None,
        }
    }

    /// What the alpha channel holds: [`AlphaClass::Opaque`] without one
    /// (from the header), else from the texels, decoding the texture at
    /// its coarsest level if it was not decoded (the class is read from
    /// every texel of the image whatever level is kept); `None` when it
    /// does not load. The evidence a planner needs: a cut-out stays
    /// opaque, partial alpha is translucency.
    pub fn alpha_class(&self) -> Option<AlphaClass> {
        if !self.header().ok()?.alpha {
            return Some(AlphaClass::Opaque);
        }
        if !self.is_decoded() {
            self.get_level(u32::MAX);
        }
        self.decoded_alpha_class()
    }

    /// Whether the texture was decoded and its image has texels that are
    /// not fully opaque (never decodes).
    pub fn decoded_with_alpha(&self) -> bool {
        self.decoded_alpha_class()
            .is_some_and(|c| c != AlphaClass::Opaque)
    }

    /// Bytes held by the decoded texels (0 before decoding).
    pub fn bytes(&self) -> usize {
        match &*read(&self.slot.decoded) {
            Some(Ok(t)) => t.bytes(),
            _ => 0,
        }
    }

    /// Makes references to the same path share one decode: the second and
    /// later references of a path in `refs` take the first one's.
    pub fn share<'a>(refs: impl IntoIterator<Item = &'a mut TextureRef>) {
        // A file read as a mask decodes to other texels: not shared with
        // the same file read as colour.
        let mut seen: HashMap<(PathBuf, bool), Arc<Slot>> = HashMap::new();
        for r in refs {
            let shared = seen
                .entry((r.path.clone(), r.mask))
                .or_insert_with(|| r.slot.clone());
            r.slot = shared.clone();
        }
    }
}

/// The lock's value, whether or not a panicking thread poisoned it (a
/// decode that panicked left nothing half-written: the slot is set only
/// after a decode returns).
fn read<T>(lock: &RwLock<T>) -> std::sync::RwLockReadGuard<'_, T> {
    lock.read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn write<T>(lock: &RwLock<T>) -> std::sync::RwLockWriteGuard<'_, T> {
    lock.write()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl PartialEq for TextureRef {
    fn eq(&self, other: &Self) -> bool {
        self.path == other.path && self.transform == other.transform && self.mask == other.mask
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

#[cfg(all(test, feature = "image"))]
mod tests {
    use super::*;

    /// A far sample decodes only the coarse levels; a near one decodes the
    /// file again down to level 0; the far sample reads the mean colour.
    #[test]
    fn decodes_down_to_the_level_a_sample_needs() {
        let dir = std::env::temp_dir().join(format!("hider-texref-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("checker.png");
        // 64 x 64 checkerboard of 1-texel squares, black and white.
        image::RgbImage::from_fn(64, 64, |x, y| {
            image::Rgb([if (x + y) % 2 == 0 { 0 } else { 255 }; 3])
        })
        .save(&path)
        .unwrap();
        let r = TextureRef::new(&path);
        assert!(!r.is_decoded());
        // One pixel spans the whole texture: level 6 (1 x 1), mid grey in
        // linear light.
        let (far, alpha) = r
            .sample_footprint([0.5, 0.5], [1.0, 0.0], [0.0, 1.0], Filter::Bilinear)
            .unwrap();
        assert_eq!(alpha, 1.0);
        assert!((far[0] - 0.5).abs() < 0.01, "{far:?}");
        assert_eq!(r.get_level(u32::MAX).unwrap().base_level(), 6);
        assert_eq!(r.bytes(), 3);
        // A pixel a quarter of a texel wide: level 0, a black or white texel.
        let (near, _) = r
            .sample_footprint([0.3, 0.3], [0.004, 0.0], [0.0, 0.004], Filter::Nearest)
            .unwrap();
        assert!(near[0] == 0.0 || near[0] == 1.0, "{near:?}");
        assert_eq!(r.get_level(u32::MAX).unwrap().base_level(), 0);
        assert!(r.coarser().is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
