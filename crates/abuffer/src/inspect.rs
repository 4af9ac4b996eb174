//! Reading one pixel's fragment list back after a frame, for teaching
//! and debugging: what the A-buffer built for that pixel and how its
//! resolve turned the list into the pixel's colour.
//!
//! Opt-in and after the fact: [`ABuffer::inspect_pixel`] reads the lists
//! the last [`Hider::render`](hider_scene::Hider::render) left in the
//! workers' pools (they stay until the next frame, as
//! [`ABuffer::sample_ids`] reads them) and resolves the pixel again with
//! the resolve the frame ran ([`crate::resolve::Resolver`]), so nothing
//! in a frame's path changes and the inspected resolve is the frame's
//! pixel. Tiles resolved from the sample buffer keep no lists
//! ([`ABufferOptions::sample_tiles`]): inspection asks for it off.

use hider_scene::frame::{BACKGROUND, BACKGROUND_DEPTH};
use hider_scene::prepare::lean::LeanTri;
use hider_scene::{Error, Hider, NO_ID, Result, ScreenScene};

use crate::abuffer::ABuffer;
use crate::bins::TILE;
use crate::fragment::{Fragment, NIL};
use crate::options::{ABufferOptions, DepthMode};
use crate::palette;
use crate::resolve::{Band, Input, Resolver};
use crate::source::{ColorCache, Source};
use crate::stats::ABufferStats;

/// One fragment of an inspected pixel's list, as the A-buffer stored it.
#[derive(Clone, Debug, PartialEq)]
pub struct InspectedFragment {
    /// Covered samples: bit `k` is sample `k` of the pattern
    /// ([`crate::SamplePattern::positions`]; the 32-sample pattern is the
    /// 8 x 4 grid, bit `k` at column `k % 8`, row `k / 8`).
    pub mask: u32,
    /// Its primitive (the lowest one merged into it).
    pub prim: u32,
    /// The primitive covering the pixel centre, [`NO_ID`] when the
    /// fragment does not cover it.
    pub centre_prim: u32,
    /// Nearest window depth over its samples and the centre.
    pub zmin: f32,
    /// Farthest window depth over its samples and the centre.
    pub zmax: f32,
    /// Window depth at the pixel centre, `INFINITY` when not covered.
    pub centre_z: f64,
    /// Per sample, the window depth the per-sample resolve compares (its
    /// triangle's plane at the sample, or a merged fragment's stored
    /// depth), `NAN` for samples it does not cover; empty in the other
    /// depth modes, whose resolve reads only `zmin` and `zmax`.
    pub sample_z: Vec<f32>,
    /// Linear colour and opacity, as the resolve shades it in this pixel.
    pub rgba: [f32; 4],
    /// Whether two or more triangles were merged into it.
    pub merged: bool,
}

/// One pixel's list and its resolve.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelInspection {
    /// The fragments in resolve order (nearest `zmin` first, lower
    /// primitive first on ties).
    pub fragments: Vec<InspectedFragment>,
    /// Per sample, the fragments covering it front to back (indices into
    /// [`Self::fragments`]): by each fragment's own depth at the sample in
    /// [`DepthMode::PerSample`], by list order in the other modes. An
    /// opaque fragment hides what follows it.
    pub sample_stacks: Vec<Vec<u32>>,
    /// The resolved colour (sRGB, 8 bits, alpha 255), the frame's pixel.
    pub color: [u8; 4],
    /// The resolved covered fraction (the union of the masks).
    pub coverage: f32,
    /// The resolved id (front-most fragment at the centre), [`NO_ID`] if
    /// none.
    pub id: u32,
    /// The resolved window depth, 1.0 for background.
    pub depth: f32,
}

