//! Reading texture files: the header (size, alpha channel) without
//! decoding, then the texels down to a mip level within the budget.

use std::path::Path;

use super::super::budget::{self, Reservation};
use super::super::mip::{self, Cascade};
use super::{AlphaCount, MAX_TEXTURE_SIDE, Texture};
use crate::{Error, Result};

/// What a texture file's header says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Header {
    pub(crate) width: u32,
    pub(crate) height: u32,
    /// Whether the image has an alpha channel (or PNG transparency).
    pub(crate) alpha: bool,
}

impl Header {
    /// Bytes per decoded texel.
    fn per_texel(&self) -> u64 {
        if self.alpha { 4 } else { 3 }
    }
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
pub fn probe(path: &Path) -> Result<(u32, u32)> {
    header(path).map(|h| (h.width, h.height))
}

/// An image file's header, checked: a regular file within the size limit,
/// a known format, sides within [`MAX_TEXTURE_SIDE`].
#[cfg(not(feature = "image"))]
pub(crate) fn header(path: &Path) -> Result<Header> {
    Err(without_image(path))
}

/// An image file's header, checked: a regular file within the size limit,
/// a known format, sides within [`MAX_TEXTURE_SIDE`].
#[cfg(feature = "image")]
pub(crate) fn header(path: &Path) -> Result<Header> {
    use image::ImageDecoder;
    let image_error = |e: image::ImageError| Error::Image {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    crate::input::check_regular(
        path,
        "texture file size in bytes",
        crate::input::MAX_TEXTURE_FILE_BYTES,
    )?;
    let decoder = image::ImageReader::open(path)
        .map_err(io_error)?
        .with_guessed_format()
        .map_err(io_error)?
        .into_decoder()
        .map_err(image_error)?;
    let (width, height) = decoder.dimensions();
    for (what, v) in [("width", width), ("height", height)] {
        if v > MAX_TEXTURE_SIDE {
            // The file named, as every texture warning does.
            return Err(Error::Image {
                path: path.to_path_buf(),
                message: format!(
                    "texture {what} {v} is over the limit of {MAX_TEXTURE_SIDE} texels \
                     (MAX_TEXTURE_SIDE)"
                ),
            });
        }
    }
    if width == 0 || height == 0 {
        return Err(Error::Image {
            path: path.to_path_buf(),
            message: "image has no pixels".into(),
        });
    }
    Ok(Header {
        width,
        height,
        alpha: decoder.color_type().has_alpha(),
    })
}

/// Counts the bytes of decoding `header`'s image down to `base` against
/// the budget, or says why not (file, size, limit, the flag).
fn reserve(path: &Path, header: &Header, base: u32) -> Result<Reservation> {
    let bytes = mip::chain_bytes(header.width, header.height, base, header.per_texel());
    Reservation::try_new(bytes).map_err(|over| Error::Image {
        path: path.to_path_buf(),
        message: format!(
            "{}x{} texture needs {} decoded (mip level {base} and coarser), over the texture \
             budget of {} ({} in use by other textures); raise it (hider render --texture-budget, or \
             hider_scene::shade::set_texture_budget)",
            header.width,
            header.height,
            budget::human_bytes(bytes),
            budget::human_bytes(over.limit),
            budget::human_bytes(over.used),
        ),
    })
}

/// Counts the image held whole by a decode that cannot stream (JPEG,
/// interlaced PNG), 4 bytes per texel, against the budget.
#[cfg(feature = "image")]
fn reserve_whole(path: &Path, header: &Header) -> Result<Reservation> {
    let bytes = u64::from(header.width) * u64::from(header.height) * 4;
    Reservation::try_new(bytes).map_err(|over| Error::Image {
        path: path.to_path_buf(),
        message: format!(
            "{}x{} texture is decoded whole (not a streamable PNG): {} while decoding, over \
             the texture budget of {} ({} in use); raise it (hider render --texture-budget, or \
             hider_scene::shade::set_texture_budget)",
            header.width,
            header.height,
            budget::human_bytes(bytes),
            budget::human_bytes(over.limit),
            budget::human_bytes(over.used),
        ),
    })
}

/// Decodes `path` down to mip level `base` (levels `base` and coarser
/// kept), header and budget checked first; as a mask (`map_d`: the alpha
/// plane is the image's first channel) when `mask`.
#[cfg(not(feature = "image"))]
pub(crate) fn load_level(path: &Path, _base: u32, _mask: bool) -> Result<Texture> {
    Err(without_image(path))
}

/// Decodes `path` down to mip level `base` (levels `base` and coarser
/// kept), header and budget checked first. PNG files that are not
/// interlaced stream row by row through the mip cascade, so the full image
/// is never held unless level 0 is asked for; other files are decoded
/// whole, then halved.
///
/// With `mask` (a `map_d` texture, scalar alpha) the alpha plane holds the
/// image's first channel (grey for a greyscale image, red for a colour
/// one), as bytes read as plain numbers (not sRGB-decoded), and is
/// classified as an alpha channel; the image's own alpha channel, if any,
/// is not read.
#[cfg(feature = "image")]
pub(crate) fn load_level(path: &Path, base: u32, mask: bool) -> Result<Texture> {
    let header = header(path)?;
    let base = base.min(mip::level_count(header.width, header.height) - 1);
    let held = Header {
        alpha: header.alpha || mask,
        ..header
    };
    let reservation = reserve(path, &held, base)?;
    let image_error = |message: String| Error::Image {
        path: path.to_path_buf(),
        message,
    };
    let streamed = stream_png(path, &header, base, mask).map_err(image_error)?;
    let (levels, class) = match streamed {
        Some(done) => done,
        None => {
            // The whole image is held while it is halved: counted too,
            // for as long as the decode runs.
            let _whole = reserve_whole(path, &header)?;
            whole(path, &header, base, mask)?
        }
    };
    let (count, kept) = (
        mip::level_count(header.width, header.height),
        levels.len() as u32,
    );
    if kept + base != count {
        return Err(image_error(format!(
            "decoded {kept} mip levels from level {base} of {count}"
        )));
    }
    Ok(Texture::from_levels(
        header.width,
        header.height,
        levels,
        class,
        Some(reservation),
    ))
}

/// Splits a decoded row of `channels` bytes per texel into sRGB bytes and
/// alpha bytes (grey expanded to RGB).
fn split_row(row: &[u8], channels: usize, rgb: &mut Vec<u8>, alpha: &mut Vec<u8>) {
    rgb.clear();
    alpha.clear();
    match channels {
        3 => rgb.extend_from_slice(row),
        4 => {
            for p in row.chunks_exact(4) {
                rgb.extend_from_slice(&p[..3]);
                alpha.push(p[3]);
            }
        }
        _ => {
            for p in row.chunks_exact(channels) {
                rgb.extend_from_slice(&[p[0], p[0], p[0]]);
                if channels == 2 {
                    alpha.push(p[1]);
                }
            }
        }
    }
}

/// The first channel of `rgb` (3 bytes per texel) as the alpha plane: a
/// mask's.
fn first_channel(rgb: &[u8], alpha: &mut Vec<u8>) {
    alpha.clear();
    alpha.extend(rgb.chunks_exact(3).map(|p| p[0]));
}

/// Running alpha class of level-0 rows.
fn classify_into(class: &mut AlphaCount, alpha: &[u8]) {
    class.add(alpha);
}

/// Streams a non-interlaced 8-bit (after expansion) PNG through the
/// cascade; `Ok(None)` for any other file, which is then decoded whole.
#[cfg(feature = "image")]
fn stream_png(
    path: &Path,
    header: &Header,
    base: u32,
    mask: bool,
) -> std::result::Result<Option<(Vec<mip::Level>, AlphaCount)>, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let Ok(mut reader) = decoder.read_info() else {
        return Ok(None);
    };
    let (color, depth) = reader.output_color_type();
    let channels = match color {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Ok(None),
    };
    let info = reader.info();
    if info.interlaced
        || depth != png::BitDepth::Eight
        || (info.width, info.height) != (header.width, header.height)
        || (channels % 2 == 0) != header.alpha
    {
        return Ok(None);
    }
    let keeps_alpha = header.alpha || mask;
    let mut cascade = Cascade::new(header.width, header.height, base, keeps_alpha);
    let (mut rgb, mut alpha) = (Vec::new(), Vec::new());
    let mut class = AlphaCount::default();
    let mut rows = 0;
    while let Some(row) = reader.next_row().map_err(|e| e.to_string())? {
        split_row(row.data(), channels, &mut rgb, &mut alpha);
        if rgb.len() != 3 * header.width as usize {
            return Err(format!("row {rows} holds {} bytes", row.data().len()));
        }
        if mask {
            first_channel(&rgb, &mut alpha);
        }
        classify_into(&mut class, &alpha);
        cascade.push(&rgb, keeps_alpha.then_some(&alpha[..]));
        rows += 1;
    }
    if rows != header.height {
        return Err(format!("{rows} rows of {}", header.height));
    }
    Ok(Some((cascade.finish(), class)))
}

/// Decodes the whole image with the `image` crate, then halves it.
#[cfg(feature = "image")]
fn whole(
    path: &Path,
    header: &Header,
    base: u32,
    mask: bool,
) -> Result<(Vec<mip::Level>, AlphaCount)> {
    let img = image::open(path).map_err(|e| Error::Image {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let (w, h) = (img.width(), img.height());
    if (w, h) != (header.width, header.height) {
        return Err(Error::Image {
            path: path.to_path_buf(),
            message: format!(
                "decoded {w}x{h}, the header said {}x{}",
                header.width, header.height
            ),
        });
    }
    let mut cascade = Cascade::new(w, h, base, header.alpha || mask);
    let mut class = AlphaCount::default();
    let (mut rgb, mut alpha) = (Vec::new(), Vec::new());
    if mask {
        let all = img.into_rgb8();
        for row in all.as_raw().chunks_exact(3 * w as usize) {
            first_channel(row, &mut alpha);
            classify_into(&mut class, &alpha);
            cascade.push(row, Some(&alpha));
        }
    } else if header.alpha {
        let rgba = img.into_rgba8();
        for row in rgba.as_raw().chunks_exact(4 * w as usize) {
            split_row(row, 4, &mut rgb, &mut alpha);
            classify_into(&mut class, &alpha);
            cascade.push(&rgb, Some(&alpha));
        }
    } else {
        let all = img.into_rgb8();
        for row in all.as_raw().chunks_exact(3 * w as usize) {
            cascade.push(row, None);
        }
    }
    Ok((cascade.finish(), class))
}

#[cfg(all(test, feature = "image"))]
mod tests {
    use super::*;
    use crate::shade::AlphaClass;

    /// A PNG streamed row by row gives the levels of the same image built
    /// in memory, whichever level the decode stops at; grey expands to
    /// RGB; the alpha is classified from every texel.
    #[test]
    fn streamed_png_equals_the_in_memory_chain() {
        let dir = std::env::temp_dir().join(format!("hider-decode-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (w, h) = (13, 7);
        let rgba = image::RgbaImage::from_fn(w, h, |x, y| {
            let a = if (x + y) % 3 == 0 { 0 } else { 255 };
            image::Rgba([(x * 19) as u8, (y * 31) as u8, ((x * y) % 256) as u8, a])
        });
        let path = dir.join("cut.png");
        rgba.save(&path).unwrap();
        let memory = Texture::from_srgba8(w, h, rgba.as_raw()).unwrap();
        assert_eq!(memory.alpha_class(), AlphaClass::Cutout);
        for base in [0, 1, 3] {
            let t = load_level(&path, base, false).unwrap();
            assert_eq!(t.base_level(), base);
            assert_eq!(t.levels[..], memory.levels[base as usize..], "base {base}");
            assert_eq!(t.alpha_class(), AlphaClass::Cutout);
        }
        let grey = dir.join("grey.png");
        image::GrayImage::from_fn(4, 4, |x, _| image::Luma([x as u8 * 60]))
            .save(&grey)
            .unwrap();
        let t = load_level(&grey, 0, false).unwrap();
        assert_eq!(t.levels[0].rgb[1], [60, 60, 60]);
        assert_eq!(t.alpha_class(), AlphaClass::Opaque);
        assert!(t.levels[0].alpha.is_none());
        // As a mask (map_d), the grey is the alpha plane, as plain numbers.
        let m = load_level(&grey, 0, true).unwrap();
        assert_eq!(
            m.levels[0].alpha.as_deref().unwrap()[..4],
            [0, 60, 120, 180]
        );
        assert_eq!(m.alpha_class(), AlphaClass::Partial);
        assert_eq!(m.partial_share(), 0.75);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
