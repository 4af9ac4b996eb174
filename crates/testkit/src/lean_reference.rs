//! The brute-force definition of the tiled z-buffer's lean front end
//! ([`hider_zbuffer::prepare_depth_into`]), worked out from the shared
//! front end's triangles.

use hider_geom::FEW_CENTRES;
use hider_geom::fixed::pixel_center;
use hider_scene::ScreenScene;
use hider_zbuffer::{DepthFragment, DepthTri};

/// What [`prepare_depth_into`](hider_zbuffer::prepare_depth_into) must
/// produce for the scene, view and options that
/// [`prepare`](fn@hider_scene::prepare) turned into `screen`, worked out by
/// brute force over each triangle's pixel box: the triangles whose box
/// holds more than [`FEW_CENTRES`] (four) pixel centres, as [`DepthTri`]s,
/// and one [`DepthFragment`] per covered centre of the others (those
/// covering none are dropped), both in primitive order. The lean front
/// end's tests and fuzz target compare it with this.
///
/// ```
/// use hider_scene::{procedural, PrepareOptions, View, prepare};
/// use hider_zbuffer::{DepthScene, prepare_depth_into};
///
/// let scene = procedural::uv_sphere(16);
/// let view = View::for_scene(&scene, 48, 48).unwrap();
/// let options = PrepareOptions::default();
/// let (tris, fragments) = hider_testkit::lean_reference(&prepare(&scene, &view, &options).unwrap());
/// let mut lean = DepthScene::new();
/// prepare_depth_into(&scene, &view, &options, &mut lean).unwrap();
/// assert!(lean.tris().copied().eq(tris));
/// assert!(lean.fragments().flatten().copied().eq(fragments));
/// ```
pub fn lean_reference(screen: &ScreenScene) -> (Vec<DepthTri>, Vec<DepthFragment>) {
    let (mut tris, mut fragments) = (Vec::new(), Vec::new());
    for t in &screen.tris {
        let Some((x0, y0, x1, y1)) = t.pixel_bounds(screen.viewport) else {
            continue;
        };
        if ((x1 - x0 + 1) * (y1 - y0 + 1)) as usize > FEW_CENTRES {
            tris.push(DepthTri::from(t));
            continue;
        }
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (cx, cy) = (pixel_center(x as i32), pixel_center(y as i32));
                if hider_geom::triangle_covers(&t.v, cx.into(), cy.into()) {
                    fragments.push(DepthFragment {
                        depth: t.depth.at_pixel(x, y),
                        x: x as u16,
                        y: y as u16,
                        prim: t.prim,
                    });
                }
            }
        }
    }
    (tris, fragments)
}
