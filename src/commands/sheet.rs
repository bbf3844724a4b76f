//! `whitted sheet IN -o SHEET.png`: a labelled contact sheet of every layer of an image
//! (OpenEXR, PNG, JPEG, TIFF or Radiance HDR).

use crate::cli::SheetArgs;
use whitted_core::error::Result;
use whitted_io::input;
use whitted_io::output::destination::{refuse_clashes, Destination};
use whitted_io::sheet::{compose, select};

pub fn run(args: &SheetArgs) -> Result<()> {
    refuse_clashes(&[&args.input], &[&args.output])?;
    let mut output = Destination::open(&args.output)?;
    let image = input::read(&args.input)?;
    let layers = select(&image, &args.layers)?;
    let sheet = compose(&image, &layers, &args.options(image.course(&args.input)?));
    output.write_png(&sheet.into_png())?;
    output.commit()
}
