//! What the Markdown report needs besides the results: where its images
//! are and how to link them, and the command that made it.

use std::path::PathBuf;

/// Options of the Markdown report: where its images are, and its command.
#[derive(Clone, Debug, Default)]
pub struct ReportOptions {
    /// How the report's images are linked from the report (`images/`).
    pub image_prefix: String,
    /// Folder holding the images, to link only those that exist.
    pub image_dir: PathBuf,
    /// The command that regenerates the report, quoted at the top.
    pub command: String,
    /// Folder the report is written to, to link only the files beside it.
    pub report_dir: PathBuf,
}

impl ReportOptions {
    /// The link to `name` beside the report, or `None` when the report's
    /// folder does not hold it (a link that would not resolve is left out).
    pub fn file_link(&self, name: &str) -> Option<String> {
        self.report_dir
            .join(name)
            .is_file()
            .then(|| name.to_owned())
    }

    /// The link to image `STEM.EXT`, or `None` when the image folder does
    /// not hold it (a plot that was not drawn is not linked).
    pub fn image_link(&self, stem: &str, ext: &str) -> Option<String> {
        let file = format!("{stem}.{ext}");
        self.image_dir
            .join(&file)
            .is_file()
            .then(|| format!("{}{file}", self.image_prefix))
    }
}
