//! Options of the tiled z-buffer.

use crate::options::{DepthFormat, DepthTest};

/// Options of [`crate::TiledZBuffer`]. `Default` is accurate (f32 window
/// depth, exactly [`crate::ZBuffer`]'s output) and fast (all cores, 64-pixel
/// tiles, hierarchical depth on).
///
/// ```
/// use hider_zbuffer::TiledZBufferOptions;
///
/// let options = TiledZBufferOptions::default().with_threads(2).with_tile_size(32);
/// assert!(options.validate().is_ok());
/// assert!(options.with_tile_size(12).validate().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct TiledZBufferOptions {
    /// Storage format of the depth buffer; the output equals
    /// [`crate::ZBuffer`]'s with the same format, pixel for pixel.
    pub depth_format: DepthFormat,
    /// Which fragments pass on a pixel nothing has written yet; the output
    /// equals [`crate::ZBuffer`]'s with the same test.
    pub depth_test: DepthTest,
    /// Worker threads rendering tiles: `1` renders on the calling thread
    /// with no pool, `0` uses every core the machine reports.
    pub threads: usize,
    /// Side of a square screen tile in pixels: a multiple of 8 (the block
    /// size) from 8 to 256. 64 keeps a tile's depth and ids (32 KB in f32)
    /// in a core's L1/L2 cache.
    pub tile_size: u32,
    /// Whether to reject triangles and 8x8 blocks whose nearest possible
    /// depth is behind everything stored there (per-tile and per-block
    /// maximum depth).
    ///
    /// A tuning knob, set only by tests: it trades keeping the tile and
    /// block maximum depths up to date for depth tests skipped. The output
    /// does not change (ids and depths are the same, pixel for pixel), only
    /// the work; the default, on, is the fast exact choice.
    pub hierarchical_z: bool,
    /// Stops the work from outside or at a deadline: polled per bin of triangles and per tile,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for TiledZBufferOptions {
    fn default() -> Self {
        Self {
            depth_format: DepthFormat::default(),
            depth_test: DepthTest::default(),
            threads: 0,
            tile_size: 64,
            hierarchical_z: true,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl TiledZBufferOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Smallest accepted [`Self::tile_size`].
    pub const MIN_TILE: u32 = 8;
    /// Largest accepted [`Self::tile_size`].
    pub const MAX_TILE: u32 = 256;
    /// Largest accepted [`Self::threads`].
    pub const MAX_THREADS: usize = 256;

    /// Sets [`Self::depth_format`].
    pub fn with_depth_format(mut self, format: DepthFormat) -> Self {
        self.depth_format = format;
        self
    }

    /// Sets [`Self::depth_test`].
    pub fn with_depth_test(mut self, test: DepthTest) -> Self {
        self.depth_test = test;
        self
    }

    /// Sets [`Self::threads`].
    pub fn with_threads(mut self, threads: usize) -> Self {
        self.threads = threads;
        self
    }

    /// Sets [`Self::tile_size`].
    pub fn with_tile_size(mut self, tile_size: u32) -> Self {
        self.tile_size = tile_size;
        self
    }

    /// Sets [`Self::hierarchical_z`].
    pub fn with_hierarchical_z(mut self, on: bool) -> Self {
        self.hierarchical_z = on;
        self
    }

    /// Checks the options, naming the first bad value.
    ///
    /// # Errors
    ///
    /// A tile size that is not a multiple of 8 from 8 to 256, or more than
    /// [`Self::MAX_THREADS`] threads.
    pub fn validate(&self) -> hider_scene::Result<()> {
        let t = self.tile_size;
        if !(Self::MIN_TILE..=Self::MAX_TILE).contains(&t) || !t.is_multiple_of(8) {
            return Err(hider_scene::Error::OutOfRange {
                what: "tile size",
                expected: "a multiple of 8 from 8 to 256",
                value: t.to_string(),
            });
        }
        if self.threads > Self::MAX_THREADS {
            return Err(hider_scene::Error::Limit {
                what: "threads",
                value: self.threads as u64,
                limit: Self::MAX_THREADS as u64,
            });
        }
        Ok(())
    }
}
