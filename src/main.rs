//! The `whitted` binary: parse the command line, run it, turn any error into one line on stderr
//! and exit status 2 (docs/cli.md, Exit status and errors).

use std::process::ExitCode;

use clap::error::ErrorKind;

use whitted::cli::{Cli, Command};
use whitted::commands;

/// Probes descriptor 1 before Rust's runtime hides a closed one (output::stdout::probe). Hand
/// written rather than a constructor crate: it is one static in the binary's own object file,
/// which the linker always keeps.
#[cfg(target_os = "linux")]
#[used]
#[link_section = ".init_array"]
static PROBE_STDOUT_BEFORE_RUNTIME: extern "C" fn() = probe_stdout;

#[cfg(target_os = "linux")]
extern "C" fn probe_stdout() {
    whitted_io::output::stdout::probe();
}

fn main() -> ExitCode {
    let cli = match Cli::parse_args() {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e),
    };
    whitted_core::interrupt::install();
    let result = match &cli.command {
        Some(Command::Render(args)) => commands::render::run(args).map(|()| true),
        Some(Command::Tonemap(args)) => commands::tonemap::run(args).map(|()| true),
        Some(Command::Info(args)) => commands::info::run(args).map(|()| true),
        Some(Command::Diff(args)) => commands::diff::run(args),
        Some(Command::Sheet(args)) => commands::sheet::run(args).map(|()| true),
        Some(Command::Merge(args)) => commands::merge::run(args).map(|()| true),
        Some(Command::Explain(args)) => commands::explain::run(args).map(|()| true),
        Some(Command::Check(args)) => commands::check::run(args),
        Some(Command::Grade(args)) => commands::grade::run(args).map(|()| true),
        Some(Command::View(args)) => commands::view::run(args).map(|()| true),
        Some(Command::Serve(args)) => commands::serve::run(args).map(|()| true),
        Some(Command::Relight(args)) => commands::relight::run(args).map(|()| true),
        Some(Command::Regions(args)) => commands::regions::run(args).map(|()| true),
        Some(Command::Completions(args)) => commands::completions::run(args).map(|()| true),
        Some(Command::Man(args)) => commands::man::run(args).map(|()| true),
        None => commands::render::run(&cli.render).map(|()| true),
    };
    // A server (`view`, `serve`) runs until it is stopped: Ctrl-C is how it ends, not an
    // error, though the status stays the signal's (128 + n) as a shell expects.
    let serving = matches!(cli.command, Some(Command::View(_) | Command::Serve(_)));
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Err(e @ whitted_core::error::Error::Interrupted { signal }) if serving => {
            eprintln!("whitted: stopped by signal {signal}");
            ExitCode::from(e.exit_code())
        }
        // A comparison that found differences (`diff`): not an error, but not a pass.
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

/// Help and version go to stdout with status 0; a bad command line gets clap's whole message
/// on stderr (what is wrong, the valid values or missing arguments, the usage line) and
/// status 2.
fn usage_error(e: &clap::Error) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        _ => {
            let _ = e.print();
            ExitCode::from(2)
        }
    }
}
