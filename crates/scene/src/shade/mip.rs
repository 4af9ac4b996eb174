//! Mip levels: a texture seen from far away is sampled from a smaller
//! copy of itself whose texels are about one pixel on screen.
//!
//! **The chain.** Level 0 is the image. Level k + 1 is level k halved in
//! each direction, rounding up (`max(1, ceil(n / 2))`): each of its texels
//! is the box-filtered mean of a 2 x 2 block of level k, the colour
//! averaged in linear light (then rounded to the nearest sRGB byte in
//! linear light) and the alpha averaged as it is stored (rounded half up).
//! An odd level's last row or column is paired with itself. The chain runs
//! down to 1 x 1. Each level is a function of level 0 alone, whichever
//! level a texture was decoded down to.
//!
//! **Decoding to a level.** The image's rows stream through a cascade of
//! one pending row per level (a cascade), so decoding down to level `b`
//! keeps levels `b` and coarser only: an 8000 x 8000 texture on a 64-pixel
//! triangle holds its 125 x 125 level and smaller, never the full image
//! (for PNG files, which are read row by row; other formats are decoded
//! whole first).
//!
//! **The level a sample reads** (GL's `LINEAR_MIPMAP_NEAREST` rule): from
//! the footprint of one pixel in level-0 texels, `rho`, the larger of the
//! lengths of the texture coordinates' derivatives along x and y (finite
//! differences one pixel apart, through the same perspective-correct
//! mapping as the sample itself), the level is `round(log2(rho))`, clamped
//! to the chain; within it the sample is filtered as asked (bilinear by
//! default). A footprint of a texel or less reads level 0.

use super::texture::{linear_table, srgb_to_linear};

/// One level of a texture: sRGB bytes (a texel's 3 together, top row
/// first: one bounds check a texel in the fetch) and, when the image has
/// an alpha channel, one alpha byte per texel.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Level {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) rgb: Vec<[u8; 3]>,
    pub(crate) alpha: Option<Vec<u8>>,
}

impl Level {
    fn empty(width: u32, height: u32, alpha: bool) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            rgb: Vec::with_capacity(n),
            alpha: alpha.then(|| Vec::with_capacity(n)),
        }
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        3 * self.rgb.len() + self.alpha.as_ref().map_or(0, Vec::len)
    }
}

/// The side of level `k + 1` given level `k`'s.
pub(crate) fn halve(n: u32) -> u32 {
    n.div_ceil(2).max(1)
}

/// Number of levels of a `width x height` chain (down to 1 x 1).
pub(crate) fn level_count(width: u32, height: u32) -> u32 {
    let (mut w, mut h, mut n) = (width, height, 1);
    while w > 1 || h > 1 {
        (w, h, n) = (halve(w), halve(h), n + 1);
    }
    n
}

/// Bytes of levels `base` and coarser of a `width x height` chain with
/// `per_texel` bytes per texel: what decoding down to `base` holds.
pub(crate) fn chain_bytes(width: u32, height: u32, base: u32, per_texel: u64) -> u64 {
    let (mut w, mut h) = (width, height);
    let mut total = 0;
    for k in 0..level_count(width, height) {
        if k >= base {
            total += u64::from(w) * u64::from(h) * per_texel;
        }
        (w, h) = (halve(w), halve(h));
    }
    total
}

/// The level a pixel whose footprint is `rho` level-0 texels reads, in a
/// chain of `levels` levels (see the module documentation).
pub(crate) fn level_for(rho: f64, levels: u32) -> u32 {
    if rho.is_nan() || rho <= 1.0 {
        return 0;
    }
    let lod = rho.log2().round();
    if lod >= f64::from(levels - 1) {
        levels - 1
    } else {
        lod as u32
    }
}

/// [`level_for`] of the footprint whose square is `rho2`, without the
/// square root and the logarithm: `round(log2 rho)` is
/// `floor(log2(2 rho^2) / 2)`, and `floor(log2 x)` of a finite positive
/// `x` is its binary exponent. The same level as [`level_for`] except
/// where `rho` is within rounding of a boundary `2^(k + 1/2)`.
#[inline]
pub(crate) fn level_for_squared(rho2: f64, levels: u32) -> u32 {
    if rho2.is_nan() || rho2 <= 1.0 {
        return 0;
    }
    let x = 2.0 * rho2;
    if !x.is_finite() {
        return levels - 1;
    }
    // x > 2: a normal number, whose biased exponent is at least 1024.
    let exponent = ((x.to_bits() >> 52) & 0x7ff) as u32 - 1023;
    (exponent / 2).min(levels - 1)
}

