//! hider: the classic hidden-surface algorithms side by side.
//!
//! This facade re-exports the workspace's crates and the [`registry`] of
//! every hider, which the `hider` command-line tool, the benchmark and the
//! cross-validating property tests all read:
//!
//! | crate | what |
//! |---|---|
//! | [`geom`] | camera, clipping, fixed-point snapping, edge functions, planes |
//! | [`scene`] | scene model, OBJ/MTL, the shared front end `prepare`, frames, the `Hider` trait |
//! | [`zbuffer`] | depth buffer with five depth formats, and its tiled parallel form |
//! | [`abuffer`] | Carpenter's A-buffer with 8x4 coverage masks, and supersampling baselines |
//! | [`painter`] | painter's algorithm: naive sort, Newell-Newell-Sancha with splitting, SVG |
//! | [`warnock`] | Warnock's area subdivision |
//! | [`scanline`] | scanline with edge table, active edge list and spans |
//! | [`oracle`] | the slow exact references every test measures against |
//! | [`vector`] | exact visible regions and hidden lines as SVG |
//! | [`plan`] | the registry of hiders, scene analysis, effect stages, the planner behind `--algo auto`, model loading |
//!
//! The `hider` command-line tool is a package of its own (`hider-cli`, the
//! workspace's root), and so is the comparative benchmark, `hider-bench`
//! with its timing programs: this library links neither their argument
//! parsing nor their plotting and reporting.
//!
//! # Example
//!
//! Render a procedural cube with every exact pixel-centre hider and check
//! that they agree:
//!
//! ```
//! use hider::scene::{prepare, procedural, Frame, PrepareOptions, View};
//!
//! let scene = procedural::cube();
//! let view = View::for_scene(&scene, 48, 48)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let mut first: Option<Frame> = None;
//! for mut hider in hider::registry::pixel_centre_hiders() {
//!     let mut frame = Frame::new(48, 48)?;
//!     hider.render(&screen, &mut frame)?;
//!     match &first {
//!         None => first = Some(frame),
//!         Some(f) => assert_eq!(f.ids, frame.ids, "{}", hider.name()),
//!     }
//! }
//! # Ok::<(), hider::scene::Error>(())
//! ```

pub use hider_abuffer as abuffer;
pub use hider_geom as geom;
pub use hider_oracle as oracle;
pub use hider_painter as painter;
pub use hider_plan as plan;
pub use hider_scanline as scanline;
pub use hider_scene as scene;
pub use hider_vector as vector;
pub use hider_warnock as warnock;
pub use hider_zbuffer as zbuffer;

/// Every hider by name (re-exported from `hider-plan`).
pub use hider_plan::registry;
