//! PNG (8 or 16 bits), JPEG, TIFF and Radiance HDR -> `Image`, through the `image` crate:
//! channels `Y`, `Y A`, `R G B` or `R G B A`, integer samples scaled to [0, 1], so a student's
//! PNG can be compared with the course's JPEG by the same tools as EXRs.

use std::io::Cursor;
use std::path::Path;

use image::{DynamicImage, ImageFormat, ImageReader, Limits};

use crate::input::image::{Channel, Format, Image, Window};
use whitted_core::error::{Error, Result};
use whitted_core::memory;

/// The largest bytes per pixel a decoded raster takes with its f32 copy (four 16-bit channels
/// as decoded, four f32 channels as stored).
const MAX_BYTES_PER_PIXEL: u64 = 4 * 2 + 4 * 4;

/// Whether a JPEG's bytes end with its end-of-image marker (FF D9), allowing the little
/// padding some writers put after it. The decoder itself fills the rows of a truncated file
/// with grey and says nothing, so a file caught half-written would pass for a good one.
fn ends_a_jpeg(bytes: &[u8]) -> bool {
    const PADDING: usize = 256;
    let tail = &bytes[bytes.len().saturating_sub(PADDING + 2)..];
    tail.windows(2).any(|w| w == [0xff, 0xd9])
}

/// Decodes `bytes` as `format`, after checking that the size its header declares fits in the
/// memory this process may use.
pub fn decode(path: &Path, bytes: &[u8], format: Format) -> Result<Image> {
    let fail = |e: image::ImageError| Error::Raster {
        path: path.to_path_buf(),
        msg: e.to_string(),
    };
    if format == Format::Jpeg && !ends_a_jpeg(bytes) {
        return Err(Error::Raster {
            path: path.to_path_buf(),
            msg: "is a truncated JPEG (no end-of-image marker): still being written?".into(),
        });
    }
    let codec = match format {
        Format::Png => ImageFormat::Png,
        Format::Jpeg => ImageFormat::Jpeg,
        Format::Tiff => ImageFormat::Tiff,
        Format::Hdr => ImageFormat::Hdr,
        Format::Exr => unreachable!("EXRs are read by input::exr"),
    };
    let budget = memory::available_bytes().unwrap_or(u64::MAX);
    let (width, height) = ImageReader::with_format(Cursor::new(bytes), codec)
        .into_dimensions()
        .map_err(fail)?;
    let pixels = u64::from(width) * u64::from(height);
    memory::check(
        pixels.saturating_mul(MAX_BYTES_PER_PIXEL),
        Some(budget),
        &format!("decoding {}", path.display()),
    )?;
    let mut limits = Limits::no_limits();
    limits.max_alloc = Some(budget);
    let mut reader = ImageReader::with_format(Cursor::new(bytes), codec);
    reader.limits(limits);
    let decoded = reader.decode().map_err(fail)?;
    let (names, pixel_type, samples) = samples(decoded);
    Ok(image(
        format,
        width as usize,
        height as usize,
        names,
        pixel_type,
        &samples,
    ))
}

/// An 8-bit RGB raster already in memory (a check's student image and reference) as the
/// `Image` its PNG would read as.
pub fn rgb8(width: usize, height: usize, bytes: &[u8]) -> Image {
    let samples: Vec<f32> = bytes.iter().map(|&b| eight_bit(b)).collect();
    image(
        Format::Png,
        width,
        height,
        &["R", "G", "B"],
        "uint8",
        &samples,
    )
}

/// An 8-bit sample scaled to [0, 1].
fn eight_bit(b: u8) -> f32 {
    f32::from(b) / 255.0
}

/// Interleaved `samples` of `names` channels as an image.
fn image(
    format: Format,
    width: usize,
    height: usize,
    names: &[&str],
    pixel_type: &'static str,
    samples: &[f32],
) -> Image {
    let channels = names
        .iter()
        .enumerate()
        .map(|(c, name)| Channel {
            name: (*name).to_string(),
            pixel_type,
            values: samples
                .iter()
                .skip(c)
                .step_by(names.len())
                .copied()
                .collect(),
        })
        .collect();
    let window = Window::at([0, 0], width, height);
    Image {
        format,
        part: None,
        width,
        height,
        data_window: window,
        display_window: window,
        channels,
        attributes: Vec::new(),
    }
}

/// Channel names, the stored sample type, and the interleaved samples as f32.
fn samples(image: DynamicImage) -> (&'static [&'static str], &'static str, Vec<f32>) {
    let eight = |v: Vec<u8>| v.into_iter().map(eight_bit).collect();
    let sixteen = |v: Vec<u16>| v.into_iter().map(|b| f32::from(b) / 65535.0).collect();
    match image {
        DynamicImage::ImageLuma8(i) => (&["Y"], "uint8", eight(i.into_raw())),
        DynamicImage::ImageLumaA8(i) => (&["Y", "A"], "uint8", eight(i.into_raw())),
        DynamicImage::ImageRgb8(i) => (&["R", "G", "B"], "uint8", eight(i.into_raw())),
        DynamicImage::ImageRgba8(i) => (&["R", "G", "B", "A"], "uint8", eight(i.into_raw())),
        DynamicImage::ImageLuma16(i) => (&["Y"], "uint16", sixteen(i.into_raw())),
        DynamicImage::ImageLumaA16(i) => (&["Y", "A"], "uint16", sixteen(i.into_raw())),
        DynamicImage::ImageRgb16(i) => (&["R", "G", "B"], "uint16", sixteen(i.into_raw())),
        DynamicImage::ImageRgba16(i) => (&["R", "G", "B", "A"], "uint16", sixteen(i.into_raw())),
        DynamicImage::ImageRgb32F(i) => (&["R", "G", "B"], "float", i.into_raw()),
        other => (
            &["R", "G", "B", "A"],
            "float",
            other.into_rgba32f().into_raw(),
        ),
    }
}
