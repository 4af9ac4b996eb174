//! What one Warnock frame did, and how a region was decided.

use hider_scene::{HiderStats, StatsTable};

use crate::classify::Class;

/// The rule that decided a leaf region of the subdivision.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rule {
    /// No polygon reaches any sample of the region: background.
    Empty,
    /// One polygon, intersecting or contained: drawn into the region by the
    /// per-sample edge test.
    SinglePolygon,
    /// One polygon surrounds the region and no other reaches it.
    SurrounderAlone,
    /// A surrounding polygon is in front of every other polygon at every
    /// sample of the region (certified at the four corners); the others were
    /// culled.
    SurrounderInFront,
    /// Subdivided down to one sample: resolved there by the z-buffer's depth
    /// test (`LESS`, ties to the earlier primitive).
    Sample,
    /// Anti-aliased mode: a one-pixel region handed to the sub-pixel
    /// subdivision.
    PixelSubdivided,
}

impl Rule {
    /// Every rule, in the order [`WarnockStats`] reports them.
    pub const ALL: [Rule; 6] = [
        Rule::Empty,
        Rule::SinglePolygon,
        Rule::SurrounderAlone,
        Rule::SurrounderInFront,
        Rule::Sample,
        Rule::PixelSubdivided,
    ];

    /// A short name for tables.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Empty => "empty",
            Rule::SinglePolygon => "single polygon",
            Rule::SurrounderAlone => "surrounder alone",
            Rule::SurrounderInFront => "surrounder in front",
            Rule::Sample => "at sample",
            Rule::PixelSubdivided => "pixel subdivided",
        }
    }
}

/// Deepest subdivision level the statistics name: a 16384-pixel window
/// reaches pixels at level 14, and 16 x 16 samples add 4 more.
pub(crate) const MAX_LEVEL: usize = 31;

/// Work counters of one Warnock frame.
///
/// Printed (through [`HiderStats::table`]) as: regions, the four
/// classifications, the leaf regions per rule, the culls, the sample
/// resolves, list copies, regions found empty by bounds and regions passed
/// through, depth evaluations, samples, peak candidates, and then two
/// counters per subdivision level reached ("regions at level 0", ..., then
/// "candidates at level 0", ...).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WarnockStats {
    /// Regions visited (classified), in the pixel pass and, in the
    /// anti-aliased mode, inside pixels.
    pub regions: u64,
    /// Regions visited per subdivision level (index 0 is the whole window;
    /// in the anti-aliased mode the levels inside a pixel continue the
    /// pixel pass's numbering).
    pub regions_per_level: Vec<u64>,
    /// Candidates examined per subdivision level (indexed like
    /// [`Self::regions_per_level`]): classifications against a region and
    /// coverage tests at a one-sample region. Their sum is
    /// [`Self::polygons_classified`]; this is the work each level does.
    pub candidates_per_level: Vec<u64>,
    /// Polygon-against-region classifications performed.
    pub polygons_classified: u64,
    /// Classifications per relation: disjoint, surrounding, contained,
    /// intersecting.
    pub disjoint: u64,
    /// See [`Self::disjoint`].
    pub surrounding: u64,
    /// See [`Self::disjoint`].
    pub contained: u64,
    /// See [`Self::disjoint`].
    pub intersecting: u64,
    /// Leaf regions per deciding rule, indexed like [`Rule::ALL`].
    pub decided: [u64; 6],
    /// Polygons dropped from a region's list because a surrounding polygon
    /// is in front of them at every sample of it.
    pub culled_behind_surrounder: u64,
    /// Regions with a surrounding polygon that could not be certified in
    /// front of all others (planes cross, or another polygon is nearer
    /// somewhere): subdivided further.
    pub surrounder_undecided: u64,
    /// One-sample regions resolved by the depth test over their candidates
    /// (the pixel-level resolves of the pixel pass, the sample-level ones
    /// inside pixels).
    pub sample_resolves: u64,
    /// Candidate indices written into the arena: the copies of survivor
    /// lists handed to children (a list every candidate of which survives
    /// is passed through uncopied).
    pub candidates_copied: u64,
    /// Regions settled empty from their parent's survivors' bounding box,
    /// without examining a candidate: the box reaches none of their
    /// samples.
    pub empty_by_bounds: u64,
    /// Regions split without classifying their list: their parent's
    /// survivors' bounding box reaches no other quadrant and cannot hold
    /// all their samples, so nothing surrounds them and they would be split
    /// anyway (counted as visits, with no candidate examined).
    pub passed_through: u64,
    /// Depth-plane evaluations (corner tests and per-sample depths).
    pub depth_evaluations: u64,
    /// Samples written into the frame or a pixel's sample buffer.
    pub samples_written: u64,
    /// Pixels resolved again sample by sample because a primitive that
    /// may cut out (an alpha cut-out) was found visible there (the
    /// anti-aliased mode; 0 in scenes without cut-outs).
    pub cutout_pixels: u64,
    /// Triangles looked at by those pixels' searches.
    pub cutout_candidates: u64,
    /// Largest number of candidate indices held at once in the arena.
    pub peak_candidates: u64,
    /// Bytes of working memory at the peak (set-up records, arena, stack,
    /// sample buffer, region record).
    pub peak_bytes: u64,
}

