//! Contact sheets: for one hard-case scene, the oracle's picture and every
//! hider's render side by side, each hider's wrong pixels painted over its
//! render, labelled with the hider's name.
//!
//! Plotters draws no text into bitmaps without a font feature, so the
//! labels use a 3 x 5 pixel font of our own: small, dependency-free and
//! enough for registry names (`a-z`, `0-9`, `-`, `_`, `.`).

use std::path::Path;

use anyhow::{Context, Result};
use hider_oracle::Reference;
use hider_scene::{Frame, ScreenScene, ShadeMode, shade_frame};
use image::{Rgba, RgbaImage};

use crate::accuracy::{Mark, marks};

/// Colour of a wrong pixel (non-tie wrong id or coverage mismatch).
pub const WRONG: [u8; 4] = [255, 0, 255, 255];
/// Colour of a tie decided differently from the oracle (accepted).
pub const TIE: [u8; 4] = [255, 220, 0, 255];
const SHEET_BACKGROUND: [u8; 4] = [40, 40, 40, 255];
const LABEL: [u8; 4] = [230, 230, 230, 255];

/// The renders of one case, in hider order.
#[derive(Clone, Debug, Default)]
pub struct ContactSheet {
    /// `(hider name, its last frame)`, colour already resolved or shaded.
    pub tiles: Vec<(String, Frame)>,
}

/// Tiles are scaled up (nearest neighbour) to at least this many pixels on
/// their longer side, so single wrong pixels stay visible.
const TILE_SIDE: u32 = 128;
const COLUMNS: u32 = 5;
const GAP: u32 = 6;
const FONT_SCALE: u32 = 2;
const LABEL_HEIGHT: u32 = 5 * FONT_SCALE + 4;

/// 3 x 5 glyphs, five rows of three bits, most significant bit left.
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_lowercase() {
        'a' => [2, 5, 7, 5, 5],
        'b' => [6, 5, 6, 5, 6],
        'c' => [3, 4, 4, 4, 3],
        'd' => [6, 5, 5, 5, 6],
        'e' => [7, 4, 6, 4, 7],
        'f' => [7, 4, 6, 4, 4],
        'g' => [3, 4, 5, 5, 3],
        'h' => [5, 5, 7, 5, 5],
        'i' => [7, 2, 2, 2, 7],
        'j' => [1, 1, 1, 5, 2],
        'k' => [5, 5, 6, 5, 5],
        'l' => [4, 4, 4, 4, 7],
        'm' => [5, 7, 7, 5, 5],
        'n' => [6, 5, 5, 5, 5],
        'o' => [2, 5, 5, 5, 2],
        'p' => [6, 5, 6, 4, 4],
        'q' => [2, 5, 5, 6, 3],
        'r' => [6, 5, 6, 5, 5],
        's' => [3, 4, 2, 1, 6],
        't' => [7, 2, 2, 2, 2],
        'u' => [5, 5, 5, 5, 7],
        'v' => [5, 5, 5, 5, 2],
        'w' => [5, 5, 7, 7, 5],
        'x' => [5, 5, 2, 5, 5],
        'y' => [5, 5, 2, 2, 2],
        'z' => [7, 1, 2, 4, 7],
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [6, 1, 2, 4, 7],
        '3' => [6, 1, 2, 1, 6],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 6, 1, 6],
        '6' => [3, 4, 7, 5, 7],
        '7' => [7, 1, 2, 2, 2],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 6],
        '-' => [0, 0, 7, 0, 0],
        '_' => [0, 0, 0, 0, 7],
        '.' => [0, 0, 0, 0, 2],
        _ => [0; 5],
    }
}

/// Width in pixels of `text` in the label font.
fn text_width(text: &str) -> u32 {
    let n = text.chars().count() as u32;
    (n * 4 * FONT_SCALE).saturating_sub(FONT_SCALE)
}

/// Draws `text` with its top-left corner at `(x, y)`, clipped to
/// `max_width` pixels and to the image.
fn draw_text(img: &mut RgbaImage, x: u32, y: u32, text: &str, max_width: u32) {
    let advance = 4 * FONT_SCALE;
    for (k, c) in text.chars().enumerate() {
        let x0 = x + k as u32 * advance;
        if x0 + 3 * FONT_SCALE > x + max_width {
            break;
        }
        for (row, bits) in glyph(c).iter().enumerate() {
            for col in 0..3u32 {
                if bits >> (2 - col) & 1 == 0 {
                    continue;
                }
                for dy in 0..FONT_SCALE {
                    for dx in 0..FONT_SCALE {
                        let (px, py) =
                            (x0 + col * FONT_SCALE + dx, y + row as u32 * FONT_SCALE + dy);
                        if px < img.width() && py < img.height() {
                            img.put_pixel(px, py, Rgba(LABEL));
                        }
                    }
                }
            }
        }
    }
}

