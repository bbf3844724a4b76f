//! PNG -> `Image`: channels `R G B` (and `A`), scaled to [0, 1], so PNGs can be compared
//! with the same tools as EXRs.

use std::path::Path;

use crate::error::{Error, Result};
use crate::input::image::{Channel, Format, Image};

pub fn decode(path: &Path, bytes: &[u8]) -> Result<Image> {
    let fail = |msg: String| Error::Png {
        path: path.to_path_buf(),
        msg,
    };
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    // Expand palettes and low bit depths to 8 bits; keep 16-bit samples.
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| fail("image too large".into()))?;
    let mut buffer = vec![0; size];
    let frame = reader
        .next_frame(&mut buffer)
        .map_err(|e| fail(e.to_string()))?;
    let names: &[&str] = match frame.color_type {
        png::ColorType::Grayscale => &["Y"],
        png::ColorType::GrayscaleAlpha => &["Y", "A"],
        png::ColorType::Rgb => &["R", "G", "B"],
        png::ColorType::Rgba => &["R", "G", "B", "A"],
        png::ColorType::Indexed => return Err(fail("palette PNGs are not supported".into())),
    };
    let (width, height) = (frame.width as usize, frame.height as usize);
    let data = &buffer[..frame.buffer_size()];
    let samples: Vec<f32> = match frame.bit_depth {
        png::BitDepth::Sixteen => data
            .chunks_exact(2)
            .map(|b| f32::from(u16::from_be_bytes([b[0], b[1]])) / 65535.0)
            .collect(),
        _ => data.iter().map(|&b| f32::from(b) / 255.0).collect(),
    };
    let kind = if frame.bit_depth == png::BitDepth::Sixteen {
        "uint16"
    } else {
        "uint8"
    };
    let channels = names
        .iter()
        .enumerate()
        .map(|(c, name)| Channel {
            name: (*name).to_string(),
            pixel_type: kind,
            values: samples
                .iter()
                .skip(c)
                .step_by(names.len())
                .copied()
                .collect(),
        })
        .collect();
    Ok(Image {
        format: Format::Png,
        width,
        height,
        channels,
        attributes: Vec::new(),
    })
}
