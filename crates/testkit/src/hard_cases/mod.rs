//! Hard cases: scenes built to break hidden-surface algorithms.
//!
//! Each generator is parameterised and deterministic (same arguments, same
//! scene, bit for bit) and returns a [`Scene`], with its own camera when the
//! fit camera would not show the difficulty. [`all`] lists one modest
//! instance of each by name, for the cross-validation suite and the
//! benchmark; [`closed_meshes`] lists the closed, consistently oriented
//! meshes the watertightness checks use.
//!
//! | case | what breaks |
//! |---|---|
//! | [`intersecting_pairs`], [`interpenetrating_boxes`] | any per-triangle depth order (painter's without splitting) |
//! | [`coplanar_overlaps`] | z-fighting: every overlap is a depth tie |
//! | [`near_coplanar_far`] | depth-buffer precision far from the camera |
//! | [`parallel_layers`] | layers `1e-4` to `1e-9` apart under telephoto, ordinary and tight depth ranges: ties that are not ties |
//! | [`slivers`], [`near_degenerate_fan`] | area near zero, ill-conditioned planes |
//! | [`fan`], [`bipyramid`], [`torus`] (and `procedural::{cube, uv_sphere}`) | cracks and double hits on shared edges and vertices |
//! | [`near_plane_crossing`] | near-plane clipping, geometry behind the eye |
//! | [`huge_depth_range`] | `near = 1e-3`, `far = 1e6`: window-depth resolution |
//! | [`huge_coordinates`] | `1e7` world coordinates with unit-size triangles |
//! | [`cyclic_overlap`] | no depth order exists at all |
//! | [`heavy_overdraw`], `procedural::random_soup` | many layers per pixel, random interpenetration |
//! | [`pinwheel`], [`bar_cycle`] | exactly symmetric cycles on a lattice: cut lines of different planes coincide on screen; tiny near planes |
//! | [`far_plane_triangle`] | window depth exactly 1, the depth buffer's clear value |
//! | [`one_pixel_pile`] | depth complexity `N` at one pixel: anything quadratic in it |
//! | [`repeated_polygon`] | hundreds of exactly coincident copies of one face |
//! | [`offset_sphere`] | a small object far from the origin (offsets up to `1e17`) |

mod degenerate;
mod extreme;
mod ordering;
mod precision;
mod shared_edges;
mod support;
pub(crate) mod symmetric;
#[cfg(test)]
mod tests;

use hider_scene::Scene;
use hider_scene::procedural;

pub use crate::cameras::{
    ONE_PIXEL_CENTRE, far_plane_camera, look_at, one_pixel_camera, pinwheel_camera,
};
pub use degenerate::{near_degenerate_fan, slivers};
pub use extreme::{far_plane_triangle, offset_sphere, one_pixel_pile, repeated_polygon};
pub use ordering::{cyclic_overlap, heavy_overdraw, interpenetrating_boxes, intersecting_pairs};
pub use precision::{
    coplanar_overlaps, huge_coordinates, huge_depth_range, near_coplanar_far, near_plane_crossing,
    parallel_layers,
};
pub use shared_edges::{bipyramid, fan, torus};
pub use symmetric::{bar_cycle, pinwheel};

/// One modest instance of every hard case, by name, derived from `seed`:
/// small enough that the exact oracle and every hider run on all of them in
/// well under a second at 64 x 64.
pub fn all(seed: u64) -> Vec<(&'static str, Scene)> {
    let s = |k: u64| seed.wrapping_mul(0x9e37_79b9_7f4a_7c15).wrapping_add(k);
    vec![
        ("intersecting_pairs", intersecting_pairs(6, s(1))),
        ("interpenetrating_boxes", interpenetrating_boxes(4, s(2))),
        ("coplanar_overlaps", coplanar_overlaps(6, s(3))),
        (
            "near_coplanar_far",
            near_coplanar_far(4, 1000.0, 1e-3, s(4)),
        ),
        ("slivers", slivers(40, s(5))),
        ("near_degenerate_fan", near_degenerate_fan(48, s(6))),
        ("fan", fan(24, s(7))),
        ("bipyramid", bipyramid(16, s(8))),
        ("cube", procedural::cube()),
        ("uv_sphere", procedural::uv_sphere(12)),
        ("torus", torus(16, 8, 1.0, 0.35)),
        ("near_plane_crossing", near_plane_crossing(30, s(9))),
        ("huge_depth_range", huge_depth_range(24, 30.0, s(10))),
        ("huge_coordinates", huge_coordinates(30, s(11), 1e7)),
        ("cyclic_overlap", cyclic_overlap(5)),
        ("cyclic_triple", procedural::cyclic_triple()),
        ("random_soup", procedural::random_soup(200, s(12))),
        ("heavy_overdraw", heavy_overdraw(100, s(13))),
        ("pinwheel_4", pinwheel(4, false, 0)),
        ("pinwheel_3_mirrored", pinwheel(3, true, 8)),
        ("pinwheel_6", pinwheel(6, false, 4)),
        ("bar_cycle_near_1e-9", bar_cycle(1e-9)),
        ("far_plane_triangle", far_plane_triangle()),
        ("one_pixel_pile", one_pixel_pile(200, s(14))),
        ("repeated_polygon", repeated_polygon(20)),
        ("offset_sphere", offset_sphere(12, 1e6)),
        (
            "telephoto_layers",
            parallel_layers(4, 1e4, 5e-6, (9990.0, 10010.0), 30.0, s(15)),
        ),
        (
            "tight_range_layers_1e-7",
            parallel_layers(3, 100.0, 1e-7, (99.9, 100.1), 20.0, s(16)),
        ),
        (
            "layers_1e-4",
            parallel_layers(3, 12.7, 1e-4, (6.35, 31.8), 45.0, s(17)),
        ),
        (
            "layers_1e-6",
            parallel_layers(3, 12.7, 1e-6, (6.35, 31.8), 45.0, s(18)),
        ),
        (
            "layers_1e-9",
            parallel_layers(3, 12.7, 1e-9, (6.35, 31.8), 45.0, s(19)),
        ),
    ]
}

/// The closed, consistently outward-wound meshes among the hard cases
/// (every edge shared by exactly two triangles with opposite directions),
/// by name: what watertightness checks need. Convex ones are marked `true`
/// (each pixel inside the silhouette meets exactly one front and one back
/// face).
pub fn closed_meshes(seed: u64) -> Vec<(&'static str, Scene, bool)> {
    vec![
        ("cube", procedural::cube(), true),
        ("uv_sphere", procedural::uv_sphere(16), true),
        ("bipyramid", bipyramid(20, seed), false),
        ("torus", torus(20, 10, 1.0, 0.4), false),
        ("box", interpenetrating_boxes(1, seed), true),
    ]
}
