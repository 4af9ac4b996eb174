//! The knobs of the vector output, as one plain struct whose `Default` is
//! the accurate choice.

/// Options of [`crate::visible_regions`], [`crate::hidden_lines`] and the
/// SVG writers.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct VectorOptions {
    /// Extra bits of sub-pixel resolution for the region polygons beyond
    /// the front end's 1/256 pixel: cut points (where a depth-intersection
    /// line or an occluding edge crosses another edge) are rounded to
    /// `1/(256 * 2^refine_bits)` pixel. Capped so that coordinates stay
    /// within the polygon library's exact range (2^29 grid units across
    /// the image). Default 6 (1/16384 pixel).
    pub refine_bits: u32,
    /// Merge the regions of one face group (coplanar, same material and
    /// same fill colour) into one path, so no seam can show between them.
    /// Default true.
    pub merge_groups: bool,
    /// A background rectangle of this colour (any SVG colour: `white`,
    /// `#102030`) under the regions or lines. Default `None`: nothing is
    /// drawn where there is no surface, so the file can be laid over
    /// anything and a plotter draws no frame.
    pub background: Option<String>,
    /// Regions SVG only: stroke each path with its own fill colour at this
    /// width (pixels), all of them clipped to the covered set. Anti-aliasing
    /// viewers (rsvg, Chromium, Inkscape) composite abutting paths one
    /// after the other, so along a shared edge both cover a pixel only
    /// partly and the background shows through: hairline seams, on a
    /// finely meshed smooth surface a visibly darker picture. The stroke
    /// spills into the neighbours and covers the seam; the clip keeps the
    /// outline of the picture exact. The paths' geometry is the same
    /// either way; translucent paths are not stroked (the stroke would
    /// blend twice over their own fill). Default 1 (see `docs/vector.md`
    /// for the measured coverage); 0 writes the bare regions.
    pub seam_stroke: f64,
    /// Decimals of the pixel coordinates written (both SVGs). Default 4:
    /// a point moves by at most 1/20000 pixel; shared corners round the
    /// same way in every path, so rounding opens no gap.
    pub decimals: u32,
    /// Lines SVG: polylines shorter than this (pixels) are left out, as
    /// dots a plotter would stab. Default 0.05.
    pub min_fragment: f64,
    /// The page in millimetres `(width, height)`: the SVG's `width` and
    /// `height` say so and the image (in pixel coordinates, `viewBox`) is
    /// fitted to it, centred. Default `None`: one CSS pixel per pixel.
    pub page_mm: Option<(f64, f64)>,
    /// Dihedral angle in degrees above which a shared edge is drawn as a
    /// crease. Default 30.
    pub crease_degrees: f64,
    /// Stroke width of lines, in pixels. Default 1.
    pub stroke_width: f64,
    /// Also draw the hidden parts of the lines, dashed, as in engineering
    /// drawings. Default false.
    pub dashed_hidden: bool,
    /// Window-depth difference below which two surfaces count as touching
    /// rather than one hiding the other (shared edges and vertices, the
    /// edges of a line's own faces). Default 1e-9.
    pub depth_tolerance: f64,
    /// Most overlapping triangle pairs the regions (and the intersection
    /// lines) may test, after culling: past it the drawing is refused
    /// (an [`hider_scene::Error::Limit`] whose `what` is [`PAIRS_LIMIT`])
    /// before its booleans allocate. Default 50,000,000 (the exactly
    /// edge-on grids of `vector_bench` need 5.3 million; the 32,000-triangle
    /// pile of `vector_scaling` 1.2 million).
    pub max_pairs: u64,
    /// Stops the drawing from outside or at a deadline: polled per batch
    /// of triangle pairs and per group of regions, it then returns
    /// [`hider_scene::Error::Cancelled`]. Default: never cancelled, and
    /// free to poll.
    pub cancel: hider_scene::Cancel,
    /// Most polygon vertices the regions may send into the map-wide
    /// passes (the per-primitive regions, counted as each is found, and
    /// the covered set's outline): past it the drawing is refused (an
    /// [`hider_scene::Error::Limit`] whose `what` is
    /// [`REGION_POINTS_LIMIT`]) before the snap rounding and the closing
    /// booleans allocate. Default 4,000,000 (`gen:soup:64000` at 256 px
    /// sends 121,198, `gen:soup:256000` at 2048 px under 300,000).
    pub max_region_points: u64,
}

/// The `what` of the [`hider_scene::Error::Limit`] refusing a drawing
/// over [`VectorOptions::max_pairs`], so that a caller can name its own
/// flag for it.
pub const PAIRS_LIMIT: &str = "overlapping triangle pairs (VectorOptions::max_pairs)";

/// The `what` of the [`hider_scene::Error::Limit`] refusing a region map
/// over [`VectorOptions::max_region_points`], so that a caller can name
/// its own flag for it.
pub const REGION_POINTS_LIMIT: &str = "region polygon vertices (VectorOptions::max_region_points)";

impl Default for VectorOptions {
    fn default() -> Self {
        Self {
            refine_bits: 6,
            merge_groups: true,
            background: None,
            seam_stroke: 1.0,
            decimals: 4,
            min_fragment: 0.05,
            page_mm: None,
            crease_degrees: 30.0,
            stroke_width: 1.0,
            dashed_hidden: false,
            depth_tolerance: 1e-9,
            max_pairs: 50_000_000,
            cancel: hider_scene::Cancel::default(),
            max_region_points: 4_000_000,
        }
    }
}

