//! Alpha cut-outs at the hiders' own samples.
//!
//! A material whose texture alpha (`map_Kd`'s alpha channel times
//! `map_d`, [`hider_scene::shade::cutout`]) is only 0 or 1 is a cut-out:
//! each sample of the pattern is alpha-tested at its own position
//! (perspective-correct texture coordinates at the sample, the texture
//! sampling of hider-scene), and a sample whose alpha is below one half is
//! not covered. In the A-buffer that clears the bits of the fragment's
//! coverage mask, before its depth bounds, culling and merging see it, so
//! the fragment is an ordinary opaque fragment over the samples that
//! remain; the supersampled z-buffers skip the sample. The pixel centre
//! (ids and depth) is tested the same way.
//!
//! A material with partial alpha (some texel strictly between 0 and 1) is
//! translucency instead: no sample is cleared, and the compositing hiders
//! give it the opacity `d` times its texture alpha (the A-buffer at the
//! fragment's pixel centre, [`AlphaTest::opacity`]).
//!
//! Only the triangles whose material may cut out are looked at
//! ([`Cutouts::may_cut`]); a scene without such a material builds no
//! [`Cutouts`] at all, so it pays nothing.

use hider_scene::shade::AlphaClass;
use hider_scene::shade::cutout::{AlphaTest, PrimAlphaTest};
use hider_scene::{ScreenScene, TextureOptions};

use crate::coverage::Coverage;
use crate::pattern::SamplePattern;

/// The alpha test of a frame's primitives at the samples of `pattern`.
#[derive(Clone, Debug)]
pub(crate) struct Cutouts<'a> {
    test: AlphaTest<'a>,
    pattern: SamplePattern,
}

impl<'a> Cutouts<'a> {
    /// The test of `scene`'s primitives at `pattern`'s samples; `None` when
    /// no material may cut out (or no prepared scene is given: the lean
    /// front end is used only for scenes without cut-outs).
    pub(crate) fn new(scene: Option<&'a ScreenScene>, pattern: SamplePattern) -> Option<Self> {
        let test = AlphaTest::new(scene?, TextureOptions::default())?;
        Some(Self { test, pattern })
    }

    /// Whether `prim`'s samples may fail the test or take a texture
    /// opacity (its material may cut out and it has texture coordinates).
    #[inline]
    pub(crate) fn may_cut(&self, prim: u32) -> bool {
        self.test.may_cut(prim)
    }

    /// The test of primitive `prim` at many pixels (a triangle's
    /// fragments): its shading setup built once ([`PrimCutout`]).
    #[inline]
    pub(crate) fn prim(&self, prim: u32) -> PrimCutout<'_, 'a> {
        PrimCutout {
            test: self.test.prim(prim),
            pattern: self.pattern,
        }
    }

    /// `c` without the samples (and the centre) of pixel `(i, j)` where
    /// `prim` fails the alpha test: [`PrimCutout::coverage`].
    pub(crate) fn coverage(&self, prim: u32, ij: (u32, u32), c: Coverage) -> Coverage {
        self.prim(prim).coverage(ij, c)
    }

    /// Whether `prim`'s material has partial alpha (translucency).
    pub(crate) fn is_partial(&self, prim: u32) -> bool {
        self.may_cut(prim) && self.test.class(prim) == AlphaClass::Partial
    }
}

/// The alpha test of one primitive at the samples of a pattern, its
/// shading setup (barycentric planes, texture headers) built once: a
/// triangle's for all its fragments in a tile (a setup per fragment was
/// about 6 % of the cut-out spider's frame).
#[derive(Clone, Debug)]
pub(crate) struct PrimCutout<'t, 'a> {
    test: PrimAlphaTest<'t, 'a>,
    pattern: SamplePattern,
}

impl PrimCutout<'_, '_> {
    /// `c` without the samples (and the centre) of pixel `(i, j)` where
    /// the primitive fails the alpha test (texture alpha below one half):
    /// the covered samples are tested, one texture sample each. Not full
    /// any more when a sample was cleared. Partial alpha is tested too: a
    /// compositing hider asks [`Self::opacity`] first.
    pub(crate) fn coverage(&mut self, ij: (u32, u32), c: Coverage) -> Coverage {
        let mut out = c;
        for (k, &pos) in self.pattern.positions().iter().enumerate() {
            if c.mask >> k & 1 == 1
                && !self
                    .test
                    .passes_at(window(ij.0, pos.0), window(ij.1, pos.1))
            {
                out.mask &= !(1 << k);
            }
        }
        if c.centre && !self.test.passes(ij.0, ij.1) {
            out.centre = false;
        }
        out.full = out.full && out.mask == c.mask && out.centre;
        out
    }

    /// `d` times the primitive's texture alpha at the centre of pixel `ij`
    /// when its material has partial alpha ([`Cutouts::opacity`]).
    #[inline]
    pub(crate) fn opacity(&mut self, ij: (u32, u32)) -> Option<f32> {
        self.test.opacity(ij)
    }
}

/// The window coordinate of the sample at `offset` (1/256 pixel) inside
/// pixel column or row `p`.
#[inline]
fn window(p: u32, offset: i32) -> f64 {
    f64::from(p) + f64::from(offset) / 256.0
}
