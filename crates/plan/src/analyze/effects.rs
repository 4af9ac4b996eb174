//! What the analysis finds: each effect with its evidence, and the time it
//! took.

/// One effect: whether it is needed and why.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Evidence {
    /// Whether the effect is present (must be simulated).
    pub present: bool,
    /// False when the search ran out of budget: `present` is then the safe
    /// assumption, not a finding.
    pub certain: bool,
    /// How many instances were found (triangles, pairs, cycles...; see
    /// [`Evidence::detail`]).
    pub count: u64,
    /// Examples as groups of primitive ids: one id, a pair, or a cycle.
    pub examples: Vec<Vec<u32>>,
    /// One sentence saying what was found.
    pub detail: String,
}

impl Evidence {
    /// A certain finding.
    pub(crate) fn found(
        present: bool,
        count: u64,
        examples: Vec<Vec<u32>>,
        detail: String,
    ) -> Self {
        Self {
            present,
            certain: true,
            count,
            examples,
            detail,
        }
    }
}

/// Wall-clock time of the analysis steps, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AnalysisTimes {
    /// Front end (prepare).
    pub prepare_ms: f64,
    /// Triangle–triangle intersection search.
    pub intersections_ms: f64,
    /// Screen overlap graph and cycles.
    pub overlaps_ms: f64,
    /// Everything.
    pub total_ms: f64,
}

/// The work of the two searches over pairs, in pairs: what grows with the
/// scene's overlaps (the pairs the bins list) and what the exact tests
/// cost. Tests that guard against quadratic growth read these, not times.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AnalysisWork {
    /// Pairs the intersection grid listed (two triangles in one cell).
    pub intersection_candidates: u64,
    /// Exact triangle–triangle tests run (pairs whose boxes meet).
    pub intersection_tests: u64,
    /// Pairs the screen tiles listed (two triangles in one tile).
    pub overlap_candidates: u64,
    /// Pairs whose screen boxes meet, tested for overlap exactly.
    pub overlap_tests: u64,
}

impl AnalysisWork {
    /// Every pair listed or tested, both searches.
    pub fn total(&self) -> u64 {
        self.intersection_candidates
            + self.intersection_tests
            + self.overlap_candidates
            + self.overlap_tests
    }
}

/// The effects a scene calls for under given
/// [`RenderOptions`](super::RenderOptions).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Effects {
    /// Triangles in the scene.
    pub triangles: u64,
    /// Pixels of the image asked for (width x height).
    pub pixels: u64,
    /// Screen triangles after the front end (for a raster plan that
    /// needs no prepared scene, the triangles a frustum test keeps: an
    /// upper bound).
    pub on_screen: u64,
    /// Translucent materials in view: needs compositing (A-buffer).
    pub transparency: Evidence,
    /// Textured triangles in view: needs the texture stage.
    pub textures: Evidence,
    /// A `map_Kd` with an alpha channel on a textured mesh: needs the
    /// alpha test of cut-outs after visibility
    /// ([`hider_scene::Stages::cutout`]).
    pub cutouts: bool,
    /// Lights or normals with shading asked: needs the Lambert stage.
    pub lighting: Evidence,
    /// Anti-aliasing asked: needs multi-sample coverage.
    pub antialiasing: Evidence,
    /// Whether ordered polygons is asked.
    pub ordered_polygons: bool,
    /// Interpenetrating triangle pairs in view.
    pub intersections: Evidence,
    /// Coplanar overlapping pairs in view (depth ties, any hider's answer
    /// is a tie-break).
    pub coplanar_overlaps: Evidence,
    /// Cycles of the "in front of" relation in view.
    pub cyclic_overlap: Evidence,
    /// Back-facing triangles on screen that may be visible.
    pub back_faces: Evidence,
    /// Overlapping pairs a naive farthest-vertex sort paints in the wrong
    /// order.
    pub naive_order_violations: Evidence,
    /// Whether dropping back faces in the front end is exact and saves
    /// work: there are back faces on screen, all certainly hidden, and no
    /// transparency shows them.
    pub cull_back_faces_exact: bool,
    /// Distance of the farthest corner in view over the near distance, for
    /// a perspective camera (1 for orthographic): an f32 window-depth
    /// buffer resolves relative view distances of about `2^-24` times
    /// this at that corner.
    pub depth_ratio: f64,
    /// Splits the painter's ordered polygons need at least for the
    /// interpenetrating pairs found (0 when the search did not run):
    /// a conservative bound ([`super::splits`]) the planner compares with
    /// the painter's split budget.
    pub painter_splits_at_least: u64,
    /// Time spent.
    pub times: AnalysisTimes,
    /// Pairs listed and tested by the searches over pairs (zero when they
    /// did not run).
    pub work: AnalysisWork,
}

impl Effects {
    /// Adds to [`Self::transparency`] the triangles among `in_view` (with
    /// texture coordinates) whose material's alpha textures (`map_Kd`'s
    /// alpha channel, `map_d`) hold partial alpha, a texel strictly
    /// between 0 and 1: translucency, which a compositing hider must
    /// draw. The evidence names each texture and the share of its texels
    /// that is partial. Textures whose alpha is only 0 or 1 are cut-outs
    /// and stay opaque ([`Self::cutouts`]). Reads headers, and decodes (at
    /// the coarsest mip level) only the alpha textures of materials in
    /// view that may cut out.
    pub(crate) fn add_partial_alpha(
        &mut self,
        screen: &hider_scene::ScreenScene,
        in_view: &[u32],
        ex: usize,
    ) {
        use hider_scene::shade::cutout::{material_may_cut_out, material_partial_alpha};
        let mut found: Vec<Option<Vec<(String, f64)>>> = vec![None; screen.materials.len()];
        let mut ids = Vec::new();
        for &p in in_view {
            let info = &screen.prims[p as usize];
            if info.uvs.is_none() {
                continue;
            }
            let m = info.material as usize;
            let partial = found[m].get_or_insert_with(|| {
                let material = &screen.materials[m];
                if material_may_cut_out(material) {
                    material_partial_alpha(material)
                } else {
                    Vec::new()
                }
            });
            if !partial.is_empty() {
                ids.push(p);
            }
        }
        if ids.is_empty() {
            return;
        }
        let mut textures: Vec<String> = found
            .into_iter()
            .flatten()
            .flatten()
            .map(|(file, share)| format!("{file}: {:.1}% of texels", 100.0 * share))
            .collect();
        textures.sort_unstable();
        textures.dedup();
        let detail = format!(
            "{} triangles in view with partial texture alpha (translucency; {})",
            ids.len(),
            textures.join(", ")
        );
        let t = &mut self.transparency;
        t.detail = if t.present {
            format!("{}; {detail}", t.detail)
        } else {
            detail
        };
        t.present = true;
        t.count += ids.len() as u64;
        let room = ex.saturating_sub(t.examples.len());
        t.examples.extend(ids.iter().take(room).map(|&p| vec![p]));
    }

    /// The effect stages these effects call for: the colour stages
    /// (texture, lighting) the colour pass runs, and the hider's
    /// (transparency, multisample) the planner picks a hider for.
    pub fn stages(&self) -> hider_scene::Stages {
        hider_scene::Stages {
            texture: self.textures.present,
            lighting: self.lighting.present,
            transparency: self.transparency.present,
            multisample: self.antialiasing.present,
            cutout: self.cutouts,
        }
    }
}
