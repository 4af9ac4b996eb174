//! Scoring a hider's ids against the oracle's [`Reference`].

use hider_scene::NO_ID;

use crate::reference::Reference;
use crate::tolerance::WINDOW_TIE_TOLERANCE;

/// How a hider's id buffer agrees with a [`Reference`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Agreement {
    /// Pixels compared (the reference's pixel count).
    pub pixels: u64,
    /// Pixels covered in one buffer and background in the other (a missing
    /// pixel in a too-short buffer counts as one). Never excused by a tie:
    /// coverage is decided by the shared exact edge functions.
    pub coverage_mismatches: u64,
    /// Pixels covered in both whose ids differ although the reference's gap
    /// is at least the tie tolerance: real errors.
    pub wrong_ids: u64,
    /// Pixels covered in both that count as ties: within the tie tolerance
    /// for [`Reference::compare`] (any id accepted), exactly equal depths
    /// for [`Reference::compare_exact`] (the reference's lower id
    /// required).
    pub ties: u64,
    /// Ties where the hider's id differs from the reference's (a subset of
    /// [`Self::ties`]; also counted in [`Self::wrong_ids`] by
    /// [`Reference::compare_exact`]).
    pub tie_differences: u64,
    /// Pixels [`Reference::compare_exact_f32`] excused: two surfaces an
    /// `f32` window depth cannot order (not a tie), where the hider's id
    /// differs from the reference's.
    pub unresolved: u64,
    /// The first pixel `(x, y)` (row-major order) with a coverage mismatch or
    /// a wrong id.
    pub first_wrong: Option<(u32, u32)>,
}

impl Agreement {
    /// No coverage mismatch and no wrong id on a non-tie pixel.
    pub fn is_exact(&self) -> bool {
        self.coverage_mismatches == 0 && self.wrong_ids == 0
    }
}

impl std::fmt::Display for Agreement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} pixels: {} coverage mismatches, {} wrong ids, {} ties ({} differing)",
            self.pixels, self.coverage_mismatches, self.wrong_ids, self.ties, self.tie_differences
        )?;
        if self.unresolved > 0 {
            write!(f, ", {} unresolved by f32", self.unresolved)?;
        }
        if let Some((x, y)) = self.first_wrong {
            write!(f, ", first wrong at ({x}, {y})")?;
        }
        Ok(())
    }
}

/// Which pixels a comparison excuses.
#[derive(Clone, Copy)]
enum Rule {
    /// Ties by relative gap below `.0` or window gap below `.1`; any id is
    /// accepted at a tie.
    Tolerant(f64, f64),
    /// Exact ties (gap 0) need the reference's id when `.1`, else any id
    /// is accepted there; other pixels whose window gap is below `.0` are
    /// excused.
    Exact(f64, bool),
}

impl Reference {
    /// Compares a hider's id buffer (row-major, [`NO_ID`] background) with
    /// this reference. A pixel is a tie when its relative gap is below
    /// `tie_tolerance` ([`crate::DEFAULT_TIE_TOLERANCE`]) or its window-depth
    /// gap is below [`crate::WINDOW_TIE_TOLERANCE`] (what an `f32` depth
    /// buffer, the format every [`hider_scene::Frame`] stores, cannot order).
    pub fn compare(&self, ids: &[u32], tie_tolerance: f64) -> Agreement {
        self.compare_with(ids, Rule::Tolerant(tie_tolerance, WINDOW_TIE_TOLERANCE))
    }

    /// Like [`Self::compare`], but ties only by the relative gap: the
    /// stricter standard a hider with `f64` (or reversed) depth can meet even
    /// where window depth has no `f32` resolution left.
    pub fn compare_strict(&self, ids: &[u32], tie_tolerance: f64) -> Agreement {
        self.compare_with(ids, Rule::Tolerant(tie_tolerance, 0.0))
    }

    /// The standard of an exact hider: its id equals the reference's on
    /// every covered pixel, exact ties included (at an exact depth tie the
    /// lower primitive id wins, in the reference and in every exact hider).
    /// Only a rounding tie ([`Self::is_tie`] but not
    /// [`Self::is_exact_tie`]) accepts any id. Ties are counted; an exact
    /// tie where the ids differ is a wrong id.
    pub fn compare_exact(&self, ids: &[u32]) -> Agreement {
        self.compare_with(ids, Rule::Exact(0.0, true))
    }

