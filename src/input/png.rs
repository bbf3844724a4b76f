//! PNG -> `Image`: channels `R G B` (and `A`), scaled to [0, 1], so PNGs can be compared
//! with the same tools as EXRs.

use std::path::Path;

use crate::error::{Error, Result};
use crate::input::image::{Channel, Format, Image};
use crate::memory;

pub fn decode(path: &Path, bytes: &[u8]) -> Result<Image> {
    let fail = |msg: String| Error::Png {
        path: path.to_path_buf(),
        msg,
    };
    // The crate's own limit (64 MiB) would refuse large real images; ours is the memory this
    // process may use, checked again below against the size the header declares.
    let budget = memory::available_bytes().unwrap_or(u64::MAX);
    let limits = png::Limits {
        bytes: usize::try_from(budget).unwrap_or(usize::MAX),
    };
    let mut decoder = png::Decoder::new_with_limits(std::io::Cursor::new(bytes), limits);
    // Expand palettes and low bit depths to 8 bits; keep 16-bit samples.
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| fail("image too large".into()))?;
    // The decoded bytes, then up to four bytes of f32 per byte for the channels.
    memory::check(
        (size as u64).saturating_mul(5),
        Some(budget),
        &format!("decoding {}", path.display()),
    )?;
    let mut buffer = memory::filled(size, 0u8)?;
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
