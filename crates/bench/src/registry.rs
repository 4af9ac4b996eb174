//! Every hider of the workspace by name: one list that the CLI, the
//! benchmark and the property tests read, so adding an algorithm is one
//! entry here.

use hider_abuffer::{
    ABuffer, ABufferOptions, SamplePattern, SortedTransparencyZBuffer, SsaaOptions,
    SupersampledZBuffer,
};
use hider_oracle::RayCastOracle;
use hider_painter::{NaivePainter, Painter};
use hider_scanline::Scanline;
use hider_scene::Hider;
use hider_warnock::{Warnock, WarnockOptions};
use hider_zbuffer::{
    DepthFormat, DepthSource, TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions,
};

/// What kind of answer a hider gives, which decides how it is checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Decides visibility at pixel centres and must equal the exact oracle
    /// on every non-tie pixel (and have identical coverage).
    ExactPixelCentre,
    /// Decides at pixel centres but is *meant* to be wrong in documented
    /// cases (naive sort, coarse depth, linear depth): measured, not
    /// required to agree.
    ApproximatePixelCentre,
    /// Resolves several samples per pixel (anti-aliasing, transparency);
    /// scored against analytic coverage.
    MultiSample,
    /// The slow exact reference itself.
    Reference,
}

/// One registered hider.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    /// Name on the command line (`--algo NAME`) and in tables.
    pub name: &'static str,
    /// One line saying what it is.
    pub description: &'static str,
    /// How it is checked.
    pub kind: Kind,
    /// Builds a fresh instance with the entry's options.
    pub make: fn() -> Box<dyn Hider>,
}

fn zbuffer(format: DepthFormat, source: DepthSource) -> Box<dyn Hider> {
    Box::new(ZBuffer::new(
        ZBufferOptions::default()
            .with_depth_format(format)
            .with_depth_source(source),
    ))
}

fn ssaa(pattern: SamplePattern) -> Box<dyn Hider> {
    Box::new(SupersampledZBuffer::new(
        SsaaOptions::default().with_pattern(pattern),
    ))
}

