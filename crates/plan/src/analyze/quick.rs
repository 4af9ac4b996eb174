//! The quick analysis a raster plan can use: no front end at all when
//! nothing the planner reads needs the prepared scene.
//!
//! Preparing every triangle (transform, clip, snap, depth planes) is what
//! the full analysis starts with, and on a soup of 10^6 triangles it costs
//! more than the z-buffer's whole render. A raster plan (no ordered
//! polygons, no pair searches) reads the prepared scene for four things
//! only: translucent and textured triangles in view, whether every back
//! face on screen is hidden (culling), and how deep the geometry in view
//! goes (reversed-Z). When no material is translucent or textured, and
//! either no mesh can be closed (the cheap edge hash of [`super::backface`]
//! turns every mesh down, so culling cannot be exact) or every triangle is
//! in a closed, outward, uncut shell (culling is exact wherever the back
//! faces fall), the first three are settled without the front end, and the depth is read off a frustum test
//! on the world-space corners, which keeps every triangle the front end
//! would (and perhaps a few it clips away: the depth found is never less
//! than the full analysis's, which only ever moves the plan toward the
//! reversed-Z buffer, exact as well).

use glam::DVec4;
use hider_geom::Projection;
use hider_scene::{Scene, View};

use super::backface;
use super::effects::{Effects, Evidence};
use super::evidence;
use super::options::RenderOptions;

/// The effects of a raster plan without the front end, or `None` when the
/// plan needs the prepared scene (see the module documentation).
pub(crate) fn effects(scene: &Scene, view: &View, options: &RenderOptions) -> Option<Effects> {
    if options.pair_searches || options.ordered_polygons {
        return None;
    }
    let plain = scene
        .materials
        .iter()
        .all(|m| m.opacity >= 1.0 && m.diffuse_texture.is_none() && m.alpha_texture.is_none());
    if !plain {
        return None;
    }
    let triangles = scene.triangle_count() as u64;
    let pixels = u64::from(options.width) * u64::from(options.height);
    // Culling small triangles costs more to prove than it saves: not
    // examined at all (no pass over the meshes).
    let examine = crate::planner::culling_pays(triangles, pixels);
    let closed = if examine {
        scene
            .meshes
            .iter()
            .filter(|m| backface::maybe_closed(&m.positions, &m.indices))
            .count()
    } else {
        0
    };
    // Culling is settled without the screen when no mesh can be closed
    // (never exact) or every triangle is in a shell that hides its back
    // faces (exact wherever they are); anything between needs to know
    // which back faces are on screen.
    let all_hidden = if closed == 0 {
        false
    } else if closed == scene.meshes.len() {
        let shells = backface::hidden_back_faces(scene, view);
        if !shells.hidden.iter().all(|&h| h) {
            return None;
        }
        true
    } else {
        return None;
    };
    let (in_view, deepest) = frustum(scene, view);
    let back_faces = if !examine {
        super::back_faces_not_examined(triangles, pixels)
    } else if all_hidden {
        Evidence::found(
            false,
            0,
            Vec::new(),
            format!(
                "not counted: every triangle of the {} meshes is in a closed shell, outward and \
                 uncut (its back faces are hidden)",
                scene.meshes.len()
            ),
        )
    } else {
        Evidence {
            present: true,
            certain: false,
            detail: format!(
                "not counted: none of the {} meshes can be closed (edge hash), so no back face \
                 is certainly hidden",
                scene.meshes.len()
            ),
            ..Evidence::default()
        }
    };
    let skipped = Evidence {
        present: true,
        certain: false,
        detail: "not searched: only ordered polygons needs it".to_owned(),
        ..Evidence::default()
    };
    Some(Effects {
        triangles,
        pixels,
        on_screen: in_view,
        ordered_polygons: false,
        depth_ratio: deepest,
        transparency: Evidence::found(false, 0, Vec::new(), "every material is opaque".into()),
        textures: Evidence::found(false, 0, Vec::new(), "no material has a map_Kd".into()),
        lighting: evidence::lighting(scene, options.shading),
        antialiasing: evidence::antialiasing(options.antialiasing),
        back_faces,
        // A shell in view shows back faces; culling them saves work.
        cull_back_faces_exact: all_hidden && in_view > 0,
        intersections: skipped.clone(),
        coplanar_overlaps: skipped.clone(),
        cyclic_overlap: skipped.clone(),
        naive_order_violations: skipped,
        ..Effects::default()
    })
}

/// The triangles not wholly outside one plane of the view's frustum, and
/// the depth ratio over them (deepest corner's distance, at most the far
/// plane's, over the near distance; 1 for an orthographic camera).
fn frustum(scene: &Scene, view: &View) -> (u64, f64) {
    // Eye-relative, as the front end transforms (see `backface`).
    let mut eye_to_camera = view.camera.view_matrix();
    eye_to_camera.w_axis = DVec4::W;
    let eye = view.camera.eye;
    let aspect = f64::from(view.viewport.width) / f64::from(view.viewport.height);
    let projection = view.camera.projection_matrix(aspect);
    let (near, far, perspective) = match view.camera.projection {
        Projection::Perspective { near, far, .. } => (near, far, true),
        Projection::Orthographic { near, far, .. } => (near, far, false),
    };
    // A hair of slack on every plane: a triangle the front end keeps by
    // rounding is kept here too.
    let slack = 1.0 + 1e-9;
    let mut count = 0u64;
    let mut deepest = near;
    // World (eye-relative) to clip space in one matrix, and the view
    // distance from the camera matrix's third row. Each corner gets an
    // outcode (one bit per frustum plane it is outside of); a triangle is
    // wholly outside one plane when its corners' codes share a bit.
    let to_clip = projection * eye_to_camera;
    let depth_row = eye_to_camera.row(2);
    let corner = |p: glam::DVec3| -> (u8, f64) {
        let r = (p - eye).extend(1.0);
        let v = to_clip * r;
        let w = v.w.abs() * slack;
        let code = u8::from(v.x > w)
            | u8::from(v.x < -w) << 1
            | u8::from(v.y > w) << 2
            | u8::from(v.y < -w) << 3
            | u8::from(v.z > w) << 4
            | u8::from(v.z < -w) << 5;
        (code, -depth_row.dot(r))
    };
    for mesh in &scene.meshes {
        // A mesh that shares its vertices (a closed sphere: a million
        // positions, six million corners) is transformed once per vertex;
        // a soup, whose vertices are used once each anyway, per corner
        // without arrays (on 3 * 10^6 corners they cost more in page
        // faults than the arithmetic).
        let shared: Option<Vec<(u8, f64)>> = (mesh.positions.len() < mesh.indices.len())
            .then(|| mesh.positions.iter().map(|&p| corner(p)).collect());
        for t in &mesh.indices {
            let c = match &shared {
                Some(codes) => t.map(|i| codes[i as usize]),
                None => t.map(|i| corner(mesh.positions[i as usize])),
            };
            if c[0].0 & c[1].0 & c[2].0 != 0 {
                continue;
            }
            count += 1;
            if perspective {
                deepest = deepest.max(c[0].1).max(c[1].1).max(c[2].1);
            }
        }
    }
    let ratio = if perspective {
        deepest.min(far) / near
    } else {
        1.0
    };
    (count, ratio)
}
