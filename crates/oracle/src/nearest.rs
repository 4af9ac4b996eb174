//! The nearest and second-nearest distinct primitives at one pixel centre.

use hider_scene::NO_ID;

/// The nearest and second-nearest distinct primitives at one pixel, as
/// `(view depth, primitive id)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nearest {
    pub(crate) first: (f64, u32),
    pub(crate) second: (f64, u32),
}

/// No surface offered yet.
pub(crate) const EMPTY: Nearest = Nearest {
    first: (f64::INFINITY, NO_ID),
    second: (f64::INFINITY, NO_ID),
};

/// `a` is nearer than `b`: smaller depth, equal depth broken by lower id.
fn nearer(a: (f64, u32), b: (f64, u32)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

impl Nearest {
    /// Offers a surface at view depth `d` of primitive `prim`.
    pub(crate) fn offer(&mut self, d: f64, prim: u32) {
        let c = (d, prim);
        if prim == self.first.1 {
            // Another piece of the winning primitive: same plane.
            self.first.0 = self.first.0.min(d);
        } else if nearer(c, self.first) {
            // The old winner is nearer than anything else that is not
            // `prim`, so it becomes the runner-up.
            self.second = self.first;
            self.first = c;
        } else if prim == self.second.1 {
            self.second.0 = self.second.0.min(d);
        } else if nearer(c, self.second) {
            self.second = c;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_keeps_distinct_primitives() {
        let mut n = EMPTY;
        n.offer(2.0, 5);
        n.offer(1.0, 7);
        n.offer(1.5, 7); // second piece of the winner
        assert_eq!(n.first, (1.0, 7));
        assert_eq!(n.second, (2.0, 5));
        n.offer(1.8, 5); // nearer piece of the runner-up
        assert_eq!(n.second, (1.8, 5));
        n.offer(0.5, 5); // runner-up overtakes
        assert_eq!(n.first, (0.5, 5));
        assert_eq!(n.second, (1.0, 7));
        n.offer(0.5, 3); // exact tie: lower id wins
        assert_eq!(n.first, (0.5, 3));
        assert_eq!(n.second, (0.5, 5));
    }
}
