//! `whitted man`: the manual page in roff, from the clap definition (`whitted man | man -l -`).

use crate::cli::Cli;
use crate::error::{Error, Result};
use crate::output::stdout;

pub fn run() -> Result<()> {
    let mut page = Vec::new();
    clap_mangen::Man::new(Cli::command_line())
        .render(&mut page)
        .map_err(|e| Error::io("-", "cannot write the manual page", e))?;
    stdout::write_all(&page)
}
