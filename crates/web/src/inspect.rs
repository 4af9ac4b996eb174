//! The A-buffer's pixel inspector: the session's view rendered at a step
//! size by the A-buffer with its lists kept, and any pixel's fragment list
//! read back from the A-buffer itself ([`ABuffer::inspect_pixel`]).

use hider_abuffer::{ABuffer, ABufferOptions, PixelInspection};
use hider_scene::frame::id_to_i32;
use hider_scene::{Frame, Hider, ScreenScene};
use wasm_bindgen::prelude::*;

use crate::session::Session;
use crate::steps::step_scene;
use crate::{JsResult, Page, js};

/// Numbers per fragment in [`InspectedPixel::fragments`].
pub const FRAGMENT_STRIDE: usize = 11;

/// The A-buffer's frame of one view, with its lists kept for inspection.
pub struct Inspection {
    screen: ScreenScene,
    abuffer: ABuffer,
    frame: Frame,
}

impl Inspection {
    /// Renders the session's scene and camera at `side` x `side` (1 to
    /// [`crate::steps::MAX_STEP_SIDE`]) with the A-buffer, `carpenter`
    /// for the paper's `zmin`/`zmax` resolve with same-surface merging
    /// ([`ABufferOptions::carpenter`]), else the registry's default; both
    /// with the sample buffer off so that every tile keeps its lists.
    pub fn record(session: &Session, side: u32, carpenter: bool) -> Result<Self, String> {
        let (screen, mut frame) = step_scene(session, side)?;
        let options = if carpenter {
            ABufferOptions::carpenter()
        } else {
            ABufferOptions::default()
        };
        let mut abuffer = ABuffer::new(options.with_sample_tiles(false));
        abuffer
            .render(&screen, &mut frame)
            .map_err(|e| e.to_string())?;
        Ok(Self {
            screen,
            abuffer,
            frame,
        })
    }

    /// The A-buffer's frame.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Pixel `(x, y)`'s list and resolve.
    pub fn pixel(&self, x: u32, y: u32) -> Result<PixelInspection, String> {
        self.abuffer
            .inspect_pixel(&self.screen, x, y)
            .map_err(|e| e.to_string())
    }
}

/// The page's A-buffer inspector (`Inspector.record(page, side, carpenter)`).
#[wasm_bindgen]
pub struct Inspector(Inspection);

#[wasm_bindgen]
impl Inspector {
    /// Renders `page`'s view at `side` x `side` (1 to 128) with the
    /// A-buffer (`carpenter`: the paper's variant), keeping its lists.
    pub fn record(page: &Page, side: u32, carpenter: bool) -> JsResult<Inspector> {
        Inspection::record(&page.session, side, carpenter)
            .map(Inspector)
            .map_err(js)
    }

    /// The frame's RGBA bytes, top row first.
    pub fn rgba(&self) -> Vec<u8> {
        self.0.frame().rgba_bytes().to_vec()
    }

    /// The frame's ids, -1 for background.
    pub fn ids(&self) -> Vec<i32> {
        self.0.frame().ids.iter().map(|&id| id_to_i32(id)).collect()
    }

    /// Pixel `(x, y)`'s fragment list and resolve.
    pub fn pixel(&self, x: u32, y: u32) -> JsResult<InspectedPixel> {
        self.0.pixel(x, y).map(InspectedPixel).map_err(js)
    }
}

/// One pixel's fragments and resolve, as the A-buffer built them.
#[wasm_bindgen]
pub struct InspectedPixel(PixelInspection);

#[wasm_bindgen]
impl InspectedPixel {
    /// The fragments in resolve order, [`FRAGMENT_STRIDE`] numbers each:
    /// mask (32 bits, bit `k` the 8 x 4 grid's cell `(k % 8, k / 8)`),
    /// primitive, primitive at the centre (-1 none), `zmin`, `zmax`,
    /// centre depth (-1 when the centre is not covered), linear red,
    /// green, blue, opacity, and 1 when merged from several triangles.
    pub fn fragments(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.0.fragments.len() * FRAGMENT_STRIDE);
        for f in &self.0.fragments {
            let centre = if f.centre_z.is_finite() {
                f.centre_z
            } else {
                -1.0
            };
            out.extend([
                f64::from(f.mask),
                f64::from(f.prim),
                f64::from(id_to_i32(f.centre_prim)),
                f64::from(f.zmin),
                f64::from(f.zmax),
                centre,
            ]);
            out.extend(f.rgba.map(f64::from));
            out.push(f64::from(u8::from(f.merged)));
        }
        out
    }

    /// Per sample, the index of the fragment in front there (-1 for none):
    /// by its own depth at the sample in per-sample mode, by list order in
    /// Carpenter's.
    pub fn front(&self) -> Vec<i32> {
        self.0
            .sample_stacks
            .iter()
            .map(|s| s.first().map_or(-1, |&i| i as i32))
            .collect()
    }

    /// Per sample, how many fragments cover it.
    pub fn depth_complexity(&self) -> Vec<u32> {
        self.0
            .sample_stacks
            .iter()
            .map(|s| s.len() as u32)
            .collect()
    }

    /// The resolved colour, RGBA bytes (the frame's pixel).
    pub fn color(&self) -> Vec<u8> {
        self.0.color.to_vec()
    }

    /// The resolved coverage (covered fraction of the samples).
    pub fn coverage(&self) -> f32 {
        self.0.coverage
    }

    /// The resolved id, -1 for background.
    pub fn id(&self) -> i32 {
        id_to_i32(self.0.id)
    }

    /// The resolved window depth, 1.0 for background.
    pub fn depth(&self) -> f32 {
        self.0.depth
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On three scenes, every pixel's inspected resolve is the A-buffer's
    /// frame pixel, and that frame is the registry's `abuffer` render of
    /// the same view (the page's Compare grid), colour and ids.
    #[test]
    fn the_inspector_shows_the_registry_abuffers_frame() {
        for spec in ["gen:intersecting", "gen:cyclic", "hard:coplanar_overlaps"] {
            let mut session = Session::new();
            session.set_scene(crate::scenes::from_spec(spec).unwrap());
            session.set_size(48, 48).unwrap();
            let registry = session.render("abuffer").unwrap();
            let inspection = Inspection::record(&session, 48, false).unwrap();
            assert_eq!(inspection.frame().color, registry.frame.color, "{spec}");
            assert_eq!(inspection.frame().ids, registry.frame.ids, "{spec}");
            let mut fragments = 0;
            for p in 0..48 * 48 {
                let px = inspection.pixel(p % 48, p / 48).unwrap();
                assert_eq!(px.color, inspection.frame().color[p as usize], "{spec} {p}");
                assert_eq!(px.id, inspection.frame().ids[p as usize], "{spec} {p}");
                fragments += px.fragments.len();
            }
            assert!(fragments > 100, "{spec}: {fragments} fragments");
            let carpenter = Inspection::record(&session, 48, true).unwrap();
            assert_eq!(
                carpenter.frame().color,
                session.render("abuffer-carpenter").unwrap().frame.color,
                "{spec}"
            );
        }
    }
}