/// Encodes a linear value as its nearest sRGB byte (nearest in linear light): the
/// first code whose midpoint with the next code is at or above the value.
/// A table of 4096 buckets gives the first candidate, a short walk (sRGB is
/// steep only near black) the answer: the same byte as a search of the
/// midpoints, several times faster.
struct Encoder {
    mid: [f32; 255],
    start: [u8; Encoder::BUCKETS],
}

impl Encoder {
    const BUCKETS: usize = 4096;

    #[inline]
    fn encode(&self, value: f32) -> u8 {
        if value.is_nan() || value <= 0.0 {
            return 0;
        }
        let bucket = ((value * Self::BUCKETS as f32) as usize).min(Self::BUCKETS - 1);
        let mut c = usize::from(self.start[bucket]);
        while c < 255 && self.mid[c] < value {
            c += 1;
        }
        c as u8
    }
}

/// The encoder's tables, built once.
fn encoder() -> &'static Encoder {
    static TABLES: std::sync::OnceLock<Encoder> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let mid: [f32; 255] =
            std::array::from_fn(|k| 0.5 * (srgb_to_linear(k as u8) + srgb_to_linear(k as u8 + 1)));
        let start = std::array::from_fn(|b| {
            let low = b as f32 / Encoder::BUCKETS as f32;
            mid.partition_point(|&m| m < low) as u8
        });
        Encoder { mid, start }
    })
}

/// A level-k row being halved: the pending row of each level.
struct Pending {
    rgb: Vec<[u8; 3]>,
    alpha: Option<Vec<u8>>,
}

/// Streams level-0 rows into the levels at and below `base`.
pub(crate) struct Cascade {
    base: u32,
    widths: Vec<u32>,
    pending: Vec<Option<Pending>>,
    /// Levels `base..`, filled row by row.
    levels: Vec<Level>,
    alpha: bool,
}

impl Cascade {
    /// A cascade for a `width x height` image (with an alpha channel when
    /// `alpha`) keeping levels `base` and coarser (`base` is clamped to the
    /// chain).
    pub(crate) fn new(width: u32, height: u32, base: u32, alpha: bool) -> Self {
        let count = level_count(width, height);
        let base = base.min(count - 1);
        let (mut w, mut h) = (width, height);
        let mut widths = Vec::new();
        let mut levels = Vec::new();
        for k in 0..count {
            widths.push(w);
            if k >= base {
                levels.push(Level::empty(w, h, alpha));
            }
            (w, h) = (halve(w), halve(h));
        }
        Self {
            base,
            widths,
            pending: (0..count).map(|_| None).collect(),
            levels,
            alpha,
        }
    }

    /// Offers the next level-0 row: sRGB bytes, 3 per texel, and the alpha
    /// bytes when the image has alpha.
    pub(crate) fn push(&mut self, rgb: &[u8], alpha: Option<&[u8]>) {
        let texels = rgb.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        self.push_at(0, texels, alpha.map(<[u8]>::to_vec));
    }

    fn push_at(&mut self, k: usize, rgb: Vec<[u8; 3]>, alpha: Option<Vec<u8>>) {
        if k >= self.base as usize {
            let level = &mut self.levels[k - self.base as usize];
            level.rgb.extend_from_slice(&rgb);
            if let (Some(a), Some(row)) = (&mut level.alpha, &alpha) {
                a.extend_from_slice(row);
            }
        }
        if k + 1 >= self.widths.len() {
            return;
        }
        match self.pending[k].take() {
            None => self.pending[k] = Some(Pending { rgb, alpha }),
            Some(above) => {
                let (r, a) = self.halve_rows(k, &above, &Pending { rgb, alpha });
                self.push_at(k + 1, r, a);
            }
        }
    }

    /// One row of level `k + 1` from two rows of level `k`.
    fn halve_rows(
        &self,
        k: usize,
        top: &Pending,
        bottom: &Pending,
    ) -> (Vec<[u8; 3]>, Option<Vec<u8>>) {
        let w = self.widths[k] as usize;
        let half = self.widths[k + 1] as usize;
        let (lut, enc) = (linear_table(), encoder());
        let mut rgb = Vec::with_capacity(half);
        for x in 0..half {
            let (x0, x1) = (2 * x, (2 * x + 1).min(w - 1));
            rgb.push(std::array::from_fn(|c| {
                let at = |row: &[[u8; 3]], k: usize| lut[usize::from(row[k][c])];
                let sum = at(&top.rgb, x0) + at(&top.rgb, x1) + at(&bottom.rgb, x0);
                enc.encode(0.25 * (sum + at(&bottom.rgb, x1)))
            }));
        }
        let alpha = match (&top.alpha, &bottom.alpha) {
            (Some(a), Some(b)) => Some(
                (0..half)
                    .map(|x| {
                        let (x0, x1) = (2 * x, (2 * x + 1).min(w - 1));
                        let sum = u32::from(a[x0]) + u32::from(a[x1]) + u32::from(b[x0]);
                        ((sum + u32::from(b[x1]) + 2) / 4) as u8
                    })
                    .collect(),
            ),
            _ => None,
        };
        (rgb, alpha)
    }

