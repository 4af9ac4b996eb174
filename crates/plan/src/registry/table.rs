//! The list of every registered hider, each built from its crate's typed
//! options.

use hider_abuffer::{
    ABuffer, ABufferOptions, SamplePattern, SortedTransparencyZBuffer, SsaaOptions,
    SupersampledZBuffer,
};
use hider_oracle::{OracleOptions, RayCastOracle};
use hider_painter::{NaivePainter, NaivePainterOptions, Painter, PainterOptions};
use hider_scanline::{Scanline, ScanlineOptions};
use hider_scene::{DynHider, Hider};
use hider_warnock::{Warnock, WarnockOptions};
use hider_zbuffer::{
    DepthFormat, DepthSource, TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions,
};

use super::entry::{Entry, Kind, Knobs};
use crate::config::HiderConfig;

/// A z-buffer with this format and source, stopped by the config's
/// cancel token.
fn zbuffer(format: DepthFormat, source: DepthSource, config: &HiderConfig) -> Box<dyn DynHider> {
    Box::new(ZBuffer::new(
        ZBufferOptions::default()
            .with_depth_format(format)
            .with_depth_source(source)
            .with_cancel(config.cancel),
    ))
}

/// The `zbuffer` entry: window depth in f32 unless the config says
/// otherwise.
fn configured_zbuffer(config: &HiderConfig) -> Box<dyn DynHider> {
    zbuffer(
        config.depth_format.unwrap_or(DepthFormat::F32),
        config.depth_source.unwrap_or(DepthSource::WindowZ),
        config,
    )
}

/// The `zbuffer-tiled` entry: its defaults (f32, every core) unless the
/// config says otherwise.
fn configured_tiled(config: &HiderConfig) -> Box<dyn DynHider> {
    let mut options = TiledZBufferOptions::default().with_cancel(config.cancel);
    if let Some(format) = config.depth_format {
        options = options.with_depth_format(format);
    }
    if let Some(threads) = config.threads {
        options = options.with_threads(threads);
    }
    Box::new(TiledZBuffer::new(options))
}

/// An A-buffer with these options, on the config's threads when it
/// names a count (every core otherwise, its default).
fn abuffer(options: ABufferOptions, config: &HiderConfig) -> Box<dyn DynHider> {
    let options = options.with_cancel(config.cancel);
    let options = config.threads.map_or(options, |t| options.with_threads(t));
    let options = config.shade.map_or(options, |s| options.with_shade(s));
    let options = config
        .max_list_len
        .map_or(options, |n| options.with_max_list_len(n));
    let options = config
        .overflow
        .map_or(options, |o| options.with_overflow(o));
    Box::new(ABuffer::new(options))
}

/// Knobs of the A-buffer entries.
const ABUFFER_KNOBS: Knobs = Knobs {
    threads: true,
    fragment_lists: true,
    ..Knobs::NONE
};

/// The supersampling options of `pattern` with the config's shade mode.
fn ssaa_options(pattern: SamplePattern, config: &HiderConfig) -> SsaaOptions {
    let options = SsaaOptions::default()
        .with_pattern(pattern)
        .with_cancel(config.cancel);
    config.shade.map_or(options, |s| options.with_shade(s))
}

/// A supersampled z-buffer with this sample pattern.
fn ssaa(pattern: SamplePattern, config: &HiderConfig) -> Box<dyn DynHider> {
    Box::new(SupersampledZBuffer::new(ssaa_options(pattern, config)))
}

/// Knobs of the `zbuffer` entry.
const ZBUFFER_KNOBS: Knobs = Knobs {
    depth_format: true,
    depth_source: true,
    ..Knobs::NONE
};

/// Knobs of the `zbuffer-tiled` entry.
const TILED_KNOBS: Knobs = Knobs {
    depth_format: true,
    threads: true,
    ..Knobs::NONE
};

/// Knobs of the painters.
const PAINTER_KNOBS: Knobs = Knobs {
    ordered_polygons: true,
    ..Knobs::NONE
};

/// Knobs of the splitting painter.
const SPLITTING_PAINTER_KNOBS: Knobs = Knobs {
    max_splits: true,
    ..PAINTER_KNOBS
};

/// The `painter` entry: its defaults, with the config's split budget.
fn painter(config: &HiderConfig) -> Box<dyn DynHider> {
    let options = PainterOptions::default().with_cancel(config.cancel);
    let options = config
        .max_splits
        .map_or(options, |n| options.with_max_splits(n));
    Box::new(Painter::new(options))
}

/// An entry without knobs.
const fn plain(
    name: &'static str,
    description: &'static str,
    kind: Kind,
    with_config: fn(&HiderConfig) -> Box<dyn DynHider>,
) -> Entry {
    Entry {
        name,
        description,
        kind,
        knobs: Knobs::NONE,
        with_config,
    }
}

