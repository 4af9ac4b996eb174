//! The scene model and the shared front end of the hider workspace.
//!
//! `hider-scene` holds what every hidden-surface algorithm shares:
//! - the world-space [`Scene`] (meshes, materials, lights, camera), loaded
//!   from OBJ + MTL ([`obj`]) or generated ([`procedural`]);
//! - the front end [`prepare()`], which turns a scene and a [`View`] into a
//!   [`ScreenScene`] of snapped, set-up [`ScreenTri`]s — no hider re-projects;
//! - the parallel hiders' one policy for their threads ([`pool`]);
//! - the [`Cancel`] token every hider polls, to stop a render from
//!   outside or after a timeout;
//! - the [`Frame`] buffers with PNG output and the GL reference id/depth
//!   dumps, written atomically;
//! - the [`Hider`] trait (options, typed stats, one `new`, one `render`)
//!   and its object-safe twin [`DynHider`];
//! - all appearance in [`shade`]: materials' colours, lighting, textures
//!   (decoded on first use), the effect stages and the colour pass over an
//!   id buffer;
//! - models by name ([`load`]): an OBJ path or a generated `gen:` scene.
//!
//! Conventions (see `docs/conventions.md`): right-handed world, camera
//! looking down -Z, GL clip space; window origin top-left with y down;
//! pixel `(i, j)` sampled at `(i + 0.5, j + 0.5)`; vertices snapped to
//! 1/256 pixel; coverage by exact integer edge functions under GL's fill
//! rule (top-left in GL's bottom-up rows); window depth `z/w` in [0, 1].
//!
//! # Features
//!
//! All three are on by default; a crate that wants the front end alone
//! (a depth buffer) can take `default-features = false`:
//! - `obj`: OBJ/MTL loading (the [`obj`] module: a parallel reader for
//!   plain files, `tobj` for everything else and as the reference;
//!   `load_obj`, `load_obj_with`, and files in [`load_model`]; without it
//!   a file given to [`load_model`] is an error saying so, `gen:` scenes
//!   still load);
//! - `image`: PNG output (`Frame::write_png`, `Frame::write_png_into`,
//!   `Frame::to_rgba_image`) and texture decoding through `image`; without
//!   it every texture file is not loaded, with an error naming the file and
//!   the feature (the id and depth dumps need no `image`);
//! - `parallel`: the parallel front end and the hiders' thread pools
//!   ([`pool`]) through `rayon`; without it everything runs on the calling
//!   thread.
//!
//! See `docs/conventions.md`, "Features".
//!
//! # Example
//!
//! Prepare a procedural cube with the fit camera and look at what the front
//! end produced:
//!
//! ```
//! use hider_scene::{prepare, procedural, PrepareOptions, View};
//!
//! let scene = procedural::cube();
//! let view = View::for_scene(&scene, 64, 64)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! assert_eq!(screen.prims.len(), 12);
//! assert_eq!(screen.stats.culled, 0);
//! // Every screen triangle is positively oriented with a depth in [0, 1].
//! for t in &screen.tris {
//!     assert!(hider_scene::geom::orient2d(t.v[0], t.v[1], t.v[2]) > 0);
//!     assert!(t.z.iter().all(|z| (0.0..=1.0).contains(z)));
//! }
//! # Ok::<(), hider_scene::Error>(())
//! ```

pub mod atomic;
pub mod cancel;
pub mod error;
pub mod frame;
pub mod hider;
pub mod input;
pub mod load;
pub mod memory_files;
pub mod model;
#[cfg(feature = "obj")]
pub mod obj;
pub mod obj_write;
pub mod pixel_rays;
pub mod pool;
pub mod prepare;
pub mod procedural;
pub mod shade;
pub mod timing;
pub mod view;

pub use cancel::{Cancel, Cancelled};
pub use error::{Error, Result};
pub use frame::{Frame, FrameBuffers, NO_ID};
pub use hider::{
    Counter, DynHider, Hider, HiderStats, OrderedPolygons, StatsTable, check_frame,
    check_frame_size,
};
pub use load::{MAX_SOUP_TRIANGLES, MAX_SPHERE_SEGMENTS, generated, load_model};
pub use model::{Illumination, Light, Material, Mesh, Scene};
#[cfg(feature = "obj")]
pub use obj::{load_obj, load_obj_with};
pub use obj_write::save_obj;
pub use pixel_rays::{PixelSurface, SurfaceOutputs, surface_at_pixels};
pub use prepare::{
    PrepareOptions, PrepareStats, PrimInfo, ScreenScene, ScreenTri, TransformPrecision, prepare,
    prepare_into,
};
pub use shade::{
    Filter, Mapping, ShadeMode, Shader, Stages, Texture, TextureOptions, TextureRef,
    TextureSampler, shade_frame,
};
pub use view::{CameraOverrides, View, fit_camera, fit_camera_to_bounds};

/// The vector maths the scene is written in (`glam::DVec3` for positions).
pub use glam;
/// The geometry crate this one builds on.
pub use hider_geom as geom;
/// The camera, one re-export away (it lives in [`geom`]).
pub use hider_geom::{Camera, Projection, Viewport};
