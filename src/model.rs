//! Loading the model a subcommand names, with the loader's warnings shown.

use anyhow::Result;
use hider::scene::Scene;

/// Loads an OBJ file or builds a generated scene (`gen:NAME`), printing the
/// loader's warnings on stderr.
pub fn load(model: &str) -> Result<Scene> {
    let scene = hider::plan::load_model(model)?;
    for w in &scene.warnings {
        eprintln!("hider: warning: {w}");
    }
    Ok(scene)
}
