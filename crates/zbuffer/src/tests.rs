//! Behaviour tests of the z-buffer: fill rule, clipping, depth formats and
//! the linear-depth demonstration.

use glam::DVec3;
use hider_geom::Camera;
use hider_scene::{Frame, Hider, Mesh, NO_ID, Scene, ScreenScene, procedural};
use hider_testkit::cameras::look_at;
use hider_testkit::screen_with;

use crate::{DepthFormat, DepthSource, ZBuffer, ZBufferOptions};

fn camera() -> Camera {
    look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 0.5, 50.0)
}

fn screen(scene: &Scene, camera: Camera, size: u32) -> ScreenScene {
    screen_with(scene, camera, size, size)
}

fn render(s: &ScreenScene, options: ZBufferOptions) -> (Frame, crate::ZBufferStats) {
    let mut f = Frame::new(s.viewport.width, s.viewport.height).unwrap();
    let stats = ZBuffer::new(options).render(s, &mut f).unwrap();
    (f, stats)
}

fn quad(z: f64, half: f64) -> Mesh {
    Mesh {
        name: format!("quad at {z}"),
        positions: vec![
            DVec3::new(-half, -half, z),
            DVec3::new(half, -half, z),
            DVec3::new(half, half, z),
            DVec3::new(-half, half, z),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    }
}

#[test]
fn shared_edge_covers_each_pixel_exactly_once() {
    // A quad of two triangles whose shared diagonal passes through pixel
    // centres: every covered pixel must be tested (and pass) exactly once.
    let mut scene = Scene::default();
    scene.push_mesh(quad(0.0, 1.3), None);
    let s = screen(&scene, camera(), 97);
    let (f, stats) = render(&s, ZBufferOptions::default());
    assert_eq!(
        stats.depth_tests,
        f.covered_count() as u64,
        "no pixel twice"
    );
    assert_eq!(stats.depth_passes, stats.depth_tests);
    // No hole: the covered pixels form a solid rectangle.
    let covered: Vec<(u32, u32)> = (0..97)
        .flat_map(|y| (0..97).map(move |x| (x, y)))
        .filter(|&(x, y)| f.ids[f.index(x, y)] != NO_ID)
        .collect();
    let (xmin, xmax) = (
        covered.iter().map(|p| p.0).min().unwrap(),
        covered.iter().map(|p| p.0).max().unwrap(),
    );
    let (ymin, ymax) = (
        covered.iter().map(|p| p.1).min().unwrap(),
        covered.iter().map(|p| p.1).max().unwrap(),
    );
    assert_eq!(covered.len() as u32, (xmax - xmin + 1) * (ymax - ymin + 1));
}

#[test]
fn closed_sphere_has_no_cracks() {
    // Every pixel inside the silhouette of a closed mesh is hit by exactly
    // two layers (front and back): depth tests = 2 x covered pixels.
    let s = screen(&procedural::uv_sphere(24), camera(), 128);
    let (f, stats) = render(&s, ZBufferOptions::default());
    assert!(f.covered_count() > 1000);
    assert_eq!(stats.depth_tests, 2 * f.covered_count() as u64);
}

#[test]
fn triangle_crossing_the_near_plane_and_one_behind_the_eye() {
    let mut scene = Scene::default();
    // Reaches from 4 units in front of the eye to 5 behind it.
    scene.push_mesh(
        Mesh {
            positions: vec![
                DVec3::new(-1.0, -1.0, 1.0),
                DVec3::new(1.0, -1.0, 1.0),
                DVec3::new(0.0, -1.0, 10.0),
            ],
            indices: vec![[0, 1, 2]],
            ..Mesh::default()
        },
        None,
    );
    // Entirely behind the eye.
    scene.push_mesh(
        Mesh {
            positions: vec![
                DVec3::new(-1.0, 0.0, 7.0),
                DVec3::new(1.0, 0.0, 7.0),
                DVec3::new(0.0, 1.0, 7.0),
            ],
            indices: vec![[0, 1, 2]],
            ..Mesh::default()
        },
        None,
    );
    let s = screen(&scene, camera(), 64);
    assert_eq!(s.stats.clipped, 1);
    assert_eq!(s.stats.culled, 1);
    let (f, _) = render(&s, ZBufferOptions::default());
    assert!(
        f.ids.iter().all(|&id| id == NO_ID || id == 0),
        "prim 1 is behind the eye"
    );
    // The floor strip reaches the bottom of the image and all depths are
    // valid window depths.
    assert!((0..64).any(|x| f.ids[f.index(x, 63)] == 0));
    assert!(f.depth.iter().all(|d| (0.0..=1.0).contains(d)));
}

#[test]
fn every_format_orders_separated_surfaces() {
    let mut scene = Scene::default();
    scene.push_mesh(quad(-1.0, 1.0), None); // far, drawn first
    scene.push_mesh(quad(0.0, 0.5), None); // near, drawn second
    scene.push_mesh(quad(-2.0, 2.0), None); // farthest, drawn last
    let s = screen(&scene, camera(), 64);
    for format in DepthFormat::ALL {
        let (f, _) = render(&s, ZBufferOptions::default().with_depth_format(format));
        let centre = f.ids[f.index(32, 32)];
        assert!(
            centre == 2 || centre == 3,
            "{format:?}: near quad visible, got {centre}"
        );
        let ring = f.ids[f.index(32, 25)];
        assert!(
            ring == 0 || ring == 1,
            "{format:?}: middle quad visible, got {ring}"
        );
        let edge = f.ids[f.index(32, 19)];
        assert!(
            edge == 4 || edge == 5,
            "{format:?}: farthest quad at the edge, got {edge}"
        );
        let d = f.depth[f.index(32, 32)];
        let want = s.tris[2].depth.at_pixel(32, 32) as f32;
        assert!((d - want).abs() < 2e-5, "{format:?}: depth {d} vs {want}");
    }
}

#[test]
fn sixteen_bit_depth_fights_where_f32_does_not() {
    // Two parallel quads 0.001 apart, 35 units away with a 0.5 near plane:
    // window depths 0.995671 and 4.1e-7 nearer, i.e. 7 f32 steps but 0.03
    // of one 16-bit step (both quantise to 65251), so 16-bit keeps the
    // first-drawn, farther quad.
    let mut scene = Scene::default();
    scene.push_mesh(quad(-30.0, 20.0), None);
    scene.push_mesh(quad(-29.999, 20.0), None);
    let s = screen(&scene, camera(), 32);
    let front = |f: &Frame| f.ids.iter().filter(|&&id| id == 2 || id == 3).count();
    let (f32_frame, _) = render(&s, ZBufferOptions::default());
    assert!(f32_frame.covered_count() > 500);
    assert_eq!(
        front(&f32_frame),
        f32_frame.covered_count(),
        "f32 separates the quads"
    );
    let (f16_frame, _) = render(
        &s,
        ZBufferOptions::default().with_depth_format(DepthFormat::Fixed16),
    );
    assert!(
        front(&f16_frame) < f16_frame.covered_count(),
        "16-bit depth cannot"
    );
}

#[test]
fn linear_view_depth_gets_intersections_wrong() {
    // The depth-buffer lesson's point: linear camera depth in screen space
    // misplaces the
    // intersection line of two triangles seen in perspective.
    let s = screen(&procedural::intersecting_pair(), camera(), 128);
    let (good, _) = render(
        &s,
        ZBufferOptions::default().with_depth_format(DepthFormat::F64),
    );
    let (bad, _) = render(
        &s,
        ZBufferOptions::default().with_depth_source(DepthSource::LinearViewZ),
    );
    let wrong = good
        .ids
        .iter()
        .zip(&bad.ids)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        good.covered_count(),
        bad.covered_count(),
        "coverage does not depend on depth"
    );
    assert!(wrong > 0, "linear depth must misplace some pixels");
}

#[test]
fn frame_of_the_wrong_size_is_an_error() {
    let s = screen(&procedural::cube(), camera(), 16);
    let mut f = Frame::new(17, 16).unwrap();
    let e = ZBuffer::default()
        .render(&s, &mut f)
        .unwrap_err()
        .to_string();
    assert!(e.contains("17x16") && e.contains("16x16"), "{e}");
}

#[test]
fn buffers_are_reused_and_results_repeat() {
    let s = screen(&procedural::random_soup(300, 1), camera(), 64);
    let mut z = ZBuffer::default();
    let mut a = Frame::new(64, 64).unwrap();
    let mut b = Frame::new(64, 64).unwrap();
    z.render(&s, &mut a).unwrap();
    z.render(&s, &mut b).unwrap();
    assert_eq!(a, b);
}
