//! `whitted tonemap IN.exr -o OUT.png`: re-encode any colour layer of an EXR as a PNG, with
//! any tone map and exposure, without re-rendering.

use crate::cli::TonemapArgs;
use whitted_core::error::{Error, Result};
use whitted_io::input;
use whitted_io::output::destination::{refuse_clashes, Destination};
use whitted_io::output::png::encode;

pub fn run(args: &TonemapArgs) -> Result<()> {
    refuse_clashes(&[&args.input], &[&args.output])?;
    let mut output = Destination::open(&args.output)?;
    let image = input::read_exr(&args.input)?;
    // A PNG gets the tone map of the year the EXR was rendered under, unless one is asked for.
    let course = args.course.course(&image, &args.input)?;
    let encoding = args.tone.request(course).encoding()?;
    let pixels = image.colour_layer(&args.layer).map_err(|msg| Error::Exr {
        path: args.input.clone(),
        msg,
    })?;
    let width = u32::try_from(image.width).map_err(|_| Error::Usage("image too wide".into()))?;
    let height = u32::try_from(image.height).map_err(|_| Error::Usage("image too tall".into()))?;
    output.write_png(&encode(&pixels, width, height, &encoding))?;
    output.commit()
}
