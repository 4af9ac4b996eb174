//! What the page holds between calls: the scene, the view, one instance of
//! each hider used (they keep their scratch memory from frame to frame)
//! and the oracle's answer for the current view, computed once per view.

use hider_oracle::{DEFAULT_TIE_TOLERANCE, OracleOptions, RayCastOracle, Reference};
use hider_plan::registry;
use hider_scene::frame::id_to_i32;
use hider_scene::shade::{Stages, render_frame};
use hider_scene::{
    CameraOverrides, DynHider, Frame, Hider, PrepareOptions, Scene, ScreenScene, ShadeMode, View,
    prepare,
};

use crate::orbit::Orbit;

/// Largest image side the page renders (the oracle's per-pixel ray cast
/// over every triangle must stay interactive).
pub const MAX_SIDE: u32 = 1024;

/// One hider's frame as the page shows it.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The hider's registry name.
    pub name: String,
    /// The frame: ids, depth and colour.
    pub frame: Frame,
    /// The hider's counters, one `name value` line each.
    pub stats: String,
}

impl Rendered {
    /// Visible primitive per pixel, row-major, -1 for background (the
    /// command line's `--ids-out` values).
    pub fn ids(&self) -> Vec<i32> {
        self.frame.ids.iter().map(|&id| id_to_i32(id)).collect()
    }

    /// The coloured image, RGBA 8 bits per channel, top row first.
    pub fn rgba(&self) -> &[u8] {
        self.frame.rgba_bytes()
    }
}

/// How a frame's ids agree with the oracle's.
#[derive(Clone, Debug, Default)]
pub struct Scored {
    /// Wrong pixels as the benchmark counts them: coverage mismatches and
    /// wrong ids off ties ([`Reference::compare`] with the default tie
    /// tolerance).
    pub wrong: u64,
    /// Pixels whose id differs from the oracle's at all (ties included).
    pub differing: u64,
    /// 1 where the id differs from the oracle's, else 0, row-major.
    pub map: Vec<u8>,
}

/// The page's state.
pub struct Session {
    scene: Scene,
    orbit: Orbit,
    width: u32,
    height: u32,
    hiders: Vec<Box<dyn DynHider>>,
    reference: Option<Reference>,
    /// The frame and prepared scene [`Session::render_bare`] reuses.
    bare: Option<(Frame, ScreenScene)>,
}

impl Default for Session {
    fn default() -> Self {
        Self::new()
    }
}

impl Session {
    /// An empty scene (the cube until the page loads another) at 256 x 256.
    pub fn new() -> Self {
        Self {
            scene: hider_scene::procedural::cube(),
            orbit: Orbit::default(),
            width: 256,
            height: 256,
            hiders: Vec::new(),
            reference: None,
            bare: None,
        }
    }

    /// The scene shown.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Shows `scene` from its own camera.
    pub fn set_scene(&mut self, scene: Scene) {
        self.scene = scene;
        self.orbit = Orbit::default();
        self.reference = None;
    }

