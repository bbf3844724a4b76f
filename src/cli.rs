//! The command line (cli.md), as clap derive types. `whitted [render options]` is
//! `whitted render [render options]`, so the course's `--input/--output/--bounces` just work.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::frame::{FrameSpec, Region};
use crate::output::exr::{ExrCompression, ExrOptions};
use crate::plan::{RenderRequest, ToneRequest};
use crate::sheet::SheetOptions;
use crate::tonemap::ToneMap;

/// Most reflection bounces accepted: each bounce is a layer in the EXR, and past this depth a
/// mirror chain's contribution is far below what a float image can show.
pub const MAX_BOUNCES: u32 = 100;

/// Largest image side accepted.
pub const MAX_SIDE: u32 = 65_535;

pub use crate::plan::MAX_THREADS;

/// Most samples per pixel accepted (a 32x32 grid).
pub const MAX_SPP: u32 = 1024;

#[derive(Debug, Parser)]
#[command(
    name = "whitted",
    version,
    about = "A Whitted ray tracer: the course's tick-exact PNG, plus HDR OpenEXR AOVs",
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// With no subcommand, whitted renders (the course's Tick2 command line).
    #[command(flatten)]
    pub render: RenderArgs,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to a PNG (the default when no subcommand is given).
    Render(RenderArgs),
    /// Tone-map a colour layer of an EXR to a PNG, without re-rendering.
    Tonemap(TonemapArgs),
    /// Show an EXR's size, layers, channels, header and per-layer statistics.
    Info(InfoArgs),
    /// Compare two EXRs (or two PNGs) layer by layer; exit 1 when they differ.
    Diff(DiffArgs),
    /// Write a labelled contact sheet of every layer of an EXR.
    Sheet(SheetArgs),
    /// Assemble EXRs rendered with --region into the full frame.
    Merge(MergeArgs),
}

#[derive(Debug, Clone, Args)]
pub struct MergeArgs {
    /// The region EXRs; together they must cover the frame exactly once
    #[arg(value_name = "PARTS.exr", required = true, num_args = 1..)]
    pub parts: Vec<PathBuf>,

    /// The full-frame EXR to write
    #[arg(short, long, value_name = "FULL.exr")]
    pub output: PathBuf,
}

#[derive(Debug, Clone, Args)]
pub struct InfoArgs {
    /// The EXR (or PNG) to describe
    #[arg(value_name = "FILE.exr")]
    pub input: PathBuf,

    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Clone, Args)]
pub struct DiffArgs {
    /// The image to check
    #[arg(value_name = "A")]
    pub actual: PathBuf,

    /// The reference it should match (relative tolerance is relative to its values)
    #[arg(value_name = "B")]
    pub reference: PathBuf,

    /// Layers to compare, comma separated [default: all]
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub layers: Vec<String>,

    /// Absolute tolerance
    #[arg(long = "abs", value_name = "T", default_value_t = 1e-6, value_parser = parse_tolerance)]
    pub abs: f64,

    /// Relative tolerance: a value fails when |a - b| > abs + rel * |b|
    #[arg(long = "rel", value_name = "T", default_value_t = 1e-5, value_parser = parse_tolerance)]
    pub rel: f64,

    /// Write a PNG showing where and by how much they differ
    #[arg(long, value_name = "OUT.png")]
    pub heatmap: Option<PathBuf>,

    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Clone, Args)]
pub struct SheetArgs {
    /// The EXR to show
    #[arg(value_name = "IN.exr")]
    pub input: PathBuf,

    /// The contact sheet PNG to write; `-` writes it to standard output
    #[arg(short, long, value_name = "SHEET.png")]
    pub output: PathBuf,

    /// Layers to show, in this order, comma separated [default: all]
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub layers: Vec<String>,

    /// Tiles per row
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub columns: u32,

    /// Width of each tile in pixels (never wider than the image)
    #[arg(long, value_name = "W", default_value_t = 320, value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub tile_width: u32,

    /// Tone map for colour layers
    #[arg(long = "tonemap", value_name = "OP", value_enum, default_value_t = ToneMapArg::Clamp)]
    pub tonemap: ToneMapArg,

    /// Exposure in stops for colour layers
    #[arg(long, value_name = "EV", default_value_t = 0.0, allow_negative_numbers = true,
          value_parser = parse_exposure)]
    pub exposure: f64,
}

#[derive(Debug, Clone, Args)]
pub struct TonemapArgs {
    /// The EXR to read (any OpenEXR file; whitted's own have every AOV)
    #[arg(value_name = "IN.exr")]
    pub input: PathBuf,

    /// PNG to write; `-` writes it to standard output
    #[arg(short, long, value_name = "OUT.png")]
    pub output: PathBuf,

    /// Colour layer to encode: `beauty` (the bare R G B) or a layer such as `direct`
    #[arg(long, value_name = "NAME", default_value = "beauty")]
    pub layer: String,

