//! Reading images back: whitted's own EXRs (or anyone's) and PNGs, as named float channels.
//! The format is recognised here, by the file's first bytes, and each reader decodes one.

pub mod attribute;
pub mod exr;
pub mod image;
pub mod raster;

use std::fs::File;
use std::io::Read;
use std::path::Path;

pub use attribute::Attribute;
pub use image::{suffix, Channel, Format, Image, Layer, Window};

use crate::openexr;
use whitted_core::error::{Error, Result};
use whitted_core::memory;

/// How many first bytes tell the formats apart.
const SIGNATURE_BYTES: usize = 10;

/// The format a file's first bytes name, if it is one `read` understands.
fn format_of(head: &[u8]) -> Option<Format> {
    let starts = |magic: &[u8]| head.starts_with(magic);
    if starts(&openexr::MAGIC) {
        Some(Format::Exr)
    } else if starts(b"\x89PNG\r\n\x1a\n") {
        Some(Format::Png)
    } else if starts(&[0xff, 0xd8, 0xff]) {
        Some(Format::Jpeg)
    } else if starts(b"II*\0") || starts(b"MM\0*") {
        Some(Format::Tiff)
    } else if starts(b"#?RADIANCE") || starts(b"#?RGBE") {
        Some(Format::Hdr)
    } else {
        None
    }
}

/// Reads an image file (OpenEXR, PNG, JPEG, TIFF or Radiance HDR), recognised by its first
/// bytes: a file of another kind (or a device such as `/dev/zero`) is refused after ten
/// bytes, and a file larger than the memory this process may use before it is read. The
/// decoders then check the sizes the header declares before allocating for them. For a
/// multi-part OpenEXR file, the first part.
pub fn read(path: &Path) -> Result<Image> {
    read_parts(path)?
        .into_iter()
        .next()
        .ok_or_else(|| Error::Exr {
            path: path.to_path_buf(),
            msg: "the file has no parts".into(),
        })
}

/// Reads every part of an image file (one for everything but multi-part OpenEXR).
pub fn read_parts(path: &Path) -> Result<Vec<Image>> {
    decode(path, read_recognised(path)?)
}

/// Decodes the bytes of an image file; `path` names it in messages.
pub fn decode(path: &Path, bytes: Vec<u8>) -> Result<Vec<Image>> {
    match format_of(&bytes) {
        Some(Format::Exr) => exr::decode(path, bytes),
        Some(format) => Ok(vec![raster::decode(path, &bytes, format)?]),
        None => Err(not_an_image(path)),
    }
}

fn not_an_image(path: &Path) -> Error {
    Error::Usage(format!(
        "{}: not an image whitted reads (OpenEXR, PNG, JPEG, TIFF or Radiance HDR)",
        path.display()
    ))
}

/// The whole file, once its first bytes say it is an image `read` understands.
pub(crate) fn read_recognised(path: &Path) -> Result<Vec<u8>> {
    read_if(
        path,
        |head| format_of(head).is_some(),
        || not_an_image(path),
    )
}

/// The whole file, once its first bytes (up to ten) pass `known`, or `unknown()`'s error
/// after reading no more than those: a device such as `/dev/zero` or a huge file of another
/// kind costs ten bytes, and a file larger than the memory this process may use is refused
/// before it is read.
pub fn read_if(
    path: &Path,
    known: impl Fn(&[u8]) -> bool,
    unknown: impl Fn() -> Error,
) -> Result<Vec<u8>> {
    let cannot = |e| Error::io(path, "cannot read", e);
    let mut file = File::open(path).map_err(cannot)?;
    let metadata = file.metadata().map_err(cannot)?;
    if metadata.is_dir() {
        return Err(cannot(std::io::Error::other("it is a directory")));
    }
    let mut head = Vec::with_capacity(SIGNATURE_BYTES);
    (&mut file)
        .take(SIGNATURE_BYTES as u64)
        .read_to_end(&mut head)
        .map_err(cannot)?;
    if !known(&head) {
        return Err(unknown());
    }
    // A regular file says how long it is; a pipe or device is read up to what memory allows.
    let budget = memory::available_bytes().unwrap_or(u64::MAX);
    if metadata.is_file() {
        memory::check(
            metadata.len(),
            Some(budget),
            &format!("reading {}", path.display()),
        )?;
    }
    let mut bytes = head;
    file.take(budget.saturating_sub(bytes.len() as u64).saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > budget {
        return Err(Error::Allocation {
            what: format!("reading {}", path.display()),
            bytes: bytes.len() as u64,
        });
    }
    Ok(bytes)
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
