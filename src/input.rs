//! Reading images back: whitted's own EXRs (or anyone's) and PNGs, as named float channels.
//! The format is recognised here, by the file's first bytes, and each reader decodes one.

pub mod exr;
pub mod image;
pub mod png;

use std::fs::File;
use std::io::Read;
use std::path::Path;

pub use image::{suffix, Channel, Format, Image, Layer};

use crate::error::{Error, Result};
use crate::memory;
use crate::openexr;

/// The first bytes of every PNG file.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// Reads an OpenEXR or PNG file, recognised by its first bytes: a file of another kind (or a
/// device such as `/dev/zero`) is refused after eight bytes, and a file larger than the memory
/// this process may use is refused before it is read. The decoders then check the sizes the
/// header declares before allocating for them.
pub fn read(path: &Path) -> Result<Image> {
    decode(path, read_recognised(path)?)
}

/// Decodes the bytes of an OpenEXR or PNG file; `path` names it in messages.
pub fn decode(path: &Path, bytes: Vec<u8>) -> Result<Image> {
    if bytes.starts_with(&openexr::MAGIC) {
        exr::decode(path, bytes)
    } else if bytes.starts_with(PNG_SIGNATURE) {
        png::decode(path, &bytes)
    } else {
        Err(not_an_image(path))
    }
}

fn not_an_image(path: &Path) -> Error {
    Error::Usage(format!("{}: not an OpenEXR or PNG file", path.display()))
}

/// The whole file, once its first bytes say it is an OpenEXR or a PNG file.
pub(crate) fn read_recognised(path: &Path) -> Result<Vec<u8>> {
    let cannot = |e| Error::io(path, "cannot read", e);
    let mut file = File::open(path).map_err(cannot)?;
    let metadata = file.metadata().map_err(cannot)?;
    if metadata.is_dir() {
        return Err(cannot(std::io::Error::other("it is a directory")));
    }
    let mut head = Vec::with_capacity(PNG_SIGNATURE.len());
    (&mut file)
        .take(PNG_SIGNATURE.len() as u64)
        .read_to_end(&mut head)
        .map_err(cannot)?;
    if !head.starts_with(&openexr::MAGIC) && !head.starts_with(PNG_SIGNATURE) {
        return Err(not_an_image(path));
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
