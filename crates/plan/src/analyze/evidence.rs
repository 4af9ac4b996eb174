//! The effects read off the prepared scene one primitive at a time:
//! transparency, textures, lighting, anti-aliasing and back faces.

use hider_scene::{Scene, ScreenScene, View};

use super::backface;
use super::effects::Evidence;
use hider_scene::shade::texture;

/// The primitives with at least one screen triangle: their ids in
/// ascending order, and a membership flag per primitive id. Both are one
/// sequential pass over the triangles; a hash set of ids cost the analysis
/// more than the evidence it serves on scenes of 10^5 triangles.
pub(crate) struct InView {
    /// The ids, ascending.
    pub ids: Vec<u32>,
    /// `member[id]`: whether primitive `id` is in view.
    member: Vec<bool>,
}

impl InView {
    /// The primitives of `screen`'s triangles.
    pub(crate) fn of(screen: &ScreenScene) -> Self {
        let mut member = vec![false; screen.prims.len()];
        for t in &screen.tris {
            member[t.prim as usize] = true;
        }
        let ids = (0..member.len() as u32)
            .filter(|&p| member[p as usize])
            .collect();
        Self { ids, member }
    }

    /// Whether primitive `id` is in view.
    pub(crate) fn contains(&self, id: u32) -> bool {
        self.member.get(id as usize).copied().unwrap_or(false)
    }
}

/// Window depth by which an opaque surface must be nearer than a
/// translucent one at a pixel centre to hide it for certain: far above the
/// rounding of any hider's depth (f32 window depth is spaced `2^-24` near
/// 1), far below the depth steps between surfaces that are meant to be
/// ordered. Closer than this counts as showing.
const HIDDEN_MARGIN: f64 = 1e-6;

/// Translucent triangles in view, and whether any pixel shows one.
///
/// With `one_sample` (no anti-aliasing asked, so the plan's hider samples
/// pixel centres), a translucent triangle counts only if some pixel centre
/// it covers (the fill rule every hider uses) has no opaque surface nearer
/// by [`HIDDEN_MARGIN`]: the opaque depth is the nearest opaque triangle's
/// depth plane at that centre, back faces included, what the one-sample
/// z-buffer would keep. Transparency no pixel shows needs no compositing
/// (and no A-buffer): drawn opaque, those triangles still lose every
/// depth test. The opaque pass runs only when translucent triangles are in
/// view.
pub(crate) fn transparency(
    screen: &ScreenScene,
    in_view: &InView,
    one_sample: bool,
    ex: usize,
) -> Evidence {
    let ids: Vec<u32> = in_view
        .ids
        .iter()
        .copied()
        .filter(|&p| screen.material(p).opacity < 1.0)
        .collect();
    let mut names: Vec<&str> = ids
        .iter()
        .map(|&p| screen.material(p).name.as_str())
        .collect();
    names.sort_unstable();
    names.dedup();
    if ids.is_empty() {
        return Evidence::found(
            false,
            0,
            Vec::new(),
            "every material in view is opaque".into(),
        );
    }
    let listed = format!(
        "{} translucent triangles in view (materials {})",
        ids.len(),
        names.join(", ")
    );
    if !one_sample {
        return Evidence::found(
            true,
            ids.len() as u64,
            ids.iter().take(ex).map(|&p| vec![p]).collect(),
            listed,
        );
    }
    let shown = shown_translucent(screen);
    if shown.is_empty() {
        return Evidence::found(
            false,
            0,
            Vec::new(),
            format!(
                "{listed}, all hidden: an opaque surface is nearer at every pixel centre they \
                 cover"
            ),
        );
    }
    Evidence::found(
        true,
        shown.len() as u64,
        shown.iter().take(ex).map(|&p| vec![p]).collect(),
        format!(
            "{listed}, {} of them in front of every opaque surface at some pixel centre",
            shown.len()
        ),
    )
}

