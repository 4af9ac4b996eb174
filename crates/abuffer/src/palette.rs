//! Per-primitive colours and opacities, computed once per frame.

use hider_scene::shade::prim_color;
use hider_scene::{ScreenScene, ShadeMode};

/// Fills `out` with `[r, g, b, opacity]` (linear) for every primitive of
/// `scene`, reusing its memory.
pub fn prim_colors(scene: &ScreenScene, mode: ShadeMode, out: &mut Vec<[f32; 4]>) {
    out.clear();
    out.extend((0..scene.prims.len() as u32).map(|prim| {
        let (rgb, alpha) = prim_color(scene, prim, mode);
        [rgb[0], rgb[1], rgb[2], alpha.clamp(0.0, 1.0)]
    }));
}

/// Converts a linear colour (already composited over the black background)
/// to an opaque sRGB pixel.
pub fn to_pixel(rgb: [f32; 3]) -> [u8; 4] {
    use hider_scene::shade::to_srgb8;
    [to_srgb8(rgb[0]), to_srgb8(rgb[1]), to_srgb8(rgb[2]), 255]
}
