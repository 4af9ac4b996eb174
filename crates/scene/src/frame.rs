//! Frame buffers and their files: PNG, and id / depth dumps in the GL
//! reference format.

use std::io::{Read, Write};
use std::path::Path;

use crate::atomic::OutputSet;
use crate::error::{Error, Result};
use crate::view::check_image_size;

/// The primitive id of a pixel no surface covers.
pub const NO_ID: u32 = u32::MAX;

/// The buffers a hider writes: per pixel the visible primitive, its window
/// depth and a colour; optionally the covered fraction of the pixel.
///
/// All buffers are row-major, top row first; pixel `(x, y)` is at index
/// `y * width + x`.
///
/// [`Frame::buffers`] says which buffers the caller wants written
/// ([`FrameBuffers`], default all three); a hider may skip the others and
/// leave them as they were.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    width: u32,
    height: u32,
    /// The buffers a render must write.
    wanted: FrameBuffers,
    /// Visible primitive id per pixel, [`NO_ID`] for background.
    pub ids: Vec<u32>,
    /// Window depth in [0, 1] per pixel, 1.0 for background.
    pub depth: Vec<f32>,
    /// Colour per pixel, RGBA8 (sRGB).
    pub color: Vec<[u8; 4]>,
    /// Fraction of each pixel covered by any surface, written by
    /// anti-aliasing hiders; empty otherwise.
    pub coverage: Vec<f32>,
}

/// Which buffers of a [`Frame`] a render must write: the frame request.
///
/// `Default` is all three, every hider's full frame. A caller that needs
/// fewer (an id pass, a depth pre-pass, a picker) says so and a hider that
/// honours the request (the tiled z-buffer's read-back) writes only those:
/// a 1024 x 1024 frame is 4 MB per buffer, and writing it costs about as
/// much as drawing a simple scene. Buffers not asked for keep whatever
/// they held before the render. Hiders that do not look at the request
/// write everything, which is always allowed.
///
/// ```
/// use hider_scene::{Frame, FrameBuffers};
///
/// let frame = Frame::new(4, 4)?.with_buffers(FrameBuffers::IDS);
/// assert!(frame.buffers().ids && !frame.buffers().depth && !frame.buffers().color);
/// assert_eq!(Frame::new(4, 4)?.buffers(), FrameBuffers::default());
/// # Ok::<(), hider_scene::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FrameBuffers {
    /// The visible primitive per pixel ([`Frame::ids`]).
    pub ids: bool,
    /// The window depth per pixel ([`Frame::depth`]).
    pub depth: bool,
    /// The colour per pixel ([`Frame::color`]).
    pub color: bool,
}

impl FrameBuffers {
    /// Every buffer: the default.
    pub const ALL: Self = Self {
        ids: true,
        depth: true,
        color: true,
    };
    /// The ids only.
    pub const IDS: Self = Self {
        ids: true,
        depth: false,
        color: false,
    };
    /// Ids and depth, no colour (what a z-buffer computes).
    pub const IDS_DEPTH: Self = Self {
        ids: true,
        depth: true,
        color: false,
    };
}

impl Default for FrameBuffers {
    fn default() -> Self {
        Self::ALL
    }
}

/// The colour of background pixels.
pub const BACKGROUND: [u8; 4] = [0, 0, 0, 255];

/// The depth of background pixels: the far plane.
pub const BACKGROUND_DEPTH: f32 = 1.0;

impl Frame {
    /// A cleared frame of `width x height` pixels; the size is checked
    /// against the limits before anything is allocated.
    pub fn new(width: u32, height: u32) -> Result<Self> {
        Self::new_for(width, height, FrameBuffers::ALL)
    }