    /// Like [`Self::compare_exact`], for an exact algorithm that keeps
    /// depth in `f32`: a pixel whose two nearest surfaces are not tied but
    /// less than [`WINDOW_TIE_TOLERANCE`] apart in window depth (what an
    /// `f32` buffer cannot order) is excused and counted in
    /// [`Agreement::unresolved`]; ties must still give the lower id.
    pub fn compare_exact_f32(&self, ids: &[u32]) -> Agreement {
        self.compare_with(ids, Rule::Exact(WINDOW_TIE_TOLERANCE, true))
    }

    /// Every pixel that is not a tie (exact or rounding) must match, with
    /// no tolerance (except pixels whose two nearest surfaces are less than
    /// `window_resolution` apart in window depth, counted in
    /// [`Agreement::unresolved`]); at a tie any id is accepted and a
    /// different one counted in [`Agreement::tie_differences`].
    ///
    /// For hostile inputs (symmetric lattices, huge offsets) where two
    /// *different* planes meet exactly at a pixel centre: a hider that
    /// evaluates each plane in `f64` sees two values that differ by
    /// rounding, and orders them by it rather than by the tie rule.
    pub fn compare_off_ties(&self, ids: &[u32], window_resolution: f64) -> Agreement {
        self.compare_with(ids, Rule::Exact(window_resolution, false))
    }

    /// Whether pixel `k` is an exact tie: covered, and its two nearest
    /// distinct primitives at exactly the same depth (`gap` and
    /// `window_gap` both 0).
    pub fn is_exact_tie(&self, k: usize) -> bool {
        self.is_tie(k) && self.window_gap.get(k) == Some(&0.0)
    }

    /// Whether pixel `k` is a tie: an exact tie, or a rounding tie (two
    /// surfaces closer in exact window depth than `f64` evaluation of their
    /// planes resolves, [`crate::plane_rounding_bound`]); `gap` is 0.
    pub fn is_tie(&self, k: usize) -> bool {
        self.ids.get(k).is_some_and(|&id| id != NO_ID) && self.gap.get(k) == Some(&0.0)
    }

    fn compare_with(&self, ids: &[u32], rule: Rule) -> Agreement {
        let mut a = Agreement {
            pixels: self.ids.len() as u64,
            ..Agreement::default()
        };
        let width = self.width.max(1) as usize;
        for (k, (&want, &gap)) in self.ids.iter().zip(&self.gap).enumerate() {
            let got = ids.get(k).copied();
            let window_gap = self.window_gap.get(k).copied().unwrap_or(f64::INFINITY);
            let (tie, excused) = match rule {
                Rule::Tolerant(tolerance, window) => {
                    let tie = gap < tolerance || window_gap < window;
                    (tie, tie)
                }
                Rule::Exact(window, ties_must_match) => {
                    // A rounding tie (gap 0, window gap not) never has to
                    // match: `f64` plane evaluation decides it.
                    let tie = gap == 0.0;
                    let exact_tie = tie && window_gap == 0.0;
                    let excused = if tie {
                        !(ties_must_match && exact_tie)
                    } else {
                        window_gap < window
                    };
                    (tie, excused)
                }
            };
            let wrong = match got {
                None => {
                    a.coverage_mismatches += 1;
                    true
                }
                Some(got) if (got == NO_ID) != (want == NO_ID) => {
                    a.coverage_mismatches += 1;
                    true
                }
                Some(got) if want == NO_ID => {
                    debug_assert_eq!(got, NO_ID);
                    false
                }
                Some(got) if tie => {
                    a.ties += 1;
                    let differs = got != want;
                    a.tie_differences += u64::from(differs);
                    let wrong = differs && !excused;
                    a.wrong_ids += u64::from(wrong);
                    wrong
                }
                Some(got) if got != want && excused => {
                    a.unresolved += 1;
                    false
                }
                Some(got) if got != want => {
                    a.wrong_ids += 1;
                    true
                }
                Some(_) => false,
            };
            if wrong && a.first_wrong.is_none() {
                a.first_wrong = Some(((k % width) as u32, (k / width) as u32));
            }
        }
        a
    }

    /// Number of covered pixels.
    pub fn covered_count(&self) -> usize {
        self.ids.iter().filter(|&&id| id != NO_ID).count()
    }

