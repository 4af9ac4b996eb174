//! Options of the z-buffer: depth storage format and depth source.

/// How depth values are stored in the buffer.
///
/// The format decides the depth *resolution*: two surfaces closer than one
/// step of the format cannot be told apart and the earlier-drawn one wins.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthFormat {
    /// 32-bit float window depth in [0, 1] (the default; what a GPU's
    /// `D32F` buffer holds).
    #[default]
    F32,
    /// 64-bit float window depth: the reference precision.
    F64,
    /// 24-bit unsigned normalised fixed point, as GL's usual depth buffer
    /// (and the GL reference renders) store it.
    Fixed24,
    /// 16-bit unsigned normalised fixed point: visibly coarse, kept to show
    /// depth fighting.
    Fixed16,
    /// 32-bit float storing `1 - depth` and testing GREATER ("reversed Z"):
    /// floats are densest near zero, which reversal puts at the far plane
    /// where perspective depth needs the resolution.
    ReversedF32,
}

impl DepthFormat {
    /// Every format, for sweeps.
    pub const ALL: [DepthFormat; 5] = [
        DepthFormat::F32,
        DepthFormat::F64,
        DepthFormat::Fixed24,
        DepthFormat::Fixed16,
        DepthFormat::ReversedF32,
    ];

    /// The name used on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            DepthFormat::F32 => "f32",
            DepthFormat::F64 => "f64",
            DepthFormat::Fixed24 => "fixed24",
            DepthFormat::Fixed16 => "fixed16",
            DepthFormat::ReversedF32 => "reversed-f32",
        }
    }

    /// Bytes per pixel of depth storage.
    pub fn bytes_per_pixel(self) -> usize {
        match self {
            DepthFormat::F64 => 8,
            DepthFormat::Fixed16 => 2,
            _ => 4,
        }
    }

    /// Parses [`DepthFormat::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// Which quantity the depth test compares.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthSource {
    /// Window depth `z/w`, affine in screen space and so interpolated
    /// exactly (the default and the correct choice).
    #[default]
    WindowZ,
    /// Camera-space depth interpolated *linearly in screen space*: wrong
    /// under perspective (the worked example of scratchapixel's depth-buffer
    /// lesson gives 4.5 where the truth is 4). Kept only as a labelled demonstration so the
    /// benchmark can show what the error costs; intersecting or nearly
    /// touching surfaces come out in the wrong order.
    LinearViewZ,
}

impl DepthSource {
    /// The name used on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            DepthSource::WindowZ => "window-z",
            DepthSource::LinearViewZ => "linear-view-z",
        }
    }

    /// Parses [`DepthSource::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        [DepthSource::WindowZ, DepthSource::LinearViewZ]
            .into_iter()
            .find(|s| s.name() == name)
    }
}

/// Which fragments the depth test lets through.
///
/// A depth buffer is cleared to the far plane's window depth, 1. With GL's
/// strict LESS against that clear value a fragment lying exactly on the far
/// plane, or one whose depth rounds to 1 in the storage format (a sphere
/// seen through a near plane of `1e-7` has every depth within `1e-8` of 1),
/// never shows, although it is inside the view volume (whose far plane is
/// closed) and the exact references draw it. The default keeps LESS between
/// fragments but lets a pixel nothing has written accept any fragment, so
/// that coverage never depends on the storage format.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthTest {
    /// A pixel nothing has written accepts any fragment inside the view
    /// volume, window depth 1 included; a written pixel accepts a fragment
    /// whose stored depth is strictly less (of equal depths the earlier,
    /// lower-id primitive stays). Agrees with the exact oracle on coverage
    /// in every format. The default.
    #[default]
    ViewVolume,
    /// GL's `glDepthFunc(GL_LESS)` against the clear value 1: a fragment
    /// whose stored depth is not below 1 is dropped even on a pixel nothing
    /// has written. What a GPU draws, for comparisons with GL renders.
    GlLess,
}

impl DepthTest {
    /// Both tests, for sweeps.
    pub const ALL: [DepthTest; 2] = [DepthTest::ViewVolume, DepthTest::GlLess];

    /// The name used on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            DepthTest::ViewVolume => "view-volume",
            DepthTest::GlLess => "gl-less",
        }
    }

    /// Parses [`DepthTest::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }
}

/// Options of [`crate::ZBuffer`]. `Default` is the accurate choice for a
/// real-time buffer: f32 window depth.
///
/// ```
/// use hider_zbuffer::{DepthFormat, ZBufferOptions};
///
/// let options = ZBufferOptions::default().with_depth_format(DepthFormat::Fixed24);
/// assert_eq!(options.depth_format, DepthFormat::Fixed24);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct ZBufferOptions {
    /// Storage format of the depth buffer.
    pub depth_format: DepthFormat,
    /// What is compared.
    pub depth_source: DepthSource,
    /// Which fragments pass on a pixel nothing has written yet.
    pub depth_test: DepthTest,
    /// Stops the work from outside or at a deadline: polled every few thousand triangles,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl ZBufferOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::depth_format`].
    pub fn with_depth_format(mut self, format: DepthFormat) -> Self {
        self.depth_format = format;
        self
    }

    /// Sets [`Self::depth_source`].
    pub fn with_depth_source(mut self, source: DepthSource) -> Self {
        self.depth_source = source;
        self
    }

    /// Sets [`Self::depth_test`].
    pub fn with_depth_test(mut self, test: DepthTest) -> Self {
        self.depth_test = test;
        self
    }
}
