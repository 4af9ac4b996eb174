//! Loading the model a subcommand names, with the loader's warnings shown.

use anyhow::Result;
use hider::scene::Scene;

use crate::progress::Progress;

/// Loads an OBJ file or builds a generated scene (`gen:NAME`), printing the
/// loader's warnings on stderr (with the spinner lifted).
pub fn load(model: &str, progress: &Progress) -> Result<Scene> {
    let scene = hider::scene::load_model(model)?;
    progress.suspend(|| {
        for w in &scene.warnings {
            crate::progress::eprint_line(&format!("hider: warning: {w}"));
        }
    });
    Ok(scene)
}
