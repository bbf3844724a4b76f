//! The command line's value enums, mapped to the library's own types so that clap stays in
//! the CLI.

use clap::ValueEnum;

use whitted_core::course::Course;
use whitted_core::tonemap::ToneMap;
use whitted_io::output::exr::ExrCompression;

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
    /// The course's own from 2018-19: sigmoid of v^1.3, gamma 1/2.2, truncating quantisation
    Sigmoid,
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
            ToneMapArg::Sigmoid => ToneMap::Sigmoid,
        }
    }
}

/// `--course` values: the profiles of docs/courses.md, by academic year.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CourseArg {
    /// The 2016-17 Tick 2 (the default): docs/rendering.md
    #[value(name = "2016-17")]
    Y2016,
    /// Tick 1: V from the ray's origin, the light's colour in the specular
    #[value(name = "2017-18")]
    Y2017,
    /// 2019-20's renderer with 2017-18's scene loader
    #[value(name = "2018-19")]
    Y2018,
    /// Tone map, N.L gate, background 0.001, planes with the sphere's materials
    #[value(name = "2019-20")]
    Y2019,
    /// 2019-20 with the shadow ray moved along N
    #[value(name = "2020-21")]
    Y2020,
    /// 2020-21 at 800x600 (also 2022-23)
    #[value(name = "2021-22", alias = "2022-23")]
    Y2021,
    /// 2021-22 with -r WxH and transmittance attributes
    #[value(name = "2023-24")]
    Y2023,
}

impl From<CourseArg> for Course {
    fn from(arg: CourseArg) -> Self {
        match arg {
            CourseArg::Y2016 => Course::Y2016,
            CourseArg::Y2017 => Course::Y2017,
            CourseArg::Y2018 => Course::Y2018,
            CourseArg::Y2019 => Course::Y2019,
            CourseArg::Y2020 => Course::Y2020,
            CourseArg::Y2021 => Course::Y2021,
            CourseArg::Y2023 => Course::Y2023,
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
