//! `whitted completions SHELL`: a completion script for the shell, from the clap definition.

use crate::cli::{Cli, CompletionsArgs};
use crate::error::Result;
use crate::output::stdout;

pub fn run(args: &CompletionsArgs) -> Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command_line(), "whitted", &mut script);
    stdout::write_all(&script)
}
