//! What the front end produces: screen triangles, per-primitive data and
//! the screen-space scene every hider consumes.

use glam::{DMat4, DVec3, DVec4, Vec2, Vec3};
use hider_geom::fixed::{FixedPt, pixel_center};
use hider_geom::{Camera, PlaneEq, Viewport};

use crate::model::{Light, Material};
use crate::view::View;

/// A triangle ready for rasterisation: snapped, positively oriented, with
/// its depth and 1/w planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenTri {
    /// Vertices in 1/256 pixel, ordered so that
    /// `orient2d(v[0], v[1], v[2]) > 0` (edge functions positive inside).
    pub v: [FixedPt; 3],
    /// Window depth `z/w` in [0, 1] at each vertex.
    pub z: [f64; 3],
    /// Clip-space `w` at each vertex (camera-space distance along the view
    /// axis for a perspective camera, 1 for an orthographic one).
    pub w: [f64; 3],
    /// Window depth as an affine function of window position.
    pub depth: PlaneEq,
    /// `1/w` as an affine function of window position, for
    /// perspective-correct attributes.
    pub inv_w: PlaneEq,
    /// Primitive id: index of the source triangle in the scene.
    pub prim: u32,
    /// Whether the source triangle faces the camera (counter-clockwise on
    /// screen, GL's default front face).
    pub front_facing: bool,
}

impl ScreenTri {
    /// The edge functions of this triangle (GL's fill rule applied, `hider_geom::edge`).
    #[inline]
    pub fn edges(&self) -> [hider_geom::EdgeFunction; 3] {
        hider_geom::edge::triangle_edges(&self.v)
    }

    /// The inclusive pixel rectangle `(x0, y0, x1, y1)` whose centres may be
    /// covered, clamped to the viewport, or `None` if it is empty.
    pub fn pixel_bounds(&self, viewport: Viewport) -> Option<(u32, u32, u32, u32)> {
        viewport.pixel_bounds(&self.v)
    }

    /// Visits every pixel centre of [`Self::pixel_bounds`], row by row, with
    /// whether the exact edge functions (fill rule) cover it: the
    /// brute-force coverage walk the references, the scene statistics and
    /// the watertightness checks share (the hiders' own loops are faster).
    pub fn for_each_centre(&self, viewport: Viewport, mut visit: impl FnMut(u32, u32, bool)) {
        let Some((x0, y0, x1, y1)) = self.pixel_bounds(viewport) else {
            return;
        };
        let edges = self.edges();
        for j in y0..=y1 {
            let py = i64::from(pixel_center(j as i32));
            for i in x0..=x1 {
                let px = i64::from(pixel_center(i as i32));
                visit(i, j, edges.iter().all(|e| e.contains(px, py)));
            }
        }
    }
}

/// Per-primitive data kept for shading and for the exact oracle, indexed by
/// primitive id.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimInfo {
    /// Corners in camera space (`f64`, before any clipping).
    pub camera: [DVec3; 3],
    /// Index into [`ScreenScene::materials`].
    pub material: u32,
    /// Per-corner normals in camera space, when the mesh has normals.
    pub normals: Option<[Vec3; 3]>,
    /// Per-corner texture coordinates, when the mesh has them.
    pub uvs: Option<[Vec2; 3]>,
    /// Per-corner colours (the diffuse colour in place of the material's),
    /// when the mesh has them.
    pub colors: Option<[[f32; 3]; 3]>,
}

