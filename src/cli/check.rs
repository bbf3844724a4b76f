//! Arguments of `whitted check` (docs/check.md).

use std::path::PathBuf;

use clap::Args;

use super::parse::*;
use super::values::CourseArg;
use super::ServeArgs;
use whitted_check::check::pass_rule::{Allowance, PassRule};

#[derive(Debug, Clone, Args)]
pub struct CheckArgs {
    /// The student's PNG (8-bit RGB; the size it has is the size rendered), or their project
    /// folder: its Tick1.java (Tick2.java for 2016-17) found, compiled by javac and run over
    /// the suite as --program is [default: the current folder, when it is a project]
    #[arg(value_name = "IMAGE.png|DIR", conflicts_with = "program")]
    pub image: Option<PathBuf>,

    /// Scene XML file the image was rendered from [default: the embedded course tick2.xml]
    #[arg(short, long, value_name = "SCENE", conflicts_with = "program")]
    pub input: Option<PathBuf>,

    /// Mirror reflection bounces the image was rendered with
    #[arg(short, long, value_name = "N", default_value_t = 2,
          value_parser = parse_bounces, allow_negative_numbers = true, conflicts_with = "program")]
    pub bounces: u32,

    /// Check a Tick 1* image: `bump` finds the parametrisation a bump-mapped image follows
    /// and names what is wrong against it [default: `bump` when the scene has a
    /// <bumpy-sphere>; without -i, the handout's bump.xml, judged as --program judges it];
    /// `distributed` says whether the image is one draw of the course's soft shadows and
    /// depth of field on distributed.xml, or of which variant (needs --course). An image of
    /// the Tick 1 renderer is that option not done
    #[arg(long, value_name = "OPTION", value_enum, conflicts_with = "program")]
    pub star: Option<StarCheck>,

    /// Largest difference of a channel, in LSB, that still passes
    #[arg(long, value_name = "LSB", default_value_t = 2)]
    pub tolerance: u8,

    /// Pixels allowed beyond --tolerance: a case passes when at most N pixels (or P% of the
    /// image's pixels) have a channel off by more than it [default: 0]
    #[arg(long, value_name = "N|P%", value_parser = parse_allowance,
          allow_hyphen_values = true)]
    pub max_beyond: Option<Allowance>,

    /// Print one JSON object instead of the text report
    #[arg(long)]
    pub json: bool,

    /// Write a PNG of where and by how much the image differs
    #[arg(long, value_name = "H.png", conflicts_with = "program")]
    pub heatmap: Option<PathBuf>,

    /// Write a report file, its format by its extension: REPORT.html, one self-contained page
    /// (per failing case your image, the reference and the difference side by side, with the
    /// worst region enlarged; the verdict, progress and findings in full); REPORT.png, a
    /// contact sheet (per failing case the images and the top diagnosis)
    #[arg(long, value_name = "REPORT.html|REPORT.png", value_parser = parse_report)]
    pub report: Option<PathBuf>,

    /// Print everything: every candidate and what its images cannot tell apart, a program's
    /// whole standard error, and the commands that rerun and explain each failing case (the
    /// default is one screen: the verdict, progress, the finding with where and fix, a line
    /// per case)
    #[arg(short, long, conflicts_with = "json")]
    pub verbose: bool,

    /// Run this program (split into words as a shell would; no shell is run) over the suite:
    /// each case as `CMD ARGS --input S --output O.png --bounces B`
    #[arg(long, value_name = "CMD ARGS")]
    pub program: Option<String>,

    /// Write the suite's scenes into DIR (made if missing), so that every failing case can be
    /// rerun and explained from your own directory (a Tick 1* program's: the handout's scenes
    /// it ran, bump.xml with its map and distributed.xml): without it no rerun command is
    /// printed. With --program or a project folder (an image check runs no scene)
    #[arg(long, value_name = "DIR")]
    pub suite_dir: Option<PathBuf>,

    /// Seconds each case of `--program` may take
    #[arg(long, value_name = "SECONDS", default_value_t = 60, value_parser = parse_timeout)]
    pub timeout: u64,

    /// Print the catalogue of mistakes and exit (with --course, that year's entries in its words)
    #[arg(long, conflicts_with_all = ["image", "program", "input", "json", "heatmap", "report", "view", "suite_dir", "verbose"])]
    pub list_bugs: bool,

    /// Open the check in the viewer: the image against the reference, the error maps, the
    /// diagnosis, and a click's two ray trees (the reference's and the top mistake's)
    #[arg(long, conflicts_with_all = ["program", "json", "heatmap", "report", "verbose"])]
    pub view: bool,

    /// The year of the course the image, project or program is of (docs/courses.md) [default:
    /// what the image's size, the scene, the project's classes or the program's main class
    /// says, else 2016-17]
    #[arg(long = "course", value_name = "YEAR", value_enum)]
    pub course: Option<CourseArg>,

    #[command(flatten)]
    pub serve: ServeArgs,
}

impl CheckArgs {
    /// When a case passes: `--tolerance` and `--max-beyond`.
    pub fn rule(&self) -> PassRule {
        PassRule {
            tolerance: self.tolerance,
            allowance: self.max_beyond.unwrap_or(Allowance::NONE),
        }
    }
}

/// The Tick 1* option an image is checked as.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum StarCheck {
    /// Option 1, bump mapping
    Bump,
    /// Option 2, soft shadows and depth of field
    Distributed,
}
