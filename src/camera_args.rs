//! The image-size and camera flags, one definition that `hider render` and
//! `hider analyze` both flatten in, so that analyze plans for the view
//! render renders: `--size` or `--width`/`--height`, `--eye`, `--target`,
//! `--up`, `--fovy`, `--near`, `--far`; and the `--precision` and
//! `--shade` values.

use anyhow::{Context, Result, bail};
use clap::Args;
use glam::DVec3;
use hider::geom::Camera;
use hider::scene::{CameraOverrides, Scene};

use crate::args;

/// Image size and camera flags.
#[derive(Args, Debug, Clone, Default)]
pub struct ViewArgs {
    /// Square image size in pixels (1 to 16384).
    #[arg(long, value_parser = args::side, conflicts_with_all = ["width", "height"])]
    size: Option<u32>,
    /// Image width in pixels (with --height).
    #[arg(long, value_parser = args::side)]
    width: Option<u32>,
    /// Image height in pixels (with --width).
    #[arg(long, value_parser = args::side)]
    height: Option<u32>,
    /// Eye position x,y,z (default: the fit camera).
    #[arg(long, value_parser = args::vec3, allow_hyphen_values = true)]
    eye: Option<DVec3>,
    /// Point looked at x,y,z.
    #[arg(long, value_parser = args::vec3, allow_hyphen_values = true)]
    target: Option<DVec3>,
    /// Up direction x,y,z.
    #[arg(long, value_parser = args::vec3, allow_hyphen_values = true)]
    up: Option<DVec3>,
    /// Vertical field of view in degrees.
    #[arg(long, value_parser = args::fovy)]
    fovy: Option<f64>,
    /// Near plane distance (default: the scene's; fitted around the scene
    /// when --eye or --target moves the camera).
    #[arg(long, value_parser = args::distance)]
    near: Option<f64>,
    /// Far plane distance (default: the scene's; fitted around the scene
    /// when --eye or --target moves the camera).
    #[arg(long, value_parser = args::distance)]
    far: Option<f64>,
}

impl ViewArgs {
    /// The image size, `--size` or `--width` and `--height` (512 x 512 by
    /// default), checked.
    pub fn image_size(&self) -> Result<(u32, u32)> {
        let (width, height) = match (self.size, self.width, self.height) {
            (Some(n), _, _) => (n, n),
            (None, Some(w), Some(h)) => (w, h),
            (None, Some(w), None) => {
                bail!("--width {w} needs --height too (or --size for a square)")
            }
            (None, None, Some(h)) => {
                bail!("--height {h} needs --width too (or --size for a square)")
            }
            (None, None, None) => (512, 512),
        };
        hider::scene::view::check_image_size(width, height).context("bad image size")?;
        Ok((width, height))
    }

    /// The camera: the scene's (or the fit camera) with the flags given
    /// applied; `--fovy`, `--near` and `--far` apply to a perspective
    /// camera.
    pub fn camera(&self, scene: &Scene) -> Camera {
        CameraOverrides {
            eye: self.eye,
            target: self.target,
            up: self.up,
            fovy: self.fovy,
            near: self.near,
            far: self.far,
        }
        .apply(scene)
    }
}

/// `--precision`: the front end's transform arithmetic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum PrecisionArg {
    /// GL-compatible: f32 transforms, clipping at the viewport's sides.
    F32,
    /// f64 transforms.
    #[default]
    F64,
}

/// `--shade`: how the image is coloured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ShadeArg {
    /// Lambert shading with the scene's lights (or the head light).
    #[default]
    Lambert,
    /// False colours from the primitive ids.
    Ids,
}

impl PrecisionArg {
    /// The front end's options for this precision, parallel above one
    /// thread (as `hider render` prepares).
    pub fn prepare_options(self, threads: usize) -> hider::scene::PrepareOptions {
        match self {
            Self::F32 => hider::scene::PrepareOptions::gl_compatible(),
            Self::F64 => hider::scene::PrepareOptions::default(),
        }
        .with_parallel(threads > 1)
    }
}

impl ShadeArg {
    /// The library's shade mode.
    pub fn mode(self) -> hider::scene::ShadeMode {
        match self {
            Self::Lambert => hider::scene::ShadeMode::Lambert,
            Self::Ids => hider::scene::ShadeMode::Ids,
        }
    }
}
