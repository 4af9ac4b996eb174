//! Counting how a hider's frame differs from a reference, and tallying
//! those counts over the cases of a property test.

use std::sync::atomic::{AtomicU64, Ordering};

use hider_scene::{Frame, NO_ID};

use crate::reference::Reference;

/// How a frame agrees with a window-depth [`Reference`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Score {
    /// Pixels compared (the reference's pixel count).
    pub pixels: u64,
    /// Pixels covered in one and background in the other (a pixel missing
    /// from a too-short frame counts as one). Never excused by a tie.
    pub coverage_mismatches: u64,
    /// Pixels covered in both whose ids differ although the two nearest
    /// primitives are at least the tie tolerance apart: real errors.
    pub wrong_ids: u64,
    /// Covered pixels whose two nearest primitives are within the tie
    /// tolerance; any id is accepted there.
    pub ties: u64,
    /// Ties where the frame's id differs from the reference's (a subset of
    /// [`Self::ties`]).
    pub tie_differences: u64,
    /// Pixels off ties with the right id (or background in both) whose
    /// depth is not the reference's depth rounded to `f32`.
    pub depth_mismatches: u64,
    /// The first pixel `(x, y)` (row-major order) with a coverage mismatch,
    /// a wrong id or a wrong depth.
    pub first_wrong: Option<(u32, u32)>,
}

impl Score {
    /// No coverage mismatch and no wrong id off ties (depths not looked at).
    pub fn ids_exact(&self) -> bool {
        self.coverage_mismatches == 0 && self.wrong_ids == 0
    }

    /// [`Self::ids_exact`] and every depth off ties equal to the
    /// reference's.
    pub fn is_exact(&self) -> bool {
        self.ids_exact() && self.depth_mismatches == 0
    }
}

impl std::fmt::Display for Score {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} pixels: {} coverage mismatches, {} wrong ids, {} wrong depths, {} ties ({} differing)",
            self.pixels,
            self.coverage_mismatches,
            self.wrong_ids,
            self.depth_mismatches,
            self.ties,
            self.tie_differences
        )?;
        if let Some((x, y)) = self.first_wrong {
            write!(f, ", first wrong at ({x}, {y})")?;
        }
        Ok(())
    }
}

/// Scores `frame` against `reference`: a covered pixel is a tie when its
/// window-depth gap is below `tie_tolerance`.
///
/// ```
/// use hider_scene::Hider;
/// use hider_scene::procedural;
/// use hider_oracle::RayCastOracle;
/// use hider_testkit::{reference, render, score::score, screen};
///
/// let s = screen(&procedural::intersecting_pair(), 24, 24);
/// let (frame, _) = render(&mut RayCastOracle::default(), &s);
/// let result = score(&reference::pixel_centre(&s), &frame, 1e-8);
/// assert!(result.ids_exact(), "{result}");
/// ```
pub fn score(reference: &Reference, frame: &Frame, tie_tolerance: f64) -> Score {
    let mut s = Score {
        pixels: reference.ids.len() as u64,
        ..Score::default()
    };
    let width = reference.width.max(1) as usize;
    for (k, &want) in reference.ids.iter().enumerate() {
        let got = frame.ids.get(k).copied();
        let wrong = match got {
            Some(got) if (got == NO_ID) == (want == NO_ID) => {
                if reference.is_tie(k, tie_tolerance) {
                    s.ties += 1;
                    s.tie_differences += u64::from(got != want);
                    false
                } else if got != want {
                    s.wrong_ids += 1;
                    true
                } else if frame.depth[k] != reference.depth[k] as f32 {
                    s.depth_mismatches += 1;
                    true
                } else {
                    false
                }
            }
            _ => {
                s.coverage_mismatches += 1;
                true
            }
        };
        if wrong && s.first_wrong.is_none() {
            s.first_wrong = Some(((k % width) as u32, (k / width) as u32));
        }
    }
    s
}

/// Counters accumulated over a property's cases (from any thread) and
/// printed at its end.
#[derive(Debug, Default)]
pub struct Tally {
    /// Cases run.
    pub cases: AtomicU64,
    /// Frames rendered.
    pub frames: AtomicU64,
    /// Pixels compared.
    pub pixels: AtomicU64,
    /// Pixels the reference covers.
    pub covered: AtomicU64,
    /// Tie pixels met.
    pub ties: AtomicU64,
    /// Tie pixels where a hider chose another id than the reference.
    pub tie_differences: AtomicU64,
}

impl Tally {
    /// Adds `v` to `counter`.
    pub fn add(counter: &AtomicU64, v: u64) {
        counter.fetch_add(v, Ordering::Relaxed);
    }

    /// Prints the tally of `property` to standard error (shown with
    /// `--nocapture`).
    pub fn report(&self, property: &str) {
        let g = |c: &AtomicU64| c.load(Ordering::Relaxed);
        eprintln!(
            "{property}: {} cases, {} frames, {} pixels ({} covered), {} tie pixels ({} where a hider chose another id), 0 failures",
            g(&self.cases),
            g(&self.frames),
            g(&self.pixels),
            g(&self.covered),
            g(&self.ties),
            g(&self.tie_differences)
        );
    }
}
