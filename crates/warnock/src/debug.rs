//! The debug picture: the final regions of the subdivision drawn over the
//! rendered image, coloured by the rule that decided them.
//!
//! Warnock's subdivision is easiest to understand by looking at it: large
//! regions where one surface hides everything or nothing is there, ever
//! smaller ones converging on silhouettes and on lines where surfaces pierce
//! each other. Enable [`crate::WarnockOptions::record_regions`], render,
//! then draw [`crate::Warnock::leaf_regions`] with [`draw_region_outlines`].

use hider_scene::Frame;

use crate::grid::Region;
use crate::stats::Rule;

/// A final region of the pixel pass: a rectangle of pixels and the rule
/// that decided it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LeafRegion {
    /// First pixel column.
    pub x0: u32,
    /// First pixel row.
    pub y0: u32,
    /// One past the last pixel column.
    pub x1: u32,
    /// One past the last pixel row.
    pub y1: u32,
    /// Subdivision level (0 is the whole window).
    pub level: u8,
    /// What decided it.
    pub rule: Rule,
}

impl LeafRegion {
    /// The leaf for a pixel-pass region.
    pub(crate) fn new(r: &Region, rule: Rule, level: usize) -> Self {
        Self {
            x0: r.u0,
            y0: r.v0,
            x1: r.u1,
            y1: r.v1,
            level: level.min(usize::from(u8::MAX)) as u8,
            rule,
        }
    }

    /// Number of pixels.
    pub fn pixels(&self) -> u64 {
        u64::from(self.x1 - self.x0) * u64::from(self.y1 - self.y0)
    }
}

/// A region of the pixel pass that was cut in four (or, holding one
/// polygon's box only in part, handed on to its one reached quadrant):
/// more than one polygon reached it and no rule settled it whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CutRegion {
    /// First pixel column.
    pub x0: u32,
    /// First pixel row.
    pub y0: u32,
    /// One past the last pixel column.
    pub x1: u32,
    /// One past the last pixel row.
    pub y1: u32,
    /// Subdivision level (0 is the whole window).
    pub level: u8,
}

impl CutRegion {
    /// The record for a pixel-pass region.
    pub(crate) fn new(r: &Region, level: usize) -> Self {
        Self {
            x0: r.u0,
            y0: r.v0,
            x1: r.u1,
            y1: r.v1,
            level: level.min(usize::from(u8::MAX)) as u8,
        }
    }
}

/// The outline colour (sRGB) of regions decided by `rule`.
pub(crate) fn rule_color(rule: Rule) -> [u8; 3] {
    match rule {
        Rule::Empty => [90, 90, 90],
        Rule::SinglePolygon => [40, 200, 80],
        Rule::SurrounderAlone => [70, 150, 255],
        Rule::SurrounderInFront => [255, 210, 40],
        Rule::Sample => [240, 50, 40],
        Rule::PixelSubdivided => [230, 60, 220],
    }
}

/// Draws `leaves` over `frame.color`: the top and left side of each region
/// in its rule's colour (so neighbouring regions share one line), and
/// one-pixel regions tinted half-way to it, since they have no inside to
/// outline.
pub fn draw_region_outlines(frame: &mut Frame, leaves: &[LeafRegion]) {
    let (w, h) = (frame.width(), frame.height());
    for leaf in leaves {
        if leaf.x1 > w || leaf.y1 > h || leaf.x0 >= leaf.x1 || leaf.y0 >= leaf.y1 {
            continue;
        }
        let c = rule_color(leaf.rule);
        if leaf.pixels() == 1 {
            let i = frame.index(leaf.x0, leaf.y0);
            let p = &mut frame.color[i];
            for k in 0..3 {
                p[k] = ((u16::from(p[k]) + u16::from(c[k])) / 2) as u8;
            }
            continue;
        }
        let paint = |frame: &mut Frame, x: u32, y: u32| {
            let i = frame.index(x, y);
            frame.color[i] = [c[0], c[1], c[2], 255];
        };
        for x in leaf.x0..leaf.x1 {
            paint(frame, x, leaf.y0);
        }
        for y in leaf.y0..leaf.y1 {
            paint(frame, leaf.x0, y);
        }
    }
}

#[cfg(test)]
mod tests {
    use hider_scene::{Frame, Hider, PrepareOptions, View, prepare, procedural};

    use crate::{Warnock, WarnockOptions};

    #[test]
    fn the_region_record_changes_nothing_and_covers_every_level_of_every_pixel() {
        let scene = procedural::intersecting_pair();
        let (w, h) = (40, 24);
        let view = View::for_scene(&scene, w, h).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let mut plain = Frame::new(w, h).unwrap();
        let mut untraced = Warnock::new(WarnockOptions::default());
        untraced.render(&screen, &mut plain).unwrap();
        assert!(untraced.leaf_regions().is_empty() && untraced.cut_regions().is_empty());
        let mut frame = Frame::new(w, h).unwrap();
        let mut traced = Warnock::new(WarnockOptions::default().with_record_regions(true));
        traced.render(&screen, &mut frame).unwrap();
        assert_eq!(frame.ids, plain.ids);
        assert_eq!(frame.depth, plain.depth);
        assert!(!traced.cut_regions().is_empty(), "the pair needs cuts");
        // Every pixel lies in one leaf, and in one cut region per level
        // above it: the record is the whole subdivision.
        for y in 0..h {
            for x in 0..w {
                let inside = |x0: u32, y0: u32, x1: u32, y1: u32| {
                    (x0..x1).contains(&x) && (y0..y1).contains(&y)
                };
                let leaves: Vec<_> = traced
                    .leaf_regions()
                    .iter()
                    .filter(|l| inside(l.x0, l.y0, l.x1, l.y1))
                    .collect();
                assert_eq!(leaves.len(), 1, "pixel {x},{y}");
                let mut levels: Vec<u8> = traced
                    .cut_regions()
                    .iter()
                    .filter(|c| inside(c.x0, c.y0, c.x1, c.y1))
                    .map(|c| c.level)
                    .collect();
                levels.sort_unstable();
                let expected: Vec<u8> = (0..leaves[0].level).collect();
                assert_eq!(levels, expected, "pixel {x},{y}");
            }
        }
    }
}
