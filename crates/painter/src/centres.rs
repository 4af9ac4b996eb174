//! Pieces that cover at most one pixel centre, ordered by what the raster
//! shows.
//!
//! The painter's raster is exact when, at every pixel centre, the pieces
//! covering it are painted far to near by their depth there: an order
//! between two pieces matters only on the centres both cover. A piece
//! that covers no centre constrains nothing, and a piece that covers one
//! centre is constrained only there, by one depth comparison per other
//! piece covering it. Newell, Newell & Sancha's tests answer a stronger
//! question (the order of the whole polygons), which for a pile of
//! sub-pixel triangles around one centre means comparing every pair whose
//! depth ranges overlap, and splitting every pair that intersects between
//! the centres: quadratic in the depth complexity. So pairs with such a
//! small piece are decided on the centre ([`centre_test`]), and the small
//! pieces still to be painted sit in a per-centre index sorted by depth
//! ([`CentreIndex`]): the one a candidate must wait for is the farthest
//! at its centre, found in logarithmic time instead of by a scan.

use std::collections::{BTreeMap, BTreeSet};

use hider_geom::Viewport;
use hider_geom::fixed::pixel_center;
use hider_scene::{ScreenScene, ScreenTri};

use crate::bins::depth_bits;
use crate::newell::CUT_MARGIN;
use crate::piece::Piece;

/// Which pixel centres a piece covers, as far as ordering cares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Centres {
    /// None at all: the piece never shows in the raster.
    None,
    /// Exactly the centre of pixel (column, row), with the window depth
    /// the raster writes there ([`depth_at`]).
    One(u32, u32, f64),
    /// Possibly several (or its box holds too many centres to count).
    Many,
}

/// Most candidate centres in a piece's box for which the covered ones are
/// counted; a larger piece is [`Centres::Many`] without looking.
const COUNTED: u64 = 4;

/// The pixel columns and rows whose centres a piece's box (widened by
/// [`CUT_MARGIN`]) may contain, clamped to the viewport; `None` if empty.
pub(crate) fn centre_box(piece: &Piece, vp: Viewport) -> Option<(u32, u32, u32, u32)> {
    let first = |m: f64| (m - CUT_MARGIN - 0.5).ceil().max(0.0);
    let last = |m: f64, n: u32| (m + CUT_MARGIN - 0.5).floor().min(f64::from(n) - 1.0);
    let (i0, i1) = (first(piece.min.x), last(piece.max.x, vp.width));
    let (j0, j1) = (first(piece.min.y), last(piece.max.y, vp.height));
    // Also false for NaN bounds.
    if !(i0 <= i1 && j0 <= j1) {
        return None;
    }
    Some((i0 as u32, i1 as u32, j0 as u32, j1 as u32))
}

/// Whether `piece` (of triangle `tri`) covers the centre of pixel `(i, j)`,
/// under the exact coverage rule it is painted with.
pub(crate) fn covers_centre(piece: &Piece, tri: &ScreenTri, (i, j): (u32, u32)) -> bool {
    piece.covers(
        tri,
        pixel_center(i as i32).into(),
        pixel_center(j as i32).into(),
    )
}

/// Which centres `piece` (of triangle `tri`) covers.
pub(crate) fn classify(piece: &Piece, tri: &ScreenTri, vp: Viewport) -> Centres {
    let Some((i0, i1, j0, j1)) = centre_box(piece, vp) else {
        return Centres::None;
    };
    if u64::from(i1 - i0 + 1) * u64::from(j1 - j0 + 1) > COUNTED {
        return Centres::Many;
    }
    let mut found = Centres::None;
    for j in j0..=j1 {
        for i in i0..=i1 {
            if covers_centre(piece, tri, (i, j)) {
                if found != Centres::None {
                    return Centres::Many;
                }
                found = Centres::One(i, j, depth_at(tri, (i, j)));
            }
        }
    }
    found
}

/// The window depth of triangle `tri` at the centre of pixel `(i, j)`, as
/// the raster writes it.
pub(crate) fn depth_at(tri: &ScreenTri, (i, j): (u32, u32)) -> f64 {
    tri.depth.eval(f64::from(i) + 0.5, f64::from(j) + 0.5)
}

/// Whether P may be painted before Q as far as the raster can tell, when
/// one of them covers at most one centre: `Some(true)` when they share no
/// centre or P is nowhere nearer on the one they share, `Some(false)` when
/// P is nearer there (Q must go first), `None` when both may cover several
/// centres (the polygon tests decide).
pub(crate) fn centre_test(
    (p, pc, pt): (&Piece, Centres, &ScreenTri),
    (q, qc, qt): (&Piece, Centres, &ScreenTri),
) -> Option<bool> {
    match (pc, qc) {
        (Centres::None, _) | (_, Centres::None) => Some(true),
        (Centres::One(i, j, zp), Centres::One(k, l, zq)) => Some((i, j) != (k, l) || zp >= zq),
        (Centres::One(i, j, zp), Centres::Many) => {
            Some(!covers_centre(q, qt, (i, j)) || zp >= depth_at(qt, (i, j)))
        }
        (Centres::Many, Centres::One(i, j, zq)) => {
            Some(!covers_centre(p, pt, (i, j)) || depth_at(pt, (i, j)) >= zq)
        }
        (Centres::Many, Centres::Many) => None,
    }
}

