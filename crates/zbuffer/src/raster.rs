//! The z-buffer hider: bounding-box traversal with incremental integer edge
//! functions and a LESS depth test (Catmull 1974; the pseudo-code of
//! scratchapixel's depth-buffer lesson).

use hider_geom::PlaneEq;
use hider_geom::fixed::{SUBPIXEL_SCALE, pixel_center};
use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, ScreenTri, check_frame};

use crate::depth::DepthBuffer;
use crate::options::{DepthFormat, DepthSource, DepthTest, ZBufferOptions};
use crate::trace::{DepthTestSink, NoTrace};

hider_scene::hider_stats! {
    /// Work counters of one z-buffer frame.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct ZBufferStats {
        /// Triangles whose bounding box met the viewport and were traversed.
        pub triangles_set_up: u64 => "triangles set up",
        /// Pixel centres whose edge functions were evaluated (the
        /// bounding-box area summed over triangles).
        pub pixels_tested: u64 => "pixels tested",
        /// Pixel centres inside a triangle, each one depth test.
        pub depth_tests: u64 => "depth tests",
        /// Depth tests that passed (depth and id written).
        pub depth_passes: u64 => "depth passes",
        /// Bytes of the depth buffer.
        pub depth_bytes: u64 => PEAK,
    }
}

/// The depth-buffer hider. Keeps its depth buffer between frames.
///
/// Triangles are drawn in primitive-id order and the test is LESS, so of two
/// surfaces at exactly the same stored depth the lower id stays: the tie rule
/// the oracle uses too. By default ([`DepthTest::ViewVolume`]) a pixel
/// nothing has written accepts any fragment, so a surface whose depth
/// rounds to the clear value 1 still shows, as in the oracle; the frame's
/// id buffer, cleared at the start of every frame, says which pixels were
/// written.
#[derive(Clone, Debug)]
pub struct ZBuffer {
    options: ZBufferOptions,
    depth: DepthBuffer,
    name: String,
}

impl ZBuffer {
    /// The name of a z-buffer with `options`: `zbuffer` followed by the
    /// non-default options (`zbuffer-fixed24`, `zbuffer-linear-z`,
    /// `zbuffer-gl-less`...).
    fn name_of(options: &ZBufferOptions) -> String {
        let format = match options.depth_format {
            DepthFormat::F32 => "",
            DepthFormat::F64 => "-f64",
            DepthFormat::Fixed24 => "-fixed24",
            DepthFormat::Fixed16 => "-fixed16",
            DepthFormat::ReversedF32 => "-reversed",
        };
        let source = match options.depth_source {
            DepthSource::WindowZ => "",
            DepthSource::LinearViewZ => "-linear-z",
        };
        let test = match options.depth_test {
            DepthTest::ViewVolume => "",
            DepthTest::GlLess => "-gl-less",
        };
        format!("zbuffer{format}{source}{test}")
    }

    fn draw(
        &mut self,
        scene: &ScreenScene,
        tri: &ScreenTri,
        linear: Option<&LinearDepth>,
        frame: &mut Frame,
        stats: &mut ZBufferStats,
        sink: &mut impl DepthTestSink,
    ) {
        let Some((x0, y0, x1, y1)) = tri.pixel_bounds(scene.viewport) else {
            return;
        };
        stats.triangles_set_up += 1;
        sink.triangle(tri.prim);
        let edges = tri.edges();
        // Which plane the test compares: window depth, or (demonstration
        // only) camera depth interpolated linearly in screen space.
        let accept_fresh = self.options.depth_test == DepthTest::ViewVolume;
        let (plane, to_window): (PlaneEq, Option<&LinearDepth>) = match linear {
            None => (tri.depth, None),
            Some(l) => match PlaneEq::from_points(&tri.v, tri.w) {
                Some(p) => (p, Some(l)),
                None => return,
            },
        };
        let step = i64::from(SUBPIXEL_SCALE);
        let px0 = i64::from(pixel_center(x0 as i32));
        let width = frame.width() as usize;
        for y in y0..=y1 {
            let py = i64::from(pixel_center(y as i32));
            // Incremental edge functions: exact integer steps of a*256.
            let mut e = edges.map(|e| e.eval(px0, py));
            let fy = f64::from(y) + 0.5;
            let row = y as usize * width;
            for x in x0..=x1 {
                stats.pixels_tested += 1;
                if e[0] > 0 && e[1] > 0 && e[2] > 0 {
                    stats.depth_tests += 1;
                    let value = plane.eval(f64::from(x) + 0.5, fy);
                    let key = match to_window {
                        None => value,
                        Some(l) => l.normalise(value),
                    };
                    let i = row + x as usize;
                    let fresh = accept_fresh && frame.ids[i] == NO_ID;
                    if let Some(stored) = self.depth.test_and_set(i, key, fresh) {
                        stats.depth_passes += 1;
                        frame.ids[i] = tri.prim;
                        frame.depth[i] = match to_window {
                            None => stored as f32,
                            Some(l) => l.to_window(l.denormalise(stored)) as f32,
                        };
                        sink.test(i, frame.depth[i], true);
                    } else {
                        sink.test(i, value as f32, false);
                    }
                }
                for k in 0..3 {
                    e[k] += edges[k].a * step;
                }
            }
        }
    }
}

