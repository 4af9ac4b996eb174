//! An optional record of every window the pixel pass looked at, each
//! polygon's class against it, and what decided it
//! ([`crate::WarnockOptions::record_classes`]), for teaching and debugging.
//!
//! The subdivision writes it as it runs: a class is recorded where the
//! loop computes it, so the record is Warnock's own reasoning, window by
//! window, including the shortcuts (a child settled empty by its parent's
//! bounding box, a child cut without a look).

use crate::classify::Class;
use crate::grid::Region;
use crate::stats::Rule;

impl Class {
    /// Every class, in the order the page and the tables list them.
    pub const ALL: [Class; 4] = [
        Class::Disjoint,
        Class::Surrounding,
        Class::Contained,
        Class::Intersecting,
    ];

    /// Its name in words.
    pub fn name(self) -> &'static str {
        match self {
            Class::Disjoint => "disjoint",
            Class::Surrounding => "surrounding",
            Class::Contained => "contained",
            Class::Intersecting => "intersecting",
        }
    }
}

/// Largest number of (window, polygon) classes kept: past it the windows
/// are still recorded, without their classes ([`WindowRecord::complete`]).
pub const MAX_CLASS_RECORDS: usize = 1 << 22;

/// How a window of the record was looked at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Look {
    /// Every candidate handed down was classified against it (then those
    /// a surrounding polygon hides everywhere were culled).
    Classified,
    /// A one-pixel window: each candidate surrounds its centre or misses it
    /// (the coverage test), and the depth test there picks the nearest.
    Sample,
    /// Not looked at: the bounding box of its parent's survivors misses it,
    /// so every candidate is disjoint (recorded as such).
    ParentBox,
    /// Not looked at: the parent's survivors' bounding box reaches only
    /// this quadrant and cannot hold all of it, so no candidate can
    /// surround it and it is cut at once (no classes).
    PassedThrough,
}

/// What became of a window.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Decided whole by this rule.
    Decided(Rule),
    /// Cut in four: several polygons reach it and no rule settles it.
    Cut,
}

/// One window of the pixel pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WindowRecord {
    /// First pixel column.
    pub x0: u32,
    /// First pixel row.
    pub y0: u32,
    /// One past the last pixel column.
    pub x1: u32,
    /// One past the last pixel row.
    pub y1: u32,
    /// Subdivision level (0 is the whole image).
    pub level: u8,
    /// How it was looked at.
    pub look: Look,
    /// What decided it.
    pub outcome: Outcome,
    /// The surrounding polygon nearest at the centre (triangle index), the
    /// one that culls what it hides, if any.
    pub front: Option<u32>,
    /// Its classes: `WindowClasses::classes[first..first + count]`.
    pub first: u32,
    /// How many classes it has.
    pub count: u32,
    /// False when the record was full and its classes were not kept.
    pub complete: bool,
}

/// One polygon's class against one window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PolygonClass {
    /// The triangle's index in the scene's triangle list (its drawing
    /// order).
    pub triangle: u32,
    /// Its relation to the window's samples.
    pub class: Class,
    /// Culled: the front surrounder is nearer at every sample of the
    /// window, so it is dropped from the window and its subwindows.
    pub hidden: bool,
}

/// The windows of one frame's pixel pass, in the order the subdivision
/// looked at them (depth first), with their polygons' classes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WindowClasses {
    /// Every window looked at or settled.
    pub windows: Vec<WindowRecord>,
    /// The classes, window after window.
    pub classes: Vec<PolygonClass>,
    /// Whether [`MAX_CLASS_RECORDS`] cut the record short.
    pub truncated: bool,
    /// Recording is on.
    pub(crate) on: bool,
    /// Where culling resumes its walk of the current window's classes.
    cursor: usize,
}

impl WindowClasses {
    /// The classes of window `w`.
    pub fn classes_of(&self, w: &WindowRecord) -> &[PolygonClass] {
        let first = w.first as usize;
        self.classes
            .get(first..first + w.count as usize)
            .unwrap_or(&[])
    }

    /// The deepest window at a level `<= level` holding pixel `(x, y)`.
    pub fn window_at(&self, x: u32, y: u32, level: u8) -> Option<usize> {
        self.windows
            .iter()
            .enumerate()
            .filter(|(_, w)| w.level <= level && (w.x0..w.x1).contains(&x))
            .filter(|(_, w)| (w.y0..w.y1).contains(&y))
            .max_by_key(|(_, w)| w.level)
            .map(|(k, _)| k)
    }

    /// Forgets the last frame; records the next one if `on`.
    pub(crate) fn reset(&mut self, on: bool) {
        self.windows.clear();
        self.classes.clear();
        self.truncated = false;
        self.on = on;
    }

    /// Opens window `r` at `level`; its classes follow. Returns its index.
    pub(crate) fn open(&mut self, r: &Region, level: usize, look: Look) -> usize {
        if !self.on {
            return usize::MAX;
        }
        self.cursor = self.classes.len();
        self.windows.push(WindowRecord {
            x0: r.u0,
            y0: r.v0,
            x1: r.u1,
            y1: r.v1,
            level: level.min(usize::from(u8::MAX)) as u8,
            look,
            outcome: Outcome::Cut,
            front: None,
            first: self.classes.len() as u32,
            count: 0,
            complete: true,
        });
        self.windows.len() - 1
    }

    /// Triangle `t` is of `class` against the window opened last.
    pub(crate) fn class(&mut self, t: u32, class: Class) {
        if !self.on {
            return;
        }
        let Some(w) = self.windows.last_mut() else {
            return;
        };
        if self.classes.len() >= MAX_CLASS_RECORDS {
            self.truncated = true;
            w.complete = false;
            return;
        }
        self.classes.push(PolygonClass {
            triangle: t,
            class,
            hidden: false,
        });
        w.count += 1;
    }

    /// The window opened last has surrounder `t` in front.
    pub(crate) fn front(&mut self, t: u32) {
        if !self.on {
            return;
        }
        if let Some(w) = self.windows.last_mut() {
            w.front = Some(t);
        }
    }

    /// Triangle `t`, classified against the window opened last, was culled
    /// behind its surrounder (culling walks the classes in order).
    pub(crate) fn hidden(&mut self, t: u32) {
        if !self.on {
            return;
        }
        while let Some(c) = self.classes.get_mut(self.cursor) {
            self.cursor += 1;
            if c.triangle == t {
                c.hidden = true;
                return;
            }
        }
    }

    /// Window `w` ended so.
    pub(crate) fn close(&mut self, w: usize, outcome: Outcome) {
        if let Some(w) = self.windows.get_mut(w) {
            w.outcome = outcome;
        }
    }

    /// Records a window settled without a look ([`Look::ParentBox`], with
    /// each of `candidates` disjoint, or [`Look::PassedThrough`]).
    pub(crate) fn unseen(&mut self, r: &Region, level: usize, look: Look, candidates: &[u32]) {
        if !self.on {
            return;
        }
        let w = self.open(r, level, look);
        let outcome = if look == Look::ParentBox {
            for &t in candidates {
                self.class(t, Class::Disjoint);
            }
            Outcome::Decided(Rule::Empty)
        } else {
            Outcome::Cut
        };
        self.close(w, outcome);
    }

    /// Bytes held (capacity).
    pub(crate) fn bytes(&self) -> usize {
        self.windows.capacity() * std::mem::size_of::<WindowRecord>()
            + self.classes.capacity() * std::mem::size_of::<PolygonClass>()
    }
}
