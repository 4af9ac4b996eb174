//! Analytic per-pixel coverage: the exact area each primitive shows inside
//! each pixel square.
//!
//! This is the ground truth the anti-aliasing hiders (MSAA, the A-buffer of
//! Carpenter 1984, whose 8x4 masks scratchapixel's depth-buffer lesson
//! describes) converge to as their sample counts grow.
//!
//! Per pixel, every screen triangle whose bounding box meets the square is
//! clipped to it (convex polygon, `f64`, from the snapped fixed-point
//! corners, which are exact in `f64`). The visible part of triangle `i` is
//! its polygon minus, for every other primitive `j`, the convex region
//! where `j` is in front of it:
//!
//! `C_ij = P_j ∩ { D_j(x, y) < D_i(x, y) }`
//!
//! with `D` the window-depth planes (`z/w` is affine in window position, so
//! "in front" is a half-plane and the intersection line of two triangles is
//! straight on screen). Cutting `P_i` by that half-plane is exactly
//! "splitting intersecting triangles along their intersection line". When
//! the two planes coincide over the pixel (coplanar surfaces) the lower
//! primitive id is in front, the tie rule of the pixel-centre hiders.
//! Pieces of one clipped primitive share a plane and never hide each other.
//!
//! Cost: with `n` triangles meeting a pixel, `O(n^2)` convex subtractions,
//! each splitting the remaining pieces along a clipper's at most 7 edges;
//! fine for the small viewports of tests and the benchmark's accuracy
//! scoring, slow on purpose for anything else.

use hider_scene::{NO_ID, ScreenScene, ScreenTri};

use crate::polygon::{DUST, HalfPlane, Point, area, clip, pixel_square, subtract};

/// Coincident planes: depth differences at or below this (window depth
/// units, over the whole pixel) are a tie.
const COPLANAR: f64 = 1e-12;

/// The analytic coverage of a frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CoverageReference {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Fraction of each pixel square covered by any surface, row-major, in
    /// [0, 1].
    pub covered: Vec<f64>,
    /// `(pixel index, primitive id, visible fraction of the pixel)` for
    /// every primitive visible in a pixel, sorted by pixel then primitive.
    /// The fractions of one pixel sum to its [`Self::covered`].
    pub fragments: Vec<(u32, u32, f64)>,
}

impl CoverageReference {
    /// The fragments of pixel `(x, y)`: `(primitive, visible fraction)`.
    pub fn pixel_fragments(&self, x: u32, y: u32) -> impl Iterator<Item = (u32, f64)> + '_ {
        let k = y * self.width + x;
        let start = self.fragments.partition_point(|f| f.0 < k);
        self.fragments[start..]
            .iter()
            .take_while(move |f| f.0 == k)
            .map(|f| (f.1, f.2))
    }

    /// The primitive showing the largest area in each pixel ([`NO_ID`]
    /// where nothing is visible; the lower id on equal areas).
    pub fn dominant_ids(&self) -> Vec<u32> {
        let mut ids = vec![NO_ID; self.covered.len()];
        let mut best = vec![0.0f64; self.covered.len()];
        for &(k, prim, a) in &self.fragments {
            let k = k as usize;
            if a > best[k] {
                best[k] = a;
                ids[k] = prim;
            }
        }
        ids
    }

    /// Mean absolute difference between these coverage fractions and
    /// `other` (e.g. a hider's `Frame::coverage`) over all pixels; a
    /// missing value counts as 0 coverage.
    pub fn mean_coverage_error(&self, other: &[f32]) -> f64 {
        if self.covered.is_empty() {
            return 0.0;
        }
        let sum: f64 = self
            .covered
            .iter()
            .enumerate()
            .map(|(k, &c)| (c - other.get(k).map_or(0.0, |&o| f64::from(o))).abs())
            .sum();
        sum / self.covered.len() as f64
    }
}

/// One triangle clipped to the pixel being resolved.
struct Clipped {
    prim: u32,
    tri: usize,
    poly: Vec<Point>,
}

/// Computes the exact visible area of every primitive in every pixel. See
/// the module documentation.
pub fn analytic_coverage(scene: &ScreenScene) -> CoverageReference {
    let vp = scene.viewport;
    let (w, h) = (vp.width as usize, vp.height as usize);
    let buckets = bucket_by_pixel(scene);
    let mut covered = vec![0.0; w * h];
    let mut fragments = Vec::new();
    let mut clipped: Vec<Clipped> = Vec::new();
    let mut scratch = Vec::new();
    let mut per_prim: Vec<(u32, f64)> = Vec::new();

    for y in 0..vp.height {
        for x in 0..vp.width {
            let k = y as usize * w + x as usize;
            let candidates = &buckets.items[buckets.start[k]..buckets.start[k + 1]];
            if candidates.is_empty() {
                continue;
            }
            clipped.clear();
            for &t in candidates {
                let tri = &scene.tris[t as usize];
                if let Some(poly) = clip_to_square(tri, (x, y), &mut scratch) {
                    clipped.push(Clipped {
                        prim: tri.prim,
                        tri: t as usize,
                        poly,
                    });
                }
            }
            per_prim.clear();
            let centre = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            for i in 0..clipped.len() {
                let a = visible_area(scene, &clipped, i, centre, &mut scratch);
                if a > DUST {
                    per_prim.push((clipped[i].prim, a));
                }
            }
            per_prim.sort_by_key(|p| p.0);
            let mut total = 0.0;
            for (n, &(prim, a)) in per_prim.iter().enumerate() {
                total += a;
                match fragments.last_mut() {
                    Some((pk, pp, pa)) if n > 0 && *pk == k as u32 && *pp == prim => *pa += a,
                    _ => fragments.push((k as u32, prim, a)),
                }
            }
            covered[k] = total.min(1.0);
        }
    }
    CoverageReference {
        width: vp.width,
        height: vp.height,
        covered,
        fragments,
    }
}

