//! Warnock's step-through: the subdivision level by level, from the
//! regions Warnock itself records ([`WarnockOptions::record_regions`]):
//! every final window with its level and the rule that decided it, and
//! ([`WarnockOptions::record_classes`]) every window looked at with each
//! polygon's class against it.

use hider_scene::Hider;
use hider_scene::frame::id_to_i32;
use hider_warnock::{
    Class, CutRegion, LeafRegion, Look, Outcome, Rule, Warnock, WarnockOptions, WindowClasses,
};
use wasm_bindgen::prelude::*;

use crate::Page;
use crate::session::Session;
use crate::steps::step_scene;

/// A recorded Warnock frame: its final windows, its ids, and every window
/// looked at with its polygons' classes.
#[derive(Clone, Debug, Default)]
pub struct WarnockSteps {
    side: u32,
    leaves: Vec<LeafRegion>,
    cuts: Vec<CutRegion>,
    ids: Vec<i32>,
    levels: usize,
    classes: WindowClasses,
    /// Each triangle's primitive id and its vertices in window pixels.
    tris: Vec<(u32, [f64; 6])>,
}

/// The page's code for a rule: its position in [`Rule::ALL`] plus one (0
/// is "not decided yet").
fn code(rule: Rule) -> u8 {
    Rule::ALL.iter().position(|&r| r == rule).unwrap_or(0) as u8 + 1
}

impl WarnockSteps {
    /// Renders the session's scene and camera at `side` x `side` with
    /// Warnock recording its regions.
    pub fn record(session: &Session, side: u32) -> Result<Self, String> {
        let (screen, mut frame) = step_scene(session, side)?;
        let options = WarnockOptions::default()
            .with_record_regions(true)
            .with_record_classes(true);
        let mut warnock = Warnock::new(options);
        warnock
            .render(&screen, &mut frame)
            .map_err(|e| e.to_string())?;
        let leaves = warnock.leaf_regions().to_vec();
        let cuts = warnock.cut_regions().to_vec();
        let levels = leaves
            .iter()
            .map(|l| usize::from(l.level) + 1)
            .max()
            .unwrap_or(0);
        Ok(Self {
            side,
            leaves,
            cuts,
            ids: frame.ids.iter().map(|&id| id_to_i32(id)).collect(),
            levels,
            classes: warnock.window_classes().clone(),
            tris: (screen.tris.iter())
                .map(|t| {
                    let p = |k: usize| [f64::from(t.v[k].x), f64::from(t.v[k].y)];
                    let [a, b, c] = [p(0), p(1), p(2)];
                    let v = [a[0], a[1], b[0], b[1], c[0], c[1]].map(|v| v / 256.0);
                    (t.prim, v)
                })
                .collect(),
        })
    }

    /// The number of steps: one per subdivision level.
    pub fn len(&self) -> usize {
        self.levels
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.levels == 0
    }

    /// After step `k` (levels `0..k` decided): per pixel, the code of the
    /// rule that decided its window (1 + its index in [`Rule::ALL`]; 0 not
    /// decided yet: its window was subdivided further), plus 16 when the
    /// window was decided at level `k - 1`, this step; and the ids of the
    /// decided pixels (the frame's, -1 elsewhere).
    pub fn step(&self, k: usize) -> (Vec<u8>, Vec<i32>) {
        let w = self.side as usize;
        let mut class = vec![0u8; w * w];
        let mut ids = vec![-1; w * w];
        for l in self.leaves.iter().filter(|l| usize::from(l.level) < k) {
            let now = if usize::from(l.level) + 1 == k { 16 } else { 0 };
            for y in l.y0..l.y1 {
                for x in l.x0..l.x1 {
                    let at = y as usize * w + x as usize;
                    class[at] = code(l.rule) + now;
                    ids[at] = self.ids[at];
                }
            }
        }
        (class, ids)
    }

