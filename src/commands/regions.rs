//! `whitted regions --parts N [--width W --height H] [--course YEAR]`: one `--region` value per line, so a
//! scheduler's array index can pick its line (`sed -n "$((i + 1))p"`).

use crate::cli::RegionsArgs;
use whitted_core::error::Result;
use whitted_core::frame::balanced_regions;
use whitted_io::output::stdout;

pub fn run(args: &RegionsArgs) -> Result<()> {
    let (width, height) = args.size();
    let lines: Vec<String> = balanced_regions(width, height, args.parts)?
        .iter()
        .map(|r| format!("{},{},{},{}", r.x0, r.y0, r.x1, r.y1))
        .collect();
    stdout::print_line(&lines.join("\n"))
}
