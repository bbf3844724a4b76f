//! Arguments of `whitted serve` (docs/serve.md).

use std::net::{IpAddr, SocketAddr};
use std::path::PathBuf;

use clap::{Args, Subcommand};

use super::values::CourseArg;

#[derive(Debug, Clone, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct ServiceArgs {
    #[command(subcommand)]
    pub action: Option<ServeAction>,

    /// The year of the course the class takes (docs/courses.md)
    #[arg(long = "course", value_name = "YEAR", value_enum, default_value_t = CourseArg::Y2016)]
    pub course: CourseArg,

    /// The address to listen on (the course's reverse proxy forwards to it)
    #[arg(long, value_name = "ADDR:PORT", default_value = "127.0.0.1:8080")]
    pub listen: SocketAddr,

    /// The data folder: the database and the uploads, made private (0700)
    #[arg(long, value_name = "DIR", default_value = "whitted-serve")]
    pub data: PathBuf,

    /// The class: Moodle's participants export or grading worksheet (CSV, the id column found
    /// by its header), or one id a line; added to those already served
    #[arg(long, value_name = "FILE")]
    pub roster: Option<PathBuf>,

    /// Workers of each kind: image checks, and program runs in the sandbox (with --slurm: the
    /// Slurm jobs in flight at once)
    #[arg(short, long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u16).range(1..=64))]
    pub jobs: u16,

    /// The address students reach it at through the reverse proxy (https://HOST): the links
    /// name it, and it is answered as a Host besides the listening address
    #[arg(long, value_name = "URL")]
    pub public_url: Option<String>,

    /// A header the trusted proxy sets to the signed-in user (staff pages at /staff/proxy)
    #[arg(long, value_name = "NAME", requires = "trusted_proxy")]
    pub trust_user_header: Option<String>,

    /// The proxy's address: --trust-user-header is read from its connections only
    #[arg(long, value_name = "ADDR", requires = "trust_user_header")]
    pub trusted_proxy: Option<IpAddr>,

    /// The users --trust-user-header may name who see the staff pages, comma-separated
    #[arg(long, value_name = "ID,...", value_delimiter = ',')]
    pub staff: Vec<String>,

    /// Seconds each case of a student's program may take
    #[arg(long, value_name = "SECONDS", default_value_t = 60)]
    pub timeout: u64,

    /// Run the projects as Slurm jobs (sbatch) instead of on this machine; the binary and
    /// --data must be on a filesystem the nodes see at the same paths
    #[arg(long)]
    pub slurm: bool,
}

#[derive(Debug, Clone, Subcommand)]
pub enum ServeAction {
    /// Print the roster with each student's link, and the staff link, as CSV
    Links(DataArgs),
    /// Revoke a student's link (their page answers no more)
    Revoke(LinkArgs),
    /// Give a student a new link (the old one is revoked)
    Reissue(LinkArgs),
    /// Copy the database consistently, while it serves (SQLite's backup)
    Backup(BackupArgs),
    /// Run one project attempt from its folder (what the service starts, here or as a Slurm job)
    #[command(hide = true)]
    RunAttempt(RunAttemptArgs),
}

#[derive(Debug, Clone, Args)]
pub struct RunAttemptArgs {
    /// The attempt's folder, with its job.json
    #[arg(value_name = "DIR")]
    pub dir: PathBuf,
}

#[derive(Debug, Clone, Args)]
pub struct DataArgs {
    /// The data folder
    #[arg(long, value_name = "DIR", default_value = "whitted-serve")]
    pub data: PathBuf,
}

#[derive(Debug, Clone, Args)]
pub struct LinkArgs {
    /// The student's id, as the roster gives it
    #[arg(value_name = "ID")]
    pub id: String,
    #[command(flatten)]
    pub data: DataArgs,
}

#[derive(Debug, Clone, Args)]
pub struct BackupArgs {
    /// The new file to write the copy to
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    #[command(flatten)]
    pub data: DataArgs,
}
