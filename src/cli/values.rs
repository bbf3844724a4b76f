//! The command line's value enums, mapped to the library's own types so that clap stays in
//! the CLI.

use clap::ValueEnum;

use crate::output::exr::ExrCompression;
use crate::tonemap::ToneMap;

/// `--tonemap` values: the tone maps of docs/tonemap.md, named for the command line.
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
