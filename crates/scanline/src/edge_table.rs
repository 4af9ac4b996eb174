//! The polygon table and the edge table, both bucketed by starting scan
//! line.
//!
//! Watkins (1970) keeps, for every scan line, the list of edges that start
//! on it (the *edge table*); walking down the image, those edges join the
//! *active edge list*, step their x crossing by a constant per row and leave
//! it after their last row. Polygons join and leave the set of active
//! polygons the same way. Here each edge enters the table as an exact
//! integer walker ([`crate::walker`]) already positioned on its first row.

use hider_geom::fixed::{HALF_PIXEL, SUBPIXEL_SCALE};
use hider_geom::orient2d;
use hider_scene::{Error, Result, ScreenTri};

use crate::span::{Active, Surface};
use crate::trace::EdgeRecord;
use crate::walker::Edge;

/// The hider's name, used in its error messages.
pub(crate) const NAME: &str = "scanline";

/// Largest |coordinate| accepted, in fixed-point units (2^25 = 131072
/// pixels, beyond the front end's guard band): keeps every edge-function
/// product and per-row step well inside `i64`.
const MAX_COORD: u32 = 1 << 25;

/// Largest number of triangles: polygon slots are 31-bit in the packed
/// crossing keys.
const MAX_POLYGONS: usize = (1 << 31) - 1;

/// A polygon of the polygon table.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Poly {
    /// Last row on which it is active.
    pub last_row: u32,
    /// First covered column on the current row (max of its left edges).
    pub l: i64,
    /// Last covered column on the current row (min of its right edges).
    pub r: i64,
}

/// First row whose pixel-centre y is `>= y` (fixed point).
fn first_row_at_or_below(y: i32) -> i64 {
    let scale = i64::from(SUBPIXEL_SCALE);
    (i64::from(y) - i64::from(HALF_PIXEL) + scale - 1).div_euclid(scale)
}

/// Last row whose pixel-centre y is `<= y` (fixed point).
fn last_row_at_or_above(y: i32) -> i64 {
    (i64::from(y) - i64::from(HALF_PIXEL)).div_euclid(i64::from(SUBPIXEL_SCALE))
}

/// The rows `[first, last]` of the image on which a triangle can cover a
/// pixel centre, or `None`.
fn polygon_rows(t: &ScreenTri, height: u32) -> Option<(u32, u32)> {
    let min_y = t.v.iter().map(|p| p.y).min()?;
    let max_y = t.v.iter().map(|p| p.y).max()?;
    let mut first = first_row_at_or_below(min_y);
    let last = last_row_at_or_above(max_y);
    // A horizontal top edge does not own its centres under GL's fill rule
    // (hider_geom::edge): they belong to the triangle above, so its row is
    // not this polygon's. (A horizontal bottom edge owns them.)
    let on_top = t.v.iter().filter(|p| p.y == min_y).count() == 2;
    if on_top
        && (i64::from(min_y) - i64::from(HALF_PIXEL)).rem_euclid(i64::from(SUBPIXEL_SCALE)) == 0
    {
        first += 1;
    }
    let first = first.max(0);
    let last = last.min(i64::from(height) - 1);
    (first <= last).then_some((first as u32, last as u32))
}

/// The rows of edge `from -> to` inside the polygon's rows, or `None` for a
/// horizontal edge or one crossing no row centre.
fn edge_rows(from_y: i32, to_y: i32, rows: (u32, u32)) -> Option<(u32, u32)> {
    if from_y == to_y {
        return None;
    }
    let first = first_row_at_or_below(from_y.min(to_y)).max(i64::from(rows.0));
    let last = last_row_at_or_above(from_y.max(to_y)).min(i64::from(rows.1));
    (first <= last).then_some((first as u32, last as u32))
}

/// Rejects triangles the exact arithmetic cannot take: vertices beyond
/// [`MAX_COORD`], non-positive orientation, non-finite depth planes.
fn check_triangle(k: usize, t: &ScreenTri) -> Result<()> {
    let fail = |message: String| {
        Err(Error::Render {
            hider: NAME.to_owned(),
            message: format!("triangle {k} (primitive {}): {message}", t.prim),
        })
    };
    if let Some(p) =
        t.v.iter()
            .find(|p| p.x.unsigned_abs() > MAX_COORD || p.y.unsigned_abs() > MAX_COORD)
    {
        return fail(format!(
            "vertex ({}, {}) is beyond +-{MAX_COORD} fixed-point units",
            p.x, p.y
        ));
    }
    let area = orient2d(t.v[0], t.v[1], t.v[2]);
    if area <= 0 {
        return fail(format!(
            "orientation {area} is not positive (the edge functions need positively oriented vertices)"
        ));
    }
    let d = t.depth;
    if ![d.x0, d.y0, d.value, d.dx, d.dy]
        .iter()
        .all(|v| v.is_finite())
    {
        return fail(format!("depth plane {d:?} is not finite"));
    }
    Ok(())
}