    #[command(flatten)]
    pub tone: ToneArgs,
}

/// How linear HDR values become PNG bytes (tonemap.md).
#[derive(Debug, Clone, Args)]
pub struct ToneArgs {
    /// Tone map: `tick` is the course's exact output; the others are sRGB-encoded
    #[arg(long = "tonemap", value_name = "OP", value_enum, default_value_t = ToneMapArg::Tick)]
    pub tonemap: ToneMapArg,

    /// Exposure in stops, applied before the tone map: v * 2^EV
    #[arg(long, value_name = "EV", default_value_t = 0.0, allow_negative_numbers = true,
          value_parser = parse_exposure)]
    pub exposure: f64,

    /// PNG bits per channel
    #[arg(long, value_name = "8|16", default_value_t = 8, value_parser = parse_depth)]
    pub png_depth: u8,

    /// Add triangular dither before rounding (8-bit, sRGB tone maps; deterministic)
    #[arg(long)]
    pub dither: bool,
}

impl ToneArgs {
    pub fn request(&self) -> ToneRequest {
        ToneRequest {
            tonemap: self.tonemap.into(),
            exposure: self.exposure,
            depth: self.png_depth,
            dither: self.dither,
        }
    }
}

#[derive(Debug, Clone, Args)]
pub struct RenderArgs {
    /// Scene XML file [default: the embedded course tick2.xml]
    #[arg(short, long, value_name = "SCENE")]
    pub input: Option<PathBuf>,

    /// Tone-mapped PNG to write; `-` writes it to standard output
    #[arg(short, long, value_name = "OUT.png", default_value = "output.png")]
    pub output: PathBuf,

    /// Write no PNG
    #[arg(long)]
    pub no_png: bool,

    /// Mirror reflection bounces after the primary hit
    #[arg(short, long, value_name = "N", default_value_t = 2,
          value_parser = parse_bounces, allow_negative_numbers = true)]
    pub bounces: u32,

    /// Image width in pixels (the field of view stays 45 degrees horizontal)
    #[arg(long, value_name = "W", default_value_t = 640, value_parser = parse_side)]
    pub width: u32,

    /// Image height in pixels
    #[arg(long, value_name = "H", default_value_t = 480, value_parser = parse_side)]
    pub height: u32,

    /// Samples per pixel on a fixed k*k stratified grid (1 = the pixel centre, the exact tick
    /// image)
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = parse_spp)]
    pub spp: u32,

    /// Render only the pixels [X0, X1) x [Y0, Y1) of the image; the EXR's data window is
    /// that crop, so parts from several machines merge into the full frame (`whitted merge`)
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_region)]
    pub region: Option<Region>,

    /// Ignore occlusion: every light reaches every point
    #[arg(long)]
    pub no_shadows: bool,

    /// Also write the multi-layer linear HDR OpenEXR (beauty and AOVs)
    #[arg(long, value_name = "FILE.exr")]
    pub exr: Option<PathBuf>,

    /// EXR layers: `all`, `beauty`, or a comma-separated list such as
    /// `direct,reflected,shadow_key` (the beauty is always written)
    #[arg(long, value_name = "all|beauty|LIST", default_value = "all")]
    pub aovs: String,

    /// Store the EXR's colour layers as half floats (masks and data layers stay float)
    #[arg(long)]
    pub half: bool,

    /// EXR compression (all lossless)
    #[arg(long, value_name = "C", value_enum, default_value_t = CompressionArg::Zip)]
    pub compression: CompressionArg,

    /// Record the render time in the EXR (`capDate`); without it, files are reproducible
    #[arg(long)]
    pub stamp_date: bool,

    #[command(flatten)]
    pub tone: ToneArgs,

    /// Worker threads [default: all cores]; the output is identical for any number
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,

    /// No progress bar and no summary line
    #[arg(short, long)]
    pub quiet: bool,
}

/// `--tonemap` values: the tone maps of tonemap.md, named for the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ToneMapArg {
    /// The course's output: clamp, no transfer function, truncating quantisation
    Tick,
    /// Clamp to [0, 1], then sRGB
    Clamp,
    /// v / (1 + v), then sRGB
    Reinhard,
    /// Narkowicz's ACES fit, then sRGB
    Aces,
    /// Blender 4's AgX base look, then sRGB
    Agx,
    /// Khronos PBR Neutral, then sRGB
    Neutral,
}

impl From<ToneMapArg> for ToneMap {
    fn from(arg: ToneMapArg) -> Self {
        match arg {
            ToneMapArg::Tick => ToneMap::Tick,
            ToneMapArg::Clamp => ToneMap::Clamp,
            ToneMapArg::Reinhard => ToneMap::Reinhard,
            ToneMapArg::Aces => ToneMap::Aces,
            ToneMapArg::Agx => ToneMap::Agx,
            ToneMapArg::Neutral => ToneMap::Neutral,
        }
    }
}

