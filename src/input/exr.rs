//! OpenEXR -> `Image`: any scanline or tiled file's first part, as f32 channels and header
//! attributes as text.

use std::path::Path;

use exr::prelude as x;

use crate::error::{Error, Result};
use crate::input::image::{Channel, Format, Image};
use crate::memory;
use crate::openexr::{self, FlatImage};

/// Reads the first part of the OpenEXR file at `path` as the `exr` crate's flat image (what
/// `merge` works on), with the same checks as `input::read`.
pub fn read_flat(path: &Path) -> Result<FlatImage> {
    let bytes = crate::input::read_recognised(path)?;
    if !bytes.starts_with(&openexr::MAGIC) {
        return Err(Error::Usage(format!(
            "{}: not an OpenEXR file (this command reads EXRs)",
            path.display()
        )));
    }
    decode_flat(path, bytes)
}

/// Decodes the first part after checking, from the header alone, that the pixels it declares
/// fit in the memory this process may use: a tiny file declaring 100000x100000 floats is an
/// error with numbers, not an abort.
fn decode_flat(path: &Path, bytes: Vec<u8>) -> Result<FlatImage> {
    let unreadable = |e: x::Error| Error::Exr {
        path: path.to_path_buf(),
        msg: format!("not a readable OpenEXR file ({e})"),
    };
    let meta =
        exr::meta::MetaData::read_from_buffered(bytes.as_slice(), false).map_err(unreadable)?;
    let needed = openexr::decoded_bytes(&meta).saturating_add(bytes.len() as u64);
    memory::check(
        needed,
        memory::available_bytes(),
        &format!("decoding {}", path.display()),
    )?;
    openexr::read_first_part(std::io::Cursor::new(bytes)).map_err(unreadable)
}

/// Decodes the first part of an OpenEXR file (scanline or tiled, any pixel types).
pub fn decode(path: &Path, bytes: Vec<u8>) -> Result<Image> {
    let image = decode_flat(path, bytes)?;
    let layer = image.layer_data;
    let channels = layer
        .channel_data
        .list
        .into_iter()
        .map(|c| {
            let pixel_type = openexr::pixel_type(&c.sample_data);
            let values = match c.sample_data {
                x::FlatSamples::F16(v) => v.iter().map(|h| h.to_f32()).collect(),
                x::FlatSamples::F32(v) => v,
                x::FlatSamples::U32(v) => v.iter().map(|&u| u as f32).collect(),
            };
            Channel {
                name: c.name.to_string(),
                pixel_type,
                values,
            }
        })
        .collect();
    let mut attributes = header_text(&image.attributes, &layer.attributes);
    let (x, y) = (
        layer.attributes.layer_position.0,
        layer.attributes.layer_position.1,
    );
    attributes.push((
        "dataWindow".into(),
        format!(
            "({x}, {y}) - ({}, {})",
            x + layer.size.0 as i32 - 1,
            y + layer.size.1 as i32 - 1
        ),
    ));
    attributes.sort();
    Ok(Image {
        format: Format::Exr,
        width: layer.size.0,
        height: layer.size.1,
        channels,
        attributes,
    })
}

/// Every header attribute of interest as readable text.
fn header_text(image: &x::ImageAttributes, layer: &x::LayerAttributes) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut put = |name: &str, value: String| out.push((name.to_string(), value));
    let w = &image.display_window;
    put(
        "displayWindow",
        format!(
            "({}, {}) - ({}, {})",
            w.position.0,
            w.position.1,
            w.position.0 + w.size.0 as i32 - 1,
            w.position.1 + w.size.1 as i32 - 1
        ),
    );
    if let Some(c) = &image.chromaticities {
        put(
            "chromaticities",
            format!(
                "red ({}, {}), green ({}, {}), blue ({}, {}), white ({}, {})",
                c.red.0, c.red.1, c.green.0, c.green.1, c.blue.0, c.blue.1, c.white.0, c.white.1
            ),
        );
    }
    let texts = [
        ("software", &layer.software_name),
        ("comments", &layer.comments),
        ("capDate", &layer.capture_date),
        ("owner", &layer.owner),
        ("name", &layer.layer_name),
    ];
    for (name, value) in texts {
        if let Some(v) = value {
            put(name, v.to_string());
        }
    }
    for (name, matrix) in [
        ("worldToCamera", &layer.world_to_camera),
        ("worldToNDC", &layer.world_to_normalized_device),
    ] {
        if let Some(m) = matrix {
            put(name, format!("{m:?}"));
        }
    }
    for (name, value) in image.other.iter().chain(layer.other.iter()) {
        let text = match value {
            x::AttributeValue::Text(t) => t.to_string(),
            x::AttributeValue::I32(i) => i.to_string(),
            x::AttributeValue::F32(f) => f.to_string(),
            x::AttributeValue::F64(f) => f.to_string(),
            other => format!("{other:?}"),
        };
        put(&name.to_string(), text);
    }
    out
}
