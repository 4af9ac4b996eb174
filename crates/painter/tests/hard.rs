//! The painter's hard cases: exactly symmetric cycles (pinwheels of bars
//! on a lattice, whose cut lines of different planes coincide on screen
//! and run through pixel centres) and tiny near planes (every depth
//! difference of the scene squeezed into the last bits of window depth).
//! The Newell painter must equal the oracle's ray cast on every pixel that
//! is not a tie, whatever the symmetry, scale or near plane.

use glam::DVec3;
use hider_geom::{Camera, Projection};
use hider_oracle::DEFAULT_TIE_TOLERANCE;
use hider_painter::{NaivePainter, Painter};
use hider_scene::{Frame, Hider, Material, Mesh, Scene, ScreenScene, procedural};
use hider_testkit::reference;

/// Rounds `v` to the lattice of step `2^-bits` (halves away from zero, so
/// that rounding commutes with the sign changes of a half or quarter
/// turn).
fn snap(v: f64, bits: u32) -> f64 {
    let scale = f64::from(1u32 << bits);
    (v * scale).round() / scale
}

/// `order` bars in a pinwheel about the z axis, each passing over the next
/// (high at its base, low at its tip): a cycle no depth order resolves.
/// Bar 0 is a parallelogram of lattice points (step `2^-bits`); bar `k` is
/// bar 0 turned by `k / order` of a turn and snapped again, so orders 2
/// and 4 are exactly symmetric. With `mirrored` the mirror image about
/// `x = 0` is added, whose bars pierce the first hand's.
fn pinwheel(order: u32, mirrored: bool, bits: u32, phase: f64, width: f64) -> Scene {
    let n = f64::from(order);
    let corner = |k: f64| {
        let a = std::f64::consts::TAU * k / n + phase;
        DVec3::new(4.0 * a.cos(), 4.0 * a.sin(), 0.0)
    };
    let along = corner(1.0) - corner(0.0);
    let lattice = |v: DVec3| DVec3::new(snap(v.x, bits), snap(v.y, bits), v.z);
    let base = lattice(corner(0.0) - along * 0.3 + DVec3::Z);
    let tip = lattice(corner(1.0) + along * 0.3 - DVec3::Z);
    let across = lattice(DVec3::new(-along.y, along.x, 0.0).normalize() * width);
    let bar = [base + across, base - across, tip - across, tip + across];
    let mut scene = Scene::default();
    for mirror in [false, true].into_iter().take(1 + usize::from(mirrored)) {
        for k in 0..order {
            let (s, c) = (std::f64::consts::TAU * f64::from(k) / n).sin_cos();
            let positions = bar
                .iter()
                .map(|v| {
                    let x = snap(v.x * c - v.y * s, bits);
                    let y = snap(v.x * s + v.y * c, bits);
                    DVec3::new(if mirror { -x } else { x }, y, v.z)
                })
                .collect();
            let indices = if mirror {
                vec![[0, 2, 1], [0, 3, 2]]
            } else {
                vec![[0, 1, 2], [0, 2, 3]]
            };
            scene.push_mesh(
                Mesh {
                    positions,
                    indices,
                    ..Mesh::default()
                },
                Some(Material::default()),
            );
        }
    }
    scene
}

/// Looking down the z axis from `z = 14` at the origin, near plane
/// `near`, far plane 100.
fn axis_camera(near: f64) -> Camera {
    Camera::perspective(DVec3::new(0.0, 0.0, 14.0), DVec3::ZERO, near, 100.0)
}

/// The scene's fit camera with its near plane moved to `near` (what the
/// command line's `--near` does).
fn fit_camera_with_near(scene: &Scene, near: f64) -> Camera {
    let mut camera = hider_scene::fit_camera(scene);
    if let Projection::Perspective { near: n, .. } = &mut camera.projection {
        *n = near;
    }
    camera
}

fn render<H: Hider>(h: &mut H, s: &ScreenScene) -> Frame {
    let mut f = Frame::new(s.viewport.width, s.viewport.height).unwrap();
    h.render(s, &mut f).unwrap();
    f
}