/// The translucent primitives (ascending, no repeats) that some pixel
/// centre shows: covered, and no opaque triangle nearer there by
/// [`HIDDEN_MARGIN`].
fn shown_translucent(screen: &ScreenScene) -> Vec<u32> {
    let vp = screen.viewport;
    let width = vp.width as usize;
    let translucent = |p: u32| screen.material(p).opacity < 1.0;
    let mut opaque = vec![f64::INFINITY; width * vp.height as usize];
    for t in screen.tris.iter().filter(|t| !translucent(t.prim)) {
        t.for_each_centre(vp, |i, j, covered| {
            if covered {
                let d = &mut opaque[j as usize * width + i as usize];
                *d = d.min(t.depth.at_pixel(i, j));
            }
        });
    }
    let mut shown: Vec<u32> = Vec::new();
    for t in screen.tris.iter().filter(|t| translucent(t.prim)) {
        if shown.last() == Some(&t.prim) {
            continue;
        }
        let mut visible = false;
        t.for_each_centre(vp, |i, j, covered| {
            visible |= covered
                && t.depth.at_pixel(i, j) < opaque[j as usize * width + i as usize] + HIDDEN_MARGIN;
        });
        if visible {
            shown.push(t.prim);
        }
    }
    shown.sort_unstable();
    shown.dedup();
    shown
}

pub(crate) fn textures(screen: &ScreenScene, in_view: &InView, ex: usize) -> Evidence {
    let mut probe: Vec<Option<std::result::Result<(u32, u32), String>>> =
        vec![None; screen.materials.len()];
    let mut ids = Vec::new();
    let mut failures: Vec<String> = Vec::new();
    for &p in &in_view.ids {
        let prim = &screen.prims[p as usize];
        let k = prim.material as usize;
        let Some(path) = &screen.materials[k].diffuse_texture else {
            continue;
        };
        let r = probe[k].get_or_insert_with(|| {
            texture::probe(path.path()).map_err(|e| {
                let msg = e.to_string();
                failures.push(msg.clone());
                msg
            })
        });
        if r.is_ok() && prim.uvs.is_some() {
            ids.push(p);
        }
    }
    let mut detail = if ids.is_empty() {
        "no triangle in view has both uvs and a loadable map_Kd".to_owned()
    } else {
        format!(
            "{} triangles in view with uvs and a loadable map_Kd",
            ids.len()
        )
    };
    if !failures.is_empty() {
        detail.push_str(&format!(
            "; textures that do not load: {}",
            failures.join("; ")
        ));
    }
    Evidence::found(
        !ids.is_empty(),
        ids.len() as u64,
        ids.iter().take(ex).map(|&p| vec![p]).collect(),
        detail,
    )
}

pub(crate) fn lighting(scene: &Scene, shading: bool) -> Evidence {
    let lights = scene.lights.len() as u64;
    let with_normals = scene
        .meshes
        .iter()
        .filter(|m| !m.normals.is_empty())
        .count() as u64;
    // Lambert shading is lighting: a scene without lights is lit by the
    // directional head light, so its faces read as shapes instead of one
    // flat silhouette per material.
    let present = shading;
    let detail = if !shading {
        "shading not asked for".to_owned()
    } else if lights == 0 {
        format!("head light (no lights in the scene), {with_normals} meshes with normals")
    } else {
        format!("{lights} lights, {with_normals} meshes with normals")
    };
    Evidence::found(present, lights + with_normals, Vec::new(), detail)
}

pub(crate) fn back_faces(scene: &Scene, view: &View, screen: &ScreenScene, ex: usize) -> Evidence {
    let back: Vec<u32> = screen
        .tris
        .iter()
        .filter(|t| !t.front_facing)
        .map(|t| t.prim)
        .collect();
    if back.is_empty() {
        // Nothing to cull: the closed-shell search would decide nothing.
        return Evidence::found(
            false,
            0,
            Vec::new(),
            "no back-facing triangles on screen".to_owned(),
        );
    }
    let shells = backface::hidden_back_faces(scene, view);
    let exposed: Vec<u32> = back
        .iter()
        .copied()
        .filter(|&p| !shells.hidden.get(p as usize).copied().unwrap_or(false))
        .collect();
    Evidence::found(
        !exposed.is_empty(),
        back.len() as u64,
        exposed.iter().take(ex).map(|&p| vec![p]).collect(),
        format!(
            "{} back-facing triangles on screen, {} of them possibly visible; {} of {} closed \
             shells outward and uncut (their back faces are hidden); {} of {} meshes certainly \
             open (edge hash)",
            back.len(),
            exposed.len(),
            shells.hiding_shells,
            shells.closed_shells,
            shells.open_by_hash,
            scene.meshes.len()
        ),
    )
}

pub(crate) fn antialiasing(asked: bool) -> Evidence {
    Evidence::found(
        asked,
        u64::from(asked),
        Vec::new(),
        if asked {
            "asked for: multi-sample coverage".into()
        } else {
            "not asked for: one sample per pixel".into()
        },
    )
}
