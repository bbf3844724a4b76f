//! The command line (docs/cli.md), as clap derive types. `whitted [render options]` is
//! `whitted render [render options]`, so the course's `--input/--output/--bounces` just work.

use std::path::{Path, PathBuf};

use clap::{Args, CommandFactory, FromArgMatches, Parser, Subcommand};

mod check;
mod grade;
mod look;
mod parse;
mod serve;
mod star;
mod values;

pub use check::{CheckArgs, StarCheck};
pub use grade::GradeArgs;
pub use look::{ExplainArgs, RelightArgs, ServeArgs, ViewArgs};
use parse::*;
pub use serve::{ServeAction, ServiceArgs};
pub use star::StarArgs;
pub use values::{CompressionArg, CourseArg, ToneMapArg};
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::frame::{FrameSpec, Region};
use whitted_io::compare::{Criteria, Tolerance};
use whitted_io::input::Image;
use whitted_io::output::exr::ExrOptions;
use whitted_io::plan::{RenderRequest, ToneRequest};
use whitted_io::sheet::SheetOptions;

pub use whitted_core::frame::limits::{MAX_BOUNCES, MAX_SIDE, MAX_SPP};
pub use whitted_io::plan::MAX_THREADS;

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

impl Cli {
    /// The command line as clap builds it from these types, with every option that takes a
    /// value accepting a negative number as that value: `--ambient -1` then reaches its parser
    /// and gets its range error, instead of clap's "unexpected argument" and a tip to write
    /// `-- -1`, which would not work. The one place that builds the command (parsing, the
    /// manual page, completions).
    pub fn command_line() -> clap::Command {
        fn negatives(command: clap::Command) -> clap::Command {
            command
                .mut_args(|arg| {
                    let takes_values = arg.get_action().takes_values();
                    arg.allow_negative_numbers(takes_values)
                })
                .mut_subcommands(negatives)
        }
        negatives(<Cli as CommandFactory>::command())
    }

