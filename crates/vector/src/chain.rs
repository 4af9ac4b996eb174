//! Joining line pieces end to end into polylines, as pen plotters want
//! them: fewer pen lifts, and no doubled ends where pieces meet.

use std::collections::HashMap;

use crate::lines::{LineKind, Polyline};

/// End points closer than this (pixels) are the same point: the ends of
/// one intersection curve's pieces come from different triangle pairs and
/// agree only to rounding.
const JOIN: f64 = 1e-4;

/// How far (pixels) an interior point may stray from the line through its
/// neighbours and still be dropped: pieces of one intersection line come
/// from different triangle pairs' snapped planes.
const STRAIGHT: f64 = 1e-3;

/// A piece: `(x, y, depth)` at both ends, its kind and object group.
pub type Piece = ([f64; 3], [f64; 3], LineKind, u32);

/// A cell of the joining hash: its coordinates, the kind of line and the
/// object group (lines of different layers are never joined).
type Cell = (i64, i64, LineKind, u32);

/// Gives end points node ids, points within [`JOIN`] of an earlier one
/// (searched in the neighbouring cells too) taking its id.
#[derive(Default)]
struct Nodes {
    cells: HashMap<Cell, Vec<(usize, [f64; 3])>>,
    count: usize,
}

impl Nodes {
    fn id(&mut self, p: [f64; 3], kind: LineKind, group: u32) -> usize {
        let (cx, cy) = ((p[0] / JOIN).floor() as i64, (p[1] / JOIN).floor() as i64);
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = self.cells.get(&(cx + dx, cy + dy, kind, group)) {
                    for &(id, q) in list {
                        if (p[0] - q[0]).hypot(p[1] - q[1]) <= JOIN {
                            return id;
                        }
                    }
                }
            }
        }
        let id = self.count;
        self.count += 1;
        self.cells
            .entry((cx, cy, kind, group))
            .or_default()
            .push((id, p));
        id
    }
}

/// Joins pieces of one kind that share end points into polylines
/// (greedily, walking from an end of degree one where there is one), then
/// removes interior points where the line goes straight on.
pub fn join_segments(pieces: &[Piece]) -> Vec<Polyline> {
    let mut nodes = Nodes::default();
    let ends: Vec<(usize, usize)> = pieces
        .iter()
        .map(|&(a, b, kind, group)| (nodes.id(a, kind, group), nodes.id(b, kind, group)))
        .collect();
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); nodes.count];
    for (k, &(a, b)) in ends.iter().enumerate() {
        at[a].push(k);
        at[b].push(k);
    }
    let mut used = vec![false; pieces.len()];
    let mut out = Vec::new();
    // Start at ends of degree one first, so open chains are walked whole.
    let mut starts: Vec<usize> = (0..pieces.len()).collect();
    starts.sort_by_key(|&k| at[ends[k].0].len().min(at[ends[k].1].len()) != 1);
    for start in starts {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b, kind, group) = pieces[start];
        let forward = at[ends[start].0].len() == 1 || at[ends[start].1].len() != 1;
        let (first, mut end, mut node) = if forward {
            (a, b, ends[start].1)
        } else {
            (b, a, ends[start].0)
        };
        let mut points = vec![first, end];
        while let Some(&next) = at[node].iter().find(|&&k| !used[k]) {
            used[next] = true;
            let (p, q, _, _) = pieces[next];
            (end, node) = if ends[next].0 == node {
                (q, ends[next].1)
            } else {
                (p, ends[next].0)
            };
            points.push(end);
        }
        let points = straighten(points);
        out.push(Polyline {
            kind,
            group,
            points: points.iter().map(|p| (p[0], p[1])).collect(),
            depths: points.iter().map(|p| p[2]).collect(),
        });
    }
    out
}

/// Drops interior points where the polyline goes straight on: within
/// [`STRAIGHT`] of the line through their neighbours.
fn straighten(points: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    let mut out: Vec<[f64; 3]> = Vec::with_capacity(points.len());
    for p in points {
        if out.len() >= 2 {
            let (a, b) = (out[out.len() - 2], out[out.len() - 1]);
            let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            let dot = (b[0] - a[0]) * (p[0] - b[0]) + (b[1] - a[1]) * (p[1] - b[1]);
            let base = (p[0] - a[0]).hypot(p[1] - a[1]);
            let tiny = (b[0] - a[0]).hypot(b[1] - a[1]) <= JOIN;
            if tiny || (cross.abs() <= STRAIGHT * base && dot > 0.0) {
                out.pop();
            }
        }
        out.push(p);
    }
    out
}
