//! Painting an ordered piece list into a frame with the shared coverage
//! rules.
//!
//! Each piece overwrites, far to near, the pixel centres it covers: those
//! its source triangle covers under the shared edge functions and fill rule and
//! that all of its cuts keep ([`Piece::covers`]). The depth written is the
//! source triangle's window-depth plane at the centre, as the z-buffer
//! writes it, so the two frames can be compared value for value.
//!
//! The tie rule of every exact hider: where a piece would overwrite a
//! centre whose painted surface has exactly the same window depth there
//! (`f64`, the value the z-buffer compares) and a lower primitive id, the
//! lower id stays, as a LESS depth test drawing in id order keeps it. The
//! depth order cannot express this itself: two coplanar overlapping
//! pieces may be painted in either order.

use hider_geom::fixed::pixel_center;
use hider_scene::{Error, Frame, Result, ScreenScene};

use crate::centres::Centres;
use crate::newell::CUT_MARGIN;
use crate::piece::Piece;

/// Marks a pixel no piece painted in the owner buffer.
pub(crate) const NO_OWNER: u32 = u32::MAX;

/// Paints `order` (indices into `pieces`, farthest first) into `frame`,
/// which must already be cleared. When `owner` is given it receives, per
/// pixel, the position in `order` of the piece painted last. `centres`,
/// when given, says per piece which centres it covers (as the ordering
/// classified them with the same coverage rule): a piece covering none is
/// skipped and one covering a single centre is written there directly,
/// with the depth computed the same way. Returns the number of pixel
/// writes.
pub(crate) fn paint(
    scene: &ScreenScene,
    (pieces, centres): (&[Piece], Option<&[Centres]>),
    order: &[u32],
    frame: &mut Frame,
    mut owner: Option<&mut Vec<u32>>,
) -> u64 {
    if let Some(o) = owner.as_deref_mut() {
        o.clear();
        o.resize(frame.len(), NO_OWNER);
    }
    let vp = scene.viewport;
    let width = frame.width() as usize;
    let mut writes = 0;
    // The f64 window depth painted at each centre, for the tie rule.
    let mut painted = vec![f64::INFINITY; frame.len()];
    let mut keeps = |frame: &Frame, k: usize, z: f64, prim: u32| {
        let tie = z == painted[k] && frame.ids[k] < prim;
        if !tie {
            painted[k] = z;
        }
        !tie
    };
    for (rank, &id) in order.iter().enumerate() {
        let piece = &pieces[id as usize];
        match centres.map(|c| c[id as usize]) {
            Some(Centres::None) => continue,
            Some(Centres::One(i, j, z)) => {
                let k = j as usize * width + i as usize;
                if !keeps(frame, k, z, piece.prim) {
                    continue;
                }
                frame.ids[k] = piece.prim;
                frame.depth[k] = z as f32;
                if let Some(o) = owner.as_deref_mut() {
                    o[k] = rank as u32;
                }
                writes += 1;
                continue;
            }
            Some(Centres::Many) | None => {}
        }
        let tri = &scene.tris[piece.source as usize];
        let Some((x0, y0, x1, y1)) = tri.pixel_bounds(vp) else {
            continue;
        };
        // A cut piece's polygon has rounded vertices: widen its box by the
        // margin so no centre it covers is skipped (coverage itself is
        // decided exactly below).
        let first = |m: f64| (m - CUT_MARGIN - 0.5).ceil().max(0.0);
        let last = |m: f64| (m + CUT_MARGIN - 0.5).floor();
        let (px0, py0) = (first(piece.min.x), first(piece.min.y));
        let (px1, py1) = (last(piece.max.x), last(piece.max.y));
        if px1 < px0 || py1 < py0 {
            continue;
        }
        // Both boxes are within the viewport after this intersection.
        let xs = (px0 as u32).max(x0)..=(px1.min(f64::from(x1)) as u32).min(x1);
        let ys = (py0 as u32).max(y0)..=(py1.min(f64::from(y1)) as u32).min(y1);
        let edges = tri.edges();
        for j in ys {
            let y = i64::from(pixel_center(j as i32));
            for i in xs.clone() {
                let x = i64::from(pixel_center(i as i32));
                if !edges.iter().all(|e| e.contains(x, y)) {
                    continue;
                }
                let (px, py) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                if !piece.cuts.iter().all(|c| c.keeps(px, py)) {
                    continue;
                }
                let k = j as usize * width + i as usize;
                let z = tri.depth.eval(px, py);
                if !keeps(frame, k, z, piece.prim) {
                    continue;
                }
                frame.ids[k] = piece.prim;
                frame.depth[k] = z as f32;
                if let Some(o) = owner.as_deref_mut() {
                    o[k] = rank as u32;
                }
                writes += 1;
            }
        }
    }
    writes
}

/// Checks what the painters rely on: finite depth planes and positively
/// oriented triangles with primitive ids in range. A hand-made scene that
/// breaks these gets an error naming the triangle, never a panic or a
/// wrong order.
pub(crate) fn validate(hider: &str, scene: &ScreenScene) -> Result<()> {
    for (k, t) in scene.tris.iter().enumerate() {
        let d = &t.depth;
        let finite = [d.x0, d.y0, d.value, d.dx, d.dy]
            .iter()
            .all(|v| v.is_finite());
        let oriented = hider_geom::orient2d(t.v[0], t.v[1], t.v[2]) > 0;
        let prim_ok = (t.prim as usize) < scene.prims.len();
        if !(finite && oriented && prim_ok) {
            return Err(Error::Render {
                hider: hider.to_owned(),
                message: format!(
                    "screen triangle {k} (primitive {}) is not set up: {}",
                    t.prim,
                    if !finite {
                        "its depth plane is not finite"
                    } else if !oriented {
                        "its vertices are not positively oriented"
                    } else {
                        "its primitive id has no primitive info"
                    }
                ),
            });
        }
    }
    Ok(())
}