    /// Parses the process's arguments with `command_line`.
    pub fn parse_args() -> Result<Cli, clap::Error> {
        let mut matches = Self::command_line().try_get_matches()?;
        Cli::from_arg_matches_mut(&mut matches).map_err(|e| e.format(&mut Self::command_line()))
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to a PNG (the default when no subcommand is given).
    Render(RenderArgs),
    /// Tone-map a colour layer of an EXR to a PNG, without re-rendering.
    Tonemap(TonemapArgs),
    /// Show an EXR's size, layers, channels, header and per-layer statistics.
    Info(InfoArgs),
    /// Compare two images (EXRs, or PNG/JPEG/TIFF/HDR) layer by layer; exit 1 when they differ.
    Diff(DiffArgs),
    /// Write a labelled contact sheet of every layer of an EXR.
    Sheet(SheetArgs),
    /// Assemble EXRs rendered with --region into the full frame.
    Merge(MergeArgs),
    /// Explain one pixel: its ray tree in the course's model, with every term of its colour.
    Explain(ExplainArgs),
    /// Test a Tick 1 (2017-18 on, --course YEAR) or Tick 2 image, project folder or program
    /// against the course's expected images, and name the mistake that made it differ.
    Check(CheckArgs),
    /// Grade a whole class: every submission of Moodle's zip compiled and run in a sandbox,
    /// checked, and written up (a report per student, the class's mistakes, Moodle's grades).
    Grade(GradeArgs),
    /// A local web viewer for an EXR (or PNG, JPEG, TIFF, HDR): layers, zoom, tone maps, error metrics, ray trees, relighting.
    View(ViewArgs),
    /// The course's tester as a service: students upload images or projects by a personal
    /// link and read the check's report; the staff watch the class live (docs/serve.md).
    Serve(ServiceArgs),
    /// Recombine an EXR's light layers with new gains (light groups), without re-rendering.
    Relight(RelightArgs),
    /// Print a balanced split of the frame into --region values, one per line (for a farm).
    Regions(RegionsArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(CompletionsArgs),
    /// Print the manual page (roff) on standard output, or write every subcommand's page.
    Man(ManArgs),
}

#[derive(Debug, Clone, Args)]
pub struct RegionsArgs {
    /// How many parts (one per farm task)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=65_535))]
    pub parts: u32,

    /// Image width in pixels [default: the course's, 640 (800 from 2021-22)]
    #[arg(long, value_name = "W", value_parser = parse_side)]
    pub width: Option<u32>,

    /// Image height in pixels [default: the course's, 480 (600 from 2021-22)]
    #[arg(long, value_name = "H", value_parser = parse_side)]
    pub height: Option<u32>,

    #[command(flatten)]
    pub course: CourseArgs,
}

impl RegionsArgs {
    /// The frame's size: as given, else the course year's.
    pub fn size(&self) -> (u32, u32) {
        let (width, height) = self.course.course().size();
        (self.width.unwrap_or(width), self.height.unwrap_or(height))
    }
}

#[derive(Debug, Clone, Args)]
pub struct ManArgs {
    /// Write whitted.1 and a page per subcommand (whitted-render.1, ...) into DIR, the pages
    /// the main page's SUBCOMMANDS section names
    #[arg(long, value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

#[derive(Debug, Clone, Args)]
pub struct CompletionsArgs {
    /// The shell to complete for
    #[arg(value_name = "SHELL", value_enum)]
    pub shell: clap_complete::Shell,
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
    /// The image to describe (OpenEXR, PNG, JPEG, TIFF or Radiance HDR)
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

    /// Pass when at most this percentage of a layer's pixels fail
    #[arg(long, value_name = "P", default_value_t = 0.0, value_parser = parse_percent)]
    pub fail_percent: f64,

    /// Pass when at most this many of a layer's pixels fail
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub allow_failures: usize,

    /// Fail if any pixel is off by more than T (absolute), whatever is allowed
    #[arg(long, value_name = "T", value_parser = parse_tolerance)]
    pub hard_fail: Option<f64>,

    /// Report pixels off by more than T (absolute) as warnings; they do not fail
    #[arg(long, value_name = "T", value_parser = parse_tolerance)]
    pub warn: Option<f64>,

    /// Write a PNG showing where and by how much they differ
    #[arg(long, value_name = "OUT.png")]
    pub heatmap: Option<PathBuf>,

    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Clone, Args)]
pub struct SheetArgs {
    /// The image to show (OpenEXR, PNG, JPEG, TIFF or Radiance HDR)
    #[arg(value_name = "IN")]
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

    /// Tone map for colour layers [default: clamp, or the course year's for a later year's
    /// EXR or with --course]
    #[arg(long = "tonemap", value_name = "OP", value_enum)]
    pub tonemap: Option<ToneMapArg>,

    #[command(flatten)]
    pub course: ToneCourseArgs,

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

    #[command(flatten)]
    pub course: ToneCourseArgs,
}

/// The image and the tick model's options, shared by `render` and `explain`.
#[derive(Debug, Clone, Args)]
pub struct FrameArgs {
    /// Mirror reflection bounces after the primary hit
    #[arg(short, long, value_name = "N", default_value_t = 2,
          value_parser = parse_bounces, allow_negative_numbers = true)]
    pub bounces: u32,

    /// Image width in pixels (the field of view stays 45 degrees horizontal) [default: the
    /// course's, 640 (800 from 2021-22)]
    #[arg(long, value_name = "W", value_parser = parse_side)]
    pub width: Option<u32>,

    /// Image height in pixels [default: the course's, 480 (600 from 2021-22)]
    #[arg(long, value_name = "H", value_parser = parse_side)]
    pub height: Option<u32>,

    /// Ignore occlusion: every light reaches every point
    #[arg(long)]
    pub no_shadows: bool,

    #[command(flatten)]
    pub course: CourseArgs,
}

/// `--course`, shared by every command that renders or reads a scene.
#[derive(Debug, Clone, Copy, Args)]
pub struct CourseArgs {
    /// The year of the course whose rules, scene format, size and tone map to follow
    /// (docs/courses.md)
    #[arg(long = "course", value_name = "YEAR", value_enum, default_value_t = CourseArg::Y2016)]
    pub course: CourseArg,
}