impl VectorOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::refine_bits`].
    pub fn with_refine_bits(mut self, bits: u32) -> Self {
        self.refine_bits = bits;
        self
    }

    /// Sets [`Self::merge_groups`].
    pub fn with_merge_groups(mut self, merge: bool) -> Self {
        self.merge_groups = merge;
        self
    }

    /// Sets [`Self::background`].
    pub fn with_background(mut self, background: Option<String>) -> Self {
        self.background = background;
        self
    }

    /// Sets [`Self::decimals`].
    pub fn with_decimals(mut self, decimals: u32) -> Self {
        self.decimals = decimals;
        self
    }

    /// Sets [`Self::min_fragment`].
    pub fn with_min_fragment(mut self, length: f64) -> Self {
        self.min_fragment = length;
        self
    }

    /// Sets [`Self::page_mm`].
    pub fn with_page_mm(mut self, page: Option<(f64, f64)>) -> Self {
        self.page_mm = page;
        self
    }

    /// Pixels per millimetre of the written drawing: the page's fit when
    /// [`Self::page_mm`] is set, else CSS's 96 pixels per inch. Converts
    /// a stroke width given in millimetres.
    pub fn pixels_per_mm(&self, width: u32, height: u32) -> f64 {
        match self.page_mm {
            Some((w, h)) => (f64::from(width) / w).max(f64::from(height) / h),
            None => 96.0 / 25.4,
        }
    }

    /// Sets [`Self::seam_stroke`].
    pub fn with_seam_stroke(mut self, width: f64) -> Self {
        self.seam_stroke = width;
        self
    }

    /// Sets [`Self::crease_degrees`].
    pub fn with_crease_degrees(mut self, degrees: f64) -> Self {
        self.crease_degrees = degrees;
        self
    }

    /// Sets [`Self::stroke_width`].
    pub fn with_stroke_width(mut self, width: f64) -> Self {
        self.stroke_width = width;
        self
    }

    /// Sets [`Self::stroke_width`] from millimetres on the written drawing
    /// of a `width` x `height` image ([`Self::pixels_per_mm`]: set the page
    /// first).
    ///
    /// ```
    /// use hider_vector::VectorOptions;
    /// let a4 = VectorOptions::default().with_page_mm(Some((210.0, 297.0)));
    /// let o = a4.with_stroke_mm(0.5, 840, 1188);
    /// assert_eq!(o.stroke_width, 2.0);
    /// ```
    pub fn with_stroke_mm(self, mm: f64, width: u32, height: u32) -> Self {
        let pixels = mm * self.pixels_per_mm(width, height);
        self.with_stroke_width(pixels)
    }

    /// Sets [`Self::dashed_hidden`].
    pub fn with_dashed_hidden(mut self, dashed: bool) -> Self {
        self.dashed_hidden = dashed;
        self
    }

    /// Sets [`Self::max_pairs`].
    pub fn with_max_pairs(mut self, pairs: u64) -> Self {
        self.max_pairs = pairs;
        self
    }

    /// Sets [`Self::max_region_points`].
    pub fn with_max_region_points(mut self, points: u64) -> Self {
        self.max_region_points = points;
        self
    }

    /// Sets [`Self::depth_tolerance`].
    pub fn with_depth_tolerance(mut self, tolerance: f64) -> Self {
        self.depth_tolerance = tolerance;
        self
    }

    /// Errors naming the first option that is out of range.
    pub(crate) fn validate(&self) -> hider_scene::Result<()> {
        let bad =
            if !(self.crease_degrees.is_finite() && (0.0..=180.0).contains(&self.crease_degrees)) {
                Some(format!(
                    "crease_degrees {} is not in [0, 180]",
                    self.crease_degrees
                ))
            } else if !(self.stroke_width.is_finite() && self.stroke_width > 0.0) {
                Some(format!(
                    "stroke_width {} is not a positive number",
                    self.stroke_width
                ))
            } else if !(self.seam_stroke.is_finite() && self.seam_stroke >= 0.0) {
                Some(format!(
                    "seam_stroke {} is not a non-negative number",
                    self.seam_stroke
                ))
            } else if !(self.depth_tolerance.is_finite() && self.depth_tolerance >= 0.0) {
                Some(format!(
                    "depth_tolerance {} is not a non-negative number",
                    self.depth_tolerance
                ))
            } else if !(self.min_fragment.is_finite() && self.min_fragment >= 0.0) {
                Some(format!(
                    "min_fragment {} is not a non-negative number",
                    self.min_fragment
                ))
            } else if self.decimals > 12 {
                Some(format!("decimals {} is above 12", self.decimals))
            } else if self
                .page_mm
                .is_some_and(|(w, h)| !(w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0))
            {
                Some(format!("page_mm {:?} is not a positive size", self.page_mm))
            } else if self.refine_bits > 16 {
                Some(format!("refine_bits {} is above 16", self.refine_bits))
            } else {
                None
            };
        match bad {
            Some(message) => Err(crate::render_error(message)),
            None => Ok(()),
        }
    }
}
