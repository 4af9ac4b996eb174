//! The SVG documents: one `<path>` per face group for the regions, one
//! `<polyline>` per joined line for the drawings.
//!
//! Region paths are written on the integer grid itself, relative from
//! point to point, under one `scale` transform: no rounding happens on the
//! way out, and small integer steps are shorter text than the pixel
//! decimals of the same points.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use hider_scene::atomic::write_atomic;
use hider_scene::{Error, Result, ScreenScene};

use crate::VectorOptions;
use crate::lines::{LineDrawing, LineKind, Polyline};
use crate::regions::RegionMap;

fn header(scene: &ScreenScene, background: Option<[u8; 3]>) -> String {
    let (w, h) = (scene.viewport.width, scene.viewport.height);
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    if let Some(bg) = background {
        let _ = writeln!(
            s,
            r##"<rect width="{w}" height="{h}" fill="#{:02x}{:02x}{:02x}"/>"##,
            bg[0], bg[1], bg[2]
        );
    }
    s
}

/// The regions SVG: the background (when [`VectorOptions::background`])
/// and one path per face group, tagged `data-prims` with its primitive
/// count and the first primitive id.
pub fn regions_svg(scene: &ScreenScene, map: &RegionMap, options: &VectorOptions) -> String {
    let bg = hider_scene::frame::BACKGROUND;
    let background = options.background.then_some([bg[0], bg[1], bg[2]]);
    let mut s = header(scene, background);
    let scale = 1.0 / map.grid.units_per_pixel();
    let _ = writeln!(
        s,
        r#"<g transform="scale({scale})" stroke="none" fill-rule="evenodd">"#
    );
    for group in &map.groups {
        let _ = write!(s, r#"<path data-prim="{}" d=""#, group.prims[0]);
        for contour in group.shapes.iter().flatten() {
            let Some(first) = contour.first() else {
                continue;
            };
            let _ = write!(s, "M{} {}l", first.x, first.y);
            let mut prev = *first;
            for (k, p) in contour.iter().enumerate().skip(1) {
                let sep = if k == 1 { "" } else { " " };
                let _ = write!(s, "{sep}{} {}", p.x - prev.x, p.y - prev.y);
                prev = *p;
            }
            s.push('z');
        }
        let _ = write!(s, r#"" fill="{}""#, group.fill);
        if group.opacity < 1.0 {
            let _ = write!(s, r#" fill-opacity="{}""#, group.opacity);
        }
        if options.seam_stroke > 0.0 {
            // In grid units: the group is drawn under the scale transform.
            let width = options.seam_stroke * map.grid.units_per_pixel();
            let _ = write!(
                s,
                r#" stroke="{}" stroke-width="{width}" stroke-linejoin="round""#,
                group.fill
            );
        }
        s.push_str("/>\n");
    }
    s.push_str("</g>\n</svg>\n");
    s
}

fn stroke_colour(kind: LineKind) -> &'static str {
    match kind {
        LineKind::Intersection => "#b03030",
        _ => "#000000",
    }
}

fn write_polylines(s: &mut String, lines: &[Polyline]) {
    for line in lines {
        let _ = write!(
            s,
            r#"<polyline stroke="{}" points=""#,
            stroke_colour(line.kind)
        );
        for (k, (x, y)) in line.points.iter().enumerate() {
            let sep = if k == 0 { "" } else { " " };
            // Four decimals: 1/10000 pixel, below any plotter's step.
            let _ = write!(s, "{sep}{},{}", round4(*x), round4(*y));
        }
        s.push_str(r#""/>"#);
        s.push('\n');
    }
}

fn round4(v: f64) -> f64 {
    (v * 1e4).round() / 1e4
}

/// The hidden-line SVG on white (when [`VectorOptions::background`]): the
/// visible polylines (intersections in red), and
/// the hidden ones dashed and grey when the drawing has them.
pub fn lines_svg(scene: &ScreenScene, drawing: &LineDrawing, options: &VectorOptions) -> String {
    // Lines are drawn on paper: white under black strokes.
    let mut s = header(scene, options.background.then_some([255, 255, 255]));
    let w = options.stroke_width;
    if !drawing.hidden.is_empty() {
        let _ = writeln!(
            s,
            r#"<g fill="none" stroke-width="{}" stroke-dasharray="{} {}" opacity="0.5" stroke-linecap="round">"#,
            w * 0.5,
            w * 3.0,
            w * 2.0
        );
        write_polylines(&mut s, &drawing.hidden);
        s.push_str("</g>\n");
    }
    let _ = writeln!(
        s,
        r#"<g fill="none" stroke-width="{w}" stroke-linecap="round" stroke-linejoin="round">"#
    );
    write_polylines(&mut s, &drawing.visible);
    s.push_str("</g>\n</svg>\n");
    s
}

fn write_text(path: &Path, doc: &str) -> Result<()> {
    write_atomic(path, |w| {
        w.write_all(doc.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

/// Writes [`regions_svg`] to `path` atomically.
pub fn write_regions_svg(
    scene: &ScreenScene,
    map: &RegionMap,
    options: &VectorOptions,
    path: &Path,
) -> Result<()> {
    write_text(path, &regions_svg(scene, map, options))
}

/// Writes [`lines_svg`] to `path` atomically.
pub fn write_lines_svg(
    scene: &ScreenScene,
    drawing: &LineDrawing,
    options: &VectorOptions,
    path: &Path,
) -> Result<()> {
    write_text(path, &lines_svg(scene, drawing, options))
}
