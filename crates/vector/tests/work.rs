//! Work counters, not times: the hidden half of a closed mesh is decided
//! without polygon booleans, because the edges between its front faces
//! match and stay off the back faces' interiors.

use hider_scene::{ShadeMode, procedural};
use hider_testkit::screen;
use hider_vector::{VectorOptions, visible_regions};

#[test]
fn a_closed_sphere_needs_booleans_only_along_its_silhouette() {
    let s = screen(&procedural::uv_sphere(48), 256, 256);
    let map = visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert).unwrap();
    let stats = map.stats;
    eprintln!("{stats:?}");
    // About half the triangles are back faces with front faces over them;
    // all but those under the silhouette are decided by one point test.
    assert!(
        stats.decided * 3 > stats.triangles,
        "only {} of {} triangles decided without a boolean",
        stats.decided,
        stats.triangles
    );
    assert!(
        stats.differences * 20 < stats.triangles,
        "{} booleans for {} triangles",
        stats.differences,
        stats.triangles
    );
}
