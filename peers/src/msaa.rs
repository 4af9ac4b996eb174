//! llvmpipe with 4x multisample anti-aliasing: what hider's A-buffer
//! (32 coverage samples per pixel, resolved to one colour) is measured
//! against.
//!
//! The workload and state are those of the single-sample measurement
//! ([`Llvmpipe::time`]: the same vertex buffer, matrix, depth test
//! `GL_LESS`, no culling, blending or dithering, one flat colour), drawn
//! into a framebuffer object whose `RGBA8` colour and
//! `DEPTH_COMPONENT24` renderbuffers have 4 samples
//! (`glRenderbufferStorageMultisample`), then resolved with
//! `glBlitFramebuffer` into a single-sample `RGBA8` framebuffer object, as
//! an application presenting an anti-aliased frame does. The span timed
//! is `glClear(COLOR | DEPTH)` + `glDrawArrays` + the resolve blit +
//! `glFinish`.
//!
//! Coverage is read back from the resolved image as covered *samples*
//! (a pixel's alpha is the covered fraction of its 4 samples) and checked
//! against the samples hider's front end covers at llvmpipe's 4 sample
//! positions ([`crate::scenes::hider_msaa_samples`]): comparing covered
//! pixels with pixel centres instead counts a pixel whose centre is
//! outside but one sample inside, which thin triangles (the spider's
//! legs) make by the hundred.

use std::time::Instant;

use super::{
    GL_ARRAY_BUFFER, GL_COLOR_ATTACHMENT0, GL_COLOR_BUFFER_BIT, GL_DEPTH_ATTACHMENT,
    GL_DEPTH_BUFFER_BIT, GL_DEPTH_COMPONENT24, GL_FRAMEBUFFER, GL_FRAMEBUFFER_COMPLETE,
    GL_RENDERBUFFER, GL_RGBA8, GL_TRIANGLES, GL_VERTEX_ARRAY, GLsizei, GLuint, GlRun, Llvmpipe,
};
use crate::scenes::Workload;

/// Samples per pixel of the multisampled framebuffer.
pub const SAMPLES: GLsizei = 4;

const GL_READ_FRAMEBUFFER: u32 = 0x8CA8;
const GL_DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const GL_NEAREST: u32 = 0x2600;
const GL_SAMPLES: u32 = 0x80A9;

/// The framebuffer objects of one measurement.
struct Targets {
    /// Multisampled draw target and the single-sample resolve target.
    fbos: [GLuint; 2],
    /// Multisampled colour and depth, single-sample colour.
    rbs: [GLuint; 3],
}