/// Triangle indices per pixel whose bounding box meets the pixel square, in
/// compressed rows (`items[start[k]..start[k + 1]]` for pixel `k`).
struct Buckets {
    start: Vec<usize>,
    items: Vec<u32>,
}

/// The inclusive pixel range `(x0, y0, x1, y1)` whose squares the
/// triangle's bounding box meets with positive area, clamped to the image.
fn square_bounds(tri: &ScreenTri, width: u32, height: u32) -> Option<(u32, u32, u32, u32)> {
    let min_x = tri.v.iter().map(|p| p.x).min()?;
    let max_x = tri.v.iter().map(|p| p.x).max()?;
    let min_y = tri.v.iter().map(|p| p.y).min()?;
    let max_y = tri.v.iter().map(|p| p.y).max()?;
    let first = |m: i32| m.div_euclid(256).max(0);
    let last = |m: i32, n: u32| ((m + 255).div_euclid(256) - 1).min(n as i32 - 1);
    let (x0, x1) = (first(min_x), last(max_x, width));
    let (y0, y1) = (first(min_y), last(max_y, height));
    (x0 <= x1 && y0 <= y1).then_some((x0 as u32, y0 as u32, x1 as u32, y1 as u32))
}

fn bucket_by_pixel(scene: &ScreenScene) -> Buckets {
    let vp = scene.viewport;
    let w = vp.width as usize;
    let mut start = vec![0usize; vp.pixel_count() + 1];
    let ranges: Vec<_> = scene
        .tris
        .iter()
        .map(|t| square_bounds(t, vp.width, vp.height))
        .collect();
    for &(x0, y0, x1, y1) in ranges.iter().flatten() {
        for y in y0..=y1 {
            for x in x0..=x1 {
                start[y as usize * w + x as usize + 1] += 1;
            }
        }
    }
    for k in 1..start.len() {
        start[k] += start[k - 1];
    }
    let mut fill = start.clone();
    let mut items = vec![0u32; start[start.len() - 1]];
    for (t, r) in ranges.iter().enumerate() {
        if let Some((x0, y0, x1, y1)) = *r {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let k = y as usize * w + x as usize;
                    items[fill[k]] = t as u32;
                    fill[k] += 1;
                }
            }
        }
    }
    Buckets { start, items }
}

/// The triangle clipped to the square of pixel `(x, y)`, in coordinates
/// relative to the pixel's top-left corner (exact: snapped corners are
/// multiples of 1/256), or `None` if they do not overlap with positive
/// area. Local coordinates keep the shoelace sums small and accurate.
fn clip_to_square(
    tri: &ScreenTri,
    (x, y): (u32, u32),
    scratch: &mut Vec<Point>,
) -> Option<Vec<Point>> {
    let (ox, oy) = (f64::from(x), f64::from(y));
    let mut poly: Vec<Point> = tri
        .v
        .iter()
        .map(|p| {
            let (px, py) = p.to_pixels();
            [px - ox, py - oy]
        })
        .collect();
    let square = pixel_square(0, 0);
    let n = square.len();
    for k in 0..n {
        // The square is clockwise on screen (positive shoelace area in
        // these y-down coordinates).
        let h = HalfPlane::inside_of_edge(square[k], square[(k + 1) % n], 1.0);
        clip(&poly, h, scratch);
        std::mem::swap(&mut poly, scratch);
        if poly.is_empty() {
            return None;
        }
    }
    (area(&poly) > DUST).then_some(poly)
}

/// The area of `clipped[i]` that no other primitive hides.
fn visible_area(
    scene: &ScreenScene,
    clipped: &[Clipped],
    i: usize,
    (cx, cy): (f64, f64),
    scratch: &mut Vec<Point>,
) -> f64 {
    let me = &clipped[i];
    let di = &scene.tris[me.tri].depth;
    let mut pieces = vec![me.poly.clone()];
    for (j, other) in clipped.iter().enumerate() {
        if j == i || other.prim == me.prim {
            continue;
        }
        let dj = &scene.tris[other.tri].depth;
        // D_j - D_i as an affine function around the pixel centre.
        let a = dj.dx - di.dx;
        let b = dj.dy - di.dy;
        let c = dj.eval(cx, cy) - di.eval(cx, cy);
        let worst = c.abs() + 0.5 * (a.abs() + b.abs());
        if worst <= COPLANAR {
            // Coincident over the whole pixel: the lower id is in front
            // wherever the two overlap.
            if other.prim > me.prim {
                continue;
            }
            scratch.clear();
            scratch.extend_from_slice(&other.poly);
        } else {
            // Where D_j - D_i = c + a (u - 1/2) + b (v - 1/2) < 0 (u, v
            // local to the pixel), j is in front.
            let front = HalfPlane {
                a: -a,
                b: -b,
                c: -(c - 0.5 * a - 0.5 * b),
            };
            clip(&other.poly, front, scratch);
        }
        if area(scratch) <= DUST {
            continue;
        }
        subtract(&mut pieces, scratch);
        if pieces.is_empty() {
            return 0.0;
        }
    }
    pieces.iter().map(|p| area(p)).sum()
}