/// The small pieces not yet painted, by the centre they cover, each set
/// sorted by the piece's depth there (as an order-preserving bit pattern),
/// then piece index.
#[derive(Clone, Debug, Default)]
pub(crate) struct CentreIndex {
    /// Keyed by (row, column), so that a box is a range per row.
    map: BTreeMap<(u32, u32), BTreeSet<(u64, u32)>>,
}

impl CentreIndex {
    /// Empties the index.
    pub fn clear(&mut self) {
        self.map.clear();
    }

    /// Whether no piece is indexed.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Builds the index from `(centre, depth, piece)` entries at once
    /// (sorted, then bulk-loaded: no search per entry).
    pub fn build(&mut self, mut entries: Vec<((u32, u32), f64, u32)>) {
        let mut keyed: Vec<((u32, u32), (u64, u32))> = entries
            .drain(..)
            .map(|((i, j), z, id)| ((j, i), (depth_bits(z), id)))
            .collect();
        keyed.sort_unstable();
        self.map = keyed
            .chunk_by(|a, b| a.0 == b.0)
            .map(|run| (run[0].0, run.iter().map(|e| e.1).collect()))
            .collect();
    }

    /// Lists piece `id`, covering only centre `(i, j)` at depth `z`.
    pub fn insert(&mut self, (i, j): (u32, u32), z: f64, id: u32) {
        self.map
            .entry((j, i))
            .or_default()
            .insert((depth_bits(z), id));
    }

    /// Takes piece `id` out, listed with the same centre and depth.
    pub fn remove(&mut self, (i, j): (u32, u32), z: f64, id: u32) {
        if let Some(set) = self.map.get_mut(&(j, i)) {
            set.remove(&(depth_bits(z), id));
            if set.is_empty() {
                self.map.remove(&(j, i));
            }
        }
    }

    /// The piece at centre `(i, j)` farther than depth `z` (strictly),
    /// other than `id`: the farthest one, if any.
    pub fn farther_than(&self, (i, j): (u32, u32), z: f64, id: u32) -> Option<u32> {
        let bits = depth_bits(z);
        self.map
            .get(&(j, i))?
            .iter()
            .rev()
            .take_while(|&&(d, _)| d > bits)
            .find(|&&(_, q)| q != id)
            .map(|&(_, q)| q)
    }

    /// The indexed centres in columns `i0..=i1` and rows `j0..=j1`.
    pub fn occupied(
        &self,
        (i0, i1, j0, j1): (u32, u32, u32, u32),
    ) -> impl Iterator<Item = (u32, u32)> + '_ {
        (j0..=j1).flat_map(move |j| {
            self.map
                .range((j, i0)..=(j, i1))
                .map(|(&(row, col), _)| (col, row))
        })
    }
}

impl crate::order::Orderer {
    /// Classifies every piece of a new frame and builds the centre index.
    pub(crate) fn index_all(&mut self, scene: &ScreenScene) {
        self.centres.clear();
        let mut entries = Vec::new();
        for (k, piece) in self.pieces.iter().enumerate() {
            if self.hidden[k] {
                self.centres.push(Centres::None);
                continue;
            }
            let c = classify(piece, &scene.tris[piece.source as usize], scene.viewport);
            self.centres.push(c);
            if let Centres::One(i, j, z) = c {
                entries.push(((i, j), z, k as u32));
            }
        }
        self.index.build(entries);
    }

    /// Classifies piece `id` (the last one pushed) and lists it in the
    /// centre index when it covers exactly one centre.
    pub(crate) fn index_piece(&mut self, id: u32, scene: &ScreenScene) {
        let piece = &self.pieces[id as usize];
        let tri = &scene.tris[piece.source as usize];
        let centres = classify(piece, tri, scene.viewport);
        if self.centres.len() <= id as usize {
            self.centres.resize(id as usize + 1, Centres::Many);
        }
        self.centres[id as usize] = centres;
        if let Centres::One(i, j, z) = centres {
            self.index.insert((i, j), z, id);
        }
    }

    /// Takes piece `id` out of the centre index (painted or split).
    pub(crate) fn unindex(&mut self, id: u32) {
        if let Centres::One(i, j, z) = self.centres[id as usize] {
            self.index.remove((i, j), z, id);
        }
    }

