//! `whitted view FILE.exr [--reference REF.exr] [--port N] [--no-browser]`.

use crate::cli::ViewArgs;
use crate::error::Result;
use crate::input;
use crate::view::serve;

pub fn run(args: &ViewArgs) -> Result<()> {
    let main = input::read_exr(&args.input)?;
    let reference = args.reference.as_deref().map(input::read_exr).transpose()?;
    serve(main, reference, args.port, args.no_browser)
}
