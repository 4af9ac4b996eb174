use super::*;
use crate::model::Mesh;
use glam::DVec3;
use hider_geom::fixed::{FixedPt, pixel_center};
use hider_geom::{Camera, orient2d};

fn camera() -> Camera {
    Camera::perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 1.0, 100.0)
}

fn one(positions: [DVec3; 3]) -> Scene {
    let mut s = Scene::default();
    s.push_mesh(
        Mesh {
            positions: positions.to_vec(),
            indices: vec![[0, 1, 2]],
            ..Mesh::default()
        },
        None,
    );
    s
}

/// A triangle around the centre of the view, counter-clockwise as the
/// camera sees it: front-facing.
const FACING: [DVec3; 3] = [
    DVec3::new(-1.0, -1.0, 0.0),
    DVec3::new(1.0, -1.0, 0.0),
    DVec3::new(0.0, 1.0, 0.0),
];

fn run(s: &Scene) -> ScreenScene {
    let view = View::new(camera(), 64, 64).unwrap();
    prepare(s, &view, &PrepareOptions::default()).unwrap()
}

#[test]
fn counter_clockwise_triangle_is_front_facing_and_reoriented() {
    let ss = run(&one(FACING));
    assert_eq!(ss.tris.len(), 1);
    let t = ss.tris[0];
    assert!(t.front_facing);
    assert!(orient2d(t.v[0], t.v[1], t.v[2]) > 0);
    // At distance 5 all three corners have w = 5 and the same depth.
    assert!(t.w.iter().all(|w| (w - 5.0).abs() < 1e-12));
    assert!((t.depth.dx).abs() < 1e-15 && t.depth.dy.abs() < 1e-15);
    // The same corners clockwise: a back face.
    let [a, b, c] = FACING;
    let culled = prepare(
        &one([a, c, b]),
        &View::new(camera(), 64, 64).unwrap(),
        &PrepareOptions::default().with_cull_back_faces(true),
    )
    .unwrap();
    assert_eq!(culled.tris.len(), 0);
    assert_eq!(culled.stats.back_faces, 1);
}

#[test]
fn triangle_crossing_near_plane_is_clipped_and_depth_stays_in_range() {
    // From z = 0 (5 in front of the eye) to z = 10 (5 behind it).
    let s = one([
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, -0.5, 10.0),
    ]);
    let ss = run(&s);
    assert_eq!(ss.stats.clipped, 1);
    assert!(!ss.tris.is_empty());
    for t in &ss.tris {
        assert!(
            t.z.iter().all(|z| (-1e-9..=1.0 + 1e-9).contains(z)),
            "{:?}",
            t.z
        );
        assert!(t.w.iter().all(|w| *w > 0.0));
    }
}

#[test]
fn triangle_behind_the_eye_disappears() {
    let s = one([
        DVec3::new(-1.0, 0.0, 6.0),
        DVec3::new(1.0, 0.0, 6.0),
        DVec3::new(0.0, 1.0, 7.0),
    ]);
    let ss = run(&s);
    assert!(ss.tris.is_empty());
    assert_eq!(ss.stats.culled, 1);
    assert_eq!(ss.prims.len(), 1, "prim info is kept for every id");
}

#[test]
fn camera_ray_hits_the_pixel_it_came_from() {
    let ss = run(&one(FACING));
    let (o, d) = ss.camera_ray(40.5, 20.5);
    let p = o + d * 3.0;
    let clip = ss.projection_matrix * p.extend(1.0);
    let win = ss.viewport.ndc_to_window(clip.truncate() / clip.w);
    assert!((win.x - 40.5).abs() < 1e-9 && (win.y - 20.5).abs() < 1e-9);
}

#[cfg(feature = "parallel")]
#[test]
fn parallel_front_end_equals_sequential() {
    // Enough triangles (in two meshes) to take the parallel path.
    let mut scene = crate::procedural::random_soup(40_000, 3);
    let second = crate::procedural::uv_sphere(40);
    scene.push_mesh(second.meshes[0].clone(), Some(second.materials[0].clone()));
    let view = View::new(camera(), 96, 64).unwrap();
    let options = PrepareOptions::default().with_parallel(true);
    let run_with = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| prepare(&scene, &view, &options).unwrap())
    };
    let one = run_with(1);
    let two = run_with(2);
    assert!(one.tris.len() > 10_000);
    assert_eq!(one, two);
    // Reusing an output gives the same result too.
    let mut reused = run_with(2);
    prepare_into(
        &crate::procedural::cube(),
        &view,
        &PrepareOptions::default(),
        &mut reused,
    )
    .unwrap();
    prepare_into(&scene, &view, &options, &mut reused).unwrap();
    assert_eq!(one, reused);
}