impl WarnockStats {
    /// Leaf regions decided by `rule`.
    pub fn decided_by(&self, rule: Rule) -> u64 {
        self.decided[rule as usize]
    }

    /// The deepest level any region reached.
    pub fn max_level(&self) -> usize {
        self.regions_per_level.len().saturating_sub(1)
    }

    /// Counts a visit to a region at `level`.
    #[inline]
    pub(crate) fn visit(&mut self, level: usize) {
        self.regions += 1;
        if self.regions_per_level.len() <= level {
            self.regions_per_level.resize(level + 1, 0);
        }
        self.regions_per_level[level] += 1;
    }

    /// Counts `n` candidates examined at `level` (the per-level work; the
    /// relations are counted one by one by [`Self::classified`]).
    #[inline]
    pub(crate) fn examined(&mut self, level: usize, n: usize) {
        if self.candidates_per_level.len() <= level {
            self.candidates_per_level.resize(level + 1, 0);
        }
        self.candidates_per_level[level] += n as u64;
    }

    /// Counts one classification.
    #[inline]
    pub(crate) fn classified(&mut self, class: Class) {
        self.polygons_classified += 1;
        match class {
            Class::Disjoint => self.disjoint += 1,
            Class::Surrounding => self.surrounding += 1,
            Class::Contained => self.contained += 1,
            Class::Intersecting => self.intersecting += 1,
        }
    }
}

/// Names of the per-level counters in the table (`&'static` as
/// [`StatsTable`] requires).
const LEVEL_NAMES: [&str; MAX_LEVEL + 1] = [
    "regions at level 0",
    "regions at level 1",
    "regions at level 2",
    "regions at level 3",
    "regions at level 4",
    "regions at level 5",
    "regions at level 6",
    "regions at level 7",
    "regions at level 8",
    "regions at level 9",
    "regions at level 10",
    "regions at level 11",
    "regions at level 12",
    "regions at level 13",
    "regions at level 14",
    "regions at level 15",
    "regions at level 16",
    "regions at level 17",
    "regions at level 18",
    "regions at level 19",
    "regions at level 20",
    "regions at level 21",
    "regions at level 22",
    "regions at level 23",
    "regions at level 24",
    "regions at level 25",
    "regions at level 26",
    "regions at level 27",
    "regions at level 28",
    "regions at level 29",
    "regions at level 30",
    "regions at level 31",
];

/// Names of the per-level candidate counters in the table.
const CANDIDATE_LEVEL_NAMES: [&str; MAX_LEVEL + 1] = [
    "candidates at level 0",
    "candidates at level 1",
    "candidates at level 2",
    "candidates at level 3",
    "candidates at level 4",
    "candidates at level 5",
    "candidates at level 6",
    "candidates at level 7",
    "candidates at level 8",
    "candidates at level 9",
    "candidates at level 10",
    "candidates at level 11",
    "candidates at level 12",
    "candidates at level 13",
    "candidates at level 14",
    "candidates at level 15",
    "candidates at level 16",
    "candidates at level 17",
    "candidates at level 18",
    "candidates at level 19",
    "candidates at level 20",
    "candidates at level 21",
    "candidates at level 22",
    "candidates at level 23",
    "candidates at level 24",
    "candidates at level 25",
    "candidates at level 26",
    "candidates at level 27",
    "candidates at level 28",
    "candidates at level 29",
    "candidates at level 30",
    "candidates at level 31",
];

