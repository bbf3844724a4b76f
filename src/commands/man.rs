//! `whitted man`: the manual page in roff, from the clap definition (`whitted man | man -l -`);
//! with `--dir DIR`, the main page and one per subcommand, as its SUBCOMMANDS section names
//! them (`whitted-render.1`, ...), for `MANPATH` or packaging.

use std::io::Write;
use std::path::Path;

use crate::cli::{Cli, ManArgs};
use whitted_core::error::{Error, Result};
use whitted_io::output::atomic::AtomicFile;
use whitted_io::output::stdout;

pub fn run(args: &ManArgs) -> Result<()> {
    let command = Cli::command_line();
    let Some(dir) = &args.dir else {
        return stdout::write_all(&page(command)?);
    };
    if !dir.is_dir() {
        return Err(Error::Usage(format!(
            "{}: not a directory (create it first)",
            dir.display()
        )));
    }
    write(dir, "whitted", page(command.clone())?)?;
    // Built, the command has clap's `help` subcommand too, which the main page names.
    let mut command = command;
    command.build();
    for sub in command.get_subcommands() {
        let name = format!("whitted-{}", sub.get_name());
        let page = page(sub.clone().display_name(name.clone()))?;
        write(dir, &name, page)?;
    }
    Ok(())
}

fn page(command: clap::Command) -> Result<Vec<u8>> {
    let mut page = Vec::new();
    clap_mangen::Man::new(command)
        .render(&mut page)
        .map_err(|e| Error::io("-", "cannot write the manual page", e))?;
    Ok(page)
}

/// `dir/name.1`, written atomically.
fn write(dir: &Path, name: &str, page: Vec<u8>) -> Result<()> {
    let path = dir.join(format!("{name}.1"));
    let mut file = AtomicFile::create(&path)?;
    file.file()
        .write_all(&page)
        .map_err(|e| Error::io(&path, "cannot write", e))?;
    file.commit()
}
