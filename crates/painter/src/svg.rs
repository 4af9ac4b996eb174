//! Vector output: the ordered piece list as SVG.
//!
//! This is what a painter's algorithm can give and a z-buffer cannot: the
//! visible surfaces as resolution-independent polygons, painted back to
//! front. Each piece becomes one `<path>` in paint order, filled with its
//! primitive's colour ([`hider_scene::shade::prim_color`], flat Lambert or
//! false colour per id) and tagged `data-prim` with its primitive id, so a
//! reader can tell which surface each path belongs to. Translucent
//! materials get `fill-opacity`, which back-to-front order composites
//! correctly.
//!
//! Both painters keep the ordered pieces of their last render and write
//! them through [`hider_scene::OrderedPolygons`]; [`LastFrame`] remembers
//! which scene that was.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use hider_scene::atomic::write_atomic;
use hider_scene::shade::{prim_color, to_srgb8};
use hider_scene::{Error, Result, ScreenScene, ShadeMode};

use crate::piece::Piece;

/// What the vector output checks the scene it is given against: the size
/// and counts of the scene last rendered, so that the pieces kept (indices
/// into its triangles and primitives) are never read against another.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LastFrame {
    width: u32,
    height: u32,
    tris: usize,
    prims: usize,
}

impl LastFrame {
    /// The shape of `scene`.
    pub fn of(scene: &ScreenScene) -> Self {
        Self {
            width: scene.viewport.width,
            height: scene.viewport.height,
            tris: scene.tris.len(),
            prims: scene.prims.len(),
        }
    }

    /// Errors unless a render succeeded (`last`) and `scene` has its shape.
    pub fn check(last: Option<&Self>, hider: &str, scene: &ScreenScene) -> Result<()> {
        let message = match last {
            None => "no vector output: render a frame successfully before writing SVG",
            Some(last) if *last != Self::of(scene) => {
                "the scene given for the SVG is not the one last rendered"
            }
            Some(_) => return Ok(()),
        };
        Err(Error::Render {
            hider: hider.to_owned(),
            message: message.to_owned(),
        })
    }
}

/// The SVG document for `pieces` (in paint order, farthest first) over
/// the scene's viewport. Pieces entirely outside the image are left out.
/// `seam_stroke` > 0 strokes each path with its fill colour at that width.
pub(crate) fn svg_document<'a>(
    scene: &ScreenScene,
    pieces: impl IntoIterator<Item = &'a Piece>,
    mode: ShadeMode,
    seam_stroke: f64,
) -> String {
    let (w, h) = (scene.viewport.width, scene.viewport.height);
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let bg = hider_scene::frame::BACKGROUND;
    let _ = writeln!(
        s,
        r##"<rect width="{w}" height="{h}" fill="#{:02x}{:02x}{:02x}"/>"##,
        bg[0], bg[1], bg[2]
    );
    let mut colors: Vec<Option<(String, f32)>> = vec![None; scene.prims.len()];
    for piece in pieces {
        let outside = piece.max.x <= 0.0
            || piece.max.y <= 0.0
            || piece.min.x >= f64::from(w)
            || piece.min.y >= f64::from(h);
        if outside {
            continue;
        }
        let (fill, opacity) = colors[piece.prim as usize]
            .get_or_insert_with(|| {
                let (rgb, a) = prim_color(scene, piece.prim, mode);
                let hex = format!(
                    "#{:02x}{:02x}{:02x}",
                    to_srgb8(rgb[0]),
                    to_srgb8(rgb[1]),
                    to_srgb8(rgb[2])
                );
                (hex, a)
            })
            .clone();
        let _ = write!(s, r#"<path data-prim="{}" d=""#, piece.prim);
        for (k, v) in piece.polygon.iter().enumerate() {
            // `{}` prints the shortest text that reads back as the same
            // f64: fixed-point vertices (multiples of 1/256) stay exact.
            let _ = write!(s, "{}{},{} ", if k == 0 { "M" } else { "L" }, v.x, v.y);
        }
        let _ = write!(s, r#"Z" fill="{fill}""#);
        if opacity < 1.0 {
            let _ = write!(s, r#" fill-opacity="{opacity}""#);
        }
        if seam_stroke > 0.0 {
            let _ = write!(
                s,
                r#" stroke="{fill}" stroke-width="{seam_stroke}" stroke-linejoin="round""#
            );
        }
        let _ = writeln!(s, "/>");
    }
    s.push_str("</svg>\n");
    s
}

/// Writes [`svg_document`] to `path` atomically (a temporary file renamed
/// into place), so a failed run never leaves a partial SVG.
pub(crate) fn write_svg<'a>(
    scene: &ScreenScene,
    pieces: impl IntoIterator<Item = &'a Piece>,
    path: &Path,
    mode: ShadeMode,
    seam_stroke: f64,
) -> Result<()> {
    let doc = svg_document(scene, pieces, mode, seam_stroke);
    write_atomic(path, |w| {
        w.write_all(doc.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}
