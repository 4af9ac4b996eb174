//! Face groups: coplanar primitives of one material and one fill colour,
//! merged into one path so that no seam can appear inside a flat face.

use std::collections::HashMap;

use hider_scene::shade::{prim_color, to_srgb8};
use hider_scene::{ScreenScene, ShadeMode};
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;

use crate::grid::Grid;
use crate::parts::{BooleanWork, overlay_by_parts};
use crate::regions::{FaceGroup, PrimRegion};

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

/// A group key with its fill interned: `(fill, opacity bits, plane)`.
type Key = (u32, u32, [i64; 4]);

/// The face group of each key, numbered by first appearance: keys equal,
/// or neighbours (the same fill and opacity, each plane component within
/// one quantum), are one group, transitively. Quantising alone puts two
/// faces of one plane whose components fall on either side of a rounding
/// boundary in two groups, and a seam between them.
fn merge_neighbours(keys: &[Key]) -> Vec<u32> {
    let mut first: HashMap<Key, usize> = HashMap::new();
    let distinct: Vec<Key> = keys
        .iter()
        .filter(|&&k| {
            let next = first.len();
            *first.entry(k).or_insert(next) == next
        })
        .copied()
        .collect();
    // Union-find over the distinct keys, the lower index the root.
    let mut parent: Vec<usize> = (0..distinct.len()).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    for (k, &(fill, alpha, plane)) in distinct.iter().enumerate() {
        for step in 0..81 {
            let mut near = plane;
            let mut code = step;
            for component in &mut near {
                *component += code % 3 - 1;
                code /= 3;
            }
            if let Some(&j) = first.get(&(fill, alpha, near)) {
                let (a, b) = (root(&mut parent, k), root(&mut parent, j));
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let mut number = vec![u32::MAX; distinct.len()];
    let mut groups = 0;
    keys.iter()
        .map(|k| {
            let r = root(&mut parent, first[k]);
            if number[r] == u32::MAX {
                number[r] = groups;
                groups += 1;
            }
            number[r]
        })
        .collect()
}

/// Assigns every region a face group and builds the groups' paths (a
/// group's union one boolean per part of its regions, see `parts.rs`).
pub(crate) fn group_regions(
    scene: &ScreenScene,
    grid: &Grid,
    prims: &mut [PrimRegion],
    mode: ShadeMode,
    merge: bool,
    work: &mut BooleanWork,
) -> Vec<FaceGroup> {
    let mut fills: HashMap<String, u32> = HashMap::new();
    let mut groups: Vec<FaceGroup> = Vec::new();
    let scale = prims
        .iter()
        .flat_map(|r| scene.prims[r.prim as usize].camera)
        .map(|p| p.abs().max_element())
        .fold(1e-300, f64::max);
    let keys: Vec<Key> = prims
        .iter()
        .enumerate()
        .map(|(k, region)| {
            if merge {
                let (fill, alpha, plane) = group_key(scene, region.prim, mode, scale);
                let next = fills.len() as u32;
                (*fills.entry(fill).or_insert(next), alpha, plane)
            } else {
                (0, k as u32, [0; 4])
            }
        })
        .collect();
    let numbers = if merge {
        merge_neighbours(&keys)
    } else {
        (0..prims.len() as u32).collect()
    };
    for (region, g) in prims.iter_mut().zip(numbers) {
        if g as usize == groups.len() {
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
            let shapes: Vec<_> = group
                .shapes
                .iter()
                .map(|s| (s.as_slice(), ShapeType::Subject))
                .collect();
            group.shapes = overlay_by_parts(grid, &shapes, OverlayRule::Subject, work);
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_one_quantum_apart_are_one_group() {
        let plane = |d: i64| [0, 0, 1_000_000, d];
        let keys = [
            (0, 0, plane(499_999)),
            (0, 0, plane(500_000)),
            // Two quanta from the first, one from the second: chained.
            (0, 0, plane(500_001)),
            // Three from the last: another plane.
            (0, 0, plane(500_004)),
            // Another colour, one quantum off: another group.
            (1, 0, plane(500_000)),
            (0, 0, [1, -1, 999_999, 500_000]),
        ];
        assert_eq!(merge_neighbours(&keys), vec![0, 0, 0, 1, 2, 0]);
    }
}