/// The polygon and edge tables of one frame, bucketed by starting row, kept
/// between frames so their memory is reused.
#[derive(Clone, Debug, Default)]
pub(crate) struct EdgeTable {
    /// The polygon table, in triangle order: a lower slot is an earlier
    /// triangle, which is what depth ties are broken by.
    pub polys: Vec<Poly>,
    /// Each polygon's depth plane and id, by slot (what the span step reads).
    pub surfaces: Vec<Surface>,
    /// Polygon slots sorted by first row (bucket `j` is
    /// `poly_order[poly_start[j]..poly_start[j + 1]]`).
    poly_order: Vec<u32>,
    poly_start: Vec<u32>,
    /// Edges sorted by first row, already positioned on it.
    edges: Vec<Edge>,
    edge_start: Vec<u32>,
}

/// Upper bound of the working bytes for `tris` triangles on a
/// `width x height` image: tables, bucket indices, the active lists (at
/// most every polygon and edge at once) and the row buffers.
pub(crate) fn table_bytes(tris: usize, width: u32, height: u32) -> u64 {
    use std::mem::size_of;
    let n = tris as u64;
    let per_polygon = size_of::<Poly>() + size_of::<Surface>() + 4 // tables + bucketed order
        + 2 * 3 * size_of::<Edge>() // edge table + active edge list
        + 4 // active polygon list
        + 2 * 8 // two crossings
        + size_of::<Active>(); // span's active polygon list
    let rows = 2 * (u64::from(height) + 1) * 4;
    let row_buffer = u64::from(width) * (8 + 4);
    n * per_polygon as u64 + rows + row_buffer
}

impl EdgeTable {
    /// Rebuilds the tables for `tris` on a `width x height` image, after
    /// checking the budget and every triangle; fills `record` with the edge
    /// table when tracing. Returns the number of (edge, row) pairs the
    /// sweep will walk.
    pub fn build(
        &mut self,
        tris: &[ScreenTri],
        height: u32,
        budget: u64,
        need: u64,
        record: Option<&mut Vec<EdgeRecord>>,
    ) -> Result<u64> {
        if tris.len() > MAX_POLYGONS {
            return Err(Error::Limit {
                what: "scanline triangles",
                value: tris.len() as u64,
                limit: MAX_POLYGONS as u64,
            });
        }
        if need > budget {
            return Err(Error::Budget {
                what: "scanline table bytes",
                value: need,
                limit: budget,
            });
        }
        let rows = height as usize;
        // Pass 1: check and count, per starting row (counting sort).
        self.poly_start.clear();
        self.poly_start.resize(rows + 1, 0);
        self.edge_start.clear();
        self.edge_start.resize(rows + 1, 0);
        let (mut polys, mut edges, mut walked) = (0usize, 0usize, 0u64);
        for (k, t) in tris.iter().enumerate() {
            check_triangle(k, t)?;
            let Some(pr) = polygon_rows(t, height) else {
                continue;
            };
            self.poly_start[pr.0 as usize + 1] += 1;
            polys += 1;
            for e in 0..3 {
                let (from, to) = (t.v[e], t.v[(e + 1) % 3]);
                if let Some(er) = edge_rows(from.y, to.y, pr) {
                    self.edge_start[er.0 as usize + 1] += 1;
                    edges += 1;
                    walked += u64::from(er.1 - er.0 + 1);
                }
            }
        }
        for j in 0..rows {
            self.poly_start[j + 1] += self.poly_start[j];
            self.edge_start[j + 1] += self.edge_start[j];
        }
        // Pass 2: fill, using the starts as moving cursors, then restore.
        self.polys.clear();
        self.polys.reserve(polys);
        self.surfaces.clear();
        self.surfaces.reserve(polys);
        self.poly_order.clear();
        self.poly_order.resize(polys, 0);
        self.edges.clear();
        self.edges.resize(edges, Edge::default());
        let mut record = record;
        if let Some(r) = record.as_deref_mut() {
            r.clear();
            r.resize(edges, EdgeRecord::default());
        }
        for (k, t) in tris.iter().enumerate() {
            let Some(pr) = polygon_rows(t, height) else {
                continue;
            };
            let slot = self.polys.len() as u32;
            self.polys.push(Poly {
                last_row: pr.1,
                l: 0,
                r: -1,
            });
            self.surfaces.push(Surface {
                plane: t.depth,
                prim: t.prim,
            });
            let cursor = &mut self.poly_start[pr.0 as usize];
            self.poly_order[*cursor as usize] = slot;
            *cursor += 1;
            let functions = t.edges();
            for (e, f) in functions.iter().enumerate() {
                let (from, to) = (t.v[e], t.v[(e + 1) % 3]);
                if let Some(er) = edge_rows(from.y, to.y, pr) {
                    let cursor = &mut self.edge_start[er.0 as usize];
                    let mut edge = Edge::start(f, slot, er.0, er.1);
                    edge.id = *cursor;
                    if let Some(r) = record.as_deref_mut() {
                        r[*cursor as usize] = EdgeRecord {
                            first_row: er.0,
                            last_row: er.1,
                            prim: t.prim,
                            triangle: k as u32,
                            side: edge.side,
                            from,
                            to,
                        };
                    }
                    self.edges[*cursor as usize] = edge;
                    *cursor += 1;
                }
            }
        }
        // Each start now holds the next bucket's start: shift back by one.
        for j in (1..=rows).rev() {
            self.poly_start[j] = self.poly_start[j - 1];
            self.edge_start[j] = self.edge_start[j - 1];
        }
        self.poly_start[0] = 0;
        self.edge_start[0] = 0;
        Ok(walked)
    }

