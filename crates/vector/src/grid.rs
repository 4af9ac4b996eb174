//! The integer grid the region polygons live on: the front end's 1/256
//! pixel refined by a power of two, clipped to the image, and a uniform
//! bin index that finds the triangles overlapping a box.

use hider_geom::fixed::SUBPIXEL_BITS;
use hider_scene::{Result, ScreenScene, ScreenTri};
use i_overlay::i_float::int::point::IntPoint;

pub(crate) mod bins;

pub use bins::Bins;

/// Largest coordinate the polygon library handles exactly: its own
/// float adapter scales inputs into `2^29`.
const LIMIT_BITS: u32 = 29;

/// The refined grid of one scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Grid {
    /// Bits added to the front end's 1/256 pixel.
    pub shift: u32,
    /// Image width in grid units.
    pub width: i64,
    /// Image height in grid units.
    pub height: i64,
}

impl Grid {
    /// The grid for `scene` with up to `refine_bits` extra bits: as many as
    /// fit in the library's exact range. Errors when even the plain grid
    /// does not fit (an image side over 2^21 pixels).
    pub fn for_scene(scene: &ScreenScene, refine_bits: u32) -> Result<Self> {
        let side = u64::from(scene.viewport.width.max(scene.viewport.height).max(1));
        let side_bits = 64 - (side - 1).leading_zeros();
        let room = LIMIT_BITS
            .checked_sub(side_bits + SUBPIXEL_BITS)
            .ok_or_else(|| {
                crate::render_error(format!(
                    "image side {side} pixels is too large for the exact polygon grid"
                ))
            })?;
        let shift = refine_bits.min(room);
        Ok(Self {
            shift,
            width: i64::from(scene.viewport.width) << (SUBPIXEL_BITS + shift),
            height: i64::from(scene.viewport.height) << (SUBPIXEL_BITS + shift),
        })
    }

    /// Grid units per pixel.
    pub fn units_per_pixel(&self) -> f64 {
        f64::from(1u32 << (SUBPIXEL_BITS + self.shift))
    }

    /// The centre of pixel `(i, j)` in grid units.
    pub fn pixel_centre(&self, i: u32, j: u32) -> (i64, i64) {
        let unit = 1i64 << (SUBPIXEL_BITS + self.shift);
        (
            i64::from(i) * unit + unit / 2,
            i64::from(j) * unit + unit / 2,
        )
    }

    /// A triangle's vertices in grid units (not clipped).
    pub fn tri_points(&self, tri: &ScreenTri) -> [(i64, i64); 3] {
        tri.v
            .map(|p| (i64::from(p.x) << self.shift, i64::from(p.y) << self.shift))
    }

    /// A grid point as pixels.
    pub fn to_pixels(&self, p: IntPoint) -> (f64, f64) {
        let u = self.units_per_pixel();
        (f64::from(p.x) / u, f64::from(p.y) / u)
    }

    /// Pixel coordinates as (unrounded) grid units.
    pub fn from_pixels(&self, x: f64, y: f64) -> (f64, f64) {
        let u = self.units_per_pixel();
        (x * u, y * u)
    }

    /// A triangle clipped to the image rectangle, as an integer polygon
    /// (cut points rounded to the grid); empty when nothing is left.
    /// Every cut of one edge against one side is computed from the edge's
    /// end points in a fixed order, so neighbours sharing the edge get the
    /// same point.
    pub fn clip_to_image(&self, pts: &[(i64, i64); 3]) -> Vec<IntPoint> {
        let inside = pts
            .iter()
            .all(|&(x, y)| (0..=self.width).contains(&x) && (0..=self.height).contains(&y));
        if inside {
            return pts
                .iter()
                .map(|&(x, y)| IntPoint::new(x as i32, y as i32))
                .collect();
        }
        let mut poly: Vec<(i64, i64)> = pts.to_vec();
        // (axis, bound, keep below) for the four sides of the image.
        for (axis, bound, below) in [
            (0, 0, false),
            (0, self.width, true),
            (1, 0, false),
            (1, self.height, true),
        ] {
            poly = clip_axis(&poly, axis, bound, below);
            if poly.is_empty() {
                return Vec::new();
            }
        }
        poly.dedup();
        while poly.len() > 1 && poly.first() == poly.last() {
            poly.pop();
        }
        if poly.len() < 3 {
            return Vec::new();
        }
        poly.iter()
            .map(|&(x, y)| IntPoint::new(x as i32, y as i32))
            .collect()
    }
}

/// Sutherland-Hodgman against one axis-aligned line, cut points rounded
/// to the nearest grid point.
fn clip_axis(poly: &[(i64, i64)], axis: usize, bound: i64, below: bool) -> Vec<(i64, i64)> {
    let coord = |p: (i64, i64)| if axis == 0 { p.0 } else { p.1 };
    let keep = |p: (i64, i64)| {
        if below {
            coord(p) <= bound
        } else {
            coord(p) >= bound
        }
    };
    let mut out = Vec::with_capacity(poly.len() + 2);
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        if keep(a) {
            out.push(a);
        }
        if keep(a) != keep(b) {
            // Cut in a fixed end-point order so both users of an edge agree.
            let (p, q) = if a < b { (a, b) } else { (b, a) };
            let (pc, qc) = (coord(p), coord(q));
            let (po, qo) = if axis == 0 { (p.1, q.1) } else { (p.0, q.0) };
            let num = i128::from(qo - po) * i128::from(bound - pc);
            let den = i128::from(qc - pc);
            let other = po + div_round(num, den) as i64;
            out.push(if axis == 0 {
                (bound, other)
            } else {
                (other, bound)
            });
        }
    }
    out
}

/// `num / den` rounded to the nearest integer (halves away from zero).
pub fn div_round(num: i128, den: i128) -> i128 {
    let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
    if num >= 0 {
        (2 * num + den) / (2 * den)
    } else {
        -((-2 * num + den) / (2 * den))
    }
}

/// Every triangle of `scene` clipped to the image on `grid` (empty when
/// nothing is left), and the inclusive box of each (`None` when empty):
/// what both the regions and the line drawing bin to find the triangles
/// that may cover a place.
pub type Clipped = (Vec<Vec<IntPoint>>, Vec<Option<(IntPoint, IntPoint)>>);

/// See [`Clipped`].
pub fn clip_all(scene: &ScreenScene, grid: &Grid) -> Clipped {
    let polys: Vec<Vec<IntPoint>> = scene
        .tris
        .iter()
        .map(|t| grid.clip_to_image(&grid.tri_points(t)))
        .collect();
    let boxes = polys.iter().map(bounds).collect();
    (polys, boxes)
}

/// The inclusive bounding box of a polygon, or of any points (a shape's
/// contours flattened, without collecting them).
pub fn bounds<'a>(points: impl IntoIterator<Item = &'a IntPoint>) -> Option<(IntPoint, IntPoint)> {
    let mut points = points.into_iter();
    let first = *points.next()?;
    Some(points.fold((first, first), |(lo, hi), p| {
        (
            IntPoint::new(lo.x.min(p.x), lo.y.min(p.y)),
            IntPoint::new(hi.x.max(p.x), hi.y.max(p.y)),
        )
    }))
}
