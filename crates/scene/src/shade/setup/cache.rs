//! The shading setups of the primitives a hider is shading, kept while it
//! shades them: a hider that shades a primitive at many points (each
//! pixel of a fragment list, each sample of a supersampled pixel) builds
//! the primitive's [`SurfaceSetup`] once, not once per point.

use super::SurfaceSetup;

/// Shading setups direct-mapped by primitive id ([`Self::SLOTS`] entries
/// once used). A pixel's fragments or samples alternate between a few
/// primitives, and neighbouring pixels see the same ones: a single last
/// entry missed on 4 of 10 pixels of the smooth-shaded spider, 64 slots
/// keep nearly all of them (assembling a setup per pixel cost 11 % of that
/// frame at 1024).
///
/// A setup is a primitive's for one frame (its planes use the frame's
/// camera): [`Self::clear`] it when the frame (or the scene) changes.
#[derive(Clone, Debug, Default)]
pub struct SetupCache {
    slots: Vec<Option<(u32, SurfaceSetup)>>,
    /// Setups built (misses), for tests and statistics.
    built: u64,
}

impl SetupCache {
    /// Entries of the table.
    pub const SLOTS: usize = 256;

    /// Forgets every setup (a new frame).
    pub fn clear(&mut self) {
        self.slots.fill(None);
    }

    /// The setup of primitive `prim`, made by `make` when it is not held.
    #[inline]
    pub fn get_or_insert_with(
        &mut self,
        prim: u32,
        make: impl FnOnce() -> SurfaceSetup,
    ) -> &mut SurfaceSetup {
        if self.slots.is_empty() {
            self.slots.resize(Self::SLOTS, None);
        }
        let slot = &mut self.slots[prim as usize % Self::SLOTS];
        if slot.as_ref().is_some_and(|(p, _)| *p != prim) {
            *slot = None;
        }
        if slot.is_none() {
            self.built += 1;
        }
        &mut slot.get_or_insert_with(|| (prim, make())).1
    }

    /// Setups built since the cache was made (each a miss).
    pub fn built(&self) -> u64 {
        self.built
    }
}

#[cfg(all(test, feature = "obj", feature = "image"))]
mod tests {
    use super::*;
    use crate::shade::texture::TextureRef;
    use crate::shade::{Texture, TextureOptions, TextureSampler};
    use crate::{PrepareOptions, View, load_obj, prepare};

    /// Colours and partial alphas through the cache are those of a setup
    /// per call, bit for bit, with primitives visited so that they share
    /// slots and come back after being evicted (the textured spider, every
    /// other material given a texture of partial alpha). Fails when a slot
    /// answers for another primitive (the id not checked).
    #[test]
    fn cached_setups_shade_as_a_setup_per_call() {
        let path = format!(
            "{}/../../assets/spider/spider.obj",
            env!("CARGO_MANIFEST_DIR")
        );
        let mut scene = load_obj(&path).unwrap();
        let texels: Vec<u8> = (0..32 * 32)
            .flat_map(|k| [(k % 251) as u8, 90, 200, if k % 3 == 0 { 255 } else { 90 }])
            .collect();
        let partial = Texture::from_srgba8(32, 32, &texels).unwrap();
        for m in scene.materials.iter_mut().step_by(2) {
            m.diffuse_texture = Some(TextureRef::from_texture("partial.png", partial.clone()));
        }
        let size = 128;
        let view = View::for_scene(&scene, size, size).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let sampler = TextureSampler::new(&screen, TextureOptions::default());
        let mut cache = SetupCache::default();
        let n = screen.prims.len() as u32;
        let (mut points, mut alphas) = (0u64, 0u64);
        for k in 0..3 * n {
            // Each primitive twice in a row (the second time a hit),
            // then the one a table's size less one further: the table's
            // slots fill, and a primitive that comes back finds its slot
            // taken.
            let prim = (k / 2 * (SetupCache::SLOTS as u32 - 1)) % n;
            let info = &screen.prims[prim as usize];
            let w = info.camera.map(|c| sampler.rays().window_of(c));
            let c = (w[0] + w[1] + w[2]) / 3.0;
            let (x, y) = (
                c.x + 0.25 * f64::from(k % 3),
                c.y - 0.125 * f64::from(k % 5),
            );
            let base = [0.25, 0.5, 0.75];
            let cached = screen.surface_rgb_cached(&sampler, &mut cache, prim, base, x, y);
            let fresh = screen.surface_rgb(&sampler, prim, base, x, y);
            assert_eq!(cached.map(f32::to_bits), fresh.map(f32::to_bits), "{prim}");
            let cached = screen.partial_alpha_at_cached(&sampler, &mut cache, prim, x, y);
            let fresh = screen.partial_alpha_at(&sampler, prim, x, y);
            assert_eq!(cached.map(f32::to_bits), fresh.map(f32::to_bits), "{prim}");
            points += 1;
            alphas += u64::from(fresh.is_some_and(|a| a < 1.0));
        }
        assert!(alphas * 10 > points, "{alphas} of {points}");
        // Each primitive's second point is a hit, its first a miss.
        let built = cache.built();
        assert!(
            built * 3 < points * 2 && built * 4 > points,
            "{built} of {points}"
        );
    }
}