/// `--course` where it only chooses a PNG's tone map, for commands that read an EXR.
#[derive(Debug, Clone, Copy, Args)]
pub struct ToneCourseArgs {
    /// The year whose tone map a PNG gets [default: the year the EXR records, else 2016-17]
    #[arg(long = "course", value_name = "YEAR", value_enum)]
    pub course: Option<CourseArg>,
}

impl ToneCourseArgs {
    /// The year asked for, else the one `image` (read from `path`) records: whose tone map a
    /// PNG of it gets. The header is read only when no year is asked for.
    pub fn course(&self, image: &Image, path: &Path) -> Result<Course> {
        match self.course {
            Some(course) => Ok(course.into()),
            None => image.course(path),
        }
    }
}

impl CourseArgs {
    pub fn course(&self) -> Course {
        self.course.into()
    }
}

impl FrameArgs {
    /// The frame these options ask for, with every layer.
    pub fn spec(&self) -> FrameSpec {
        let course = self.course.course();
        let (width, height) = course.size();
        FrameSpec {
            width: self.width.unwrap_or(width),
            height: self.height.unwrap_or(height),
            bounces: self.bounces,
            shadows: !self.no_shadows,
            course,
            ..FrameSpec::default()
        }
    }
}

/// How linear HDR values become PNG bytes (docs/tonemap.md).
#[derive(Debug, Clone, Args)]
pub struct ToneArgs {
    /// Tone map: `tick` and `sigmoid` are the course's exact outputs; the others are
    /// sRGB-encoded [default: the course year's, `tick` (`sigmoid` from 2018-19)]
    #[arg(long = "tonemap", value_name = "OP", value_enum)]
    pub tonemap: Option<ToneMapArg>,

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
    /// The encoding asked for, `course`'s tone map unless `--tonemap` names one.
    pub fn request(&self, course: Course) -> ToneRequest {
        ToneRequest {
            tonemap: self.tonemap.map_or(course.tonemap(), Into::into),
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

    #[command(flatten)]
    pub frame: FrameArgs,

    /// Samples per pixel on a fixed k*k stratified grid (1 = the pixel centre, the exact tick
    /// image)
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = parse_spp)]
    pub spp: u32,

    /// Render only the pixels [X0, X1) x [Y0, Y1) of the image; the EXR's data window is
    /// that crop, so parts from several machines merge into the full frame (`whitted merge`)
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_region, allow_hyphen_values = true)]
    pub region: Option<Region>,

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

    #[command(flatten)]
    pub star: StarArgs,

    /// Worker threads [default: all cores]; the output is identical for any number
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,

    /// No progress bar and no summary line
    #[arg(short, long)]
    pub quiet: bool,
}

impl RenderArgs {
    /// The render asked for, as plain data for `RenderPlan::new` to check.
    pub fn request(&self) -> RenderRequest {
        RenderRequest {
            input: self.input.clone(),
            png: (!self.no_png).then(|| self.output.clone()),
            exr: self.exr.clone(),
            frame: FrameSpec {
                region: self.region,
                spp: self.spp,
                aovs: self.aovs.clone(),
                ..self.frame.spec()
            },
            exr_options: ExrOptions {
                compression: self.compression.into(),
                half: self.half,
            },
            tone: self.tone.request(self.frame.course.course()),
            threads: self.threads,
            stamp_date: self.stamp_date,
        }
    }
}

impl DiffArgs {
    /// When a layer passes.
    pub fn criteria(&self) -> Criteria {
        Criteria {
            tolerance: Tolerance {
                abs: self.abs,
                rel: self.rel,
            },
            fail_percent: self.fail_percent,
            allow_failures: self.allow_failures,
            hard_fail: self.hard_fail,
            warn: self.warn,
        }
    }
}

