//! Arguments of `whitted grade` (docs/grade.md).

use std::path::PathBuf;

use clap::Args;

use super::parse::*;
use clap::ValueEnum;
use whitted_check::check::pass_rule::{Allowance, PassRule};
use whitted_grade::{Grading, Rerun};

#[derive(Debug, Clone, Args)]
pub struct GradeArgs {
    /// Moodle's "Download all submissions" zip, a folder with a folder per student, or one
    /// student's project folder
    #[arg(value_name = "SUBMISSIONS", required_unless_present_any = ["calibrate", "write_skeleton"])]
    pub submissions: Option<PathBuf>,

    /// Where the reports, class.csv, mistakes.csv, moodle.csv and index.html go (made if
    /// missing; a rerun into it skips the students already graded)
    #[arg(short, long, value_name = "OUTDIR")]
    pub output: PathBuf,

    /// Grade no one: print each student's id and whether OUTDIR holds their finished result
    /// (`done`) or not (`todo`), one per line, in the order --part shares them out
    #[arg(long)]
    pub list: bool,

    /// Grade no one: print, from the results in OUTDIR alone, how many students each channel
    /// tolerance and pixel allowance would pass and the diagnosed mistakes of those it passes
    /// beyond the graded setting (a --max-beyond given adds its column)
    #[arg(long, conflicts_with_all = ["list", "only", "part", "rerun"])]
    pub calibrate: bool,

    /// Grade no one: write whitted's clean-room skeleton of the --course year into OUTDIR (a new
    /// folder), its sources under src/ in the course's package: the classes a student's files
    /// are compiled against
    #[arg(long, conflicts_with_all = ["list", "calibrate", "only", "part", "rerun", "skeleton", "submissions"])]
    pub write_skeleton: bool,

    /// The course's sources to compile against: 2016-17's gfx/tick2, or from 2017-18 the
    /// year's tick1 folder (found anywhere under DIR) [default: whitted's clean-room skeleton of
    /// the year, with the course's API]
    #[arg(long, value_name = "DIR")]
    pub skeleton: Option<PathBuf>,

    #[command(flatten)]
    pub course: super::CourseArgs,

    /// A folder of the course's hidden scenes (*.xml), added to the suite, each at the bounces
    /// its name says (`hidden_b2.xml`; 2 when it says none)
    #[arg(long, value_name = "DIR")]
    pub scenes: Option<PathBuf>,

    /// Students graded at once [default: the cores]
    #[arg(short, long, value_name = "N", value_parser = parse_jobs)]
    pub jobs: Option<usize>,

    /// Seconds each case may take (a compilation gets at least 60)
    #[arg(long, value_name = "SECONDS", default_value_t = 60, value_parser = parse_timeout)]
    pub timeout: u64,

    /// Memory for each program in MiB (the JVM's heap gets half)
    #[arg(long, value_name = "MIB", default_value_t = 1024, value_parser = parse_memory)]
    pub memory: u64,

    /// Grade finished students again: `failed` (errors and timeouts) or `all`
    #[arg(long, value_name = "WHICH", value_enum)]
    pub rerun: Option<RerunArg>,

    /// Run the students' code without a sandbox: only for code you trust (every report says so)
    #[arg(long)]
    pub no_sandbox: bool,

    /// The grade, out of 100: `pass-fail` (100 when every counted case passes) or `fraction`
    /// (the weighted share of counted cases passed)
    #[arg(long, value_name = "HOW", value_enum, default_value = "pass-fail")]
    pub grade: GradeHow,

    /// Largest difference of a channel, in LSB, that still passes
    #[arg(long, value_name = "LSB", default_value_t = 2)]
    pub tolerance: u8,

    /// Pixels allowed beyond --tolerance: a case passes when at most N pixels (or P% of the
    /// image's pixels) have a channel off by more than it [default: 0]
    #[arg(long, value_name = "N|P%", value_parser = parse_allowance,
          allow_hyphen_values = true)]
    pub max_beyond: Option<Allowance>,

    /// Count whitted's diagnostic scenes (shadows.xml, mirrors.xml) towards the grade too; by
    /// default they inform the diagnosis and the report and score nothing
    #[arg(long, conflicts_with = "rubric")]
    pub count_diagnostic: bool,

    /// A rubric weighing the cases: lines `CASE WEIGHT`, CASE a case (`tick2.xml -b 2`) or a
    /// scene (`tick2.xml`, every bounce count); cases it does not name score nothing
    #[arg(long, value_name = "FILE")]
    pub rubric: Option<PathBuf>,

    /// Grade only these students again (ids as the class lists them), keeping everyone else's
    /// results and rows
    #[arg(long, value_name = "ID", num_args = 1..)]
    pub only: Vec<String>,

    /// Show the --scenes cases to students in full (their images, the reference, the
    /// commands); by default a hidden case is reported by name and verdict only
    #[arg(long)]
    pub show_hidden: bool,

    /// Grade only the K-th of N shares of the class (a farm's array task), leaving the class
    /// files to a run without --part
    #[arg(long, value_name = "K/N", value_parser = parse_part)]
    pub part: Option<(usize, usize)>,

    /// No progress bar
    #[arg(short, long)]
    pub quiet: bool,
}

/// `--rerun`: clap's names for [`Rerun`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RerunArg {
    /// Only those whose result ended in an error or a timeout
    Failed,
    /// Everyone
    All,
}

impl From<RerunArg> for Rerun {
    fn from(which: RerunArg) -> Rerun {
        match which {
            RerunArg::Failed => Rerun::Failed,
            RerunArg::All => Rerun::All,
        }
    }
}

/// `--grade`: clap's names for [`Grading`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum GradeHow {
    /// 100 when every counted case passes, else 0
    PassFail,
    /// The weighted share of counted cases passed
    Fraction,
}

impl From<GradeHow> for Grading {
    fn from(how: GradeHow) -> Grading {
        match how {
            GradeHow::PassFail => Grading::PassFail,
            GradeHow::Fraction => Grading::Fraction,
        }
    }
}

fn parse_jobs(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=1024).contains(&n) => Ok(n),
        _ => Err(format!("expected a whole number from 1 to 1024, got `{s}`")),
    }
}

fn parse_memory(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(n) if (64..=1 << 20).contains(&n) => Ok(n),
        _ => Err(format!("expected MiB from 64 to 1048576, got `{s}`")),
    }
}

fn parse_part(s: &str) -> Result<(usize, usize), String> {
    let parsed = s.split_once('/').and_then(|(k, n)| {
        Some((
            k.trim().parse::<usize>().ok()?,
            n.trim().parse::<usize>().ok()?,
        ))
    });
    match parsed {
        Some((k, n)) if n >= 1 && (1..=n).contains(&k) && n <= 100_000 => Ok((k, n)),
        _ => Err(format!("expected K/N with 1 <= K <= N, got `{s}`")),
    }
}

impl GradeArgs {
    /// When a case passes: `--tolerance` and `--max-beyond`.
    pub fn rule(&self) -> PassRule {
        PassRule {
            tolerance: self.tolerance,
            allowance: self.max_beyond.unwrap_or(Allowance::NONE),
        }
    }
}