/// Wrong ids off ties of the Newell painter and of the naive one against
/// the oracle's ray cast, and the covered pixel count.
fn wrong_pixels(s: &ScreenScene) -> (u64, u64, u64) {
    let oracle = reference::ray_cast(s);
    let frame = render(&mut Painter::default(), s);
    let newell = oracle.compare_strict(&frame.ids, DEFAULT_TIE_TOLERANCE);
    assert_eq!(newell.coverage_mismatches, 0, "{newell}");
    let naive = render(&mut NaivePainter::default(), s);
    let naive = oracle.compare_strict(&naive.ids, DEFAULT_TIE_TOLERANCE);
    (
        newell.wrong_ids,
        naive.wrong_ids,
        frame.covered_count() as u64,
    )
}

/// Near planes from `1e-7` down to `1e-12`.
const TINY_NEARS: [f64; 6] = [1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];

/// Renders `what` behind each of `nears` (`screen_at` makes the screen
/// scene for a near plane) and adds a failure for each with wrong pixels.
fn check_near_planes(
    what: &str,
    nears: &[f64],
    screen_at: impl Fn(f64) -> ScreenScene,
    failures: &mut Vec<String>,
) {
    for &near in nears {
        let (wrong, naive, covered) = wrong_pixels(&screen_at(near));
        if wrong > 0 {
            failures.push(format!(
                "{what}, near {near}: {wrong} wrong of {covered} (naive {naive})"
            ));
        }
    }
}

/// Where the first corner of the pinwheel's polygon sits: on the y axis
/// (bars along diagonals for order 4, cut lines along the axes) or at 45
/// degrees (bars along the axes, cut lines along pixel-centre diagonals).
const PHASES: [f64; 3] = [
    std::f64::consts::FRAC_PI_2,
    std::f64::consts::FRAC_PI_4,
    0.0,
];

