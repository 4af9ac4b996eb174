//! The options of the front end.

use hider_geom::fixed::GUARD_BAND_PIXELS;

use crate::Cancel;

/// Arithmetic used for the model-view-projection transform.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TransformPrecision {
    /// Transform, divide and map in `f64` (the accurate default; keeps huge
    /// coordinates with small triangles apart).
    #[default]
    F64,
    /// Round the view-projection matrix and the vertices to `f32` and
    /// transform, divide and map in `f32`, as a GL implementation does.
    /// Reproduces the GL reference renders' snapped vertices.
    F32,
}

/// Options of [`prepare`](crate::prepare()). `Default` is the accurate choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrepareOptions {
    /// Transform arithmetic.
    pub precision: TransformPrecision,
    /// Guard band beyond each image side, in pixels; triangles reaching
    /// further are clipped. At most [`GUARD_BAND_PIXELS`].
    pub guard_band_pixels: u32,
    /// Drop triangles facing away from the camera (GL's `GL_CULL_FACE` with
    /// counter-clockwise front faces). Off by default: the GL reference
    /// renders cull nothing.
    pub cull_back_faces: bool,
    /// Process large scenes (over 32k triangles) in chunks on the current
    /// rayon thread pool. The result is identical; whether it is faster
    /// depends on free cores, so it is off by default and the CLI turns it
    /// on with `--threads` above 1.
    pub parallel: bool,
    /// Stops the front end between triangles when cancelled (polled every
    /// [`POLL_EVERY`](crate::cancel::POLL_EVERY) triangles): a hider's own
    /// token polls only its own loops, and the front end of a large scene
    /// takes tens of milliseconds. The default token never stops it.
    pub cancel: Cancel,
}

impl Default for PrepareOptions {
    fn default() -> Self {
        Self {
            precision: TransformPrecision::F64,
            guard_band_pixels: GUARD_BAND_PIXELS,
            cull_back_faces: false,
            parallel: false,
            cancel: Cancel::default(),
        }
    }
}

impl PrepareOptions {
    /// The options that reproduce a GL pipeline, Mesa's llvmpipe on every
    /// pixel of the reference renders: the `f32` transform, and no guard
    /// band, because llvmpipe's draw module clips triangles at the
    /// viewport's sides (a triangle reaching beyond them is cut there, and
    /// its snapped pieces own slightly different pixels along its long
    /// edges than the uncut triangle would: measured on a grazing view of
    /// the strips scene).
    pub fn gl_compatible() -> Self {
        Self::default()
            .with_precision(TransformPrecision::F32)
            .with_guard_band_pixels(0)
    }

    /// Sets [`Self::precision`].
    pub fn with_precision(mut self, precision: TransformPrecision) -> Self {
        self.precision = precision;
        self
    }

    /// Sets [`Self::cull_back_faces`].
    pub fn with_cull_back_faces(mut self, cull: bool) -> Self {
        self.cull_back_faces = cull;
        self
    }

    /// Sets [`Self::parallel`].
    pub fn with_parallel(mut self, parallel: bool) -> Self {
        self.parallel = parallel;
        self
    }

    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::guard_band_pixels`] (clamped to [`GUARD_BAND_PIXELS`]).
    pub fn with_guard_band_pixels(mut self, pixels: u32) -> Self {
        self.guard_band_pixels = pixels.min(GUARD_BAND_PIXELS);
        self
    }
}