    /// A small piece still to be painted that is farther than P on a
    /// centre both cover (P must wait for it), if any.
    pub(crate) fn centre_blocker(&self, p: u32, scene: &ScreenScene) -> Option<u32> {
        if self.index.is_empty() {
            return None;
        }
        let pp = &self.pieces[p as usize];
        let pt = &scene.tris[pp.source as usize];
        match self.centres[p as usize] {
            Centres::None => None,
            Centres::One(i, j, z) => self.index.farther_than((i, j), z, p),
            Centres::Many => {
                let bounds = centre_box(pp, scene.viewport)?;
                self.index
                    .occupied(bounds)
                    .filter(|&c| covers_centre(pp, pt, c))
                    .find_map(|c| self.index.farther_than(c, depth_at(pt, c), p))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::{FixedPt, PlaneEq};

    /// A triangle in 1/256 pixel units, at constant depth `z`.
    fn tri(v: [(i32, i32); 3], z: f64) -> ScreenTri {
        let v = v.map(|(x, y)| FixedPt::new(x, y));
        ScreenTri {
            v,
            z: [z; 3],
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, [z; 3]).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        }
    }

    #[test]
    fn pieces_are_classified_by_the_centres_they_cover() {
        let vp = Viewport::new(8, 8);
        // Around the centre of pixel (2, 3) = (2.5, 3.5) px: 640, 896.
        let one = tri([(600, 850), (700, 870), (630, 950)], 0.5);
        assert_eq!(
            classify(&Piece::from_tri(&one, 0), &one, vp),
            Centres::One(2, 3, 0.5)
        );
        // Between centres.
        let none = tri([(520, 520), (600, 520), (520, 600)], 0.5);
        assert_eq!(
            classify(&Piece::from_tri(&none, 0), &none, vp),
            Centres::None
        );
        // Over two centres, and a large one not counted.
        let two = tri([(100, 100), (450, 100), (100, 400)], 0.5);
        assert_eq!(classify(&Piece::from_tri(&two, 0), &two, vp), Centres::Many);
        let big = tri([(0, 0), (2048, 0), (0, 2048)], 0.5);
        assert_eq!(classify(&Piece::from_tri(&big, 0), &big, vp), Centres::Many);
        // Off screen.
        let off = tri([(-900, -900), (-700, -900), (-900, -700)], 0.5);
        assert_eq!(classify(&Piece::from_tri(&off, 0), &off, vp), Centres::None);
    }

    #[test]
    fn the_index_gives_the_farthest_other_piece_on_a_centre() {
        let mut index = CentreIndex::default();
        index.build(vec![((1, 1), 0.3, 0), ((1, 1), 0.7, 1), ((2, 1), 0.9, 2)]);
        index.insert((1, 1), 0.5, 3);
        // Piece 0 at 0.3 must wait for the farthest, piece 1 at 0.7.
        assert_eq!(index.farther_than((1, 1), 0.3, 0), Some(1));
        // The farthest waits for nobody; its own entry does not count.
        assert_eq!(index.farther_than((1, 1), 0.7, 1), None);
        index.remove((1, 1), 0.7, 1);
        assert_eq!(index.farther_than((1, 1), 0.3, 0), Some(3));
        // Equal depth is a tie, not a wait.
        assert_eq!(index.farther_than((1, 1), 0.5, 0), None);
        assert_eq!(
            index.occupied((0, 7, 0, 7)).collect::<Vec<_>>(),
            [(1, 1), (2, 1)]
        );
        assert_eq!(index.occupied((2, 7, 0, 7)).collect::<Vec<_>>(), [(2, 1)]);
    }

    #[test]
    fn pairs_with_a_small_piece_are_decided_on_its_centre() {
        let vp = Viewport::new(8, 8);
        let small = tri([(600, 850), (700, 870), (630, 950)], 0.5);
        let far = tri([(0, 0), (2048, 0), (0, 2048)], 0.8);
        let near = tri([(0, 0), (2048, 0), (0, 2048)], 0.2);
        let elsewhere = tri([(1500, 1500), (2000, 1500), (1500, 2000)], 0.2);
        let (s, f, n, e) = (
            Piece::from_tri(&small, 0),
            Piece::from_tri(&far, 1),
            Piece::from_tri(&near, 2),
            Piece::from_tri(&elsewhere, 3),
        );
        let c = |p: &Piece, t: &ScreenTri| classify(p, t, vp);
        let (cs, cf, cn, ce) = (c(&s, &small), c(&f, &far), c(&n, &near), c(&e, &elsewhere));
        assert_eq!(centre_test((&f, cf, &far), (&s, cs, &small)), Some(true));
        assert_eq!(centre_test((&s, cs, &small), (&f, cf, &far)), Some(false));
        assert_eq!(centre_test((&s, cs, &small), (&n, cn, &near)), Some(true));
        // No shared centre: either order.
        assert_eq!(
            centre_test((&s, cs, &small), (&e, ce, &elsewhere)),
            Some(true)
        );
        // Two large pieces: the polygon tests decide.
        assert_eq!(centre_test((&f, cf, &far), (&n, cn, &near)), None);
    }
}