#[test]
fn exactly_symmetric_pinwheels_are_exact_off_ties() {
    let mut failures = Vec::new();
    for order in 2..=6 {
        for mirrored in [false, true] {
            for (bits, phase) in [0, 2, 8].into_iter().flat_map(|b| PHASES.map(|p| (b, p))) {
                for (width, size) in [0.6, 1.0]
                    .into_iter()
                    .flat_map(|w| [64, 128, 256].map(|s| (w, s)))
                {
                    let scene = pinwheel(order, mirrored, bits, phase, width);
                    let s = hider_testkit::screen_with(&scene, axis_camera(0.1), size, size);
                    let (wrong, _, covered) = wrong_pixels(&s);
                    if wrong > 0 {
                        failures.push(format!(
                            "order {order} mirrored {mirrored} bits {bits} phase {phase} width {width} at {size}: \
                             {wrong} wrong of {covered}"
                        ));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn tiny_near_planes_do_not_confuse_the_plane_tests() {
    let mut failures = Vec::new();
    let intersecting = procedural::intersecting_pair();
    check_near_planes(
        "intersecting pair",
        &[1e-8, 1e-9, 1e-12],
        |near| {
            let camera = fit_camera_with_near(&intersecting, near);
            hider_testkit::screen_with(&intersecting, camera, 128, 128)
        },
        &mut failures,
    );
    let cycle = pinwheel(3, false, 8, std::f64::consts::FRAC_PI_2, 0.6);
    check_near_planes(
        "bar cycle",
        &TINY_NEARS,
        |near| hider_testkit::screen_with(&cycle, axis_camera(near), 128, 128),
        &mut failures,
    );
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The shared hard-case families of `hider-testkit`: its pinwheels (order
/// 2 to 6, one or both hands, integer and dyadic lattices) and its cycle
/// of three bars behind near planes from `1e-7` down to `1e-12`.
#[test]
fn the_testkit_symmetric_families_are_exact_off_ties() {
    use hider_testkit::hard_cases::{bar_cycle, pinwheel, pinwheel_camera};
    let mut failures = Vec::new();
    for order in 2..=6 {
        for mirrored in [false, true] {
            for bits in [0, 3, 8] {
                let scene = pinwheel(order, mirrored, bits);
                for size in [64, 256] {
                    let camera = pinwheel_camera(0.1);
                    let s = hider_testkit::screen_with(&scene, camera, size, size);
                    let (wrong, _, covered) = wrong_pixels(&s);
                    if wrong > 0 {
                        failures.push(format!(
                            "pinwheel {order} mirrored {mirrored} bits {bits} at {size}: \
                             {wrong} wrong of {covered}"
                        ));
                    }
                }
            }
        }
    }
    check_near_planes(
        "bar cycle",
        &TINY_NEARS,
        |near| hider_testkit::screen(&bar_cycle(near), 128, 128),
        &mut failures,
    );
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Many tiny triangles over one pixel centre: each covers that centre
/// only, so they are ordered on it, with no split and a bounded number of
/// comparisons per triangle (the polygon tests compared every pair whose
/// depth ranges overlapped and split every pair crossing between centres:
/// the split budget ran out at ten thousand). Time is measured by the
/// `pile` example, not here.
#[test]
fn a_pile_over_one_pixel_costs_a_bounded_number_of_comparisons_per_triangle() {
    let n = 20_000;
    let s = hider_testkit::screen(&hider_testkit::hard_cases::one_pixel_pile(n, 5), 64, 64);
    let mut painter = Painter::default();
    let mut frame = Frame::new(64, 64).unwrap();
    let stats = painter.render(&s, &mut frame).unwrap();
    assert_eq!(stats.splits, 0, "{stats:?}");
    assert_eq!(stats.pieces_out, u64::from(n));
    let log_n = f64::from(n).log2();
    assert!(
        (stats.comparisons as f64) < 4.0 * f64::from(n) * log_n,
        "{} comparisons for {n} triangles",
        stats.comparisons
    );
    let reference = reference::pixel_centre(&s);
    assert_eq!(frame.ids, reference.ids);
}

/// Every hard case of `hider-testkit`, at several seeds and sizes: the
/// painter equals the oracle's ray cast off ties, by relative gap alone
/// (the strict standard: no excuse for what an `f32` depth cannot order).
#[test]
fn every_testkit_hard_case_is_exact_off_ties() {
    let mut failures = Vec::new();
    for seed in 0..8 {
        for (name, scene) in hider_testkit::hard_cases::all(seed) {
            for size in [48, 96, 160] {
                let s = hider_testkit::screen(&scene, size, size);
                let mut painter = Painter::default();
                let mut frame = Frame::new(size, size).unwrap();
                if let Err(e) = painter.render(&s, &mut frame) {
                    failures.push(format!("{name} seed {seed} at {size}: {e}"));
                    continue;
                }
                let agreement =
                    reference::ray_cast(&s).compare_strict(&frame.ids, DEFAULT_TIE_TOLERANCE);
                if !agreement.is_exact() {
                    failures.push(format!("{name} seed {seed} at {size}: {agreement}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Pixels whose id differs from the ray cast's although the two nearest
/// surfaces are at least the tie tolerance apart (relative gap) *and* the
/// front end's window depths tell them apart by more than a few units in
/// the last place. Behind a near plane of `1e-12` a relative gap of `1e-4`
/// can be no window-depth gap at all: no window-space hider (the
/// z-buffer on the same planes included) can see it, so it is a tie here.
fn wrong_where_window_depth_resolves(oracle: &hider_oracle::Reference, ids: &[u32]) -> u64 {
    let resolved = 8.0 * f64::EPSILON;
    let mut wrong = 0;
    for (k, (&want, &got)) in oracle.ids.iter().zip(ids).enumerate() {
        let tie = oracle.gap[k] < DEFAULT_TIE_TOLERANCE || oracle.window_gap[k] <= resolved;
        if (want == hider_scene::NO_ID) != (got == hider_scene::NO_ID) || (want != got && !tie) {
            wrong += 1;
        }
    }
    wrong
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
    /// Piles of large random triangles (many intersections and cycles)
    /// behind near planes from `1e-1` down to `1e-12`: exact off ties by
    /// relative gap, whatever squeezes the window depths.
    #[test]
    fn piles_behind_any_near_plane_are_exact_off_ties(
        n in 2u32..40, seed in 0u64..1000, near_exponent in 1i32..=12,
    ) {
        let scene = hider_testkit::hard_cases::heavy_overdraw(n, seed);
        let camera = fit_camera_with_near(&scene, 10f64.powi(-near_exponent));
        let s = hider_testkit::screen_with(&scene, camera, 48, 48);
        let frame = render(&mut Painter::default(), &s);
        let wrong = wrong_where_window_depth_resolves(&reference::ray_cast(&s), &frame.ids);
        proptest::prop_assert_eq!(wrong, 0);
    }
}