    /// Number of covered pixels that are ties in the sense of
    /// [`Self::compare`].
    pub fn tie_count(&self, tie_tolerance: f64) -> usize {
        (0..self.ids.len())
            .filter(|&k| {
                self.ids[k] != NO_ID
                    && (self.gap[k] < tie_tolerance
                        || self
                            .window_gap
                            .get(k)
                            .is_some_and(|&w| w < WINDOW_TIE_TOLERANCE))
            })
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference() -> Reference {
        Reference {
            width: 2,
            height: 2,
            ids: vec![NO_ID, 1, 2, 3],
            depth: vec![1.0, 0.5, 0.5, 0.5],
            gap: vec![f64::INFINITY, f64::INFINITY, 1e-9, 0.1],
            window_gap: vec![f64::INFINITY, f64::INFINITY, 1e-9, 1e-2],
        }
    }

    #[test]
    fn identical_ids_agree_exactly() {
        let r = reference();
        let a = r.compare(&r.ids, 1e-5);
        assert!(a.is_exact());
        assert_eq!(a.pixels, 4);
        assert_eq!(a.ties, 1);
        assert_eq!(a.tie_differences, 0);
        assert_eq!(a.first_wrong, None);
    }

    #[test]
    fn ties_are_counted_not_failed_and_errors_are_located() {
        let r = reference();
        let a = r.compare(&[NO_ID, 1, 9, 3], 1e-5);
        assert!(a.is_exact());
        assert_eq!((a.ties, a.tie_differences), (1, 1));
        let a = r.compare(&[NO_ID, 1, 2, 9], 1e-5);
        assert!(!a.is_exact());
        assert_eq!(a.wrong_ids, 1);
        assert_eq!(a.first_wrong, Some((1, 1)));
        // With a tolerance above the gap of pixel (1, 1) it is a tie.
        assert!(r.compare_strict(&[NO_ID, 1, 2, 9], 0.2).is_exact());
    }

    #[test]
    fn exact_comparison_requires_the_tie_rule() {
        let mut r = reference();
        // Pixel (0, 1) is close (1e-9) but no tie: it must match.
        let a = r.compare_exact(&[NO_ID, 1, 9, 3]);
        assert_eq!((a.wrong_ids, a.ties), (1, 0));
        // f32 cannot order a window gap of 1e-9: excused, not a tie.
        let a = r.compare_exact_f32(&[NO_ID, 1, 9, 3]);
        assert!(a.is_exact());
        assert_eq!(a.unresolved, 1);
        // An exact tie must give the reference's (lower) id.
        r.gap[2] = 0.0;
        r.window_gap[2] = 0.0;
        assert!(r.is_exact_tie(2) && !r.is_exact_tie(3));
        let a = r.compare_exact(&[NO_ID, 1, 9, 3]);
        assert_eq!((a.wrong_ids, a.ties, a.tie_differences), (1, 1, 1));
        assert!(!r.compare_exact_f32(&[NO_ID, 1, 9, 3]).is_exact());
        assert!(r.compare_exact(&r.ids).is_exact());
        // A rounding tie (gap 0, window gap not) accepts any id.
        r.window_gap[2] = 1e-17;
        assert!(r.is_tie(2) && !r.is_exact_tie(2));
        assert!(r.compare_exact(&[NO_ID, 1, 9, 3]).is_exact());
        r.window_gap[2] = 0.0;
        let a = r.compare_off_ties(&[NO_ID, 1, 9, 3], 0.0);
        assert!(a.is_exact());
        assert_eq!((a.ties, a.tie_differences), (1, 1));
        assert_eq!(r.compare_off_ties(&[NO_ID, 1, 2, 9], 0.0).wrong_ids, 1);
    }

    #[test]
    fn surfaces_an_f32_buffer_cannot_order_are_ties_unless_strict() {
        let mut r = reference();
        r.window_gap[3] = 1e-8; // below 2^-22: a tie for compare
        assert!(r.compare(&[NO_ID, 1, 2, 9], 1e-5).is_exact());
        assert_eq!(r.compare_strict(&[NO_ID, 1, 2, 9], 1e-5).wrong_ids, 1);
    }

    #[test]
    fn coverage_mismatches_and_short_buffers_are_errors() {
        let r = reference();
        let a = r.compare(&[0, 1, 2, 3], 1e-5);
        assert_eq!(a.coverage_mismatches, 1);
        assert_eq!(a.first_wrong, Some((0, 0)));
        let a = r.compare(&[NO_ID, NO_ID], 1e-5);
        assert_eq!(a.coverage_mismatches, 3);
        assert_eq!(a.first_wrong, Some((1, 0)));
    }
}