/// Every registered hider, exact ones first.
pub fn all() -> Vec<Entry> {
    vec![
        Entry {
            name: "zbuffer",
            description: "depth buffer, f32 window depth",
            kind: Kind::ExactPixelCentre,
            make: || zbuffer(DepthFormat::F32, DepthSource::WindowZ),
        },
        Entry {
            name: "zbuffer-f64",
            description: "depth buffer, f64 window depth",
            kind: Kind::ExactPixelCentre,
            make: || zbuffer(DepthFormat::F64, DepthSource::WindowZ),
        },
        Entry {
            name: "zbuffer-reversed",
            description: "depth buffer, reversed-Z f32",
            kind: Kind::ExactPixelCentre,
            make: || zbuffer(DepthFormat::ReversedF32, DepthSource::WindowZ),
        },
        Entry {
            name: "zbuffer-tiled",
            description: "binned, tiled, hierarchical-z parallel z-buffer; bit-identical to zbuffer",
            kind: Kind::ExactPixelCentre,
            make: || Box::new(TiledZBuffer::new(TiledZBufferOptions::default())),
        },
        Entry {
            name: "zbuffer-fixed24",
            description: "depth buffer, 24-bit fixed point (GL-like)",
            kind: Kind::ApproximatePixelCentre,
            make: || zbuffer(DepthFormat::Fixed24, DepthSource::WindowZ),
        },
        Entry {
            name: "zbuffer-fixed16",
            description: "depth buffer, 16-bit fixed point",
            kind: Kind::ApproximatePixelCentre,
            make: || zbuffer(DepthFormat::Fixed16, DepthSource::WindowZ),
        },
        Entry {
            name: "painter-naive",
            description: "painter's algorithm, plain sort by farthest vertex (wrong on intersections and cycles)",
            kind: Kind::ApproximatePixelCentre,
            make: || Box::new(NaivePainter::default()),
        },
        Entry {
            name: "zbuffer-linear-z",
            description: "depth buffer comparing camera z interpolated linearly (the seed's error)",
            kind: Kind::ApproximatePixelCentre,
            make: || zbuffer(DepthFormat::F32, DepthSource::LinearViewZ),
        },
        Entry {
            name: "scanline",
            description: "scanline (Watkins): edge table, active edge list, depth-ordered spans",
            kind: Kind::ExactPixelCentre,
            make: || Box::new(Scanline::new()),
        },
        Entry {
            name: "painter",
            description: "painter's algorithm, Newell-Newell-Sancha tests with splitting",
            kind: Kind::ExactPixelCentre,
            make: || Box::new(Painter::default()),
        },
        Entry {
            name: "warnock",
            description: "Warnock area subdivision to pixel size",
            kind: Kind::ExactPixelCentre,
            make: || Box::new(Warnock::default()),
        },
        Entry {
            name: "warnock-4x4",
            description: "Warnock subdividing to 4x4 samples per pixel (anti-aliased)",
            kind: Kind::MultiSample,
            make: || {
                Box::new(Warnock::new(
                    WarnockOptions::default().with_samples_per_side(4),
                ))
            },
        },
        Entry {
            name: "abuffer",
            description: "A-buffer, 8x4 coverage masks, per-sample depth (exact), order-independent transparency",
            kind: Kind::MultiSample,
            make: || Box::new(ABuffer::new(ABufferOptions::default())),
        },
        Entry {
            name: "abuffer-carpenter",
            description: "A-buffer as in Carpenter 1984: zmin/zmax per fragment, same-surface merging",
            kind: Kind::MultiSample,
            make: || Box::new(ABuffer::new(ABufferOptions::carpenter())),
        },
        Entry {
            name: "ssaa-4",
            description: "supersampled z-buffer, 4 samples (subset of the A-buffer mask)",
            kind: Kind::MultiSample,
            make: || ssaa(SamplePattern::Grid4),
        },
        Entry {
            name: "ssaa-8",
            description: "supersampled z-buffer, 8 samples",
            kind: Kind::MultiSample,
            make: || ssaa(SamplePattern::Grid8),
        },
        Entry {
            name: "ssaa-16",
            description: "supersampled z-buffer, 16 samples",
            kind: Kind::MultiSample,
            make: || ssaa(SamplePattern::Grid16),
        },
        Entry {
            name: "ssaa-32",
            description: "supersampled z-buffer, 32 samples (the A-buffer's mask)",
            kind: Kind::MultiSample,
            make: || ssaa(SamplePattern::Grid32),
        },
        Entry {
            name: "ssaa-sorted",
            description: "32-sample z-buffer, opaque first then transparent sorted back to front (order-dependent)",
            kind: Kind::MultiSample,
            make: || Box::new(SortedTransparencyZBuffer::new(SsaaOptions::default())),
        },
        Entry {
            name: "oracle",
            description: "exact reference: per-pixel ray cast in f64 over every triangle (slow)",
            kind: Kind::Reference,
            make: || Box::new(RayCastOracle::default()),
        },
    ]
}

/// The entry with this name.
pub fn by_name(name: &str) -> Option<Entry> {
    all().into_iter().find(|e| e.name == name)
}

/// Fresh instances of every hider that must equal the oracle on non-tie
/// pixels.
pub fn pixel_centre_hiders() -> Vec<Box<dyn Hider>> {
    all()
        .into_iter()
        .filter(|e| e.kind == Kind::ExactPixelCentre)
        .map(|e| (e.make)())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_instances_carry_them() {
        let entries = all();
        for (i, a) in entries.iter().enumerate() {
            assert!(
                entries[i + 1..].iter().all(|b| b.name != a.name),
                "{}",
                a.name
            );
            assert_eq!((a.make)().name(), a.name);
        }
        assert!(by_name("nope").is_none());
        assert!(!pixel_centre_hiders().is_empty());
    }
}
