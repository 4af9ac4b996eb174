//! The SVG documents: the regions as one `<path>` per face group, the
//! drawings as `<polyline>`s, both layered for editors and plotters.
//!
//! Coordinates are pixels (y down), absolute, with
//! [`VectorOptions::decimals`] decimals: no transform to undo in an
//! editor, and a corner shared by two paths is rounded the same way in
//! both, so rounding opens no gap between regions. Layers are `<g>`s with
//! Inkscape's `inkscape:groupmode="layer"` and a label, one per object
//! group (regions), or one per line kind holding one per object group
//! (lines).

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use hider_scene::atomic::write_atomic;
use hider_scene::{Error, Result, ScreenScene};
use i_overlay::i_float::int::point::IntPoint;

use crate::VectorOptions;
use crate::document::{SvgInfo, escape};
use crate::lines::{LineDrawing, LineKind, Polyline};
use crate::regions::RegionMap;
use crate::splitter::IntShapes;

/// `v` with at most `decimals` decimals, trailing zeros trimmed.
fn number(s: &mut String, v: f64, decimals: u32) {
    let scale = 10f64.powi(decimals as i32);
    let r = (v * scale).round() / scale;
    // -0 prints as "-0".
    let r = if r == 0.0 { 0.0 } else { r };
    let start = s.len();
    let _ = write!(s, "{r:.*}", decimals as usize);
    if s[start..].contains('.') {
        let trimmed = s[start..].trim_end_matches('0').trim_end_matches('.').len();
        s.truncate(start + trimmed);
    }
}