    /// The windows decided at levels `0..k`, `x0 y0 x1 y1` each (pixel
    /// edges, the second corner one past the last pixel).
    pub fn windows(&self, k: usize) -> Vec<u32> {
        self.leaves
            .iter()
            .filter(|l| usize::from(l.level) < k)
            .flat_map(|l| [l.x0, l.y0, l.x1, l.y1])
            .collect()
    }

    /// The windows cut at step `k` (level `k - 1`): several polygons reach
    /// them and no rule settles them whole; `x0 y0 x1 y1` each.
    pub fn cuts(&self, k: usize) -> Vec<u32> {
        self.cuts
            .iter()
            .filter(|c| usize::from(c.level) + 1 == k)
            .flat_map(|c| [c.x0, c.y0, c.x1, c.y1])
            .collect()
    }

    /// Per rule, how many windows it decided at levels `0..k` and their
    /// pixels, one `rule<TAB>windows<TAB>pixels` a line.
    pub fn counts(&self, k: usize) -> String {
        Rule::ALL
            .iter()
            .map(|&rule| {
                let of: Vec<_> = self
                    .leaves
                    .iter()
                    .filter(|l| l.rule == rule && usize::from(l.level) < k)
                    .collect();
                let pixels: u64 = of.iter().map(|l| l.pixels()).sum();
                format!("{}\t{}\t{pixels}", rule.name(), of.len())
            })
            .collect::<Vec<_>>()
            .join("\n")
    }
}

/// Numbers per window in [`WarnockSteps::window`].
pub const WINDOW_STRIDE: usize = 11;
/// Numbers per polygon in [`WarnockSteps::window_classes`].
pub const CLASS_STRIDE: usize = 5;

/// The page's code for a look: its position in this list.
const LOOKS: [Look; 4] = [
    Look::Classified,
    Look::Sample,
    Look::ParentBox,
    Look::PassedThrough,
];

impl WarnockSteps {
    /// The window to show for pixel `(x, y)` after step `k`: the one of
    /// level `k - 1` holding it, or its final window if that was decided
    /// at a lower level. `None` at step 0 or outside the image.
    pub fn window_at(&self, k: usize, x: u32, y: u32) -> Option<usize> {
        let level = u8::try_from(k.checked_sub(1)?).unwrap_or(u8::MAX);
        self.classes.window_at(x, y, level)
    }

    /// Window `w`, [`WINDOW_STRIDE`] numbers: `x0 y0 x1 y1` (pixel edges),
    /// level, look (0 classified, 1 one-pixel sample, 2 settled by the
    /// parent's bounding box, 3 cut without a look), outcome (0 cut, else
    /// the rule's code as in [`Self::step`]), front surrounder's triangle
    /// (-1 none), classes recorded, 1 if complete, polygons culled behind
    /// the surrounder. Empty for no such window.
    pub fn window(&self, w: usize) -> Vec<f64> {
        let Some(r) = self.classes.windows.get(w) else {
            return Vec::new();
        };
        let classes = self.classes.classes_of(r);
        let outcome = match r.outcome {
            Outcome::Cut => 0,
            Outcome::Decided(rule) => code(rule),
        };
        let look = LOOKS.iter().position(|&l| l == r.look).unwrap_or(0);
        vec![
            f64::from(r.x0),
            f64::from(r.y0),
            f64::from(r.x1),
            f64::from(r.y1),
            f64::from(r.level),
            look as f64,
            f64::from(outcome),
            r.front.map_or(-1.0, f64::from),
            classes.len() as f64,
            f64::from(u8::from(r.complete)),
            classes.iter().filter(|c| c.hidden).count() as f64,
        ]
    }

