//! The nearest and second-nearest distinct primitives at one pixel centre.

use std::cmp::Ordering;

use hider_scene::NO_ID;

/// A surface offered at a pixel centre: the screen triangle (an index into
/// `ScreenScene::tris`), its primitive and a depth key (the view depth of
/// the ray cast on source planes; unused by the exact comparison, which
/// recomputes the depth from the triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Candidate {
    pub(crate) tri: u32,
    pub(crate) prim: u32,
    pub(crate) key: f64,
}

/// The nearest and second-nearest distinct primitives at one pixel.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nearest {
    pub(crate) first: Candidate,
    pub(crate) second: Candidate,
}

const NONE: Candidate = Candidate {
    tri: u32::MAX,
    prim: NO_ID,
    key: f64::INFINITY,
};

/// No surface offered yet.
pub(crate) const EMPTY: Nearest = Nearest {
    first: NONE,
    second: NONE,
};

impl Nearest {
    /// Offers `c`; `cmp` orders two candidates' depths (`Less`: the first is
    /// nearer). At equal depth the lower primitive id is nearer: the tie
    /// rule of every exact hider (GL's LESS test drawing in id order).
    pub(crate) fn offer(
        &mut self,
        c: Candidate,
        mut cmp: impl FnMut(&Candidate, &Candidate) -> Ordering,
    ) {
        let mut nearer = |a: &Candidate, b: &Candidate| {
            b.prim == NO_ID || (cmp(a, b).then(a.prim.cmp(&b.prim)) == Ordering::Less)
        };
        if self.first.prim == NO_ID {
            self.first = c;
        } else if c.prim == self.first.prim {
            // Another piece of the winning primitive.
            if nearer(&c, &self.first) {
                self.first = c;
            }
        } else if nearer(&c, &self.first) {
            // The old winner is nearer than anything else that is not
            // `c.prim`, so it becomes the runner-up.
            self.second = self.first;
            self.first = c;
        } else if c.prim == self.second.prim {
            if nearer(&c, &self.second) {
                self.second = c;
            }
        } else if nearer(&c, &self.second) {
            self.second = c;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(key: f64, prim: u32) -> Candidate {
        Candidate {
            tri: prim,
            prim,
            key,
        }
    }

    #[test]
    fn nearest_keeps_distinct_primitives() {
        let by_key = |a: &Candidate, b: &Candidate| a.key.total_cmp(&b.key);
        let mut n = EMPTY;
        let pair = |n: &Nearest| ((n.first.key, n.first.prim), (n.second.key, n.second.prim));
        n.offer(c(2.0, 5), by_key);
        n.offer(c(1.0, 7), by_key);
        n.offer(c(1.5, 7), by_key); // farther piece of the winner
        assert_eq!(pair(&n), ((1.0, 7), (2.0, 5)));
        n.offer(c(1.8, 5), by_key); // nearer piece of the runner-up
        assert_eq!(pair(&n).1, (1.8, 5));
        n.offer(c(0.5, 5), by_key); // runner-up overtakes
        assert_eq!(pair(&n), ((0.5, 5), (1.0, 7)));
        n.offer(c(0.5, 3), by_key); // exact tie: lower id wins
        assert_eq!(pair(&n), ((0.5, 3), (0.5, 5)));
        n.offer(c(0.5, 4), by_key); // a tie with the runner-up, lower id
        assert_eq!(pair(&n), ((0.5, 3), (0.5, 4)));
    }
}
