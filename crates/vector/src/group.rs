//! Face groups: coplanar primitives of one material and one fill colour,
//! merged into one path so that no seam can appear inside a flat face.

use std::collections::HashMap;

use hider_scene::shade::{prim_color, to_srgb8};
use hider_scene::{ScreenScene, ShadeMode};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;

use crate::regions::{FaceGroup, PrimRegion};
use crate::splitter::list_overlay;

/// The key that puts coplanar primitives of one colour together: the fill
/// colour and opacity as written, and the camera-space plane quantised,
/// its offset relative to `scale` (one length for the whole scene: a
/// per-triangle scale would give each triangle of one plane its own key).
fn group_key(
    scene: &ScreenScene,
    prim: u32,
    mode: ShadeMode,
    scale: f64,
) -> (String, u32, [i64; 4]) {
    let (rgb, a) = prim_color(scene, prim, mode);
    let fill = format!(
        "#{:02x}{:02x}{:02x}",
        to_srgb8(rgb[0]),
        to_srgb8(rgb[1]),
        to_srgb8(rgb[2])
    );
    let c = scene.prims[prim as usize].camera;
    let n = (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero();
    // About six significant digits: triangles of one flat face agree far
    // closer than that, distinct faces differ far more.
    let q = |v: f64| (v * 1e6).round() as i64;
    let key = [q(n.x), q(n.y), q(n.z), q(n.dot(c[0]) / scale)];
    (fill, a.to_bits(), key)
}

/// Assigns every region a face group and builds the groups' paths.
pub(crate) fn group_regions(
    scene: &ScreenScene,
    prims: &mut [PrimRegion],
    mode: ShadeMode,
    merge: bool,
) -> Vec<FaceGroup> {
    let mut index: HashMap<(String, u32, [i64; 4]), u32> = HashMap::new();
    let mut groups: Vec<FaceGroup> = Vec::new();
    let scale = prims
        .iter()
        .flat_map(|r| scene.prims[r.prim as usize].camera)
        .map(|p| p.abs().max_element())
        .fold(1e-300, f64::max);
    for (k, region) in prims.iter_mut().enumerate() {
        let key = if merge {
            group_key(scene, region.prim, mode, scale)
        } else {
            (String::new(), k as u32, [0; 4])
        };
        let next = groups.len() as u32;
        let g = *index.entry(key).or_insert(next);
        if g == next {
            let (rgb, a) = prim_color(scene, region.prim, mode);
            let fill = format!(
                "#{:02x}{:02x}{:02x}",
                to_srgb8(rgb[0]),
                to_srgb8(rgb[1]),
                to_srgb8(rgb[2])
            );
            groups.push(FaceGroup {
                prims: Vec::new(),
                fill,
                opacity: a,
                shapes: Vec::new(),
            });
        }
        region.group = g;
        groups[g as usize].prims.push(region.prim);
        groups[g as usize]
            .shapes
            .extend(region.shapes.iter().cloned());
    }
    for group in &mut groups {
        if group.prims.len() > 1 || group.shapes.len() > 1 {
            let points = group.shapes.iter().flatten().map(Vec::len).sum();
            let mut overlay = list_overlay(points);
            for shape in &group.shapes {
                overlay.add_contours(shape, ShapeType::Subject);
            }
            group.shapes = overlay.overlay(OverlayRule::Subject, FillRule::NonZero);
        }
    }
    groups
}