    /// Why window `w` ended as it did, in words.
    pub fn window_text(&self, w: usize) -> String {
        let Some(r) = self.classes.windows.get(w) else {
            return String::new();
        };
        let classes = self.classes.classes_of(r);
        let live = classes
            .iter()
            .filter(|c| c.class != Class::Disjoint && !c.hidden)
            .count();
        let looked = match r.look {
            Look::Classified => format!(
                "{} polygons handed down and classified against the window",
                classes.len()
            ),
            Look::Sample => format!(
                "one pixel: each of the {} polygons handed down covers its centre (surrounding) or not (disjoint)",
                classes.len()
            ),
            Look::ParentBox => format!(
                "not looked at: the bounding box of the parent's {} survivors misses it, so each is disjoint",
                classes.len()
            ),
            Look::PassedThrough => "not looked at: the parent's survivors' bounding box reaches only this quadrant and cannot hold it whole, so nothing can surround it".to_owned(),
        };
        let why = match r.outcome {
            Outcome::Cut if r.look == Look::PassedThrough => {
                "cut in four at once, its list handed down unread".to_owned()
            }
            Outcome::Cut => format!(
                "subdivided: {live} polygons still reach it and no rule settles it"
            ),
            Outcome::Decided(Rule::Empty) => "decided empty: no polygon reaches it".to_owned(),
            Outcome::Decided(Rule::SinglePolygon) => {
                "decided: a single polygon inside or intersecting it, drawn by the edge test"
                    .to_owned()
            }
            Outcome::Decided(Rule::SurrounderAlone) => {
                "decided: one polygon surrounds it, alone".to_owned()
            }
            Outcome::Decided(Rule::SurrounderInFront) => {
                "decided: a surrounding polygon in front of all others (they are culled, hidden at every sample)".to_owned()
            }
            Outcome::Decided(Rule::Sample) => {
                "decided at pixel size: the depth test at its centre among the covering polygons"
                    .to_owned()
            }
            Outcome::Decided(rule) => format!("decided: {}", rule.name()),
        };
        let full = if r.complete {
            ""
        } else {
            " (the record was full: classes not kept)"
        };
        format!(
            "window {}-{} x {}-{}, level {}: {looked}; {why}{full}",
            r.x0, r.x1, r.y0, r.y1, r.level
        )
    }

    /// Window `w`'s polygons, [`CLASS_STRIDE`] numbers each: triangle,
    /// primitive, class (its index in [`Class::ALL`]: 0 disjoint, 1
    /// surrounding, 2 contained, 3 intersecting), 1 if culled behind the
    /// front surrounder, 1 if it is the front surrounder.
    pub fn window_classes(&self, w: usize) -> Vec<f64> {
        let Some(r) = self.classes.windows.get(w) else {
            return Vec::new();
        };
        (self.classes.classes_of(r).iter())
            .flat_map(|c| {
                let class = Class::ALL.iter().position(|&k| k == c.class).unwrap_or(0);
                let prim = self.tris.get(c.triangle as usize).map_or(0, |t| t.0);
                [
                    f64::from(c.triangle),
                    f64::from(prim),
                    class as f64,
                    f64::from(u8::from(c.hidden)),
                    f64::from(u8::from(r.front == Some(c.triangle))),
                ]
            })
            .collect()
    }

    /// The outlines of window `w`'s polygons in the order of
    /// [`Self::window_classes`], six numbers each (three vertices, window
    /// pixels).
    pub fn window_outlines(&self, w: usize) -> Vec<f64> {
        let Some(r) = self.classes.windows.get(w) else {
            return Vec::new();
        };
        (self.classes.classes_of(r).iter())
            .flat_map(|c| self.tris.get(c.triangle as usize).map_or([0.0; 6], |t| t.1))
            .collect()
    }
}

#[wasm_bindgen]
impl Page {
    /// The window shown for pixel `(x, y)` after step `k` of Warnock's
    /// record (the one at level `k - 1` holding it, or its final window),
    /// or -1.
    pub fn warnock_window_at(&self, k: usize, x: u32, y: u32) -> i32 {
        (self.warnock.window_at(k, x, y)).map_or(-1, |w| i32::try_from(w).unwrap_or(-1))
    }

    /// Window `w`: 11 numbers (see `WarnockSteps::window`).
    pub fn warnock_window(&self, w: usize) -> Vec<f64> {
        self.warnock.window(w)
    }

