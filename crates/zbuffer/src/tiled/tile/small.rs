//! Triangles whose box in the tile is a few pixels: a plain scan of the
//! box, for which block set-up would cost more than it saves.

use hider_geom::fixed::{SUBPIXEL_SCALE, pixel_center};

use super::super::key::DepthKey;
use super::super::raster_tri::RasterTri;
use super::TileBuf;

impl<K: DepthKey> TileBuf<K> {
    /// A triangle whose box in the tile is a few pixels: a plain scan of
    /// the box, scalar (too short to vectorise), evaluating the depth only
    /// where the edges pass.
    #[inline(always)]
    pub(super) fn small<T: RasterTri>(&mut self, tri: &T, x0: u32, y0: u32, x1: u32, y1: u32) {
        let edges = hider_geom::edge::triangle_edges(tri.v());
        let unit = i64::from(SUBPIXEL_SCALE);
        let px = i64::from(pixel_center(x0 as i32));
        let sx = edges.map(|e| e.a * unit);
        let p = tri.depth();
        let (mut inside, mut passes) = (0u32, 0u32);
        // Half-open ranges: `a..=b` loops carry an extra exhausted flag
        // (a tenth of the sphere's small-triangle instructions).
        for y in y0..y1 + 1 {
            let py = i64::from(pixel_center(y as i32));
            // Biased by one: inside iff all three are >= 0, i.e. the OR of
            // the three has no sign bit (exact; |E| < 2^50).
            let [mut e0, mut e1, mut e2] = edges.map(|e| e.eval(px, py) - 1);
            let ty = p.dy * ((f64::from(y) + 0.5) - p.y0);
            for x in x0..x1 + 1 {
                if (e0 | e1 | e2) >= 0 {
                    inside += 1;
                    let key = K::encode(p.value + p.dx * ((f64::from(x) + 0.5) - p.x0) + ty);
                    let i = self.at(x, y);
                    if key < self.keys[i] {
                        self.keys[i] = key;
                        self.ids[i] = tri.prim();
                        passes += 1;
                    }
                }
                e0 += sx[0];
                e1 += sx[1];
                e2 += sx[2];
            }
        }
        self.stats.pixels_tested += u64::from((x1 - x0 + 1) * (y1 - y0 + 1));
        self.stats.depth_tests += u64::from(inside);
        self.stats.depth_passes += u64::from(passes);
        if passes > 0 {
            self.note_passes_in_rect(x0, y0, x1, y1, passes);
        }
    }
}
