//! The `Hider` trait every hidden-surface algorithm implements, its
//! object-safe twin [`DynHider`] for registries, and the uniform
//! [`StatsTable`] every hider's typed stats convert into.
//!
//! One shape for every hider: a hider is built from its options with
//! [`Hider::new`], renders with [`Hider::render`], and returns its own typed
//! stats (documented fields, read as fields, never looked up by string). The
//! benchmark and the command line see every hider through [`DynHider`] and
//! print the stats as a [`StatsTable`].

use std::path::Path;

use crate::error::Result;
use crate::frame::Frame;
use crate::model::Scene;
use crate::prepare::{PrepareOptions, ScreenScene, prepare_into};
use crate::shade::ShadeMode;
use crate::view::View;
use hider_geom::Viewport;

/// Work counters in one uniform shape: what the benchmark tabulates and the
/// command line prints, for any hider without knowing it.
///
/// Built from a hider's typed stats (see [`HiderStats`]); code that needs a
/// particular counter reads the typed field instead.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StatsTable {
    /// Named counters, in the order the hider reports them.
    pub counters: Vec<(&'static str, u64)>,
    /// Peak bytes of working memory (buffers, fragment arenas, lists), not
    /// counting the output frame.
    pub peak_bytes: u64,
    /// [`HiderStats::warnings`] of the frame.
    pub warnings: Vec<String>,
}

impl std::fmt::Display for StatsTable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (k, (name, value)) in self.counters.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{name} {value}")?;
        }
        if self.peak_bytes > 0 {
            write!(f, ", peak bytes {}", self.peak_bytes)?;
        }
        Ok(())
    }
}

/// A hider's typed stats: a struct whose documented fields count the work
/// that explains its time, convertible into the uniform [`StatsTable`].
///
/// Implemented by the [`hider_stats!`](crate::hider_stats) macro, which
/// keeps each counter's printed name beside its field.
pub trait HiderStats: Clone + std::fmt::Debug {
    /// The counters as the benchmark prints them.
    fn table(&self) -> StatsTable;

    /// What a user must be told about the frame, one line each (lost
    /// fragments, a budget that cut work short): empty by default. The
    /// command line prints them as warnings; [`StatsTable::warnings`]
    /// carries them through [`DynHider`].
    fn warnings(&self) -> Vec<String> {
        Vec::new()
    }
}

/// A value the stats table can print as a counter.
pub trait Counter {
    /// The value as an unsigned count.
    fn count(&self) -> u64;
}

impl Counter for u64 {
    fn count(&self) -> u64 {
        *self
    }
}

impl Counter for u32 {
    fn count(&self) -> u64 {
        u64::from(*self)
    }
}

impl Counter for usize {
    fn count(&self) -> u64 {
        *self as u64
    }
}