#[test]
fn pixel_bounds_cover_exactly_the_candidate_centres() {
    let ss = run(&one(FACING));
    let t = ss.tris[0];
    let (x0, y0, x1, y1) = t.pixel_bounds(ss.viewport).unwrap();
    let edges = t.edges();
    let mut inside = 0;
    for j in 0..64 {
        for i in 0..64 {
            let (px, py) = (
                i64::from(pixel_center(i as i32)),
                i64::from(pixel_center(j as i32)),
            );
            if edges.iter().all(|e| e.contains(px, py)) {
                inside += 1;
                assert!((x0..=x1).contains(&i) && (y0..=y1).contains(&j));
            }
        }
    }
    assert!(inside > 0);
}

/// The UV sphere scaled by `scale` (rounded to multiples of 16, so that
/// adding a power-of-two offset near 1e17 is exact) and offset by
/// `offset` on every axis.
fn lattice_sphere(scale: f64, offset: f64) -> Scene {
    let mut s = crate::procedural::uv_sphere(24);
    for p in &mut s.meshes[0].positions {
        *p = (*p * scale / 16.0).round() * 16.0 + DVec3::splat(offset);
    }
    s
}

fn screen_of(scene: &Scene, camera: Camera) -> ScreenScene {
    let view = View::new(camera, 96, 96).unwrap();
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

/// Each triangle's id, snapped corners and window depths: what must not
/// change when the scene only moves or scales exactly.
fn snapped(s: &ScreenScene) -> Vec<(u32, [FixedPt; 3], [f64; 3])> {
    s.tris.iter().map(|t| (t.prim, t.v, t.z)).collect()
}

#[test]
fn a_scene_far_from_the_origin_renders_as_at_the_origin() {
    // 2^56 is about 7.2e16; the spacing of f64 there is 16. The view
    // matrix's translation cancelled two products near 1e17 and lost the
    // sphere's last digits; the eye-relative transform subtracts exactly.
    let offset = 2f64.powi(56);
    let far = lattice_sphere(1024.0, offset);
    let near = lattice_sphere(1024.0, 0.0);
    let camera = crate::fit_camera(&far);
    let mut moved = camera;
    moved.eye -= DVec3::splat(offset);
    moved.target -= DVec3::splat(offset);
    let (a, b) = (screen_of(&far, camera), screen_of(&near, moved));
    assert!(a.tris.len() > 500);
    assert_eq!(snapped(&a), snapped(&b));
    assert_eq!(
        a.prims.iter().map(|p| p.camera).collect::<Vec<_>>(),
        b.prims.iter().map(|p| p.camera).collect::<Vec<_>>()
    );
}

#[test]
fn coordinates_near_1e200_render_as_the_unit_scene() {
    // Scaling by a power of two is exact through the whole front end once
    // the camera and the transform stop overflowing.
    let k = 2f64.powi(664);
    let unit = crate::procedural::uv_sphere(24);
    let mut big = unit.clone();
    for p in &mut big.meshes[0].positions {
        *p *= k;
    }
    let (a, b) = (
        screen_of(&unit, crate::fit_camera(&unit)),
        screen_of(&big, crate::fit_camera(&big)),
    );
    assert!(a.tris.len() > 500);
    assert_eq!(snapped(&a), snapped(&b));
}

#[test]
fn a_cancelled_token_stops_both_front_ends() {
    // A large scene's front end takes tens of milliseconds: a hider's own
    // polls start only after it, so the front ends poll the token too.
    let view = View::new(camera(), 64, 64).unwrap();
    let scene = one(FACING);
    let token = crate::Cancel::new();
    let options = PrepareOptions::default().with_cancel(token);
    assert!(prepare(&scene, &view, &options).is_ok());
    let mut lean = lean::LeanScene::new();
    assert!(lean::prepare_lean_into(&scene, &view, &options, &mut lean).is_ok());
    token.cancel();
    let cancelled = |e: crate::Error| matches!(e, crate::Error::Cancelled(_));
    assert!(cancelled(prepare(&scene, &view, &options).unwrap_err()));
    assert!(cancelled(
        lean::prepare_lean_into(&scene, &view, &options, &mut lean).unwrap_err()
    ));
    // The default token never stops it.
    assert!(prepare(&scene, &view, &PrepareOptions::default()).is_ok());
}