impl Llvmpipe {
    /// Draws `work` into a 4-sample framebuffer and resolves it, at least
    /// `warmups` times (see [`crate::timed_runs`]), then `runs` times,
    /// timed (clear + draw + resolve blit + `glFinish`); then reads the
    /// resolved image back and counts the pixels any sample covers.
    pub fn time_msaa(
        &mut self,
        work: &Workload,
        warmups: usize,
        runs: usize,
    ) -> Result<GlRun, String> {
        let side = work.size as GLsizei;
        self.bind_window(work.size)?;
        let targets = self.msaa_targets(side)?;
        let gl = &self.gl;
        let vertices = work.positions.len() as GLsizei;
        // SAFETY: the context is current on this thread (bound above).
        let vbo = unsafe { super::draw_state(gl, work, side) };
        self.check("multisample set-up")?;

        let [draw, resolve] = targets.fbos;
        let ms = crate::timed_runs(warmups, runs, || {
            let t = Instant::now();
            // SAFETY: the context is current; the bound VBO holds
            // `vertices` vertices; both framebuffers are complete and
            // `side x side`.
            unsafe {
                (gl.glBindFramebuffer)(GL_FRAMEBUFFER, draw);
                (gl.glClear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                (gl.glDrawArrays)(GL_TRIANGLES, 0, vertices);
                (gl.glBindFramebuffer)(GL_READ_FRAMEBUFFER, draw);
                (gl.glBindFramebuffer)(GL_DRAW_FRAMEBUFFER, resolve);
                (gl.glBlitFramebuffer)(
                    0,
                    0,
                    side,
                    side,
                    0,
                    0,
                    side,
                    side,
                    GL_COLOR_BUFFER_BIT,
                    GL_NEAREST,
                );
                (gl.glFinish)();
            }
            t.elapsed().as_secs_f64() * 1e3
        });
        self.check("multisample drawing and resolve")?;

        let (covered, samples);
        // SAFETY: the context is current; the names deleted are the ones
        // generated here.
        unsafe {
            (gl.glBindFramebuffer)(GL_FRAMEBUFFER, resolve);
            (covered, samples) = super::covered_pixels(gl, side, SAMPLES);
            (gl.glDisableClientState)(GL_VERTEX_ARRAY);
            (gl.glBindBuffer)(GL_ARRAY_BUFFER, 0);
            (gl.glDeleteBuffers)(1, &vbo);
            (gl.glBindFramebuffer)(GL_FRAMEBUFFER, 0);
            (gl.glDeleteFramebuffers)(2, targets.fbos.as_ptr());
            (gl.glDeleteRenderbuffers)(3, targets.rbs.as_ptr());
        }
        self.check("multisample read-back")?;
        Ok(GlRun {
            ms,
            read_ms: Vec::new(),
            covered,
            samples,
        })
    }

    /// Creates the 4-sample draw framebuffer and the single-sample resolve
    /// framebuffer, both `side x side`, and checks that the first really
    /// has 4 samples and a 24-bit depth buffer.
    fn msaa_targets(&mut self, side: GLsizei) -> Result<Targets, String> {
        let gl = &self.gl;
        let mut t = Targets {
            fbos: [0; 2],
            rbs: [0; 3],
        };
        // SAFETY: the context is current; the arrays passed have the
        // lengths given.
        let (status, samples, depth_bits) = unsafe {
            (gl.glGenRenderbuffers)(3, t.rbs.as_mut_ptr());
            (gl.glGenFramebuffers)(2, t.fbos.as_mut_ptr());
            (gl.glBindRenderbuffer)(GL_RENDERBUFFER, t.rbs[0]);
            (gl.glRenderbufferStorageMultisample)(GL_RENDERBUFFER, SAMPLES, GL_RGBA8, side, side);
            (gl.glBindRenderbuffer)(GL_RENDERBUFFER, t.rbs[1]);
            (gl.glRenderbufferStorageMultisample)(
                GL_RENDERBUFFER,
                SAMPLES,
                GL_DEPTH_COMPONENT24,
                side,
                side,
            );
            (gl.glBindRenderbuffer)(GL_RENDERBUFFER, t.rbs[2]);
            (gl.glRenderbufferStorage)(GL_RENDERBUFFER, GL_RGBA8, side, side);
            (gl.glBindFramebuffer)(GL_FRAMEBUFFER, t.fbos[1]);
            (gl.glFramebufferRenderbuffer)(
                GL_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                GL_RENDERBUFFER,
                t.rbs[2],
            );
            let resolve = (gl.glCheckFramebufferStatus)(GL_FRAMEBUFFER);
            (gl.glBindFramebuffer)(GL_FRAMEBUFFER, t.fbos[0]);
            (gl.glFramebufferRenderbuffer)(
                GL_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                GL_RENDERBUFFER,
                t.rbs[0],
            );
            (gl.glFramebufferRenderbuffer)(
                GL_FRAMEBUFFER,
                GL_DEPTH_ATTACHMENT,
                GL_RENDERBUFFER,
                t.rbs[1],
            );
            let draw = (gl.glCheckFramebufferStatus)(GL_FRAMEBUFFER);
            let (mut samples, mut depth_bits) = (0, 0);
            (gl.glGetIntegerv)(GL_SAMPLES, &mut samples);
            (gl.glGetIntegerv)(super::GL_DEPTH_BITS, &mut depth_bits);
            let status = if draw != GL_FRAMEBUFFER_COMPLETE {
                draw
            } else {
                resolve
            };
            (status, samples, depth_bits)
        };
        if status != GL_FRAMEBUFFER_COMPLETE {
            return Err(format!(
                "multisample framebuffer incomplete: 0x{status:04x}"
            ));
        }
        if samples != SAMPLES || depth_bits != 24 {
            return Err(format!(
                "multisample framebuffer has {samples} samples and {depth_bits} depth bits, \
                 not {SAMPLES} and 24"
            ));
        }
        Ok(t)
    }
}