    /// The levels kept, once every level-0 row was pushed: an odd level's
    /// last row is halved with itself.
    pub(crate) fn finish(mut self) -> Vec<Level> {
        for k in 0..self.pending.len() {
            if let Some(last) = self.pending[k].take() {
                let (r, a) = self.halve_rows(k, &last, &last);
                self.push_at(k + 1, r, a);
            }
        }
        debug_assert!(self.levels.iter().all(|l| {
            l.rgb.len() == l.width as usize * l.height as usize
                && l.alpha.as_ref().is_none_or(|a| a.len() == l.rgb.len())
        }));
        debug_assert!(self.alpha || self.levels.iter().all(|l| l.alpha.is_none()));
        self.levels
    }
}

/// Levels `base..` of an image held whole (sRGB bytes, 3 per texel, and
/// optional alpha bytes).
pub(crate) fn chain(
    width: u32,
    height: u32,
    rgb: &[u8],
    alpha: Option<&[u8]>,
    base: u32,
) -> Vec<Level> {
    let mut cascade = Cascade::new(width, height, base, alpha.is_some());
    let (w, h) = (width as usize, height as usize);
    for y in 0..h {
        cascade.push(
            &rgb[3 * w * y..3 * w * (y + 1)],
            alpha.map(|a| &a[w * y..w * (y + 1)]),
        );
    }
    cascade.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_inverts_the_decode_table() {
        for c in 0..=255u8 {
            assert_eq!(encoder().encode(srgb_to_linear(c)), c);
        }
        assert_eq!(encoder().encode(-1.0), 0);
        assert_eq!(encoder().encode(2.0), 255);
        // The table's answer is the search's, across the range.
        let mid: Vec<f32> = (0..255u8)
            .map(|k| 0.5 * (srgb_to_linear(k) + srgb_to_linear(k + 1)))
            .collect();
        for k in 0..=100_000 {
            let v = k as f32 / 100_000.0;
            assert_eq!(
                encoder().encode(v),
                mid.partition_point(|&m| m < v) as u8,
                "{v}"
            );
        }
    }

    #[test]
    fn chain_sizes_round_up_to_one_texel() {
        assert_eq!(level_count(1, 1), 1);
        assert_eq!(level_count(8000, 8000), 14);
        assert_eq!(level_count(5, 2), 4); // 5x2, 3x1, 2x1, 1x1
        assert_eq!(chain_bytes(4, 4, 0, 3), 3 * (16 + 4 + 1));
        assert_eq!(chain_bytes(4, 4, 1, 4), 4 * (4 + 1));
        assert_eq!(level_for(0.3, 5), 0);
        assert_eq!(level_for(f64::NAN, 5), 0);
        assert_eq!(level_for(3.0, 5), 2); // log2 3 = 1.58
        assert_eq!(level_for(1e9, 5), 4);
    }

    /// Levels are the same whichever level the decode stopped at, and each
    /// is the linear-light box mean of the one above it.
    #[test]
    fn levels_do_not_depend_on_the_base() {
        let (w, h) = (7u32, 5u32);
        let rgb: Vec<u8> = (0..3 * w * h).map(|k| (k * 37 % 251) as u8).collect();
        let alpha: Vec<u8> = (0..w * h)
            .map(|k| if k % 3 == 0 { 0 } else { 255 })
            .collect();
        let full = chain(w, h, &rgb, Some(&alpha), 0);
        assert_eq!(full.len(), 4);
        assert_eq!((full[1].width, full[1].height), (4, 3));
        assert_eq!(full[0].rgb.concat(), rgb);
        for base in 1..4 {
            let part = chain(w, h, &rgb, Some(&alpha), base);
            assert_eq!(part[..], full[base as usize..], "base {base}");
        }
        // Level 1's first texel: the mean of the top-left 2 x 2 block.
        let mean = (0..3)
            .map(|c| {
                let at = |x: usize, y: usize| srgb_to_linear(rgb[3 * (y * 7 + x) + c]);
                encoder().encode(0.25 * (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)))
            })
            .collect::<Vec<_>>();
        assert_eq!(full[1].rgb[0][..], mean[..]);
        // Level 1's last column pairs column 6 with itself.
        let a = |x: usize, y: usize| u32::from(alpha[y * 7 + x]);
        let last = (2 * a(6, 0) + 2 * a(6, 1) + 2) / 4;
        assert_eq!(u32::from(full[1].alpha.as_ref().unwrap()[3]), last);
    }
}