impl ABuffer {
    /// The fragment list of pixel `(x, y)` after the last
    /// [`Hider::render`](hider_scene::Hider::render) of `scene` (the same
    /// prepared scene: the lists name its triangles), and the pixel's
    /// resolve, computed by the frame's own resolve. Needs
    /// [`ABufferOptions::sample_tiles`] off (sample-buffer tiles keep no
    /// lists); refuses a pixel outside the last frame.
    pub fn inspect_pixel(&self, scene: &ScreenScene, x: u32, y: u32) -> Result<PixelInspection> {
        let options: &ABufferOptions = self.options();
        if options.sample_tiles && options.depth == DepthMode::PerSample {
            return Err(Error::OutOfRange {
                what: "A-buffer inspection",
                expected: "sample_tiles off (sample-buffer tiles keep no lists)",
                value: "sample_tiles on".into(),
            });
        }
        let ((w, h), items, pool) = self.last_lists((y / TILE) as usize);
        if x >= w || y >= h || scene.viewport.width != w || scene.viewport.height != h {
            return Err(Error::OutOfRange {
                what: "inspected pixel",
                expected: "inside the last frame, of the scene it rendered",
                value: format!("({x}, {y}) of a {w}x{h} frame"),
            });
        }
        let p = y as usize * w as usize + x as usize;
        let Some(pool) = pool else {
            return Ok(empty());
        };
        let tris: Vec<LeanTri> = scene.tris.iter().map(LeanTri::from).collect();
        let sampler = palette::sampler(scene, options.shade);
        let source = Source::screen(scene, &tris, sampler.as_ref()).with_items(items);
        let mut colors = ColorCache::default();
        colors.begin(source.prims());
        let mut input = Input {
            scene: &source,
            pool,
            colors: &mut colors,
            options,
        };
        let ij = (x, y);
        let positions = options.pattern.positions();
        let mut list: Vec<Fragment> = Vec::new();
        let mut cur = pool.head(p);
        while cur != NIL {
            let f = *pool.get(cur);
            list.push(f);
            cur = f.next;
        }
        list.sort_by(Fragment::order);
        let fragments: Vec<InspectedFragment> = list
            .iter()
            .map(|f| {
                let plane = &source.items[f.tri as usize].plane;
                let per_sample = options.depth == DepthMode::PerSample;
                let sample_z = (0..positions.len() * usize::from(per_sample))
                    .map(|k| {
                        if f.mask >> k & 1 == 1 {
                            pool.sample_depth(plane, f, ij, positions, k)
                        } else {
                            f32::NAN
                        }
                    })
                    .collect();
                InspectedFragment {
                    mask: f.mask,
                    prim: f.prim,
                    centre_prim: f.centre_prim,
                    zmin: f.zmin,
                    zmax: f.zmax,
                    centre_z: f.centre_z,
                    sample_z,
                    rgba: input.rgba(f, ij),
                    merged: f.is_merged(),
                }
            })
            .collect();
        let sample_stacks = (0..positions.len())
            .map(|k| {
                let mut stack: Vec<u32> = (0..fragments.len() as u32)
                    .filter(|&i| fragments[i as usize].mask >> k & 1 == 1)
                    .collect();
                if options.depth == DepthMode::PerSample {
                    // The per-sample resolve's order: depth at the
                    // sample, then primitive.
                    stack.sort_by(|&a, &b| {
                        let (fa, fb) = (&fragments[a as usize], &fragments[b as usize]);
                        fa.sample_z[k]
                            .total_cmp(&fb.sample_z[k])
                            .then(fa.prim.cmp(&fb.prim))
                    });
                }
                stack
            })
            .collect();
        // The frame's resolve on this one pixel, into a band that holds
        // only it.
        let (mut id, mut depth) = ([NO_ID], [BACKGROUND_DEPTH]);
        let (mut color, mut coverage) = ([BACKGROUND], [0.0f32]);
        let mut band = Band {
            width: w as usize,
            first: p,
            ids: &mut id,
            depth: &mut depth,
            color: &mut color,
            coverage: &mut coverage,
        };
        let mut resolver = Resolver::default();
        resolver.begin();
        let mut stats = ABufferStats::default();
        resolver.resolve_tile(&mut input, (x, y, x, y), &mut band, &mut stats);
        Ok(PixelInspection {
            fragments,
            sample_stacks,
            color: color[0],
            coverage: coverage[0],
            id: id[0],
            depth: depth[0],
        })
    }
}

