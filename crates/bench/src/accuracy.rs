//! Scoring a frame against the exact references of `hider-oracle`: ids and
//! depth against the ray-cast [`Reference`] (pixel-centre hiders), coverage
//! against the analytic [`CoverageReference`] (multi-sample hiders).

use hider_oracle::{CoverageReference, Reference, WINDOW_TIE_TOLERANCE};
use hider_scene::{Frame, NO_ID};

/// How a pixel-centre frame compares with the oracle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IdScore {
    /// Covered in one and not the other.
    pub coverage_mismatches: u64,
    /// Covered non-tie pixels with another id than the oracle's.
    pub wrong_ids: u64,
    /// `wrong_ids` over the covered non-tie pixels (0 when there are none).
    pub wrong_fraction: f64,
    /// Covered pixels where the two nearest surfaces tie.
    pub ties: u64,
    /// Ties decided differently from the oracle.
    pub tie_differences: u64,
    /// Mean |depth - oracle depth| over pixels covered in both.
    pub depth_error_mean: f64,
    /// Largest |depth - oracle depth| over pixels covered in both.
    pub depth_error_max: f64,
}

/// Scores `frame` against `reference` with the oracle's own comparison
/// ([`Reference::compare`], so a tie here is a tie in the test suite) and
/// adds the depth error.
///
/// The depth error is measured against the oracle's window depth, which
/// comes from the exact ray-plane intersection: it shows what a depth
/// format or an interpolation mode does to the stored depth even where it
/// does not (yet) flip an id.
pub fn score_ids(reference: &Reference, frame: &Frame, tie_tolerance: f64) -> IdScore {
    let a = reference.compare(&frame.ids, tie_tolerance);
    let non_tie = (reference.covered_count() as u64).saturating_sub(a.ties);
    let (mut sum, mut max, mut n) = (0.0f64, 0.0f64, 0u64);
    for ((&id, &d), (&rid, &rd)) in frame
        .ids
        .iter()
        .zip(&frame.depth)
        .zip(reference.ids.iter().zip(&reference.depth))
    {
        if id != NO_ID && rid != NO_ID {
            let e = (f64::from(d) - f64::from(rd)).abs();
            if e.is_finite() {
                sum += e;
                max = max.max(e);
                n += 1;
            }
        }
    }
    IdScore {
        coverage_mismatches: a.coverage_mismatches,
        wrong_ids: a.wrong_ids,
        wrong_fraction: if non_tie == 0 {
            0.0
        } else {
            a.wrong_ids as f64 / non_tie as f64
        },
        ties: a.ties,
        tie_differences: a.tie_differences,
        depth_error_mean: if n == 0 { 0.0 } else { sum / n as f64 },
        depth_error_max: max,
    }
}

/// Mean absolute coverage error of a multi-sample frame, or `None` if the
/// hider wrote no coverage (then it cannot be scored as multi-sample).
pub fn score_coverage(reference: &CoverageReference, frame: &Frame) -> Option<f64> {
    if frame.coverage.len() != reference.covered.len() {
        return None;
    }
    Some(reference.mean_coverage_error(&frame.coverage))
}

/// What a pixel of a contact sheet marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mark {
    /// Agrees with the oracle (or a tie decided the same way).
    Agree,
    /// Wrong id on a non-tie pixel, or a coverage mismatch.
    Wrong,
    /// A tie decided differently (accepted, but shown).
    TieDifference,
}

/// Whether pixel `k` is a tie under the rule of [`Reference::compare`]:
/// relative gap below `tie_tolerance`, or window-depth gap below what an
/// `f32` depth buffer resolves ([`WINDOW_TIE_TOLERANCE`]).
fn is_tie(reference: &Reference, k: usize, tie_tolerance: f64) -> bool {
    reference.gap.get(k).is_some_and(|&g| g < tie_tolerance)
        || reference
            .window_gap
            .get(k)
            .is_some_and(|&w| w < WINDOW_TIE_TOLERANCE)
}

/// Per-pixel marks of `ids` against the oracle, with the same tie rule as
/// [`Reference::compare`].
pub fn marks(reference: &Reference, ids: &[u32], tie_tolerance: f64) -> Vec<Mark> {
    reference
        .ids
        .iter()
        .enumerate()
        .map(|(k, &want)| {
            let got = ids.get(k).copied().unwrap_or(NO_ID);
            if (got == NO_ID) != (want == NO_ID) {
                Mark::Wrong
            } else if got == want {
                Mark::Agree
            } else if is_tie(reference, k, tie_tolerance) {
                Mark::TieDifference
            } else {
                Mark::Wrong
            }
        })
        .collect()
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
            window_gap: vec![f64::INFINITY, f64::INFINITY, 1e-9, 0.1],
        }
    }

    #[test]
    fn ids_depth_and_marks_are_scored() {
        let r = reference();
        let mut f = Frame::new(2, 2).unwrap();
        f.ids = vec![NO_ID, 1, 9, 7];
        f.depth = vec![1.0, 0.25, 0.5, 0.5];
        let s = score_ids(&r, &f, 1e-5);
        assert_eq!((s.wrong_ids, s.ties, s.tie_differences), (1, 1, 1));
        assert_eq!(s.coverage_mismatches, 0);
        // 2 covered non-tie pixels, one wrong.
        assert_eq!(s.wrong_fraction, 0.5);
        assert_eq!(s.depth_error_max, 0.25);
        assert!((s.depth_error_mean - 0.25 / 3.0).abs() < 1e-12);
        assert_eq!(
            marks(&r, &f.ids, 1e-5),
            [Mark::Agree, Mark::Agree, Mark::TieDifference, Mark::Wrong]
        );
        f.ids = vec![0, 1, 2, 3];
        assert_eq!(score_ids(&r, &f, 1e-5).coverage_mismatches, 1);
        assert_eq!(marks(&r, &f.ids, 1e-5)[0], Mark::Wrong);
    }

    #[test]
    fn coverage_needs_the_frame_to_carry_it() {
        let c = CoverageReference {
            width: 2,
            height: 1,
            covered: vec![1.0, 0.5],
            fragments: vec![],
        };
        let mut f = Frame::new(2, 1).unwrap();
        assert_eq!(score_coverage(&c, &f), None);
        f.coverage = vec![1.0, 0.25];
        assert_eq!(score_coverage(&c, &f), Some(0.125));
    }
}
