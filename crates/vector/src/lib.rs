//! Exact visible regions and hidden-line drawings as vector output.
//!
//! A painter's SVG is a stack of overlapping pieces: everything hidden is
//! still in the file, painted over, and viewers show hairline seams where
//! anti-aliased neighbours meet. This crate writes what is actually seen:
//! - [`visible_regions`]: for every primitive the exact part of the image
//!   where it is the nearest surface, as integer polygons on the front
//!   end's 1/256-pixel grid (refined), regions of one flat face merged
//!   into one path ([`regions_svg`]);
//! - [`hidden_lines`] / [`hidden_lines_in`]: the visible parts of
//!   silhouettes, open boundaries, creases, material boundaries and
//!   surface intersections as polylines joined end to end and ordered for
//!   a pen plotter ([`lines_svg`] / [`lines_document`]), optionally with
//!   the hidden parts dashed.
//!
//! Both work in object space on the [`hider_scene::ScreenScene`] every
//! hider consumes. The regions agree with the pixel-centre hiders at every
//! pixel centre that is not a depth tie (the tests check it against the
//! z-buffer on every hard case); the lines are decided against the
//! unsnapped camera-space triangles and match a ray-cast reference. The
//! SVG documents are in pixel coordinates, layered by object (Inkscape
//! layers, [`SvgInfo`]), with a title and description, and the regions
//! are stroked against the seams anti-aliasing viewers draw. The method
//! and its cost are described in `docs/vector.md`.
//!
//! ```
//! use hider_scene::{prepare, procedural, PrepareOptions, ShadeMode, View};
//! use hider_vector::{hidden_lines, regions_svg, visible_regions, VectorOptions};
//!
//! let scene = procedural::cube();
//! let screen = prepare(&scene, &View::for_scene(&scene, 64, 64)?, &PrepareOptions::default())?;
//! let options = VectorOptions::default();
//! let map = visible_regions(&screen, &options, ShadeMode::Lambert)?;
//! let svg = regions_svg(&screen, &map, &options);
//! assert_eq!(svg.matches("<path data-prim").count(), map.groups.len());
//! let lines = hidden_lines(&screen, &map, &options)?;
//! assert!(!lines.visible.is_empty());
//! # Ok::<(), hider_scene::Error>(())
//! ```

mod chain;
mod close;
mod closed;
mod contact;
mod cover;
mod cull;
mod document;
mod grid;
mod group;
mod hot;
mod lines;
mod options;
mod ownership;
mod pairs;
mod parts;
mod regions;
mod snap;
mod splitter;
mod stars;
mod subtract;
mod svg;
mod sweep;

pub use document::{ObjectGroups, SvgInfo};
pub use grid::Grid;
pub use lines::{
    Feature, LineDrawing, LineKind, LineStats, Polyline, Visibility, feature_visibility,
    hidden_lines, hidden_lines_in, line_features, pen_up_travel,
};
pub use options::{PAIRS_LIMIT, REGION_POINTS_LIMIT, VectorOptions};
pub use regions::{FaceGroup, PrimRegion, RegionMap, RegionStats, line_pairs, visible_regions};
pub use svg::{
    kind_name, lines_document, lines_svg, regions_document, regions_svg, write_document,
    write_lines_svg, write_regions_svg,
};

/// The scene crate this one renders from (scene model, OBJ loading, the
/// front end, frames, the camera, `glam`), so that one dependency is
/// enough to render.
pub use hider_scene as scene;

/// The error every failure of this crate is reported as.
pub(crate) fn render_error(message: String) -> hider_scene::Error {
    hider_scene::Error::Render {
        hider: "vector".to_owned(),
        message,
    }
}
