//! Tick 1*'s bump maps read as the course reads them (`ImageIO.read`, then the blue byte of
//! `getRGB`), through the same reader, memory checks and size limits as every image input.

use std::path::Path;

use whitted_core::error::{Error, Result};
use whitted_core::star::BumpMap;

use crate::input::{self, Format};

/// Reads the bump map at `path` for the `<bumpy-sphere>` at `at` (`file:line:col`): any
/// failure is one message naming both.
pub fn read(path: &Path, at: &str) -> Result<BumpMap> {
    let fail = |why: String| Error::Usage(format!("{at}: bump map {}: {why}", path.display()));
    let image = input::read(path).map_err(|e| fail(e.to_string()))?;
    if image.format == Format::Exr {
        return Err(fail("an OpenEXR file, not an 8-bit image (PNG)".into()));
    }
    let channel = |names: &[&str]| {
        names
            .iter()
            .find_map(|n| image.channel(n))
            .map(|c| c.values.as_slice())
    };
    let (Some(r), Some(g), Some(b)) = (
        channel(&["R", "Y"]),
        channel(&["G", "Y"]),
        channel(&["B", "Y"]),
    ) else {
        return Err(fail("has no colour or grey channels".into()));
    };
    // `getRGB` gives 8 bits a channel whatever the file holds.
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let rgb: Vec<[u8; 3]> = r
        .iter()
        .zip(g)
        .zip(b)
        .map(|((&r, &g), &b)| [byte(r), byte(g), byte(b)])
        .collect();
    BumpMap::from_rgb8(image.width, image.height, &rgb)
        .ok_or_else(|| fail(format!("an empty image ({}x{})", image.width, image.height)))
}
