//! Reading the image a student's program wrote: an 8-bit RGB(A) PNG, checked (signature,
//! header, size, memory) before a single pixel is decoded, since it comes from a program that
//! may be wrong in any way.

use std::path::Path;

use whitted_core::error::{Error, Result};
use whitted_core::frame::limits::MAX_SIDE;
use whitted_core::memory;

/// An 8-bit RGB image, three bytes a pixel, row-major, top row first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rgb8 {
    pub width: u32,
    pub height: u32,
    pub bytes: Vec<u8>,
}

impl Rgb8 {
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.bytes[i], self.bytes[i + 1], self.bytes[i + 2]]
    }
}

const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];
const JPEG_SIGNATURE: [u8; 3] = [0xff, 0xd8, 0xff];

/// Reads `path` as the tick PNG. Refuses, with one clear message: a JPEG (lossy, so no byte
/// can be trusted), anything that is not a PNG, a PNG that is not 8-bit RGB or RGBA, and a size
/// no render can have.
pub fn read(path: &Path) -> Result<Rgb8> {
    let bytes = png_bytes(path)?;
    decode(&bytes).map_err(|msg| fail(path, msg))
}

/// Reads `path` as the tick PNG of `width` x `height`: an image of another size is its size,
/// found in its header without decoding a pixel (a program's 30000x30000 PNG costs nothing).
pub fn read_expecting(
    path: &Path,
    width: u32,
    height: u32,
) -> Result<std::result::Result<Rgb8, (u32, u32)>> {
    let bytes = png_bytes(path)?;
    let size = header_size(&bytes).map_err(|msg| fail(path, msg))?;
    if size != (width, height) {
        return Ok(Err(size));
    }
    decode(&bytes).map(Ok).map_err(|msg| fail(path, msg))
}

fn fail(path: &Path, msg: String) -> Error {
    Error::Raster {
        path: path.to_path_buf(),
        msg,
    }
}

/// The size a PNG's header gives, nothing decoded: the IHDR chunk, which the format puts
/// first, right after the signature. Read here rather than through the decoder, which reads on
/// to the first image data before it reports the header (a header alone is then "truncated").
fn header_size(bytes: &[u8]) -> Result<(u32, u32), String> {
    let field = |at: usize| {
        bytes
            .get(at..at + 4)
            .and_then(|b| <[u8; 4]>::try_from(b).ok())
            .map(u32::from_be_bytes)
    };
    match (bytes.get(12..16), field(16), field(20)) {
        (Some(b"IHDR"), Some(width), Some(height)) => Ok((width, height)),
        _ => Err("is not a readable PNG: it does not start with its IHDR header".into()),
    }
}

/// The bytes of `path` when it is a PNG; a JPEG and anything else are refused.
fn png_bytes(path: &Path) -> Result<Vec<u8>> {
    let fail = |msg: String| fail(path, msg);
    // A pipe would block the open until a writer comes, a device never ends: neither is a
    // program's PNG.
    let metadata = std::fs::metadata(path).map_err(|e| Error::io(path, "cannot read", e))?;
    if !metadata.is_file() {
        return Err(fail(
            "is not a regular file (a directory, device, pipe or socket)".into(),
        ));
    }
    let signature =
        |head: &[u8]| head.starts_with(&PNG_SIGNATURE) || head.starts_with(&JPEG_SIGNATURE);
    let bytes = whitted_io::input::read_if(path, signature, || {
        fail("is not a PNG (no PNG signature)".into())
    })?;
    if bytes.starts_with(&JPEG_SIGNATURE) {
        return Err(fail(
            "is a JPEG: its compression is lossy, so its bytes cannot be compared with the \
             reference; check the PNG your program wrote"
                .into(),
        ));
    }
    if !bytes.starts_with(&PNG_SIGNATURE) {
        return Err(fail("is not a PNG (no PNG signature)".into()));
    }
    Ok(bytes)
}

/// Decodes PNG bytes after checking the header; the message says what is wrong.
pub fn decode(bytes: &[u8]) -> Result<Rgb8, String> {
    let budget = memory::available_bytes().unwrap_or(u64::MAX);
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_limits(png::Limits {
        bytes: usize::try_from(budget).unwrap_or(usize::MAX),
    });
    let mut reader = decoder
        .read_info()
        .map_err(|e| format!("is not a readable PNG: {e}"))?;
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(format!(
            "is {width}x{height}: no render has that size (1 to {MAX_SIDE} pixels a side)"
        ));
    }
    let channels = match (info.color_type, info.bit_depth) {
        (png::ColorType::Rgb, png::BitDepth::Eight) => 3,
        (png::ColorType::Rgba, png::BitDepth::Eight) => 4,
        (colour, depth) => {
            return Err(format!(
                "is a {colour:?} PNG of {} bits per sample; the tick image is 8-bit RGB",
                depth as u8
            ))
        }
    };
    let size = u64::from(width) * u64::from(height) * channels;
    memory::check(size.saturating_mul(2), Some(budget), "decoding the PNG")
        .map_err(|e| e.to_string())?;
    let mut data = vec![
        0;
        reader
            .output_buffer_size()
            .ok_or("is too large to decode")?
    ];
    let frame = reader
        .next_frame(&mut data)
        .map_err(|e| format!("is not a readable PNG: {e}"))?;
    data.truncate(frame.buffer_size());
    let bytes = if channels == 4 {
        data.chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect()
    } else {
        data
    };
    Ok(Rgb8 {
        width,
        height,
        bytes,
    })
}