/// Declares a hider's stats struct and its [`HiderStats`] table in one
/// place: each field carries the name the table prints it under, `PEAK` for
/// the peak working bytes, or `_` for a field the table leaves out. An
/// optional `warnings: path` after the struct names the function (taking
/// `&Self`, returning `Vec<String>`) behind [`HiderStats::warnings`].
///
/// ```
/// hider_scene::hider_stats! {
///     /// What the example hider did.
///     #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
///     pub struct ExampleStats {
///         /// Triangles drawn.
///         pub triangles: u64 => "triangles",
///         /// Bytes of the depth buffer.
///         pub bytes: u64 => PEAK,
///         /// Kept for the caller, not printed.
///         pub internal: u32 => _,
///     }
/// }
/// use hider_scene::HiderStats;
/// let s = ExampleStats { triangles: 3, bytes: 64, internal: 1 };
/// assert_eq!(s.table().counters, vec![("triangles", 3)]);
/// assert_eq!(s.table().peak_bytes, 64);
/// assert!(s.table().warnings.is_empty());
///
/// hider_scene::hider_stats! {
///     /// A hider that can lose work.
///     #[derive(Clone, Copy, Debug, Default)]
///     pub struct LossyStats {
///         /// Fragments dropped.
///         pub dropped: u64 => "dropped",
///     }
///     warnings: LossyStats::lost
/// }
/// impl LossyStats {
///     fn lost(&self) -> Vec<String> {
///         (self.dropped > 0)
///             .then(|| format!("{} fragments dropped", self.dropped))
///             .into_iter()
///             .collect()
///     }
/// }
/// let lossy = LossyStats { dropped: 2 };
/// assert_eq!(lossy.table().warnings, vec!["2 fragments dropped".to_owned()]);
/// ```
#[macro_export]
macro_rules! hider_stats {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $(
                $(#[$field_meta:meta])*
                $field_vis:vis $field:ident : $field_ty:ty => $label:tt
            ),* $(,)?
        }
        $(warnings: $warnings:path)?
    ) => {
        $(#[$meta])*
        $vis struct $name {
            $(
                $(#[$field_meta])*
                $field_vis $field: $field_ty,
            )*
        }

        impl $crate::HiderStats for $name {
            fn table(&self) -> $crate::StatsTable {
                let mut table = $crate::StatsTable::default();
                $( $crate::__hider_stats_entry!(table, $label, self.$field); )*
                table.warnings = $crate::HiderStats::warnings(self);
                table
            }
            $(
                fn warnings(&self) -> Vec<String> {
                    $warnings(self)
                }
            )?
        }
    };
}

/// One field of [`hider_stats!`] into the table.
#[doc(hidden)]
#[macro_export]
macro_rules! __hider_stats_entry {
    ($table:ident, PEAK, $value:expr) => {
        $table.peak_bytes = $crate::Counter::count(&$value);
    };
    ($table:ident, _, $value:expr) => {};
    ($table:ident, $label:literal, $value:expr) => {
        $table
            .counters
            .push(($label, $crate::Counter::count(&$value)));
    };
}

/// A hidden-surface algorithm.
///
/// `render` draws a [`ScreenScene`] into a [`Frame`] of the same size: it
/// clears the frame and writes, per pixel, the id and window depth of the
/// visible primitive. Hiders that resolve colour themselves (anti-aliasing,
/// transparency) also fill `color` (and `coverage`) and say so through
/// [`Hider::resolves_color`]; for the others the caller shades from the ids
/// with [`crate::shade::shade_frame`].
///
/// Every knob that changes behaviour lives in [`Hider::Options`], whose
/// `Default` is the accurate choice. `&mut self` lets a hider keep its
/// scratch memory (depth buffers, edge tables, fragment arenas) from one
/// frame to the next.
pub trait Hider {
    /// Every knob that changes the hider's behaviour.
    type Options: Default + Clone;
    /// The typed work counters of one frame.
    type Stats: HiderStats;

    /// A hider with these options; no memory is taken until the first frame.
    fn new(options: Self::Options) -> Self
    where
        Self: Sized;

    /// The options the hider was built with.
    fn options(&self) -> &Self::Options;

    /// A short name for tables and messages (`"zbuffer"`, `"warnock"`...).
    fn name(&self) -> &str;

    /// Renders `scene` into `frame`, returning the work done.
    ///
    /// Errors when the frame's size differs from the scene's viewport or a
    /// budget the hider documents is exceeded.
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Self::Stats>;

    /// The whole pipeline from the world-space scene: the front end, then
    /// [`Hider::render`]. The default prepares into `screen` with the shared
    /// front end ([`prepare_into`], reusing its memory); a hider with a
    /// front end of its own overrides it, and then `screen` is left as it
    /// was. This is the span a frame loop (and `hider render --repeat`)
    /// times.
    fn render_scene(
        &mut self,
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        screen: &mut ScreenScene,
        frame: &mut Frame,
    ) -> Result<Self::Stats> {
        prepare_into(scene, view, options, screen)?;
        self.render(screen, frame)
    }

    /// Refuses a `width x height` frame whose working memory is over a
    /// budget of the hider's, before the caller allocates anything: the
    /// error `render` would give at that size, from the size alone. The
    /// default allows every size (a hider whose memory does not grow with
    /// the frame's pixels, or whose budgets depend on the scene, checks in
    /// `render`). A caller about to allocate a frame calls it first, so an
    /// absurd size costs no frame of gigabytes.
    fn check_size(&self, width: u32, height: u32) -> Result<()> {
        let _ = (width, height);
        Ok(())
    }

    /// Whether `render` writes the frame's colour itself.
    fn resolves_color(&self) -> bool {
        false
    }

    /// Whether the hider composites translucent surfaces (every surface in
    /// a sample, in depth order); the others keep one surface per sample
    /// and draw translucent ones opaque.
    fn composites_transparency(&self) -> bool {
        false
    }

    /// The depth-ordered, split polygons of the last frame, for hiders that
    /// compute them (the painters); `None` for the others. (The exact
    /// visible regions and hidden lines are `hider-vector`'s, from any
    /// prepared scene.)
    fn ordered_polygons(&self) -> Option<&dyn OrderedPolygons> {
        None
    }
}

/// The depth-ordered polygons of a painter's last frame.
pub trait OrderedPolygons {
    /// Writes the polygons of the last frame rendered from `scene` as SVG,
    /// coloured by `mode`, atomically.
    fn write_svg(&self, scene: &ScreenScene, path: &Path, mode: ShadeMode) -> Result<()>;
}

/// The object-safe face of [`Hider`], for registries that hold hiders of
/// different types: the same calls, with the stats as a [`StatsTable`].
/// Every [`Hider`] is one through the blanket implementation.
pub trait DynHider {
    /// See [`Hider::name`].
    fn name(&self) -> &str;
    /// [`Hider::render`], the stats as a table.
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<StatsTable>;
    /// [`Hider::render_scene`], the stats as a table.
    fn render_scene(
        &mut self,
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        screen: &mut ScreenScene,
        frame: &mut Frame,
    ) -> Result<StatsTable>;
    /// See [`Hider::check_size`].
    fn check_size(&self, width: u32, height: u32) -> Result<()>;
    /// See [`Hider::resolves_color`].
    fn resolves_color(&self) -> bool;
    /// See [`Hider::composites_transparency`].
    fn composites_transparency(&self) -> bool;
    /// See [`Hider::ordered_polygons`].
    fn ordered_polygons(&self) -> Option<&dyn OrderedPolygons>;
}

impl<H: Hider> DynHider for H {
    fn name(&self) -> &str {
        Hider::name(self)
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<StatsTable> {
        Hider::render(self, scene, frame).map(|s| s.table())
    }

    fn render_scene(
        &mut self,
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        screen: &mut ScreenScene,
        frame: &mut Frame,
    ) -> Result<StatsTable> {
        Hider::render_scene(self, scene, view, options, screen, frame).map(|s| s.table())
    }

    fn check_size(&self, width: u32, height: u32) -> Result<()> {
        Hider::check_size(self, width, height)
    }

    fn resolves_color(&self) -> bool {
        Hider::resolves_color(self)
    }

    fn composites_transparency(&self) -> bool {
        Hider::composites_transparency(self)
    }

    fn ordered_polygons(&self) -> Option<&dyn OrderedPolygons> {
        Hider::ordered_polygons(self)
    }
}

/// Checks that a frame matches the scene's viewport: the first thing every
/// hider does.
pub fn check_frame(hider: &str, scene: &ScreenScene, frame: &Frame) -> Result<()> {
    check_frame_size(hider, scene.viewport, frame)
}

/// [`check_frame`] for a scene prepared for `viewport` (a depth-only scene
/// of a hider's own front end, or any other input of that size).
pub fn check_frame_size(hider: &str, viewport: Viewport, frame: &Frame) -> Result<()> {
    let vp = viewport;
    if frame.width() != vp.width || frame.height() != vp.height {
        return Err(crate::error::Error::Render {
            hider: hider.to_owned(),
            message: format!(
                "frame is {}x{} but the scene was prepared for {}x{}",
                frame.width(),
                frame.height(),
                vp.width,
                vp.height
            ),
        });
    }
    Ok(())
}
