//! The warning for an empty picture: when no triangle covers a pixel, say
//! why (outside the view, back faces culled, seen edge-on, too small) and
//! suggest a camera that sees something, rather than writing a black image
//! without a word.

use glam::DVec3;
use hider::geom::Projection;
use hider::scene::{Scene, ScreenScene};

/// Relative distance of the eye from a triangle's plane under which the
/// triangle counts as seen edge-on: the plane through the eye projects to
/// a line, which covers no pixel centre except by a tie.
const EDGE_ON: f64 = 1e-9;

/// Triangles of zero area in world space and triangles whose plane holds
/// the eye (or, for an orthographic camera, the view direction), with the
/// unit normal of the first of those.
fn edge_on(scene: &Scene, screen: &ScreenScene) -> (usize, usize, Option<DVec3>) {
    let camera = &screen.camera;
    let dir = (camera.target - camera.eye).normalize_or_zero();
    let orthographic = matches!(camera.projection, Projection::Orthographic { .. });
    let (mut flat, mut edge_on, mut normal) = (0, 0, None);
    for (_, m, t) in scene.triangles() {
        let [a, b, c] = scene.triangle_positions(m, t);
        let n = (b - a).cross(c - a);
        let len = n.length();
        if len == 0.0 || !len.is_finite() {
            flat += 1;
            continue;
        }
        let n = n / len;
        let off_plane = if orthographic {
            n.dot(dir).abs()
        } else {
            let to_eye = camera.eye - a;
            n.dot(to_eye).abs() / to_eye.length().max(f64::MIN_POSITIVE)
        };
        if off_plane <= EDGE_ON {
            edge_on += 1;
            // The side the up vector points to: the suggestion raises the eye.
            normal.get_or_insert(if n.dot(camera.up) < 0.0 { -n } else { n });
        }
    }
    (flat, edge_on, normal)
}

/// A compact `x,y,z` for a flag value.
fn xyz(v: DVec3) -> String {
    let n = |x: f64| {
        let s = format!("{x:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".to_owned()
        } else {
            s.to_owned()
        }
    };
    format!("{},{},{}", n(v.x), n(v.y), n(v.z))
}

/// "1 triangle" or "N triangles".
fn count(n: usize) -> String {
    if n == 1 {
        "1 triangle".to_owned()
    } else {
        format!("{n} triangles")
    }
}

/// The subject of a sentence about `n` triangles and its verb `to be`:
/// ("the triangle", "is") or ("all N triangles", "are").
fn all(n: usize) -> (String, &'static str) {
    if n == 1 {
        ("the triangle".to_owned(), "is")
    } else {
        (format!("all {n} triangles"), "are")
    }
}

/// The warning when `covered` is 0 (nothing on screen), else `None`.
pub fn nothing_on_screen(scene: &Scene, screen: &ScreenScene, covered: usize) -> Option<String> {
    if covered > 0 {
        return None;
    }
    let stats = &screen.stats;
    let total = scene.triangle_count();
    let camera = &screen.camera;
    let (flat, edge_on, normal) = edge_on(scene, screen);
    let (culled, back) = (stats.culled as usize, stats.back_faces as usize);
    let why = if total > flat && edge_on == total - flat {
        let (who, is) = all(edge_on);
        format!("{who} {is} seen edge-on (the eye lies in their plane: they project to a line)")
    } else if culled == total {
        let (who, is) = all(total);
        format!(
            "{who} {is} outside the view (behind the eye, off screen, or beyond the near or \
             far plane)"
        )
    } else if back > 0 && back + culled == total {
        let (who, is) = all(back);
        format!("{who} in view {is} back faces, culled")
    } else if screen.tris.is_empty() && back == 0 && culled == 0 {
        let (who, _) = all(total);
        format!(
            "{who} {} zero area on screen (smaller than the 1/256-pixel snapping step \
             or seen edge-on)",
            if total == 1 { "has" } else { "have" }
        )
    } else if screen.tris.is_empty() {
        format!(
            "of {}, {culled} are outside the view, {back} back faces culled and the rest of \
             zero area on screen",
            count(total)
        )
    } else {
        let (who, _) = all(screen.tris.len());
        format!(
            "{who} on screen cover{} no pixel centre (thinner or smaller than a pixel)",
            if screen.tris.len() == 1 { "s" } else { "" }
        )
    };
    let distance = (camera.eye - camera.target).length();
    let suggestion = match normal {
        // Off the plane by half the viewing distance: about 27 degrees.
        Some(n) if distance > 0.0 => format!(
            "; try --eye {} (off their plane)",
            xyz(camera.eye + n * (0.5 * distance))
        ),
        _ => format!(
            "; try another --eye (now {}) or --target (now {})",
            xyz(camera.eye),
            xyz(camera.target)
        ),
    };
    Some(format!("nothing on screen: {why}{suggestion}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_for_flags_are_compact() {
        assert_eq!(xyz(DVec3::new(1.0, -0.25, 1e-9)), "1,-0.25,0");
        assert_eq!(xyz(DVec3::new(-0.00001, 2.5, 100.0)), "0,2.5,100");
    }
}
