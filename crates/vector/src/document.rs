//! What an SVG says about itself: a title and description (model,
//! camera, size) and the object groups its paths are layered by.

use hider_scene::{Scene, ScreenScene};

/// Which object (OBJ `o`/`g` group, or generated mesh) each primitive
/// belongs to: the meshes of a [`Scene`] in primitive-id order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjectGroups {
    /// The name of each group.
    names: Vec<String>,
    /// The first primitive id of each group, ascending; `starts[0] == 0`.
    starts: Vec<u32>,
}

impl Default for ObjectGroups {
    /// One group, `scene`, holding every primitive.
    fn default() -> Self {
        Self {
            names: vec!["scene".to_owned()],
            starts: vec![0],
        }
    }
}

impl ObjectGroups {
    /// The meshes of `scene`, in primitive-id order (empty meshes left
    /// out). A scene without meshes has the one default group.
    pub fn from_scene(scene: &Scene) -> Self {
        let mut names = Vec::new();
        let mut starts = Vec::new();
        let mut at = 0u32;
        for mesh in &scene.meshes {
            if mesh.indices.is_empty() {
                continue;
            }
            names.push(if mesh.name.is_empty() {
                format!("object{}", names.len())
            } else {
                mesh.name.clone()
            });
            starts.push(at);
            at += mesh.indices.len() as u32;
        }
        if names.is_empty() {
            return Self::default();
        }
        Self { names, starts }
    }

    /// The number of groups.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether there is no group (never: there is at least one).
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The group of primitive `prim`.
    pub fn group_of(&self, prim: u32) -> u32 {
        (self.starts.partition_point(|&s| s <= prim).max(1) - 1) as u32
    }

    /// The name of group `group`.
    pub fn name(&self, group: u32) -> &str {
        &self.names[group as usize]
    }

    /// An XML id for group `group` inside a layer called `prefix`: the
    /// name's letters, digits, `-` and `_`, and the group's index (names
    /// need not be unique).
    pub fn id(&self, prefix: &str, group: u32) -> String {
        let name: String = self
            .name(group)
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        format!("{prefix}-{group}-{name}")
    }
}

/// The document-level metadata of an SVG: `<title>`, `<desc>` and the
/// object groups paths are layered by.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SvgInfo {
    /// The `<title>` (empty: none written).
    pub title: String,
    /// The `<desc>` (empty: none written).
    pub description: String,
    /// The object groups: one Inkscape layer each.
    pub groups: ObjectGroups,
}

impl SvgInfo {
    /// Title `model`, a description naming the model, the camera, the
    /// image size and the coordinate convention, and the scene's object
    /// groups.
    pub fn for_scene(scene: &Scene, model: &str, screen: &ScreenScene) -> Self {
        let c = &screen.camera;
        let v = |p: glam::DVec3| format!("{:.4},{:.4},{:.4}", p.x, p.y, p.z);
        let projection = match c.projection {
            hider_geom::Projection::Perspective {
                fovy_degrees,
                near,
                far,
            } => format!("perspective, fovy {fovy_degrees} degrees, near {near}, far {far}"),
            hider_geom::Projection::Orthographic { .. } => "orthographic".to_owned(),
        };
        let description = format!(
            "model {model}; {} triangles in {} objects; camera eye {} target {} up {}, {projection}; \
             image {} x {} pixels; coordinates are pixels (y down) with at most 4 decimals",
            scene.triangle_count(),
            scene.meshes.len(),
            v(c.eye),
            v(c.target),
            v(c.up),
            screen.viewport.width,
            screen.viewport.height,
        );
        Self {
            title: model.to_owned(),
            description,
            groups: ObjectGroups::from_scene(scene),
        }
    }

    /// With another description line appended (a note for the reader,
    /// such as that region fills are flat).
    pub fn with_note(mut self, note: &str) -> Self {
        if !self.description.is_empty() {
            self.description.push_str("; ");
        }
        self.description.push_str(note);
        self
    }
}

/// Escapes text for XML content and attribute values.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}