/// The table's name of the leaf-region counter of each rule.
fn decided_name(rule: Rule) -> &'static str {
    match rule {
        Rule::Empty => "decided empty",
        Rule::SinglePolygon => "decided single polygon",
        Rule::SurrounderAlone => "decided surrounder alone",
        Rule::SurrounderInFront => "decided surrounder in front",
        Rule::Sample => "decided at sample",
        Rule::PixelSubdivided => "pixels subdivided",
    }
}

/// Written out rather than declared with `hider_scene::hider_stats!`: the
/// table holds one counter per subdivision level the frame reached, a
/// number known only after the frame, and one per rule of an array field.
impl HiderStats for WarnockStats {
    fn table(&self) -> StatsTable {
        let mut counters = vec![
            ("regions", self.regions),
            ("polygons classified", self.polygons_classified),
            ("disjoint", self.disjoint),
            ("surrounding", self.surrounding),
            ("contained", self.contained),
            ("intersecting", self.intersecting),
        ];
        for rule in Rule::ALL {
            counters.push((decided_name(rule), self.decided_by(rule)));
        }
        counters.extend([
            ("culled behind surrounder", self.culled_behind_surrounder),
            ("surrounder undecided", self.surrounder_undecided),
            ("sample resolves", self.sample_resolves),
            ("candidates copied", self.candidates_copied),
            ("empty by bounds", self.empty_by_bounds),
            ("passed through", self.passed_through),
            ("depth evaluations", self.depth_evaluations),
            ("samples written", self.samples_written),
            ("peak candidates", self.peak_candidates),
        ]);
        counters.extend(
            LEVEL_NAMES
                .iter()
                .copied()
                .zip(self.regions_per_level.iter().copied()),
        );
        counters.extend(
            CANDIDATE_LEVEL_NAMES
                .iter()
                .copied()
                .zip(self.candidates_per_level.iter().copied()),
        );
        // Last, and only for frames with cut-outs: the table of every other
        // frame is the one it was.
        if self.cutout_pixels > 0 {
            counters.extend([
                ("cut-out pixels", self.cutout_pixels),
                ("cut-out candidates", self.cutout_candidates),
            ]);
        }
        StatsTable {
            counters,
            peak_bytes: self.peak_bytes,
            warnings: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The benchmark prints the counters under these names, in this order,
    /// with as many levels as the frame reached.
    #[test]
    fn the_table_keeps_the_printed_names_and_order() {
        let stats = WarnockStats {
            regions: 5,
            regions_per_level: vec![1, 4],
            candidates_per_level: vec![3, 7],
            decided: [1, 2, 3, 4, 5, 6],
            peak_bytes: 99,
            ..WarnockStats::default()
        };
        let table = stats.table();
        let names: Vec<&str> = table.counters.iter().map(|&(name, _)| name).collect();
        assert_eq!(
            names,
            [
                "regions",
                "polygons classified",
                "disjoint",
                "surrounding",
                "contained",
                "intersecting",
                "decided empty",
                "decided single polygon",
                "decided surrounder alone",
                "decided surrounder in front",
                "decided at sample",
                "pixels subdivided",
                "culled behind surrounder",
                "surrounder undecided",
                "sample resolves",
                "candidates copied",
                "empty by bounds",
                "passed through",
                "depth evaluations",
                "samples written",
                "peak candidates",
                "regions at level 0",
                "regions at level 1",
                "candidates at level 0",
                "candidates at level 1",
            ]
        );
        assert_eq!(table.counters[0], ("regions", 5));
        assert_eq!(table.counters[11], ("pixels subdivided", 6));
        assert_eq!(table.counters[22], ("regions at level 1", 4));
        assert_eq!(table.counters[24], ("candidates at level 1", 7));
        assert_eq!(table.peak_bytes, 99);
    }
}
