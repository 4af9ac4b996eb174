//! The Mesa llvmpipe peer, driven through OSMesa (Debian bookworm's
//! `libosmesa6`, Mesa 22.3.6: the build the GL reference renders in
//! `shared/gl-reference` were made with).
//!
//! libOSMesa is opened at run time (`libloading`) rather than linked, so a
//! machine without it still builds and runs the other peers and gets one
//! line saying what to install. Every GL entry point is looked up with
//! `OSMesaGetProcAddress`. `PEERS_OSMESA=/path/to/libOSMesa.so` loads
//! another build instead of the system's.
//!
//! Per workload: the `f32` triangle list is uploaded once into a vertex
//! buffer object (`glGenBuffers` + `glBufferData`, `GL_STATIC_DRAW`) and
//! drawn as a vertex array from it; the matrix is loaded once with
//! `glLoadMatrixf` on `GL_PROJECTION` with an identity modelview (fixed
//! function, like the reference renders); depth test `GL_LESS` with a
//! 24-bit depth buffer cleared to 1.0, no culling, no blending, one flat
//! colour. The span timed is `glClear(COLOR | DEPTH)` + `glDrawArrays` +
//! `glFinish`.
//!
//! Render target ([`Target`]): by default a framebuffer object with an
//! `RGBA8` colour and a `DEPTH_COMPONENT24` renderbuffer of `size x size`
//! (as the reference renders: `target=fbo/z24`), so the image stays in
//! GL's memory, as hider's tiled z-buffer leaves it in its tiles.
//! [`Target::Window`] renders into OSMesa's own `size x size` RGBA `u8`
//! buffer with a 24-bit depth buffer instead; there Mesa copies the whole
//! colour buffer into that memory on every `glFinish`
//! (`osmesa_st_framebuffer_flush_front`), which the span then includes.
//!
//! The thread count is llvmpipe's `LP_NUM_THREADS`, read once per process
//! when the first context is created; the driver runs this module in a
//! child process per thread count.

use std::ffi::{CStr, c_char, c_void};
use std::time::Instant;

use libloading::Library;

use crate::scenes::Workload;

/// Reference renders for hider's GL agreement test (a child module: it
/// drives the same context and entry points).
#[path = "reference.rs"]
pub mod reference;

/// llvmpipe with 4x multisampling, resolved (a child module: the same
/// context and entry points).
#[path = "msaa.rs"]
pub mod msaa;

type GLenum = u32;
type GLint = i32;
type GLuint = u32;
type GLsizei = i32;
type GLbitfield = u32;
type GLboolean = u8;
type GLfloat = f32;
type GLdouble = f64;
type GLubyte = u8;
type GLsizeiptr = isize;

const GL_RGBA: GLenum = 0x1908;
const GL_UNSIGNED_BYTE: GLenum = 0x1401;
const GL_COLOR_BUFFER_BIT: GLbitfield = 0x4000;
const GL_DEPTH_BUFFER_BIT: GLbitfield = 0x0100;
const GL_TRIANGLES: GLenum = 0x0004;
const GL_DEPTH_TEST: GLenum = 0x0B71;
const GL_LESS: GLenum = 0x0201;
const GL_CULL_FACE: GLenum = 0x0B44;
const GL_BLEND: GLenum = 0x0BE2;
const GL_DITHER: GLenum = 0x0BD0;
const GL_PROJECTION: GLenum = 0x1701;
const GL_MODELVIEW: GLenum = 0x1700;
const GL_VERTEX_ARRAY: GLenum = 0x8074;
const GL_FLOAT: GLenum = 0x1406;
const GL_ARRAY_BUFFER: GLenum = 0x8892;
const GL_STATIC_DRAW: GLenum = 0x88E4;
const GL_FLAT: GLenum = 0x1D00;
const GL_RENDERER: GLenum = 0x1F01;
const GL_VERSION: GLenum = 0x1F02;
const GL_DEPTH_BITS: GLenum = 0x0D56;
const GL_FRAMEBUFFER: GLenum = 0x8D40;
const GL_RENDERBUFFER: GLenum = 0x8D41;
const GL_RGBA8: GLenum = 0x8058;
const GL_DEPTH_COMPONENT24: GLenum = 0x81A6;
const GL_DEPTH_COMPONENT: GLenum = 0x1902;
const GL_COLOR_ATTACHMENT0: GLenum = 0x8CE0;
const GL_DEPTH_ATTACHMENT: GLenum = 0x8D00;
const GL_FRAMEBUFFER_COMPLETE: GLenum = 0x8CD5;

