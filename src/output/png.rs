//! Display-encoded pixels -> PNG file bytes.

use std::io::Write;

/// An encoded image ready for the PNG encoder: 8- or 16-bit RGB, row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct PngImage {
    pub width: u32,
    pub height: u32,
    pub pixels: PngPixels,
    /// Whether the values are sRGB-encoded (then the file says so with an `sRGB` chunk).
    /// The `tick` output is not: the course's file carries no colour metadata.
    pub srgb: bool,
}

/// Channel values, three per pixel.
#[derive(Debug, Clone, PartialEq)]
pub enum PngPixels {
    Eight(Vec<u8>),
    Sixteen(Vec<u16>),
}

/// Encodes `image` as a PNG into `out`.
pub fn write_png(out: impl Write, image: &PngImage) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(out, image.width, image.height);
    encoder.set_color(png::ColorType::Rgb);
    if image.srgb {
        // Also writes the gAMA and cHRM fallbacks the PNG spec recommends beside sRGB.
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    }
    match &image.pixels {
        PngPixels::Eight(bytes) => {
            encoder.set_depth(png::BitDepth::Eight);
            let mut writer = encoder.write_header()?;
            writer.write_image_data(bytes)?;
            writer.finish()
        }
        PngPixels::Sixteen(values) => {
            encoder.set_depth(png::BitDepth::Sixteen);
            let mut writer = encoder.write_header()?;
            let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
            writer.write_image_data(&bytes)?;
            writer.finish()
        }
    }
}