/// `--compression` values: the lossless OpenEXR codecs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CompressionArg {
    None,
    Rle,
    /// ZIP, one scanline per block
    Zips,
    /// ZIP, 16 scanlines per block (the default, as in most renderers)
    Zip,
    Piz,
}

impl From<CompressionArg> for ExrCompression {
    fn from(arg: CompressionArg) -> Self {
        match arg {
            CompressionArg::None => ExrCompression::None,
            CompressionArg::Rle => ExrCompression::Rle,
            CompressionArg::Zips => ExrCompression::Zips,
            CompressionArg::Zip => ExrCompression::Zip,
            CompressionArg::Piz => ExrCompression::Piz,
        }
    }
}

impl RenderArgs {
    /// The render asked for, as plain data for `RenderPlan::new` to check.
    pub fn request(&self) -> RenderRequest {
        RenderRequest {
            input: self.input.clone(),
            png: (!self.no_png).then(|| self.output.clone()),
            exr: self.exr.clone(),
            frame: FrameSpec {
                width: self.width,
                height: self.height,
                region: self.region,
                spp: self.spp,
                bounces: self.bounces,
                shadows: !self.no_shadows,
                aovs: self.aovs.clone(),
                ..FrameSpec::default()
            },
            exr_options: ExrOptions {
                compression: self.compression.into(),
                half: self.half,
            },
            tone: self.tone.request(),
            threads: self.threads,
            stamp_date: self.stamp_date,
        }
    }
}

impl SheetArgs {
    pub fn options(&self) -> SheetOptions {
        SheetOptions {
            columns: self.columns,
            tile_width: self.tile_width,
            tonemap: self.tonemap.into(),
            exposure: self.exposure,
        }
    }
}

fn parse_bounces(s: &str) -> Result<u32, String> {
    let n: i64 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected a whole number of bounces, got `{s}`"))?;
    if n < 0 {
        return Err(format!("bounces must be >= 0, got {n}"));
    }
    u32::try_from(n)
        .ok()
        .filter(|&n| n <= MAX_BOUNCES)
        .ok_or_else(|| format!("at most {MAX_BOUNCES} bounces are supported, got {n}"))
}

fn parse_side(s: &str) -> Result<u32, String> {
    let n: u64 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected a whole number of pixels, got `{s}`"))?;
    u32::try_from(n)
        .ok()
        .filter(|&n| (1..=MAX_SIDE).contains(&n))
        .ok_or_else(|| format!("must be between 1 and {MAX_SIDE} pixels, got {n}"))
}

fn parse_spp(s: &str) -> Result<u32, String> {
    let n: u32 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected a whole number of samples, got `{s}`"))?;
    let k = n.isqrt();
    if n == 0 || k * k != n || n > MAX_SPP {
        return Err(format!(
            "samples per pixel must be a square k*k (1, 4, 9, 16, ...) up to {MAX_SPP}, got {n}"
        ));
    }
    Ok(n)
}

fn parse_exposure(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(ev) if ev.is_finite() && ev.abs() <= 64.0 => Ok(ev),
        _ => Err(format!(
            "expected an exposure in stops between -64 and 64, got `{s}`"
        )),
    }
}

fn parse_region(s: &str) -> Result<Region, String> {
    let numbers: Vec<u32> = s
        .split(',')
        .map(|n| n.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("expected X0,Y0,X1,Y1 in whole pixels, got `{s}`"))?;
    match numbers[..] {
        [x0, y0, x1, y1] if x0 < x1 && y0 < y1 => Ok(Region { x0, y0, x1, y1 }),
        [_, _, _, _] => Err(format!("the region `{s}` is empty (X0 < X1 and Y0 < Y1)")),
        _ => Err(format!("expected four numbers X0,Y0,X1,Y1, got `{s}`")),
    }
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(t),
        _ => Err(format!("expected a tolerance >= 0, got `{s}`")),
    }
}

fn parse_depth(s: &str) -> Result<u8, String> {
    match s.trim() {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("PNG depth is 8 or 16, got `{s}`")),
    }
}

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected a number of threads >= 1 and <= {MAX_THREADS}, got `{s}`"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn bounds_are_enforced() {
        assert_eq!(parse_bounces("3"), Ok(3));
        assert!(parse_bounces("-1").unwrap_err().contains(">= 0"));
        assert!(parse_bounces("101").is_err());
        assert!(parse_side("0").is_err());
        assert!(parse_side("70000").is_err());
        assert_eq!(parse_side("640"), Ok(640));
        assert!(parse_threads("0").is_err());
        assert_eq!(parse_spp("16"), Ok(16));
        assert!(parse_spp("8").unwrap_err().contains("square"));
        assert!(parse_spp("0").is_err());
        assert_eq!(parse_exposure("-1.5"), Ok(-1.5));
        assert!(parse_exposure("nan").is_err());
        assert!(parse_depth("12").is_err());
    }
}
