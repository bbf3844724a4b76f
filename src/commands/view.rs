//! `whitted view IMAGE [--reference REF] [--port N] [--no-browser]`: an EXR, or a PNG, JPEG,
//! TIFF or Radiance HDR through the same readers as `info` and `diff`, so that a student's
//! PNG can be set against the reference.

use crate::cli::ViewArgs;
use crate::error::{Error, Result};
use crate::input::{self, Image};
use crate::view::serve;

pub fn run(args: &ViewArgs) -> Result<()> {
    let main = input::read(&args.input)?;
    let reference = args.reference.as_deref().map(input::read).transpose()?;
    if let (Some(reference), Some(path)) = (&reference, &args.reference) {
        comparable(&main, reference).map_err(|why| {
            Error::Usage(format!(
                "{} cannot be compared with {}: {why}",
                path.display(),
                args.input.display()
            ))
        })?;
    }
    serve(main, reference, args.port, args.no_browser)
}

/// Whether a reference can stand beside the image for A/B: the same size and the same layers.
fn comparable(main: &Image, reference: &Image) -> std::result::Result<(), String> {
    if (main.width, main.height) != (reference.width, reference.height) {
        return Err(format!(
            "it is {}x{}, the image {}x{}",
            reference.width, reference.height, main.width, main.height
        ));
    }
    let names =
        |image: &Image| -> Vec<String> { image.layers().into_iter().map(|l| l.name).collect() };
    let (ours, theirs) = (names(main), names(reference));
    if ours != theirs {
        let missing: Vec<&String> = ours.iter().filter(|n| !theirs.contains(n)).collect();
        let extra: Vec<&String> = theirs.iter().filter(|n| !ours.contains(n)).collect();
        return Err(format!(
            "its layers differ (missing: {missing:?}; not in the image: {extra:?})"
        ));
    }
    Ok(())
}
