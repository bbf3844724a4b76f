//! `whitted relight IN.exr -o OUT`: the image with other light gains, from the light layers.

use glam::DVec3;

use crate::cli::RelightArgs;
use whitted_core::error::{Error, Result};
use whitted_core::memory;
use whitted_io::input;
use whitted_io::output::atomic::AtomicFile;
use whitted_io::output::destination::{refuse_clashes, Destination};
use whitted_io::output::exr::{write_rgba, Placement};
use whitted_io::output::png::encode;
use whitted_io::relight::{relight, working_bytes, RelightSpec};

pub fn run(args: &RelightArgs) -> Result<()> {
    refuse_clashes(&[&args.input], &[&args.output])?;
    let to_exr = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    if to_exr {
        refuse_png_options(args)?;
    }
    let image = input::read_exr(&args.input)?;
    // A PNG gets the tone map of the year the EXR was rendered under, unless one is asked for.
    let course = args.course.course(&image, &args.input)?;
    let encoding = args.tone.request(course).encoding()?;
    memory::check(
        working_bytes(image.width * image.height),
        memory::available_bytes(),
        &format!("relighting a {}x{} image", image.width, image.height),
    )?;
    let spec = RelightSpec {
        lights: args
            .lights
            .iter()
            .map(|(name, g)| (name.clone(), DVec3::from_array(*g)))
            .collect(),
        no_shadow: args.no_shadow.clone(),
        ambient: DVec3::splat(args.ambient),
        background: DVec3::splat(args.background),
    };
    let pixels = relight(&image, &spec).map_err(|msg| Error::Exr {
        path: args.input.clone(),
        msg,
    })?;
    if to_exr {
        refuse_overflow(&pixels)?;
        let mut file = AtomicFile::create(&args.output)?;
        let (data, display) = (image.data_window, image.display_window);
        let placement = Placement {
            size: (image.width, image.height),
            origin: (data.min[0] as i32, data.min[1] as i32),
            display: (
                (display.min[0] as i32, display.min[1] as i32),
                (
                    (display.max[0] - display.min[0] + 1) as usize,
                    (display.max[1] - display.min[1] + 1) as usize,
                ),
            ),
        };
        write_rgba(file.file(), placement, &pixels).map_err(|msg| Error::Exr {
            path: args.output.clone(),
            msg,
        })?;
        whitted_core::interrupt::check()?;
        return file.commit();
    }
    let mut output = Destination::open(&args.output)?;
    let size = |n: usize| u32::try_from(n).map_err(|_| Error::Usage("image too large".into()));
    output.write_png(&encode(
        &pixels,
        size(image.width)?,
        size(image.height)?,
        &encoding,
    ))?;
    output.commit()
}

/// The options that only shape a PNG, refused for an EXR output (which is linear and float):
/// silently ignoring them would hand back another image than the one asked for.
fn refuse_png_options(args: &RelightArgs) -> Result<()> {
    let tone = &args.tone;
    let given = [
        (tone.tonemap.is_some(), "--tonemap"),
        (tone.exposure != 0.0, "--exposure"),
        (tone.png_depth != 8, "--png-depth"),
        (tone.dither, "--dither"),
    ];
    match given.iter().find(|(on, _)| *on) {
        Some((_, option)) => Err(Error::Usage(format!(
            "{option} shapes a PNG; the EXR output {} is linear float (write a .png, or leave {option} out)",
            args.output.display()
        ))),
        None => Ok(()),
    }
}

/// Refuses relit values an EXR cannot hold: a finite gain can still overflow float32, and
/// the file would then hold infinities (as `render`, whitted never writes Inf or NaN).
fn refuse_overflow(pixels: &[DVec3]) -> Result<()> {
    let limit = f64::from(f32::MAX);
    let bad = pixels
        .iter()
        .flat_map(|p| p.to_array())
        .find(|v| !v.is_finite() || v.abs() > limit);
    match bad {
        Some(v) => Err(Error::Usage(format!(
            "the gains make a value ({v:e}) that a float EXR cannot hold (at most {limit:e}); \
             use smaller gains"
        ))),
        None => Ok(()),
    }
}