    /// The polygons and edges starting on `row`.
    pub fn bucket(&self, row: u32) -> (&[u32], &[Edge]) {
        let j = row as usize;
        (
            &self.poly_order[self.poly_start[j] as usize..self.poly_start[j + 1] as usize],
            &self.edges[self.edge_start[j] as usize..self.edge_start[j + 1] as usize],
        )
    }

    /// Number of polygons in the table.
    pub fn polygon_count(&self) -> usize {
        self.polys.len()
    }

    /// Number of edges in the table.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Bytes held (capacity).
    pub fn bytes(&self) -> u64 {
        use std::mem::size_of;
        (self.polys.capacity() * size_of::<Poly>()
            + self.surfaces.capacity() * size_of::<Surface>()
            + (self.poly_order.capacity()
                + self.poly_start.capacity()
                + self.edge_start.capacity())
                * 4
            + self.edges.capacity() * size_of::<Edge>()) as u64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::FixedPt;

    #[test]
    fn row_ranges_follow_centres_and_the_bottom_rule() {
        assert_eq!(first_row_at_or_below(128), 0);
        assert_eq!(first_row_at_or_below(129), 1);
        assert_eq!(first_row_at_or_below(-500), -2);
        assert_eq!(last_row_at_or_above(383), 0);
        assert_eq!(last_row_at_or_above(384), 1);
        let tri = |v: [FixedPt; 3]| ScreenTri {
            v,
            z: [0.5; 3],
            w: [1.0; 3],
            depth: hider_geom::PlaneEq::constant(0.5),
            inv_w: hider_geom::PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        };
        // Bottom edge exactly on the centres of row 3: owned.
        let bottom = tri([
            FixedPt::new(128, 128),
            FixedPt::new(1000, 896),
            FixedPt::new(128, 896),
        ]);
        assert!(orient2d(bottom.v[0], bottom.v[1], bottom.v[2]) > 0);
        assert_eq!(polygon_rows(&bottom, 100), Some((0, 3)));
        // Top edge on row 0's centres: not owned.
        let top = tri([
            FixedPt::new(128, 128),
            FixedPt::new(1000, 128),
            FixedPt::new(128, 896),
        ]);
        assert!(orient2d(top.v[0], top.v[1], top.v[2]) > 0);
        assert_eq!(polygon_rows(&top, 100), Some((1, 3)));
        assert_eq!(polygon_rows(&top, 2), Some((1, 1)));
        // Between two row centres: nothing.
        let thin = tri([
            FixedPt::new(0, 130),
            FixedPt::new(1000, 140),
            FixedPt::new(0, 300),
        ]);
        assert_eq!(polygon_rows(&thin, 100), None);
    }
}
