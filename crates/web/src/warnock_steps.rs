//! Warnock's step-through: the subdivision level by level, from the
//! regions Warnock itself records ([`WarnockOptions::record_regions`]):
//! every final window with its level and the rule that decided it.

use hider_scene::Hider;
use hider_scene::frame::id_to_i32;
use hider_warnock::{CutRegion, LeafRegion, Rule, Warnock, WarnockOptions};

use crate::session::Session;
use crate::steps::step_scene;

/// A recorded Warnock frame: its final windows and its ids.
#[derive(Clone, Debug, Default)]
pub struct WarnockSteps {
    side: u32,
    leaves: Vec<LeafRegion>,
    cuts: Vec<CutRegion>,
    ids: Vec<i32>,
    levels: usize,
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
        let mut warnock = Warnock::new(WarnockOptions::default().with_record_regions(true));
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
}
