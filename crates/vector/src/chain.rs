//! Joining line pieces end to end into polylines, as pen plotters want
//! them: fewer pen lifts, and no doubled ends where pieces meet.

use std::collections::HashMap;

use crate::lines::{LineKind, Polyline};

/// End points closer than this (pixels) are the same point.
const JOIN: f64 = 1e-6;

fn key(p: (f64, f64)) -> (i64, i64) {
    ((p.0 / JOIN).round() as i64, (p.1 / JOIN).round() as i64)
}

/// Joins segments of one kind that share end points into polylines
/// (greedily, walking from an end of degree one where there is one), then
/// removes interior points where the line goes straight on.
pub fn join_segments(segments: &[((f64, f64), (f64, f64), LineKind)]) -> Vec<Polyline> {
    let mut at: HashMap<((i64, i64), LineKind), Vec<usize>> = HashMap::new();
    for (k, &(a, b, kind)) in segments.iter().enumerate() {
        at.entry((key(a), kind)).or_default().push(k);
        at.entry((key(b), kind)).or_default().push(k);
    }
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    // Start at ends of degree one first, so open chains are walked whole.
    let mut starts: Vec<usize> = (0..segments.len()).collect();
    starts.sort_by_key(|&k| {
        let (a, b, kind) = segments[k];
        let degree = |p| at.get(&(key(p), kind)).map_or(0, Vec::len);
        degree(a).min(degree(b)) != 1
    });
    for start in starts {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b, kind) = segments[start];
        let degree = |p| at.get(&(key(p), kind)).map_or(0, Vec::len);
        let (first, mut end) = if degree(a) == 1 || degree(b) != 1 { (a, b) } else { (b, a) };
        let mut points = vec![first, end];
        while let Some(&next) = at
            .get(&(key(end), kind))
            .and_then(|list| list.iter().find(|&&k| !used[k]))
        {
            used[next] = true;
            let (p, q, _) = segments[next];
            end = if key(p) == key(end) { q } else { p };
            points.push(end);
        }
        out.push(Polyline { kind, points: straighten(points) });
    }
    out
}

/// Drops interior points where the polyline goes straight on (collinear
/// within a relative 1e-9 of the segment lengths).
fn straighten(points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(points.len());
    for p in points {
        if out.len() >= 2 {
            let (a, b) = (out[out.len() - 2], out[out.len() - 1]);
            let cross = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
            let dot = (b.0 - a.0) * (p.0 - b.0) + (b.1 - a.1) * (p.1 - b.1);
            let scale = ((b.0 - a.0).hypot(b.1 - a.1)) * ((p.0 - b.0).hypot(p.1 - b.1));
            if cross.abs() <= 1e-9 * scale && dot > 0.0 {
                out.pop();
            }
        }
        out.push(p);
    }
    out
}