/// The library names tried, in order.
const LIBRARY_NAMES: [&str; 3] = ["libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"];

/// The environment variable that names another libOSMesa to load (a path),
/// instead of the system's.
pub const LIBRARY_VARIABLE: &str = "PEERS_OSMESA";

/// What to install when the library is missing.
pub const INSTALL_HINT: &str = "apt-get install -y libosmesa6-dev";

/// Where llvmpipe draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A framebuffer object (`RGBA8` + `DEPTH_COMPONENT24` renderbuffers).
    Fbo,
    /// OSMesa's own buffer in the caller's memory (copied to on `glFinish`).
    Window,
}

impl Target {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Target::Fbo => "fbo",
            Target::Window => "window",
        }
    }

    /// Parses a command-line name.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "fbo" => Some(Target::Fbo),
            "window" => Some(Target::Window),
            _ => None,
        }
    }
}

/// Declares the GL entry points used, as a struct of function pointers
/// filled by `OSMesaGetProcAddress`.
macro_rules! gl_api {
    ($($name:ident: fn($($arg:ty),*) $(-> $ret:ty)?;)*) => {
        /// The GL entry points this peer calls.
        #[allow(non_snake_case, reason = "the fields keep the GL entry points' own names")]
        struct Gl {
            $($name: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl Gl {
            /// Looks every entry point up; the first missing one is an
            /// error naming it.
            ///
            /// # Safety
            /// `get` must be libOSMesa's `OSMesaGetProcAddress`, and each
            /// signature above must be the one the GL specification gives.
            #[allow(clippy::useless_transmute, reason = "the transmute is the identity for the fn() entry points")]
            unsafe fn load(get: GetProcAddress) -> Result<Self, String> {
                Ok(Self {
                    $($name: {
                        let name = concat!(stringify!($name), "\0");
                        // SAFETY: `name` is NUL-terminated; `get` is
                        // OSMesaGetProcAddress (the caller's contract).
                        let f = unsafe { get(name.as_ptr().cast()) }
                            .ok_or_else(|| format!("libOSMesa lacks {}", stringify!($name)))?;
                        // SAFETY: a GL entry point of this name has this
                        // signature (the caller's contract); function
                        // pointers have one size.
                        unsafe {
                            std::mem::transmute::<
                                unsafe extern "C" fn(),
                                unsafe extern "C" fn($($arg),*) $(-> $ret)?,
                            >(f)
                        }
                    },)*
                })
            }
        }
    };
}

gl_api! {
    glGetError: fn() -> GLenum;
    glGetString: fn(GLenum) -> *const GLubyte;
    glGetIntegerv: fn(GLenum, *mut GLint);
    glViewport: fn(GLint, GLint, GLsizei, GLsizei);
    glEnable: fn(GLenum);
    glDisable: fn(GLenum);
    glDepthFunc: fn(GLenum);
    glShadeModel: fn(GLenum);
    glColor4ub: fn(GLubyte, GLubyte, GLubyte, GLubyte);
    glClearColor: fn(GLfloat, GLfloat, GLfloat, GLfloat);
    glClearDepth: fn(GLdouble);
    glMatrixMode: fn(GLenum);
    glLoadMatrixf: fn(*const GLfloat);
    glLoadIdentity: fn();
    glEnableClientState: fn(GLenum);
    glDisableClientState: fn(GLenum);
    glVertexPointer: fn(GLint, GLenum, GLsizei, *const c_void);
    glColorPointer: fn(GLint, GLenum, GLsizei, *const c_void);
    glGenBuffers: fn(GLsizei, *mut GLuint);
    glBindBuffer: fn(GLenum, GLuint);
    glBufferData: fn(GLenum, GLsizeiptr, *const c_void, GLenum);
    glDeleteBuffers: fn(GLsizei, *const GLuint);
    glGenFramebuffers: fn(GLsizei, *mut GLuint);
    glBindFramebuffer: fn(GLenum, GLuint);
    glCheckFramebufferStatus: fn(GLenum) -> GLenum;
    glFramebufferRenderbuffer: fn(GLenum, GLenum, GLenum, GLuint);
    glDeleteFramebuffers: fn(GLsizei, *const GLuint);
    glGenRenderbuffers: fn(GLsizei, *mut GLuint);
    glBindRenderbuffer: fn(GLenum, GLuint);
    glRenderbufferStorage: fn(GLenum, GLenum, GLsizei, GLsizei);
    glRenderbufferStorageMultisample: fn(GLenum, GLsizei, GLenum, GLsizei, GLsizei);
    glBlitFramebuffer: fn(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLbitfield, GLenum);
    glDeleteRenderbuffers: fn(GLsizei, *const GLuint);
    glClear: fn(GLbitfield);
    glDrawArrays: fn(GLenum, GLint, GLsizei);
    glFinish: fn();
    glReadPixels: fn(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, *mut c_void);
}

type GetProcAddress = unsafe extern "C" fn(*const c_char) -> Option<unsafe extern "C" fn()>;
type CreateContextExt =
    unsafe extern "C" fn(GLenum, GLint, GLint, GLint, *mut c_void) -> *mut c_void;
type MakeCurrent =
    unsafe extern "C" fn(*mut c_void, *mut c_void, GLenum, GLsizei, GLsizei) -> GLboolean;
type DestroyContext = unsafe extern "C" fn(*mut c_void);

/// An OSMesa context, current on this thread, with the GL entry points.
pub struct Llvmpipe {
    gl: Gl,
    make_current: MakeCurrent,
    destroy: DestroyContext,
    context: *mut c_void,
    /// OSMesa's colour buffer (RGBA `u8`, as `u32` for alignment); it must
    /// outlive the context's use of it, so it lives here.
    window: Vec<u32>,
    window_side: u32,
    /// Keeps the library loaded while the pointers above are in use
    /// (dropped last: fields drop in declaration order).
    _library: Library,
}

/// One workload's result.
pub struct GlRun {
    /// Milliseconds of each timed run (warm-ups excluded).
    pub ms: Vec<f64>,
    /// Milliseconds of each timed run of the frame delivered in client
    /// memory: clear + draw + `glReadPixels` of the colour (RGBA8) and of
    /// the depth (`GL_FLOAT`), which waits for the draw as `glFinish`
    /// does: what a caller of hider's `render` gets (a `Frame`).
    pub read_ms: Vec<f64>,
    /// Pixels covered in the last frame (alpha not 0 on read-back).
    pub covered: u64,
    /// Samples covered in the last frame: a pixel's alpha is the covered
    /// fraction of its samples after the resolve (all or none with one).
    pub samples: u64,
}

impl Llvmpipe {
    /// Opens libOSMesa and creates a current RGBA context with a 24-bit
    /// depth buffer. A missing library is an error naming what to install.
    pub fn open() -> Result<Self, String> {
        let mut tried = Vec::new();
        let chosen = std::env::var(LIBRARY_VARIABLE).ok();
        let names = match &chosen {
            Some(path) => vec![path.as_str()],
            None => LIBRARY_NAMES.to_vec(),
        };
        let library = names
            .iter()
            .find_map(|name| {
                // SAFETY: loading libOSMesa runs its initialisers, which
                // have no preconditions.
                unsafe { Library::new(name) }
                    .map_err(|e| tried.push(e.to_string()))
                    .ok()
            })
            .ok_or_else(|| {
                format!(
                    "libOSMesa not found ({}); install it with `{INSTALL_HINT}`",
                    tried.last().map_or("", String::as_str)
                )
            })?;
        // SAFETY: these are the OSMesa entry points declared in osmesa.h,
        // with those signatures.
        let (get, create, make_current, destroy) = unsafe {
            let sym = |e: libloading::Error| format!("libOSMesa: {e}");
            (
                *library
                    .get::<GetProcAddress>(b"OSMesaGetProcAddress\0")
                    .map_err(sym)?,
                *library
                    .get::<CreateContextExt>(b"OSMesaCreateContextExt\0")
                    .map_err(sym)?,
                *library
                    .get::<MakeCurrent>(b"OSMesaMakeCurrent\0")
                    .map_err(sym)?,
                *library
                    .get::<DestroyContext>(b"OSMesaDestroyContext\0")
                    .map_err(sym)?,
            )
        };
        // SAFETY: `get` is OSMesaGetProcAddress and the signatures in
        // `gl_api!` are the specification's.
        let gl = unsafe { Gl::load(get)? };
        // SAFETY: plain constructor call; a null share list is allowed.
        let context = unsafe { create(GL_RGBA, 24, 0, 0, std::ptr::null_mut()) };
        if context.is_null() {
            return Err("OSMesaCreateContextExt failed".into());
        }
        let mut me = Self {
            gl,
            make_current,
            destroy,
            context,
            window: Vec::new(),
            window_side: 0,
            _library: library,
        };
        me.bind_window(1)?;
        Ok(me)
    }

    /// Makes the context current on a `side x side` OSMesa buffer.
    fn bind_window(&mut self, side: u32) -> Result<(), String> {
        if self.window_side == side {
            return Ok(());
        }
        self.window = vec![0; side as usize * side as usize];
        self.window_side = side;
        // SAFETY: `window` holds side x side RGBA u8 pixels and lives in
        // `self` as long as the context may write to it (until the next
        // bind or drop, which destroys the context first).
        let ok = unsafe {
            (self.make_current)(
                self.context,
                self.window.as_mut_ptr().cast(),
                GL_UNSIGNED_BYTE,
                side as GLsizei,
                side as GLsizei,
            )
        };
        if ok == 0 {
            return Err(format!("OSMesaMakeCurrent at {side} x {side} failed"));
        }
        Ok(())
    }

    /// `GL_RENDERER` and `GL_VERSION`.
    pub fn describe(&self) -> String {
        let string = |name| {
            // SAFETY: the context is current; glGetString returns null or a
            // static NUL-terminated string.
            let p = unsafe { (self.gl.glGetString)(name) };
            if p.is_null() {
                "?".to_owned()
            } else {
                // SAFETY: non-null, NUL-terminated, static (above).
                unsafe { CStr::from_ptr(p.cast()) }
                    .to_string_lossy()
                    .into_owned()
            }
        };
        format!("{} / {}", string(GL_RENDERER), string(GL_VERSION))
    }

    /// The first pending GL error as an error message.
    fn check(&self, what: &str) -> Result<(), String> {
        // SAFETY: the context is current.
        let e = unsafe { (self.gl.glGetError)() };
        if e == 0 {
            Ok(())
        } else {
            Err(format!("GL error 0x{e:04x} after {what}"))
        }
    }

    /// Draws `work` at least `warmups` times (see [`crate::timed_runs`]),
    /// then `runs` times, timed
    /// (clear + draw + `glFinish`), then reads the image back and counts
    /// covered pixels.
    pub fn time(
        &mut self,
        work: &Workload,
        target: Target,
        warmups: usize,
        runs: usize,
    ) -> Result<GlRun, String> {
        let side = work.size as GLsizei;
        self.bind_window(work.size)?;
        let gl = &self.gl;
        let vertices = work.positions.len() as GLsizei;
        let vbo;
        let (mut fbo, mut rbs) = (0, [0; 2]);
        // SAFETY: the context is current on this thread; every pointer
        // handed to GL points to live memory of the size given
        // (`positions` is `3 * vertices` f32s; `mvp` 16 f32s).
        unsafe {
            if target == Target::Fbo {
                (gl.glGenRenderbuffers)(2, rbs.as_mut_ptr());
                (gl.glBindRenderbuffer)(GL_RENDERBUFFER, rbs[0]);
                (gl.glRenderbufferStorage)(GL_RENDERBUFFER, GL_RGBA8, side, side);
                (gl.glBindRenderbuffer)(GL_RENDERBUFFER, rbs[1]);
                (gl.glRenderbufferStorage)(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, side, side);
                (gl.glGenFramebuffers)(1, &mut fbo);
                (gl.glBindFramebuffer)(GL_FRAMEBUFFER, fbo);
                (gl.glFramebufferRenderbuffer)(
                    GL_FRAMEBUFFER,
                    GL_COLOR_ATTACHMENT0,
                    GL_RENDERBUFFER,
                    rbs[0],
                );
                (gl.glFramebufferRenderbuffer)(
                    GL_FRAMEBUFFER,
                    GL_DEPTH_ATTACHMENT,
                    GL_RENDERBUFFER,
                    rbs[1],
                );
                let status = (gl.glCheckFramebufferStatus)(GL_FRAMEBUFFER);
                if status != GL_FRAMEBUFFER_COMPLETE {
                    return Err(format!("framebuffer incomplete: 0x{status:04x}"));
                }
            } else {
                (gl.glBindFramebuffer)(GL_FRAMEBUFFER, 0);
            }
            let mut depth_bits = 0;
            (gl.glGetIntegerv)(GL_DEPTH_BITS, &mut depth_bits);
            if depth_bits != 24 {
                return Err(format!("depth buffer has {depth_bits} bits, not 24"));
            }
            vbo = draw_state(gl, work, side);
        }
        self.check("set-up")?;

        let ms = crate::timed_runs(warmups, runs, || {
            let t = Instant::now();
            // SAFETY: the context is current; the bound VBO holds
            // `vertices` vertices.
            unsafe {
                (gl.glClear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                (gl.glDrawArrays)(GL_TRIANGLES, 0, vertices);
                (gl.glFinish)();
            }
            t.elapsed().as_secs_f64() * 1e3
        });
        self.check("drawing")?;
        let n = side as usize * side as usize;
        let (mut color, mut depth) = (vec![0_u32; n], vec![0_f32; n]);
        let read_ms = crate::timed_runs(warmups, runs, || {
            let t = Instant::now();
            // SAFETY: the context is current; the bound VBO holds
            // `vertices` vertices; `color` and `depth` hold side x side
            // 4-byte values.
            unsafe {
                (gl.glClear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                (gl.glDrawArrays)(GL_TRIANGLES, 0, vertices);
                (gl.glReadPixels)(
                    0,
                    0,
                    side,
                    side,
                    GL_RGBA,
                    GL_UNSIGNED_BYTE,
                    color.as_mut_ptr().cast(),
                );
                (gl.glReadPixels)(
                    0,
                    0,
                    side,
                    side,
                    GL_DEPTH_COMPONENT,
                    GL_FLOAT,
                    depth.as_mut_ptr().cast(),
                );
            }
            t.elapsed().as_secs_f64() * 1e3
        });
        std::hint::black_box((&color, &depth));
        self.check("drawing and reading back")?;

        let (covered, samples);
        // SAFETY: the context is current; the names deleted are the ones
        // generated above (0 is ignored by the delete calls).
        unsafe {
            (covered, samples) = covered_pixels(gl, side, 1);
            (gl.glDisableClientState)(GL_VERTEX_ARRAY);
            (gl.glBindBuffer)(GL_ARRAY_BUFFER, 0);
            (gl.glDeleteBuffers)(1, &vbo);
            (gl.glBindFramebuffer)(GL_FRAMEBUFFER, 0);
            (gl.glDeleteFramebuffers)(1, &fbo);
            (gl.glDeleteRenderbuffers)(2, rbs.as_ptr());
        }
        self.check("read-back")?;
        Ok(GlRun {
            ms,
            read_ms,
            covered,
            samples,
        })
    }
}

impl Drop for Llvmpipe {
    fn drop(&mut self) {
        // SAFETY: `context` came from OSMesaCreateContextExt and is
        // destroyed once, while the library is still loaded.
        unsafe { (self.destroy)(self.context) };
    }
}

/// Reads the bound framebuffer (`side x side`) back and counts the pixels
/// with a non-zero alpha and the samples covered, for `samples` samples
/// per pixel: the clear colour has alpha 0, the drawn colour 255, and a
/// resolved multisample pixel the covered fraction of its samples
/// (`k * 255 / samples`, rounded), so `alpha * samples / 255` rounded is
/// the pixel's count of covered samples.
///
/// # Safety
///
/// A GL context must be current on this thread and `gl` its functions.
unsafe fn covered_pixels(gl: &Gl, side: GLsizei, samples: GLsizei) -> (u64, u64) {
    let mut pixels = vec![0u32; side as usize * side as usize];
    // SAFETY: the caller's context is current; `pixels` holds side x side
    // RGBA u8 pixels.
    unsafe {
        (gl.glReadPixels)(
            0,
            0,
            side,
            side,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            pixels.as_mut_ptr().cast(),
        );
    }
    // Alpha is the top byte of each little-endian RGBA pixel.
    let alpha = pixels.iter().map(|&p| u64::from(p >> 24));
    let n = samples as u64;
    alpha.fold((0, 0), |(covered, sampled), a| {
        (covered + u64::from(a != 0), sampled + (a * n + 127) / 255)
    })
}

/// The fixed-function state both measurements (single-sample and 4x
/// MSAA) draw with: viewport, the workload's matrix, depth test LESS, no
/// culling, blending or dithering, flat white, clear to black and depth
/// 1; the workload's positions in a new vertex buffer, bound. Returns the
/// buffer.
///
/// # Safety
///
/// A GL context must be current on this thread and `gl` its functions.
unsafe fn draw_state(gl: &Gl, work: &Workload, side: GLsizei) -> GLuint {
    let mut vbo = 0;
    // SAFETY: the caller's context is current; every pointer handed to GL
    // points to live memory of the size given (`positions` is
    // `3 * vertices` f32s; `mvp` 16 f32s).
    unsafe {
        (gl.glViewport)(0, 0, side, side);
        (gl.glMatrixMode)(GL_PROJECTION);
        (gl.glLoadMatrixf)(work.mvp.to_cols_array().as_ptr());
        (gl.glMatrixMode)(GL_MODELVIEW);
        (gl.glLoadIdentity)();
        (gl.glEnable)(GL_DEPTH_TEST);
        (gl.glDepthFunc)(GL_LESS);
        (gl.glDisable)(GL_CULL_FACE);
        (gl.glDisable)(GL_BLEND);
        (gl.glDisable)(GL_DITHER);
        (gl.glShadeModel)(GL_FLAT);
        (gl.glColor4ub)(255, 255, 255, 255);
        (gl.glClearColor)(0.0, 0.0, 0.0, 0.0);
        (gl.glClearDepth)(1.0);
        (gl.glGenBuffers)(1, &mut vbo);
        (gl.glBindBuffer)(GL_ARRAY_BUFFER, vbo);
        (gl.glBufferData)(
            GL_ARRAY_BUFFER,
            std::mem::size_of_val(work.positions.as_slice()) as GLsizeiptr,
            work.positions.as_ptr().cast(),
            GL_STATIC_DRAW,
        );
        (gl.glVertexPointer)(3, GL_FLOAT, 0, std::ptr::null());
        (gl.glEnableClientState)(GL_VERTEX_ARRAY);
    }
    vbo
}

/// The number of threads of this process besides the calling one (the
/// llvmpipe rasteriser threads, once a context exists), from `/proc`.
pub fn other_threads() -> Option<usize> {
    let tasks = std::fs::read_dir("/proc/self/task").ok()?.count();
    tasks.checked_sub(1)
}