impl SheetArgs {
    /// The sheet's options for an image rendered under `recorded` (the year its header names):
    /// `--tonemap`, else the year's tone map where a year is asked for or recorded, else clamp.
    pub fn options(&self, recorded: Course) -> SheetOptions {
        let course = self.course.course.map(Course::from).unwrap_or(recorded);
        let tonemap = match (self.tonemap, self.course.course) {
            (Some(op), _) => op.into(),
            (None, Some(_)) => course.tonemap(),
            (None, None) if !course.is_default() => course.tonemap(),
            (None, None) => whitted_core::tonemap::ToneMap::Clamp,
        };
        SheetOptions {
            columns: self.columns,
            tile_width: self.tile_width,
            tonemap,
            exposure: self.exposure,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command_line().debug_assert();
    }

    #[test]
    fn negative_numbers_reach_their_parsers() {
        for args in [
            &["whitted", "explain", "--pixel", "-1,0"][..],
            &["whitted", "render", "--region", "-1,0,4,4"],
            &["whitted", "check", "x.png", "--tolerance", "-1"],
            &["whitted", "check", "x.png", "--max-beyond", "-1"],
            &[
                "whitted",
                "grade",
                "class.zip",
                "-o",
                "out",
                "--max-beyond",
                "-5%",
            ],
            &["whitted", "diff", "a", "b", "--fail-percent", "-1"],
            &["whitted", "render", "--width", "-5"],
        ] {
            let matches = Cli::command_line().try_get_matches_from(args);
            let e = matches.expect_err("refused");
            assert_eq!(
                e.kind(),
                clap::error::ErrorKind::ValueValidation,
                "{args:?}: {e}"
            );
            assert!(!e.to_string().contains("-- -"), "{e}");
        }
        let ok = Cli::command_line().try_get_matches_from(["whitted", "render", "-o", "-"]);
        assert!(ok.is_ok());
        // A gain may be negative (a light taken away): it reaches relight as -1.
        let args = [
            "whitted",
            "relight",
            "a.exr",
            "-o",
            "b.png",
            "--ambient",
            "-1",
        ];
        let matches = Cli::command_line()
            .try_get_matches_from(args)
            .expect("parses");
        let (_, relight) = matches.subcommand().expect("relight");
        assert_eq!(relight.get_one::<f64>("ambient"), Some(&-1.0));
    }

    #[test]
    fn a_course_year_chooses_the_size_and_the_tone_map_unless_they_are_given() {
        use whitted_core::tonemap::ToneMap;
        let render = |args: &[&str]| {
            let matches = Cli::command_line()
                .try_get_matches_from(args)
                .expect("parses");
            let (_, sub) = matches.subcommand().expect("render");
            RenderArgs::from_arg_matches(sub).expect("render args")
        };
        let later = render(&["whitted", "render", "--course", "2023-24"]).request();
        assert_eq!((later.frame.width, later.frame.height), (800, 600));
        assert_eq!(later.tone.tonemap, ToneMap::Sigmoid);
        assert_eq!(later.frame.course, Course::Y2023);
        let given = render(&[
            "whitted",
            "render",
            "--course",
            "2022-23",
            "--width",
            "64",
            "--tonemap",
            "aces",
        ])
        .request();
        assert_eq!((given.frame.width, given.frame.height), (64, 600));
        assert_eq!(given.tone.tonemap, ToneMap::Aces);
        assert_eq!(given.frame.course, Course::Y2021);
        let default = render(&["whitted", "render"]).request();
        assert_eq!((default.frame.width, default.frame.height), (640, 480));
        assert_eq!(default.tone.tonemap, ToneMap::Tick);

        let sheet = |args: &[&str], recorded: Course| {
            let matches = Cli::command_line()
                .try_get_matches_from(args)
                .expect("parses");
            let (_, sub) = matches.subcommand().expect("sheet");
            SheetArgs::from_arg_matches(sub)
                .expect("sheet args")
                .options(recorded)
                .tonemap
        };
        let base = ["whitted", "sheet", "a.exr", "-o", "s.png"];
        assert_eq!(sheet(&base, Course::Y2016), ToneMap::Clamp);
        assert_eq!(sheet(&base, Course::Y2020), ToneMap::Sigmoid);
        let asked = [&base[..], &["--course", "2016-17"]].concat();
        assert_eq!(sheet(&asked, Course::Y2020), ToneMap::Tick);
    }
}
