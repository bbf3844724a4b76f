//! Reading images back: whitted's own EXRs (or anyone's) and PNGs, as named float channels.
//! The format is recognised here, by the file's first bytes, and each reader decodes one.

pub mod exr;
pub mod image;
pub mod png;

use std::path::Path;

pub use image::{suffix, Channel, Format, Image, Layer};

use crate::error::{Error, Result};
use crate::openexr;

/// The first bytes of every PNG file.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// Reads an OpenEXR or PNG file, recognised by its first bytes.
pub fn read(path: &Path) -> Result<Image> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, "cannot read", e))?;
    if bytes.starts_with(&openexr::MAGIC) {
        exr::decode(path, bytes)
    } else if bytes.starts_with(PNG_SIGNATURE) {
        png::decode(path, &bytes)
    } else {
        Err(Error::Usage(format!(
            "{}: not an OpenEXR or PNG file",
            path.display()
        )))
    }
}

/// Reads an OpenEXR file; anything else is an error.
pub fn read_exr(path: &Path) -> Result<Image> {
    let image = read(path)?;
    if image.format != Format::Exr {
        return Err(Error::Usage(format!(
            "{}: not an OpenEXR file (this command reads EXRs)",
            path.display()
        )));
    }
    Ok(image)
}
