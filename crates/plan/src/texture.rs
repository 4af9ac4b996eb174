//! Diffuse textures (`map_Kd`): loading and sampling.
//!
//! The texture code lives in [`hider_scene::texture`], beside the surface
//! colour lookup that every colour-resolving hider calls
//! ([`hider_scene::surface`]); it is re-exported here, where the effect
//! stages and the analysis use it.

pub use hider_scene::texture::*;