/// The sheet as an image: first the oracle's picture (shaded from its ids),
/// then every tile with its wrong pixels in [`WRONG`] and differently
/// decided ties in [`TIE`].
pub fn compose(
    screen: &ScreenScene,
    reference: &Reference,
    sheet: &ContactSheet,
    tie_tolerance: f64,
) -> Result<RgbaImage> {
    let (w, h) = (reference.width, reference.height);
    let mut oracle = Frame::new(w, h)?;
    oracle.ids.clone_from(&reference.ids);
    oracle.depth.clone_from(&reference.depth);
    shade_frame(screen, &mut oracle, ShadeMode::Lambert)?;
    let mut tiles: Vec<(String, Vec<[u8; 4]>)> = vec![("oracle".into(), oracle.color)];
    for (name, frame) in &sheet.tiles {
        let mut color = frame.color.clone();
        for (c, m) in color
            .iter_mut()
            .zip(marks(reference, &frame.ids, tie_tolerance))
        {
            match m {
                Mark::Agree => {}
                Mark::Wrong => *c = WRONG,
                Mark::TieDifference => *c = TIE,
            }
        }
        tiles.push((name.clone(), color));
    }
    let scale = (TILE_SIDE / w.max(h).max(1)).max(1);
    let (tw, th) = (w * scale, h * scale);
    // Columns are as wide as the longest label, so no name is cut.
    let label_width = tiles
        .iter()
        .map(|(name, _)| text_width(name))
        .max()
        .unwrap_or(0);
    let cw = tw.max(label_width);
    let cols = (tiles.len() as u32).min(COLUMNS);
    let rows = (tiles.len() as u32).div_ceil(cols);
    let width = GAP + cols * (cw + GAP);
    let height = GAP + rows * (th + LABEL_HEIGHT + GAP);
    let mut img = RgbaImage::from_pixel(width, height, Rgba(SHEET_BACKGROUND));
    for (k, (name, color)) in tiles.iter().enumerate() {
        let (col, row) = (k as u32 % cols, k as u32 / cols);
        let x0 = GAP + col * (cw + GAP);
        let y0 = GAP + row * (th + LABEL_HEIGHT + GAP);
        draw_text(&mut img, x0, y0, name, cw);
        let y0 = y0 + LABEL_HEIGHT;
        for y in 0..th {
            for x in 0..tw {
                let c = color[((y / scale) * w + x / scale) as usize];
                img.put_pixel(x0 + x, y0 + y, Rgba(c));
            }
        }
    }
    Ok(img)
}

/// Composes the sheet and writes it as PNG, atomically.
pub fn write_contact_sheet(
    path: &Path,
    screen: &ScreenScene,
    reference: &Reference,
    sheet: &ContactSheet,
    tie_tolerance: f64,
) -> Result<()> {
    let img = compose(screen, reference, sheet, tie_tolerance)?;
    hider_scene::atomic::write_atomic(path, |out| {
        img.write_to(out, image::ImageFormat::Png)
            .map_err(|e| hider_scene::Error::Image {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
    })
    .with_context(|| format!("writing {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_oracle::RayCastOracle;
    use hider_plan::registry;
    use hider_testkit::screen;

    #[test]
    fn wrong_pixels_are_painted_and_tiles_laid_out() {
        let scene = crate::scenes::linear_depth_probe();
        let screen = screen(&scene, 32, 32);
        let reference = RayCastOracle::default().evaluate(&screen);
        let mut sheet = ContactSheet::default();
        for name in ["zbuffer", "zbuffer-linear-z"] {
            let mut z = registry::by_name(name).unwrap().make();
            let mut f = Frame::new(32, 32).unwrap();
            z.render(&screen, &mut f).unwrap();
            shade_frame(&screen, &mut f, ShadeMode::Lambert).unwrap();
            sheet.tiles.push((z.name().to_owned(), f));
        }
        let img = compose(&screen, &reference, &sheet, 1e-5).unwrap();
        // Three tiles of 128 px (32 px scaled by 4) in one row.
        assert_eq!(img.width(), GAP + 3 * (128 + GAP));
        assert_eq!(img.height(), GAP + 128 + LABEL_HEIGHT + GAP);
        let tile_has_wrong = |col: u32| {
            let x0 = GAP + col * (128 + GAP);
            (0..128)
                .any(|y| (0..128).any(|x| img.get_pixel(x0 + x, GAP + LABEL_HEIGHT + y).0 == WRONG))
        };
        assert!(!tile_has_wrong(0) && !tile_has_wrong(1));
        assert!(
            tile_has_wrong(2),
            "linear z must misplace the intersection line"
        );
        // The label strip holds text.
        assert!(
            (0..LABEL_HEIGHT).any(|y| (0..128).any(|x| img.get_pixel(GAP + x, GAP + y).0 == LABEL))
        );
    }

    #[test]
    fn long_names_are_not_cut() {
        let scene = crate::scenes::linear_depth_probe();
        let screen = screen(&scene, 32, 32);
        let reference = RayCastOracle::default().evaluate(&screen);
        let mut f = Frame::new(32, 32).unwrap();
        let mut z = registry::by_name("zbuffer").unwrap().make();
        z.render(&screen, &mut f).unwrap();
        let name = "abuffer-carpenter";
        let sheet = ContactSheet {
            tiles: vec![(name.to_owned(), f)],
        };
        let img = compose(&screen, &reference, &sheet, 1e-5).unwrap();
        let cw = text_width(name);
        assert!(cw > 128, "the name is wider than a tile");
        assert_eq!(img.width(), GAP + 2 * (cw + GAP));
        // The name's last letters, right of the tile's 128 pixels, are drawn.
        let x0 = GAP + cw + GAP;
        assert!(
            (0..LABEL_HEIGHT).any(|y| (128..cw).any(|x| img.get_pixel(x0 + x, GAP + y).0 == LABEL))
        );
    }
}
