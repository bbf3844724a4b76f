//! Arguments of the commands that look closer at a render: `explain`, `relight`, `view`.

use std::path::PathBuf;

use clap::Args;

use super::parse::*;
use super::{FrameArgs, ToneArgs, ToneCourseArgs};
use whitted_check::mistakes::{Bug, Mistakes};
use whitted_core::frame::FrameSpec;

#[derive(Debug, Clone, Args)]
pub struct ExplainArgs {
    /// Scene XML file [default: the embedded course tick2.xml]
    #[arg(short, long, value_name = "SCENE")]
    pub input: Option<PathBuf>,

    /// The pixel, X,Y from the top left
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: (u32, u32),

    #[command(flatten)]
    pub frame: FrameArgs,

    /// Print JSON instead of the tree
    #[arg(long)]
    pub json: bool,

    /// Trace the pixel as a program with this mistake would (an id of
    /// `whitted check --list-bugs`; repeat it for several)
    #[arg(long = "bug", value_name = "ID", value_parser = parse_bug)]
    pub bugs: Vec<Bug>,

    /// With --bug: the reference's tree and the mistake's side by side, only the steps that
    /// differ (the vectors R, V, L and the terms that change)
    #[arg(long, requires = "bugs", conflicts_with = "json")]
    pub compare: bool,
}

impl ExplainArgs {
    /// The mistakes asked for (none: the course's model).
    pub fn mistakes(&self) -> Mistakes {
        Mistakes::of(&self.bugs)
    }

    /// The frame the pixel belongs to, as a program with those mistakes renders it.
    pub fn frame(&self) -> FrameSpec {
        self.mistakes().frame_spec(&self.reference_frame())
    }

    /// The frame the pixel belongs to, as the course's program renders it.
    pub fn reference_frame(&self) -> FrameSpec {
        FrameSpec {
            aovs: "beauty".into(),
            ..self.frame.spec()
        }
    }
}

#[derive(Debug, Clone, Args)]
pub struct ViewArgs {
    /// The image to look at: OpenEXR, PNG, JPEG, TIFF or Radiance HDR
    #[arg(value_name = "IMAGE")]
    pub input: PathBuf,

    /// A reference of the same size and layers, for A/B and the error metrics
    #[arg(long, value_name = "REF")]
    pub reference: Option<PathBuf>,

    /// The scene the image was rendered from, so that a click shows the pixel's ray tree
    /// (a whitted EXR records which scene it was: another one is refused; one of the embedded
    /// tick2 scene needs none)
    #[arg(short = 'i', long = "input", value_name = "SCENE")]
    pub scene: Option<PathBuf>,

    #[command(flatten)]
    pub serve: ServeArgs,
}

/// How the viewer is served: `view`'s options, and `check --view`'s.
#[derive(Debug, Clone, Args)]
pub struct ServeArgs {
    /// Port on 127.0.0.1 (0: any free port)
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub port: u16,

    /// Only print the URL; do not try to open a browser
    #[arg(long)]
    pub no_browser: bool,

    /// Reload when the file changes on disk (in check mode, check it again)
    #[arg(long)]
    pub watch: bool,
}

#[derive(Debug, Clone, Args)]
pub struct RelightArgs {
    /// A whitted EXR with light layers (`--aovs all`)
    #[arg(value_name = "IN.exr")]
    pub input: PathBuf,

    /// The relit image: an EXR (R, G, B, A) or a PNG (tone-mapped); `-` writes a PNG to
    /// standard output
    #[arg(short, long, value_name = "OUT.exr|OUT.png")]
    pub output: PathBuf,

    /// A light's gain: NAME=G or NAME=R,G,B (NAME as in its layer: `0` for `light_0`)
    #[arg(long = "light", value_name = "NAME=GAIN", value_parser = parse_light_gain)]
    pub lights: Vec<(String, [f64; 3])>,

    /// Show this light without its shadows (its `unshadowed_` layer)
    #[arg(long = "no-shadow", value_name = "NAME")]
    pub no_shadow: Vec<String>,

    /// Gain of the ambient term
    #[arg(long, value_name = "GAIN", default_value_t = 1.0, value_parser = parse_gain)]
    pub ambient: f64,

    /// Gain of the background
    #[arg(long, value_name = "GAIN", default_value_t = 1.0, value_parser = parse_gain)]
    pub background: f64,

    #[command(flatten)]
    pub tone: ToneArgs,

    #[command(flatten)]
    pub course: ToneCourseArgs,
}