/// What the front end did, for statistics and warnings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PrepareStats {
    /// Triangles in the scene.
    pub input: u64,
    /// Triangles dropped entirely (behind the eye, outside the view, beyond
    /// near or far).
    pub culled: u64,
    /// Triangles cut by the near, far or guard-band planes.
    pub clipped: u64,
    /// Triangles (or clipped pieces) dropped because their snapped area is
    /// zero: they cover no sample.
    pub degenerate: u64,
    /// Back-facing triangles dropped by [`PrepareOptions::cull_back_faces`](crate::PrepareOptions::cull_back_faces).
    pub back_faces: u64,
    /// Screen triangles produced.
    pub output: u64,
    /// Triangles dropped by a depth-only front end of a hider's own (the
    /// tiled z-buffer's) because they certainly cover no pixel centre;
    /// always 0 from [`prepare`](crate::prepare()), which keeps them.
    pub empty: u64,
    /// Triangles a depth-only front end of a hider's own handed over as
    /// the pixels they cover rather than as triangles, because their box
    /// holds at most four pixel centres; not counted in [`Self::output`].
    /// Always 0 from [`prepare`](crate::prepare()).
    pub fragmented: u64,
}

impl PrepareStats {
    /// Adds the per-triangle counters of another run of triangles (all but
    /// [`Self::input`] and [`Self::output`], which describe a whole frame).
    pub fn add(&mut self, other: &Self) {
        self.empty += other.empty;
        self.fragmented += other.fragmented;
        self.culled += other.culled;
        self.clipped += other.clipped;
        self.degenerate += other.degenerate;
        self.back_faces += other.back_faces;
    }
}

/// A scene in screen space: what every hider consumes.
#[derive(Clone, Debug, PartialEq)]
pub struct ScreenScene {
    /// The image size.
    pub viewport: Viewport,
    /// The camera used.
    pub camera: Camera,
    /// World to camera space.
    pub view_matrix: DMat4,
    /// Camera space to clip space.
    pub projection_matrix: DMat4,
    /// The triangles, in primitive-id order (pieces of one clipped triangle
    /// are adjacent).
    pub tris: Vec<ScreenTri>,
    /// Per-primitive data, indexed by primitive id.
    pub prims: Vec<PrimInfo>,
    /// Materials; the scene's, plus the default material at the end.
    pub materials: Vec<Material>,
    /// Lights in camera space.
    pub lights: Vec<Light>,
    /// What the front end did.
    pub stats: PrepareStats,
}

impl ScreenScene {
    /// A scene with nothing in it yet, for [`crate::prepare_into`] (or a
    /// hider's own front end) to fill: `view`'s viewport and camera,
    /// identity matrices, no triangles.
    pub fn empty(view: &View) -> Self {
        Self {
            viewport: view.viewport,
            camera: view.camera,
            view_matrix: DMat4::IDENTITY,
            projection_matrix: DMat4::IDENTITY,
            tris: Vec::new(),
            prims: Vec::new(),
            materials: Vec::new(),
            lights: Vec::new(),
            stats: PrepareStats::default(),
        }
    }

    /// The material of a primitive.
    pub fn material(&self, prim: u32) -> &Material {
        &self.materials[self.prims[prim as usize].material as usize]
    }

    /// Whether the camera is a perspective one.
    pub fn is_perspective(&self) -> bool {
        matches!(
            self.camera.projection,
            hider_geom::Projection::Perspective { .. }
        )
    }

    /// The camera-space ray through window position `(x, y)` (pixels):
    /// `(origin, direction)`, direction not normalised. For a perspective
    /// camera the origin is the eye; for an orthographic one it lies on the
    /// near plane.
    pub fn camera_ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let vp = self.viewport;
        let ndc_x = 2.0 * x / f64::from(vp.width) - 1.0;
        let ndc_y = 1.0 - 2.0 * y / f64::from(vp.height);
        let inv = self.projection_matrix.inverse();
        let near = inv * DVec4::new(ndc_x, ndc_y, -1.0, 1.0);
        let far = inv * DVec4::new(ndc_x, ndc_y, 1.0, 1.0);
        let near = near.truncate() / near.w;
        let far = far.truncate() / far.w;
        if self.is_perspective() {
            (DVec3::ZERO, near)
        } else {
            (near, far - near)
        }
    }
}
