//! `whitted completions SHELL`: a completion script for the shell, from the clap definition.

use crate::cli::{Cli, CompletionsArgs};
use whitted_core::error::Result;
use whitted_io::output::stdout;

pub fn run(args: &CompletionsArgs) -> Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command_line(), "whitted", &mut script);
    stdout::write_all(&script)
}
