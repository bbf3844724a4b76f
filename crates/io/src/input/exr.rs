//! OpenEXR -> `Image`s: every part of a scanline or tiled file, as f32 channels, with its
//! windows and typed header attributes.

use std::path::Path;

use exr::prelude as x;

use crate::input::attribute::Attribute;
use crate::input::image::{Channel, Format, Image, Window};
use crate::openexr::{self, FlatImage};
use whitted_core::error::{Error, Result};
use whitted_core::memory;

/// Reads the single-part OpenEXR file at `path` as the `exr` crate's flat image (what `merge`
/// works on), with the same checks as `input::read`; a multi-part file is refused.
pub fn read_flat(path: &Path) -> Result<FlatImage> {
    let bytes = crate::input::read_recognised(path)?;
    if !bytes.starts_with(&openexr::MAGIC) {
        return Err(Error::Usage(format!(
            "{}: not an OpenEXR file (this command reads EXRs)",
            path.display()
        )));
    }
    let parts = check_memory(path, &bytes)?;
    if parts > 1 {
        // Its other parts would be dropped without a word.
        return Err(Error::Usage(format!(
            "{}: has {parts} parts; this command reads single-part EXRs (as `whitted render` writes)",
            path.display()
        )));
    }
    openexr::read_first_part(std::io::Cursor::new(bytes)).map_err(|e| unreadable(path, e))
}

/// Decodes every part of an OpenEXR file (scanline or tiled, any pixel types).
pub fn decode(path: &Path, bytes: Vec<u8>) -> Result<Vec<Image>> {
    check_memory(path, &bytes)?;
    let image =
        openexr::read_all_parts(std::io::Cursor::new(bytes)).map_err(|e| unreadable(path, e))?;
    let display = &image.attributes.display_window;
    let display_window = Window::at(
        [i64::from(display.position.0), i64::from(display.position.1)],
        display.size.0,
        display.size.1,
    );
    let shared = shared_attributes(&image.attributes);
    let parts = image
        .layer_data
        .into_iter()
        .map(|layer| part(layer, display_window, &shared))
        .collect();
    Ok(parts)
}

/// Checks, from the headers alone, that the pixels they declare fit in the memory this process
/// may use: a tiny file declaring 100000x100000 floats is an error with numbers, not an abort.
/// Checks that decoding the file fits in memory; returns its number of parts.
fn check_memory(path: &Path, bytes: &[u8]) -> Result<usize> {
    let meta =
        exr::meta::MetaData::read_from_buffered(bytes, false).map_err(|e| unreadable(path, e))?;
    memory::check(
        openexr::decoded_bytes(&meta).saturating_add(bytes.len() as u64),
        memory::available_bytes(),
        &format!("decoding {}", path.display()),
    )?;
    Ok(meta.headers.len())
}

fn unreadable(path: &Path, e: x::Error) -> Error {
    Error::Exr {
        path: path.to_path_buf(),
        msg: format!("not a readable OpenEXR file ({e})"),
    }
}

/// One part as an `Image`.
fn part(
    layer: x::Layer<x::AnyChannels<x::FlatSamples>>,
    display_window: Window,
    shared: &[(String, Attribute)],
) -> Image {
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
                name: openexr::text(&c.name),
                pixel_type,
                values,
            }
        })
        .collect();
    let position = layer.attributes.layer_position;
    let data_window = Window::at(
        [i64::from(position.0), i64::from(position.1)],
        layer.size.0,
        layer.size.1,
    );
    let mut attributes = shared.to_vec();
    attributes.extend(part_attributes(&layer.attributes));
    for (name, window) in [
        ("dataWindow", data_window),
        ("displayWindow", display_window),
    ] {
        attributes.push((
            name.into(),
            Attribute::Box {
                min: window.min,
                max: window.max,
            },
        ));
    }
    attributes.sort_by(|a, b| a.0.cmp(&b.0));
    Image {
        format: Format::Exr,
        part: layer.attributes.layer_name.as_ref().map(openexr::text),
        width: layer.size.0,
        height: layer.size.1,
        data_window,
        display_window,
        channels,
        attributes,
    }
}

/// The attributes every part shares (chromaticities and anything the crate does not name).
fn shared_attributes(image: &x::ImageAttributes) -> Vec<(String, Attribute)> {
    let mut out = Vec::new();
    if let Some(c) = &image.chromaticities {
        let pair = |v: x::Vec2<f32>| [f64::from(v.0), f64::from(v.1)];
        out.push((
            "chromaticities".into(),
            Attribute::Chromaticities {
                red: pair(c.red),
                green: pair(c.green),
                blue: pair(c.blue),
                white: pair(c.white),
            },
        ));
    }
    out.extend(
        image
            .other
            .iter()
            .map(|(name, value)| (openexr::text(name), typed(value))),
    );
    out
}

/// One part's own attributes.
fn part_attributes(layer: &x::LayerAttributes) -> Vec<(String, Attribute)> {
    let mut out = Vec::new();
    let texts = [
        ("software", &layer.software_name),
        ("comments", &layer.comments),
        ("capDate", &layer.capture_date),
        ("owner", &layer.owner),
        ("name", &layer.layer_name),
    ];
    for (name, value) in texts {
        if let Some(v) = value {
            out.push((name.to_string(), Attribute::Text(openexr::text(v))));
        }
    }
    for (name, matrix) in [
        ("worldToCamera", &layer.world_to_camera),
        ("worldToNDC", &layer.world_to_normalized_device),
    ] {
        if let Some(m) = matrix {
            out.push((name.to_string(), Attribute::matrix(m)));
        }
    }
    out.extend(
        layer
            .other
            .iter()
            .map(|(name, value)| (openexr::text(name), typed(value))),
    );
    out
}

/// An attribute value the crate keeps generically, typed.
fn typed(value: &x::AttributeValue) -> Attribute {
    match value {
        x::AttributeValue::Text(t) => Attribute::Text(openexr::text(t)),
        x::AttributeValue::I32(i) => Attribute::Integer(i64::from(*i)),
        x::AttributeValue::F32(f) => Attribute::Number(f64::from(*f)),
        x::AttributeValue::F64(f) => Attribute::Number(*f),
        x::AttributeValue::IntegerBounds(b) => {
            let window = Window::at(
                [i64::from(b.position.0), i64::from(b.position.1)],
                b.size.0,
                b.size.1,
            );
            Attribute::Box {
                min: window.min,
                max: window.max,
            }
        }
        x::AttributeValue::FloatVec2(v) => Attribute::Vector(vec![f64::from(v.0), f64::from(v.1)]),
        x::AttributeValue::FloatVec3(v) => {
            Attribute::Vector(vec![f64::from(v.0), f64::from(v.1), f64::from(v.2)])
        }
        x::AttributeValue::IntVec2(v) => Attribute::Vector(vec![f64::from(v.0), f64::from(v.1)]),
        x::AttributeValue::Matrix3x3(m) => Attribute::matrix(m),
        x::AttributeValue::Matrix4x4(m) => Attribute::matrix(m),
        other => Attribute::Other(format!("{other:?}")),
    }
}
