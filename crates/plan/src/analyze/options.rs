//! What the caller wants rendered: the inputs of the analysis besides the
//! scene.

use hider_geom::Camera;
use hider_scene::{PrepareOptions, Scene, View};

use crate::error::Result;

/// Default of [`RenderOptions::pair_budget`].
pub const DEFAULT_PAIR_BUDGET: u64 = 50_000_000;

/// What the caller wants rendered: the inputs of the analysis besides the
/// scene. `Default` is a 512 x 512 shaded raster image without
/// anti-aliasing from the scene's own (or the fit) camera.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The camera; `None` for the scene's camera or else the fit camera.
    pub camera: Option<Camera>,
    /// Whether a shaded picture is asked for (false: ids / false colours
    /// only, so lighting is never needed).
    pub shading: bool,
    /// Whether anti-aliased edges are asked for.
    pub antialiasing: bool,
    /// Whether the painter's ordered polygons (its SVG) are asked for.
    pub ordered_polygons: bool,
    /// The front end's options.
    pub prepare: PrepareOptions,
    /// Most candidate pairs each pair search examines.
    pub pair_budget: u64,
    /// Whether the pair searches (intersections, coplanar overlaps, cyclic
    /// overlaps, naive-order violations) run when no ordered polygons is
    /// asked. Only the planner's ordered-polygons rule reads them, and on
    /// 10^5 triangles they take seconds where the render takes a fraction
    /// of one, so a raster render may leave them out (they are then
    /// reported as not ruled out). On by default: the analysis reports
    /// everything. With ordered polygons asked they always run.
    pub pair_searches: bool,
    /// Most examples kept per effect.
    pub max_examples: usize,
    /// The painter's split budget the caller will build it with
    /// ([`HiderConfig::max_splits`](crate::HiderConfig::max_splits)), which
    /// the planner's up-front refusal of ordered polygons compares its
    /// prediction with; `None` for the painter's automatic budget.
    pub max_splits: Option<u64>,
    /// Stops the work from outside or at a deadline: polled in the analysis's pair searches,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            camera: None,
            shading: true,
            antialiasing: false,
            ordered_polygons: false,
            prepare: PrepareOptions::default(),
            pair_budget: DEFAULT_PAIR_BUDGET,
            pair_searches: true,
            max_examples: 5,
            max_splits: None,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl RenderOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets the image size.
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        (self.width, self.height) = (width, height);
        self
    }
    /// Sets [`Self::camera`].
    pub fn with_camera(mut self, camera: Option<Camera>) -> Self {
        self.camera = camera;
        self
    }
    /// Sets [`Self::shading`].
    pub fn with_shading(mut self, shading: bool) -> Self {
        self.shading = shading;
        self
    }
    /// Sets [`Self::antialiasing`].
    pub fn with_antialiasing(mut self, antialiasing: bool) -> Self {
        self.antialiasing = antialiasing;
        self
    }
    /// Sets [`Self::ordered_polygons`].
    pub fn with_ordered_polygons(mut self, ordered_polygons: bool) -> Self {
        self.ordered_polygons = ordered_polygons;
        self
    }
    /// Sets [`Self::prepare`].
    pub fn with_prepare(mut self, prepare: PrepareOptions) -> Self {
        self.prepare = prepare;
        self
    }
    /// Sets [`Self::pair_budget`].
    pub fn with_pair_budget(mut self, budget: u64) -> Self {
        self.pair_budget = budget;
        self
    }
    /// Sets [`Self::pair_searches`].
    pub fn with_pair_searches(mut self, pair_searches: bool) -> Self {
        self.pair_searches = pair_searches;
        self
    }
    /// Sets [`Self::max_splits`].
    pub fn with_max_splits(mut self, max_splits: Option<u64>) -> Self {
        self.max_splits = max_splits;
        self
    }
    /// Sets [`Self::max_examples`].
    pub fn with_max_examples(mut self, max_examples: usize) -> Self {
        self.max_examples = max_examples;
        self
    }

    /// What these options ask for, in words: "a shaded 512 x 512 image",
    /// with "anti-aliased" and "with ordered polygons" when asked.
    ///
    /// ```
    /// use hider_plan::RenderOptions;
    ///
    /// let asked = RenderOptions::default().with_antialiasing(true).requested();
    /// assert_eq!(asked, "an anti-aliased shaded 512 x 512 image");
    /// ```
    pub fn requested(&self) -> String {
        let mut words = Vec::new();
        if self.antialiasing {
            words.push("anti-aliased");
        }
        words.push(if self.shading {
            "shaded"
        } else {
            "id-coloured"
        });
        let article = if words[0].starts_with(['a', 'e', 'i', 'o', 'u']) {
            "an"
        } else {
            "a"
        };
        let mut s = format!(
            "{article} {} {} x {} image",
            words.join(" "),
            self.width,
            self.height
        );
        if self.ordered_polygons {
            s.push_str(" with ordered polygons");
        }
        s
    }

    /// The view these options describe for `scene` (size checked).
    pub fn view(&self, scene: &Scene) -> Result<View> {
        Ok(match self.camera {
            Some(c) => View::new(c, self.width, self.height)?,
            None => View::for_scene(scene, self.width, self.height)?,
        })
    }
}