    /// Why window `w` ended as it did, in words.
    pub fn warnock_window_text(&self, w: usize) -> String {
        self.warnock.window_text(w)
    }

    /// Window `w`'s polygons and their classes, 5 numbers each (see
    /// `WarnockSteps::window_classes`).
    pub fn warnock_window_classes(&self, w: usize) -> Vec<f64> {
        self.warnock.window_classes(w)
    }

    /// Window `w`'s polygons' outlines, 6 numbers each.
    pub fn warnock_window_outlines(&self, w: usize) -> Vec<f64> {
        self.warnock.window_outlines(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_windows_tile_the_frame_and_the_last_step_is_warnocks_frame() {
        for spec in ["gen:cyclic", "gen:intersecting", "gen:soup:80"] {
            let mut session = Session::new();
            session.set_scene(crate::scenes::from_spec(spec).unwrap());
            session.set_size(48, 48).unwrap();
            let steps = WarnockSteps::record(&session, 48).unwrap();
            // Recording the regions changes nothing in the frame.
            assert_eq!(
                steps.ids,
                session.render("warnock").unwrap().ids(),
                "{spec}"
            );
            // Every pixel lies in exactly one final window.
            let mut seen = vec![0u32; 48 * 48];
            for l in &steps.leaves {
                for y in l.y0..l.y1 {
                    for x in l.x0..l.x1 {
                        seen[(y * 48 + x) as usize] += 1;
                    }
                }
            }
            assert!(seen.iter().all(|&n| n == 1), "{spec}");
            let (class, ids) = steps.step(steps.len());
            assert!(class.iter().all(|&c| c > 0), "{spec}");
            assert_eq!(ids, steps.ids, "{spec}");
            assert!(steps.step(0).0.iter().all(|&c| c == 0));
            assert!(steps.len() > 1, "{spec}: one level");
            // Step k's undecided pixels are exactly those of the windows
            // cut at level k - 1.
            for k in 1..steps.len() {
                let mut cut = vec![false; 48 * 48];
                for c in steps.cuts(k).chunks(4) {
                    for y in c[1]..c[3] {
                        for x in c[0]..c[2] {
                            cut[(y * 48 + x) as usize] = true;
                        }
                    }
                }
                let (class, _) = steps.step(k);
                assert!(
                    class.iter().zip(&cut).all(|(&c, &u)| (c == 0) == u),
                    "{spec} {k}"
                );
            }
        }
        assert!(WarnockSteps::record(&Session::new(), 500).is_err());
    }

    #[test]
    fn a_clicked_window_lists_its_polygons_classes() {
        let mut session = Session::new();
        session.set_scene(crate::scenes::from_spec("gen:intersecting").unwrap());
        session.set_size(48, 48).unwrap();
        let steps = WarnockSteps::record(&session, 48).unwrap();
        assert_eq!(steps.window_at(0, 10, 10), None);
        // Step 1 shows the whole image: every triangle is classified.
        let root = steps.window_at(1, 10, 10).unwrap();
        let w = steps.window(root);
        assert_eq!(w.len(), WINDOW_STRIDE);
        assert_eq!((w[0], w[1], w[2], w[3], w[4]), (0.0, 0.0, 48.0, 48.0, 0.0));
        let classes = steps.window_classes(root);
        assert_eq!(classes.len(), steps.tris.len() * CLASS_STRIDE);
        assert_eq!(steps.window_outlines(root).len(), steps.tris.len() * 6);
        assert!(steps.window_text(root).contains("subdivided"));
        // At the last step every pixel's window is its final one, whose
        // rule is the one the step shows there.
        let last = steps.len();
        let (class, _) = steps.step(last);
        for (x, y) in [(0, 0), (24, 24), (30, 10), (47, 47)] {
            let k = steps.window_at(last, x, y).unwrap();
            let w = steps.window(k);
            assert!(w[0] <= f64::from(x) && f64::from(x) < w[2]);
            assert_eq!(
                w[6],
                f64::from(class[(y * 48 + x) as usize] & 15),
                "{x},{y}"
            );
        }
    }
}