/// The hiders that decide at pixel centres, exact or approximate.
fn pixel_centre() -> [Entry; 11] {
    use DepthFormat::{F32, F64, Fixed16, Fixed24, ReversedF32};
    use DepthSource::{LinearViewZ, WindowZ};
    use Kind::{ApproximatePixelCentre as Approximate, ExactPixelCentre as Exact};
    [
        Entry {
            knobs: ZBUFFER_KNOBS,
            ..plain(
                "zbuffer",
                "depth buffer, f32 window depth",
                Exact,
                configured_zbuffer,
            )
        },
        plain(
            "zbuffer-f64",
            "depth buffer, f64 window depth",
            Exact,
            |c| zbuffer(F64, WindowZ, c),
        ),
        plain(
            "zbuffer-reversed",
            "depth buffer, reversed-Z f32",
            Exact,
            |c| zbuffer(ReversedF32, WindowZ, c),
        ),
        Entry {
            knobs: TILED_KNOBS,
            ..plain(
                "zbuffer-tiled",
                "binned, tiled, hierarchical-z parallel z-buffer; bit-identical to zbuffer",
                Exact,
                configured_tiled,
            )
        },
        plain(
            "zbuffer-fixed24",
            "depth buffer, 24-bit fixed point (GL-like)",
            Approximate,
            |c| zbuffer(Fixed24, WindowZ, c),
        ),
        plain(
            "zbuffer-fixed16",
            "depth buffer, 16-bit fixed point",
            Approximate,
            |c| zbuffer(Fixed16, WindowZ, c),
        ),
        Entry {
            knobs: PAINTER_KNOBS,
            ..plain(
                "painter-naive",
                "painter's algorithm, plain sort by farthest vertex (wrong on intersections and cycles)",
                Approximate,
                |c| {
                    Box::new(NaivePainter::new(
                        NaivePainterOptions::default().with_cancel(c.cancel),
                    ))
                },
            )
        },
        plain(
            "zbuffer-linear-z",
            "depth buffer comparing camera z interpolated linearly on the screen (wrong under perspective)",
            Approximate,
            |c| zbuffer(F32, LinearViewZ, c),
        ),
        plain(
            "scanline",
            "scanline (Watkins): edge table, active edge list, depth-ordered spans",
            Exact,
            |c| {
                Box::new(Scanline::new(
                    ScanlineOptions::default().with_cancel(c.cancel),
                ))
            },
        ),
        Entry {
            knobs: SPLITTING_PAINTER_KNOBS,
            ..plain(
                "painter",
                "painter's algorithm, Newell-Newell-Sancha tests with splitting",
                Exact,
                painter,
            )
        },
        plain(
            "warnock",
            "Warnock area subdivision to pixel size",
            Exact,
            |c| {
                Box::new(Warnock::new(
                    WarnockOptions::default().with_cancel(c.cancel),
                ))
            },
        ),
    ]
}

/// The hiders that resolve several samples per pixel.
fn multisample() -> [Entry; 8] {
    use Kind::MultiSample;
    [
        plain(
            "warnock-4x4",
            "Warnock subdividing to 4x4 samples per pixel (anti-aliased)",
            MultiSample,
            |c| {
                let options = WarnockOptions::default()
                    .with_samples_per_side(4)
                    .with_cancel(c.cancel);
                let options = c.shade.map_or(options, |s| options.with_shade(s));
                Box::new(Warnock::new(options))
            },
        ),
        Entry {
            knobs: ABUFFER_KNOBS,
            ..plain(
                "abuffer",
                "A-buffer, 8x4 coverage masks, per-sample depth (exact), order-independent transparency",
                MultiSample,
                |c| abuffer(ABufferOptions::default(), c),
            )
        },
        Entry {
            knobs: ABUFFER_KNOBS,
            ..plain(
                "abuffer-carpenter",
                "A-buffer as in Carpenter 1984: zmin/zmax per fragment, same-surface merging",
                MultiSample,
                |c| abuffer(ABufferOptions::carpenter(), c),
            )
        },
        plain(
            "ssaa-4",
            "supersampled z-buffer, 4 samples (subset of the A-buffer mask)",
            MultiSample,
            |c| ssaa(SamplePattern::Grid4, c),
        ),
        plain(
            "ssaa-8",
            "supersampled z-buffer, 8 samples",
            MultiSample,
            |c| ssaa(SamplePattern::Grid8, c),
        ),
        plain(
            "ssaa-16",
            "supersampled z-buffer, 16 samples",
            MultiSample,
            |c| ssaa(SamplePattern::Grid16, c),
        ),
        plain(
            "ssaa-32",
            "supersampled z-buffer, 32 samples (the A-buffer's mask)",
            MultiSample,
            |c| ssaa(SamplePattern::Grid32, c),
        ),
        plain(
            "ssaa-sorted",
            "32-sample z-buffer, opaque first then transparent sorted back to front (order-dependent)",
            MultiSample,
            |c| {
                Box::new(SortedTransparencyZBuffer::new(ssaa_options(
                    SsaaOptions::default().pattern,
                    c,
                )))
            },
        ),
    ]
}

/// Every registered hider, in the order tables list them: those deciding
/// at pixel centres, the multi-sample ones, then the exact reference.
pub fn all() -> Vec<Entry> {
    let mut entries = pixel_centre().to_vec();
    entries.extend(multisample());
    entries.push(plain(
        "oracle",
        "exact reference: per-pixel ray cast in f64 over every triangle (slow)",
        Kind::Reference,
        |c| {
            Box::new(RayCastOracle::new(
                OracleOptions::default().with_cancel(c.cancel),
            ))
        },
    ));
    entries
}