    /// Sets the image size, refusing sizes above [`MAX_SIDE`] or zero.
    pub fn set_size(&mut self, width: u32, height: u32) -> Result<(), String> {
        if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
            return Err(format!(
                "image size {width}x{height}: the page renders 1 to {MAX_SIDE} pixels a side"
            ));
        }
        if (width, height) != (self.width, self.height) {
            self.width = width;
            self.height = height;
            self.reference = None;
        }
        Ok(())
    }

    /// The image size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Sets the orbit camera.
    pub fn set_orbit(&mut self, orbit: Orbit) {
        if orbit != self.orbit {
            self.orbit = orbit;
            self.reference = None;
        }
    }

    /// The camera of the current view, as the command line's flags would
    /// set it.
    pub fn camera(&self) -> CameraOverrides {
        self.orbit.overrides(&self.scene)
    }

    /// The current view.
    pub fn view(&self) -> Result<View, String> {
        View::new(self.camera().apply(&self.scene), self.width, self.height)
            .map_err(|e| e.to_string())
    }

    /// Renders the current view with the registered hider `name`, as
    /// `hider render --algo NAME` does: the hider's own front end, then the
    /// colour pass unless it resolves colour itself.
    pub fn render(&mut self, name: &str) -> Result<Rendered, String> {
        let view = self.view()?;
        let k = self.hider_index(name)?;
        let hider = self.hiders[k].as_mut();
        let mut frame = Frame::new(self.width, self.height).map_err(|e| e.to_string())?;
        let mut screen = ScreenScene::empty(&view);
        let stages = Stages::for_scene(&self.scene, true);
        let stats = render_frame(
            hider,
            &self.scene,
            &view,
            &PrepareOptions::default(),
            &stages,
            ShadeMode::Lambert,
            &mut screen,
            &mut frame,
        )
        .map_err(|e| e.to_string())?;
        let mut lines: Vec<String> = stats
            .counters
            .iter()
            .map(|(n, v)| format!("{n} {v}"))
            .collect();
        lines.push(format!("peak_bytes {}", stats.peak_bytes));
        lines.extend(stats.warnings.iter().map(|w| format!("warning: {w}")));
        Ok(Rendered {
            name: name.to_owned(),
            frame,
            stats: lines.join("\n"),
        })
    }

    /// Renders the current view with hider `name` without the colour pass
    /// and without copying anything out: the call `hider render --repeat`
    /// times (the hider's front end and its render), for timing in the
    /// page. Returns the covered pixel count.
    pub fn render_bare(&mut self, name: &str) -> Result<usize, String> {
        let view = self.view()?;
        let k = self.hider_index(name)?;
        let (width, height) = (self.width, self.height);
        let frame = self.bare.get_or_insert_with(|| {
            (
                Frame::new(width, height).expect("checked size"),
                ScreenScene::empty(&view),
            )
        });
        if frame.0.width() != width || frame.0.height() != height {
            frame.0.resize(width, height).map_err(|e| e.to_string())?;
        }
        self.hiders[k]
            .render_scene(
                &self.scene,
                &view,
                &PrepareOptions::default(),
                &mut frame.1,
                &mut frame.0,
            )
            .map_err(|e| e.to_string())?;
        Ok(frame.0.covered_count())
    }

    /// The index of hider `name` among those built, built now if not yet.
    fn hider_index(&mut self, name: &str) -> Result<usize, String> {
        if let Some(k) = self.hiders.iter().position(|h| h.name() == name) {
            return Ok(k);
        }
        let entry = registry::find(name).map_err(|e| e.to_string())?;
        self.hiders.push(entry.make());
        Ok(self.hiders.len() - 1)
    }

    /// The oracle's answer for the current view (computed on first use
    /// after a change of scene, size or camera).
    pub fn reference(&mut self) -> Result<&Reference, String> {
        if self.reference.is_none() {
            let view = self.view()?;
            let screen = prepare(&self.scene, &view, &PrepareOptions::default())
                .map_err(|e| e.to_string())?;
            let reference = RayCastOracle::new(OracleOptions::default())
                .try_evaluate(&screen)
                .map_err(|e| e.to_string())?;
            self.reference = Some(reference);
        }
        Ok(self.reference.as_ref().expect("set above"))
    }

    /// How `ids` (the page's -1 background) agree with the oracle.
    pub fn score(&mut self, ids: &[i32]) -> Result<Scored, String> {
        let reference = self.reference()?;
        let ids: Vec<u32> = ids
            .iter()
            .map(|&id| u32::try_from(id).unwrap_or(hider_scene::NO_ID))
            .collect();
        let agreement = reference.compare(&ids, DEFAULT_TIE_TOLERANCE);
        let map: Vec<u8> = reference
            .ids
            .iter()
            .zip(&ids)
            .map(|(a, b)| u8::from(a != b))
            .collect();
        Ok(Scored {
            wrong: agreement.coverage_mismatches + agreement.wrong_ids,
            differing: map.iter().map(|&m| u64::from(m)).sum(),
            map,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_exact_hider_scores_zero_and_the_naive_painter_does_not() {
        let mut session = Session::new();
        session.set_scene(crate::scenes::from_spec("gen:intersecting").unwrap());
        session.set_size(48, 48).unwrap();
        for entry in registry::all() {
            let r = session.render(entry.name).unwrap();
            let ids = r.ids();
            assert_eq!(ids.len(), 48 * 48);
            assert_eq!(r.rgba().len(), 48 * 48 * 4);
            let covered = ids.iter().filter(|&&id| id >= 0).count();
            assert_eq!(session.render_bare(entry.name).unwrap(), covered);
            let s = session.score(&ids).unwrap();
            if entry.kind == registry::Kind::ExactPixelCentre {
                assert_eq!(s.wrong, 0, "{}", entry.name);
            }
            if entry.name == "painter-naive" {
                assert!(s.wrong > 0, "the naive painter is wrong on intersections");
            }
        }
        assert!(session.render("nonesuch").unwrap_err().contains("nonesuch"));
        assert!(session.set_size(0, 10).is_err());
    }
}