/// Maps camera depth (clip w) to [0, 1] for the linear-depth demonstration,
/// and back to window depth for the output.
struct LinearDepth {
    near: f64,
    far: f64,
}

impl LinearDepth {
    fn for_scene(scene: &ScreenScene, source: DepthSource) -> Result<Option<Self>> {
        if source == DepthSource::WindowZ {
            return Ok(None);
        }
        match scene.camera.projection {
            hider_geom::Projection::Perspective { near, far, .. } => Ok(Some(Self { near, far })),
            // Orthographic window depth is already linear in camera depth:
            // the demonstration has nothing to show.
            hider_geom::Projection::Orthographic { .. } => Err(Error::Render {
                hider: "zbuffer".into(),
                message: "depth source linear-view-z needs a perspective camera".into(),
            }),
        }
    }

    fn normalise(&self, w: f64) -> f64 {
        (w - self.near) / (self.far - self.near)
    }

    fn denormalise(&self, t: f64) -> f64 {
        self.near + t * (self.far - self.near)
    }

    /// GL window depth of a point at camera distance `w`, clamped to
    /// [0, 1]: clipped vertices sit on the near plane only up to rounding,
    /// and with a near plane close to zero the formula amplifies that
    /// rounding far outside the range (found by fuzzing).
    fn to_window(&self, w: f64) -> f64 {
        let (n, f) = (self.near, self.far);
        let ndc = (f + n) / (f - n) - 2.0 * f * n / ((f - n) * w);
        ((ndc + 1.0) * 0.5).clamp(0.0, 1.0)
    }
}

impl Default for ZBuffer {
    fn default() -> Self {
        Self::new(ZBufferOptions::default())
    }
}

impl Hider for ZBuffer {
    type Options = ZBufferOptions;
    type Stats = ZBufferStats;

    /// A z-buffer with the given options. Its [`Hider::name`] is `zbuffer`
    /// followed by the non-default options (`zbuffer-fixed24`,
    /// `zbuffer-linear-z`...).
    fn new(options: ZBufferOptions) -> Self {
        Self {
            name: Self::name_of(&options),
            options,
            depth: DepthBuffer::default(),
        }
    }

    fn options(&self) -> &ZBufferOptions {
        &self.options
    }

    fn name(&self) -> &str {
        &self.name
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<ZBufferStats> {
        self.render_with(scene, frame, &mut NoTrace)
    }
}

impl ZBuffer {
    /// [`Hider::render`] with every depth test reported to `sink`
    /// ([`crate::trace`]).
    pub(crate) fn render_with(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
        sink: &mut impl DepthTestSink,
    ) -> Result<ZBufferStats> {
        check_frame(&self.name, scene, frame)?;
        frame.clear();
        self.depth.clear(self.options.depth_format, frame.len());
        let mut stats = ZBufferStats::default();
        let linear = LinearDepth::for_scene(scene, self.options.depth_source)?;
        for (k, tri) in scene.tris.iter().enumerate() {
            self.options.cancel.poll_every(k)?;
            self.draw(scene, tri, linear.as_ref(), frame, &mut stats, sink);
        }
        stats.depth_bytes = self.depth.bytes() as u64;
        Ok(stats)
    }
}