fn header(scene: &ScreenScene, options: &VectorOptions, info: &SvgInfo) -> String {
    let (w, h) = (scene.viewport.width, scene.viewport.height);
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let size = match options.page_mm {
        Some((pw, ph)) => format!(r#"width="{pw}mm" height="{ph}mm""#),
        None => format!(r#"width="{w}" height="{h}""#),
    };
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" {size} viewBox="0 0 {w} {h}">"#
    );
    if !info.title.is_empty() {
        let _ = writeln!(s, "<title>{}</title>", escape(&info.title));
    }
    if !info.description.is_empty() {
        let _ = writeln!(s, "<desc>{}</desc>", escape(&info.description));
    }
    if let Some(bg) = &options.background {
        let _ = writeln!(
            s,
            r#"<rect id="background" width="{w}" height="{h}" fill="{}"/>"#,
            escape(bg)
        );
    }
    s
}

/// Path data of integer polygons in pixels: `M x y L x y ... Z` per
/// contour, absolute.
fn path_data(s: &mut String, shapes: &IntShapes, map: &RegionMap, decimals: u32) {
    let point = |s: &mut String, p: IntPoint| {
        let (x, y) = map.grid.to_pixels(p);
        number(s, x, decimals);
        s.push(' ');
        number(s, y, decimals);
    };
    for contour in shapes.iter().flatten() {
        let Some(first) = contour.first() else {
            continue;
        };
        s.push('M');
        point(s, *first);
        for (k, p) in contour.iter().enumerate().skip(1) {
            s.push_str(if k == 1 { "L" } else { " " });
            point(s, *p);
        }
        s.push('Z');
    }
}

/// The regions SVG with `info`'s title, description and object layers:
/// one path per face group (`data-prim`: its first primitive), in the
/// layer of its first primitive's object, the layers clipped to the
/// covered set and stroked against seams when
/// [`VectorOptions::seam_stroke`] is above 0.
pub fn regions_document(
    scene: &ScreenScene,
    map: &RegionMap,
    options: &VectorOptions,
    info: &SvgInfo,
) -> String {
    let mut s = header(scene, options, info);
    let d = options.decimals;
    let seams = options.seam_stroke > 0.0;
    if seams {
        s.push_str(r#"<defs><clipPath id="covered"><path clip-rule="evenodd" d=""#);
        path_data(&mut s, &map.covered, map, d);
        s.push_str("\"/></clipPath></defs>\n");
        let _ = writeln!(
            s,
            r#"<g id="regions" clip-path="url(#covered)" fill-rule="evenodd" stroke-width="{}" stroke-linejoin="round">"#,
            options.seam_stroke
        );
    } else {
        s.push_str("<g id=\"regions\" stroke=\"none\" fill-rule=\"evenodd\">\n");
    }
    // Groups in layer order; within a layer in the map's order (ascending
    // first primitive), so a file is the same run to run.
    let mut order: Vec<(u32, usize)> = map
        .groups
        .iter()
        .enumerate()
        .map(|(k, g)| (info.groups.group_of(g.prims[0]), k))
        .collect();
    order.sort_unstable();
    for layer in order.chunk_by(|a, b| a.0 == b.0) {
        let object = layer[0].0;
        let _ = writeln!(
            s,
            r#"<g id="{}" inkscape:groupmode="layer" inkscape:label="{}">"#,
            info.groups.id("regions", object),
            escape(info.groups.name(object))
        );
        for &(_, k) in layer {
            let group = &map.groups[k];
            let _ = write!(s, r#"<path data-prim="{}" d=""#, group.prims[0]);
            path_data(&mut s, &group.shapes, map, d);
            let _ = write!(s, r#"" fill="{}""#, group.fill);
            if group.opacity < 1.0 {
                let _ = write!(s, r#" fill-opacity="{}""#, group.opacity);
            }
            // A translucent path is not stroked: its stroke would lie
            // over its own fill and its neighbour's, blending twice there.
            if seams && group.opacity >= 1.0 {
                let _ = write!(s, r#" stroke="{}""#, group.fill);
            }
            s.push_str("/>\n");
        }
        s.push_str("</g>\n");
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// [`regions_document`] without title, description or object layers
/// (one layer, `scene`).
pub fn regions_svg(scene: &ScreenScene, map: &RegionMap, options: &VectorOptions) -> String {
    regions_document(scene, map, options, &SvgInfo::default())
}

/// The layer name of a line kind.
pub fn kind_name(kind: LineKind) -> &'static str {
    match kind {
        LineKind::Silhouette => "silhouette",
        LineKind::Boundary => "boundary",
        LineKind::Crease => "crease",
        LineKind::Material => "material",
        LineKind::Intersection => "intersection",
    }
}

fn stroke_colour(kind: LineKind) -> &'static str {
    match kind {
        LineKind::Intersection => "#b03030",
        _ => "#000000",
    }
}

/// Writes `lines` (in plotting order, each object group contiguous) as
/// one layer per object group under `prefix`, its polylines in groups of
/// one line kind (`class` and id suffix the kind's name, numbered: the
/// plotting order may come back to a kind within an object).
fn write_layers(
    s: &mut String,
    lines: &[Polyline],
    prefix: &str,
    info: &SvgInfo,
    decimals: u32,
    hidden: bool,
) {
    for group_run in lines.chunk_by(|a, b| a.group == b.group) {
        let g = group_run[0].group;
        let id = info.groups.id(prefix, g);
        let _ = writeln!(
            s,
            r#"<g id="{id}" inkscape:groupmode="layer" inkscape:label="{}">"#,
            escape(info.groups.name(g))
        );
        let mut seen = [0u32; 5];
        for kind_run in group_run.chunk_by(|a, b| a.kind == b.kind) {
            let kind = kind_run[0].kind;
            let name = kind_name(kind);
            let n = &mut seen[kind as usize];
            *n += 1;
            let colour = if hidden {
                "#808080"
            } else {
                stroke_colour(kind)
            };
            let _ = writeln!(
                s,
                r#"<g id="{id}-{name}-{n}" class="{name}" stroke="{colour}">"#
            );
            for line in kind_run {
                s.push_str(r#"<polyline points=""#);
                for (k, &(x, y)) in line.points.iter().enumerate() {
                    if k > 0 {
                        s.push(' ');
                    }
                    number(s, x, decimals);
                    s.push(',');
                    number(s, y, decimals);
                }
                s.push_str("\"/>\n");
            }
            s.push_str("</g>\n");
        }
        s.push_str("</g>\n");
    }
}

/// The hidden-line SVG with `info`'s title, description and object
/// groups: one Inkscape layer per object group (id `lines-<index>-<name>`),
/// its polylines in groups per line kind (`class` `silhouette`, `crease`,
/// `boundary`, `material` or `intersection`, intersections in red), in the
/// drawing's (plotting) order; the hidden parts, when the drawing has
/// them, in the same structure under `hidden-...`, dashed and grey, after
/// the visible ones.
pub fn lines_document(
    scene: &ScreenScene,
    drawing: &LineDrawing,
    options: &VectorOptions,
    info: &SvgInfo,
) -> String {
    let mut s = header(scene, options, info);
    let w = options.stroke_width;
    let _ = writeln!(
        s,
        r#"<g id="lines" fill="none" stroke-width="{w}" stroke-linecap="round" stroke-linejoin="round">"#
    );
    write_layers(
        &mut s,
        &drawing.visible,
        "lines",
        info,
        options.decimals,
        false,
    );
    s.push_str("</g>\n");
    if !drawing.hidden.is_empty() {
        let _ = writeln!(
            s,
            r#"<g id="hidden" fill="none" stroke-width="{}" stroke-dasharray="{} {}" stroke-linecap="round">"#,
            w * 0.5,
            w * 3.0,
            w * 2.0
        );
        write_layers(
            &mut s,
            &drawing.hidden,
            "hidden",
            info,
            options.decimals,
            true,
        );
        s.push_str("</g>\n");
    }
    s.push_str("</svg>\n");
    s
}

/// [`lines_document`] without title, description or object layers.
pub fn lines_svg(scene: &ScreenScene, drawing: &LineDrawing, options: &VectorOptions) -> String {
    lines_document(scene, drawing, options, &SvgInfo::default())
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

/// Writes an SVG document (from [`regions_document`] or
/// [`lines_document`]) to `path` atomically.
pub fn write_document(path: &Path, document: &str) -> Result<()> {
    write_text(path, document)
}
