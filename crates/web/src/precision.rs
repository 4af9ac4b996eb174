//! The depth-precision view: two near-coplanar planes
//! ([`hider_testkit::hard_cases::parallel_layers`]) rendered by every
//! registered depth-buffer variant (one per depth format and depth
//! source), each scored against the oracle: the share of pixels that
//! fight (show the wrong plane).

use hider_plan::registry;
use wasm_bindgen::prelude::*;

use crate::session::{Rendered, Scored, Session};
use crate::{JsResult, js};

/// Distance of the nearer plane from the eye (world units).
pub const DISTANCE: f64 = 10.0;

/// The registered depth-buffer variants: the registry's entries whose
/// description starts with "depth buffer" (one depth format or source
/// each; the tiled z-buffer, bit-identical to `zbuffer`, is not one).
pub fn formats() -> Vec<&'static str> {
    registry::all()
        .iter()
        .filter(|e| e.description.starts_with("depth buffer"))
        .map(|e| e.name)
        .collect()
}

/// One variant's frame and its fights.
pub struct Fought {
    /// The registry name.
    pub name: &'static str,
    /// Its frame.
    pub rendered: Rendered,
    /// Its agreement with the oracle (`differing`: the fighting pixels).
    pub scored: Scored,
}

/// Two planes `gap * DISTANCE` apart at [`DISTANCE`], seen through a
/// camera with clip distances `near` and `far`, at `side` x `side`, by
/// every variant of [`formats`]; with the oracle's covered pixel count.
pub fn fight(gap: f64, near: f64, far: f64, side: u32) -> Result<(Vec<Fought>, u64), String> {
    if !(gap > 0.0 && gap <= 0.5) {
        return Err(format!("plane gap {gap}: 0 < gap <= 0.5 (of the distance)"));
    }
    if !(near > 0.0 && near < 0.9 * DISTANCE) {
        return Err(format!("near {near}: 0 < near < {}", 0.9 * DISTANCE));
    }
    let back = DISTANCE * (1.0 + 2.0 * gap);
    if !(far > 1.1 * back && far.is_finite()) {
        return Err(format!(
            "far {far}: more than {} (behind the planes)",
            1.1 * back
        ));
    }
    if side == 0 || side > crate::steps::MAX_STEP_SIDE {
        return Err(format!(
            "precision view size {side}: 1 to 128 pixels a side"
        ));
    }
    let mut session = Session::new();
    let scene = hider_testkit::hard_cases::parallel_layers(2, DISTANCE, gap, (near, far), 40.0, 1);
    session.set_scene(scene);
    session.set_size(side, side)?;
    let covered = session
        .reference()?
        .ids
        .iter()
        .filter(|&&id| id != hider_scene::NO_ID)
        .count();
    let mut out = Vec::new();
    for name in formats() {
        let rendered = session.render(name)?;
        let scored = session.score(&rendered.ids())?;
        out.push(Fought {
            name,
            rendered,
            scored,
        });
    }
    Ok((out, covered as u64))
}

/// The page's depth-precision view (`new Precision()`, then `run`).
#[wasm_bindgen]
#[derive(Default)]
pub struct Precision {
    results: Vec<Fought>,
    covered: u64,
}

#[wasm_bindgen]
impl Precision {
    /// No frames yet.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Precision {
        Precision::default()
    }

    /// Renders the two planes, `gap` (a fraction of their distance, 10)
    /// apart, with clip distances `near` and `far`, at `side` x `side`,
    /// with every depth-buffer variant; returns how many.
    pub fn run(&mut self, gap: f64, near: f64, far: f64, side: u32) -> JsResult<usize> {
        let (results, covered) = fight(gap, near, far, side).map_err(js)?;
        self.results = results;
        self.covered = covered;
        Ok(self.results.len())
    }

    /// Variant `k`'s registry name.
    pub fn name(&self, k: usize) -> String {
        self.results
            .get(k)
            .map(|f| f.name.to_owned())
            .unwrap_or_default()
    }

    /// Variant `k`'s description in the registry.
    pub fn describe(&self, k: usize) -> String {
        crate::Page::describe(&self.name(k))
    }

    /// Variant `k`'s image, RGBA bytes.
    pub fn rgba(&self, k: usize) -> Vec<u8> {
        self.results
            .get(k)
            .map(|f| f.rendered.rgba().to_vec())
            .unwrap_or_default()
    }

    /// Variant `k`'s fighting pixels: 1 where its id is not the oracle's.
    pub fn map(&self, k: usize) -> Vec<u8> {
        self.results
            .get(k)
            .map(|f| f.scored.map.clone())
            .unwrap_or_default()
    }

    /// Variant `k`'s count of fighting pixels.
    pub fn fights(&self, k: usize) -> u32 {
        self.results
            .get(k)
            .map_or(0, |f| u32::try_from(f.scored.differing).unwrap_or(u32::MAX))
    }

    /// The pixels the oracle sees a plane in.
    pub fn covered(&self) -> u32 {
        u32::try_from(self.covered).unwrap_or(u32::MAX)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fights(gap: f64, near: f64, far: f64) -> Vec<(&'static str, u64)> {
        let (results, covered) = fight(gap, near, far, 64).unwrap();
        assert!(covered > 64 * 64 / 2, "{covered} covered");
        results
            .iter()
            .map(|f| (f.name, f.scored.differing))
            .collect()
    }

    #[test]
    fn wide_gaps_never_fight_and_tiny_far_ones_fight_more_in_16_bits() {
        let names = formats();
        for name in [
            "zbuffer",
            "zbuffer-f64",
            "zbuffer-fixed16",
            "zbuffer-fixed24",
        ] {
            assert!(names.contains(&name), "{name} not in {names:?}");
        }
        assert!(!names.contains(&"zbuffer-tiled"));
        let wide = fights(0.05, 1.0, 100.0);
        assert!(wide.iter().all(|&(_, n)| n == 0), "{wide:?}");
        let tiny = fights(1e-5, 0.01, 1000.0);
        let of = |name| tiny.iter().find(|f| f.0 == name).unwrap().1;
        assert!(of("zbuffer-fixed16") > of("zbuffer"), "{tiny:?}");
        assert_eq!(of("zbuffer-f64"), 0, "{tiny:?}");
        let refused = |gap, near, far| fight(gap, near, far, 64).err().unwrap();
        assert!(refused(0.0, 1.0, 100.0).contains("gap"));
        assert!(refused(0.01, 20.0, 100.0).contains("near"));
        assert!(refused(0.01, 1.0, 10.0).contains("far"));
    }
}