/// A pixel no fragment reached: the background.
fn empty() -> PixelInspection {
    PixelInspection {
        fragments: Vec::new(),
        sample_stacks: Vec::new(),
        color: BACKGROUND,
        coverage: 0.0,
        id: NO_ID,
        depth: BACKGROUND_DEPTH,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::{Frame, Hider, PrepareOptions, View, prepare, procedural};

    /// Every pixel's inspected resolve is the frame's pixel (colour, id,
    /// depth and coverage), in every depth mode, on the hard cases and
    /// scenes with intersections and translucent materials; every pixel
    /// lists its fragments in resolve order, their masks' union its
    /// coverage.
    #[test]
    fn the_inspected_resolve_is_the_frame() {
        // Half the sphere's and one of the pair's materials translucent:
        // lists that composite several fragments per sample.
        let mut glass = procedural::intersecting_pair();
        glass.materials[0].opacity = 0.5;
        let mut sphere = procedural::uv_sphere(12);
        for m in sphere.materials.iter_mut().step_by(2) {
            m.opacity = 0.4;
        }
        let mut scenes = vec![procedural::intersecting_pair(), glass, sphere];
        scenes.extend(
            hider_testkit::hard_cases::all(3)
                .into_iter()
                .map(|(_, s)| s),
        );
        let (mut listed, mut translucent) = (0, 0);
        for scene in &scenes {
            let view = View::for_scene(scene, 40, 40).unwrap();
            let screen = prepare(scene, &view, &PrepareOptions::default()).unwrap();
            for depth in [
                DepthMode::PerSample,
                DepthMode::MinMax,
                DepthMode::ZminOrder,
            ] {
                let options = ABufferOptions::default()
                    .with_depth(depth)
                    .with_sample_tiles(false);
                let mut abuffer = ABuffer::new(options);
                let mut frame = Frame::new(40, 40).unwrap();
                abuffer.render(&screen, &mut frame).unwrap();
                for p in 0..frame.len() {
                    let (x, y) = ((p % 40) as u32, (p / 40) as u32);
                    let got = abuffer.inspect_pixel(&screen, x, y).unwrap();
                    assert_eq!(got.color, frame.color[p], "{depth:?} ({x}, {y})");
                    assert_eq!(got.id, frame.ids[p]);
                    assert_eq!(got.depth, frame.depth[p]);
                    assert_eq!(got.coverage, frame.coverage[p]);
                    let union = got.fragments.iter().fold(0, |m, f| m | f.mask);
                    assert_eq!(union.count_ones() as f32 / 32.0, got.coverage);
                    for pair in got.fragments.windows(2) {
                        assert!(pair[0].zmin <= pair[1].zmin);
                    }
                    listed += got.fragments.len();
                    translucent += got.fragments.iter().filter(|f| f.rgba[3] < 1.0).count();
                }
            }
        }
        assert!(listed > 1000, "{listed} fragments inspected");
        assert!(translucent > 100, "{translucent} translucent fragments");
    }

    #[test]
    fn inspection_refuses_sample_tiles_and_pixels_outside() {
        let scene = procedural::cube();
        let view = View::for_scene(&scene, 16, 16).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let mut frame = Frame::new(16, 16).unwrap();
        let mut sampled = ABuffer::new(ABufferOptions::default());
        sampled.render(&screen, &mut frame).unwrap();
        let e = sampled.inspect_pixel(&screen, 8, 8).unwrap_err();
        assert!(e.to_string().contains("sample_tiles"), "{e}");
        let mut lists = ABuffer::new(ABufferOptions::default().with_sample_tiles(false));
        lists.render(&screen, &mut frame).unwrap();
        assert!(lists.inspect_pixel(&screen, 16, 0).is_err());
        let centre = lists.inspect_pixel(&screen, 8, 8).unwrap();
        assert_eq!(centre.sample_stacks.len(), 32);
        assert!(centre.sample_stacks.iter().all(|s| !s.is_empty()));
    }
}