    /// A frame of `width x height` pixels that renders will be asked for
    /// `wanted` only ([`Self::with_buffers`]): those buffers cleared as by
    /// [`Self::new`], the others allocated zeroed and never written here.
    /// The operating system maps zeroed memory only when it is first
    /// written, so a buffer that no render writes costs no memory: a hider
    /// that honours the request (the tiled z-buffer) leaves the colour of
    /// an id and depth pass untouched, 1 GB at 16384 x 16384. What an
    /// unwanted buffer holds is unspecified, as after any render that was
    /// not asked for it.
    ///
    /// ```
    /// use hider_scene::{Frame, FrameBuffers, NO_ID};
    /// let frame = Frame::new_for(4, 3, FrameBuffers::IDS_DEPTH)?;
    /// assert_eq!(frame.buffers(), FrameBuffers::IDS_DEPTH);
    /// assert!(frame.ids.iter().all(|&id| id == NO_ID));
    /// assert_eq!(frame.color.len(), 12);
    /// # Ok::<(), hider_scene::Error>(())
    /// ```
    pub fn new_for(width: u32, height: u32, wanted: FrameBuffers) -> Result<Self> {
        check_image_size(width, height)?;
        let n = width as usize * height as usize;
        // `vec![0; n]` of a zero value is one zeroed allocation (calloc),
        // which large sizes get as fresh pages from the kernel.
        Ok(Self {
            width,
            height,
            wanted,
            ids: if wanted.ids {
                vec![NO_ID; n]
            } else {
                vec![0; n]
            },
            depth: if wanted.depth {
                vec![BACKGROUND_DEPTH; n]
            } else {
                vec![0.0; n]
            },
            color: if wanted.color {
                vec![BACKGROUND; n]
            } else {
                vec![[0; 4]; n]
            },
            coverage: Vec::new(),
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The buffers a render must write (default all).
    pub fn buffers(&self) -> FrameBuffers {
        self.wanted
    }

    /// Sets the buffers a render must write ([`FrameBuffers`]).
    pub fn set_buffers(&mut self, wanted: FrameBuffers) {
        self.wanted = wanted;
    }

    /// The frame with [`Self::set_buffers`] applied.
    pub fn with_buffers(mut self, wanted: FrameBuffers) -> Self {
        self.wanted = wanted;
        self
    }

    /// Number of pixels.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether the frame has no pixels (never true for a checked size).
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// Buffer index of pixel `(x, y)`.
    #[inline]
    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Resets every buffer to background (ids [`NO_ID`], depth 1, colour
    /// [`BACKGROUND`], coverage emptied).
    pub fn clear(&mut self) {
        self.ids.fill(NO_ID);
        self.depth.fill(BACKGROUND_DEPTH);
        self.color.fill(BACKGROUND);
        self.coverage.clear();
    }

    /// Makes the frame `width x height` and clears it, reusing memory.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        check_image_size(width, height)?;
        let n = width as usize * height as usize;
        self.width = width;
        self.height = height;
        self.ids.resize(n, NO_ID);
        self.depth.resize(n, BACKGROUND_DEPTH);
        self.color.resize(n, BACKGROUND);
        self.clear();
        Ok(())
    }

    /// Number of pixels some primitive covers.
    pub fn covered_count(&self) -> usize {
        self.ids.iter().filter(|&&id| id != NO_ID).count()
    }

    /// Bytes held by the buffers.
    pub fn bytes(&self) -> usize {
        self.ids.len() * 4 + self.depth.len() * 4 + self.color.len() * 4 + self.coverage.len() * 4
    }

    /// The colour of pixel `(x, y)` (sRGB RGBA), `None` outside the frame.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        (x < self.width && y < self.height).then(|| self.color[self.index(x, y)])
    }

    /// The colour buffer as RGBA bytes, top row first: what an image
    /// library or a GPU upload takes.
    pub fn rgba_bytes(&self) -> &[u8] {
        self.color.as_flattened()
    }

    /// The colour buffer as an `image` crate picture; an error when the
    /// buffer (a public field) no longer holds width x height pixels.
    ///
    /// ```
    /// let mut frame = hider_scene::Frame::new(4, 2)?;
    /// frame.color[5] = [255, 0, 0, 255];
    /// let image = frame.to_rgba_image()?;
    /// assert_eq!(image.get_pixel(1, 1).0, [255, 0, 0, 255]);
    /// assert_eq!(frame.pixel(1, 1), Some([255, 0, 0, 255]));
    /// assert_eq!(frame.pixel(4, 0), None);
    /// assert_eq!(frame.rgba_bytes().len(), 4 * 2 * 4);
    /// # Ok::<(), hider_scene::Error>(())
    /// ```
    #[cfg(feature = "image")]
    pub fn to_rgba_image(&self) -> Result<image::RgbaImage> {
        image::RgbaImage::from_raw(self.width, self.height, self.rgba_bytes().to_vec()).ok_or_else(
            || {
                Error::InvalidScene(format!(
                    "the frame's colour buffer holds {} pixels, not {} x {}",
                    self.color.len(),
                    self.width,
                    self.height
                ))
            },
        )
    }

    /// Writes the colour buffer as an 8-bit RGBA PNG, atomically.
    #[cfg(feature = "image")]
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let mut set = OutputSet::new();
        self.write_png_into(&mut set, path)?;
        set.commit()
    }

    /// Writes the ids as int32 little-endian, -1 for background, top row
    /// first (the GL reference `.i32` format), atomically.
    pub fn write_ids(&self, path: &Path) -> Result<()> {
        let mut set = OutputSet::new();
        self.write_ids_into(&mut set, path)?;
        set.commit()
    }

    /// Writes the depth as float32 little-endian window depth, 1.0 for
    /// background, top row first (the GL reference `.f32` format),
    /// atomically.
    pub fn write_depth(&self, path: &Path) -> Result<()> {
        let mut set = OutputSet::new();
        self.write_depth_into(&mut set, path)?;
        set.commit()
    }

    /// [`Self::write_png`] staged in `set`: in place only when the set is
    /// committed with the other outputs of the run.
    #[cfg(feature = "image")]
    pub fn write_png_into(&self, set: &mut OutputSet, path: &Path) -> Result<()> {
        // The colour buffer is already RGBA bytes: borrowed, not copied (a
        // copy was a second full frame, 1 GB at 16384 x 16384).
        let bytes = self.rgba_bytes();
        set.stage(path, |w| {
            let encoder = image::codecs::png::PngEncoder::new(w);
            image::ImageEncoder::write_image(
                encoder,
                bytes,
                self.width,
                self.height,
                image::ExtendedColorType::Rgba8,
            )
            .map_err(|e| Error::Image {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
        })
    }

    /// [`Self::write_ids`] staged in `set`.
    pub fn write_ids_into(&self, set: &mut OutputSet, path: &Path) -> Result<()> {
        let bytes: Vec<u8> = self
            .ids
            .iter()
            .flat_map(|&id| id_to_i32(id).to_le_bytes())
            .collect();
        stage_bytes(set, path, &bytes)
    }

    /// [`Self::write_depth`] staged in `set`.
    pub fn write_depth_into(&self, set: &mut OutputSet, path: &Path) -> Result<()> {
        let bytes: Vec<u8> = self.depth.iter().flat_map(|d| d.to_le_bytes()).collect();
        stage_bytes(set, path, &bytes)
    }
}

/// An id as stored in dump files: -1 for [`NO_ID`].
pub fn id_to_i32(id: u32) -> i32 {
    if id == NO_ID { -1 } else { id as i32 }
}

fn stage_bytes(set: &mut OutputSet, path: &Path, bytes: &[u8]) -> Result<()> {
    set.stage(path, |w| {
        w.write_all(bytes).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

fn read_exact_values(path: &Path, count: usize) -> Result<Vec<[u8; 4]>> {
    let mut file = std::fs::File::open(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let len = file
        .metadata()
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?
        .len();
    if len != count as u64 * 4 {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: 0,
            message: format!("expected {} bytes ({count} values), found {len}", count * 4),
        });
    }
    let mut bytes = Vec::with_capacity(count * 4);
    file.read_to_end(&mut bytes).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(bytes
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect())
}

/// Reads an id dump of `width x height` values (-1 becomes [`NO_ID`]).
pub fn read_ids(path: &Path, width: u32, height: u32) -> Result<Vec<u32>> {
    check_image_size(width, height)?;
    Ok(read_exact_values(path, width as usize * height as usize)?
        .into_iter()
        .map(|b| {
            let v = i32::from_le_bytes(b);
            if v < 0 { NO_ID } else { v as u32 }
        })
        .collect())
}

/// Reads a depth dump of `width x height` float32 values.
pub fn read_depth(path: &Path, width: u32, height: u32) -> Result<Vec<f32>> {
    check_image_size(width, height)?;
    Ok(read_exact_values(path, width as usize * height as usize)?
        .into_iter()
        .map(f32::from_le_bytes)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dumps_round_trip_with_minus_one_background() {
        let dir = std::env::temp_dir().join(format!("hider-frame-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut f = Frame::new(3, 2).unwrap();
        f.ids[1] = 7;
        f.depth[1] = 0.25;
        f.write_ids(&dir.join("a.i32")).unwrap();
        f.write_depth(&dir.join("a.f32")).unwrap();
        #[cfg(feature = "image")]
        f.write_png(&dir.join("a.png")).unwrap();
        let raw = std::fs::read(dir.join("a.i32")).unwrap();
        assert_eq!(&raw[..8], &[255, 255, 255, 255, 7, 0, 0, 0]);
        assert_eq!(read_ids(&dir.join("a.i32"), 3, 2).unwrap(), f.ids);
        assert_eq!(read_depth(&dir.join("a.f32"), 3, 2).unwrap(), f.depth);
        assert!(read_ids(&dir.join("a.i32"), 4, 2).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn absurd_sizes_are_refused_before_allocating() {
        assert!(Frame::new(0, 1).is_err());
        assert!(Frame::new(100_000, 100_000).is_err());
        let mut f = Frame::new(2, 2).unwrap();
        assert!(f.resize(16385, 1).is_err());
        f.resize(4, 1).unwrap();
        assert_eq!(f.len(), 4);
    }
}
