//! Reassembling EXRs rendered with `--region` (on one machine or many) into the full frame,
//! byte-identical to rendering it in one go.
//!
//! Parts must agree on the display window, the channels and their pixel types, and together
//! cover every pixel exactly once. The header is the first part's, with the data window set
//! to the whole frame; since a region render records the same header as a full render (the
//! region is not part of the recorded command), the merged file equals the full render's.

use std::path::PathBuf;

use exr::prelude as x;

use crate::openexr::{self, FlatImage};
use whitted_core::error::{Error, Result};
use whitted_core::memory;

/// Places every part's pixels into one full-frame image, after checking that the parts fit
/// together.
pub fn merge(parts: &[FlatImage], names: &[PathBuf]) -> Result<FlatImage> {
    check_parts(parts, names)?;
    assemble(parts)
}

/// The parts share the first part's display window, channels and pixel types, lie inside the
/// frame, and cover every pixel exactly once.
fn check_parts(parts: &[FlatImage], names: &[PathBuf]) -> Result<()> {
    let usage = |msg: String| Error::Usage(msg);
    let Some(first) = parts.first() else {
        return Err(usage("there are no parts to merge".into()));
    };
    let display = first.attributes.display_window;
    let (width, height) = (display.size.0, display.size.1);
    let signature = |p: &FlatImage| -> Vec<(String, &'static str)> {
        p.layer_data
            .channel_data
            .list
            .iter()
            .map(|c| (openexr::text(&c.name), openexr::pixel_type(&c.sample_data)))
            .collect()
    };
    let channels = signature(first);
    // The frame's size comes from a header: check it fits before allocating for it (a map of
    // which part covers each pixel, then the merged channels).
    let per_pixel = std::mem::size_of::<Option<usize>>() as u64 + 4 * channels.len() as u64;
    memory::check(
        (width as u64)
            .saturating_mul(height as u64)
            .saturating_mul(per_pixel),
        memory::available_bytes(),
        &format!("a merged {width}x{height} frame"),
    )?;
    let mut covered = memory::filled(width * height, None::<usize>)?;
    for (i, part) in parts.iter().enumerate() {
        let name = names[i].display();
        if part.attributes.display_window != display {
            return Err(usage(format!(
                "{name}: its display window differs from the first part's"
            )));
        }
        if let Some(difference) = render_difference(first, part) {
            return Err(usage(format!(
                "{name}: not a part of the same render as {} ({difference})",
                names[0].display()
            )));
        }
        if signature(part) != channels {
            return Err(usage(format!(
                "{name}: its channels or pixel types differ from the first part's"
            )));
        }
        let position = part.layer_data.attributes.layer_position;
        let size = part.layer_data.size;
        let (x0, y0) = (
            position.0 - display.position.0,
            position.1 - display.position.1,
        );
        if x0 < 0 || y0 < 0 || x0 as usize + size.0 > width || y0 as usize + size.1 > height {
            return Err(usage(format!(
                "{name}: its data window lies outside the frame"
            )));
        }
        for y in y0 as usize..y0 as usize + size.1 {
            for x in x0 as usize..x0 as usize + size.0 {
                if let Some(other) = covered[y * width + x].replace(i) {
                    return Err(usage(format!(
                        "{name} and {} both cover pixel ({x}, {y})",
                        names[other].display()
                    )));
                }
            }
        }
    }
    if let Some(gap) = covered.iter().position(Option::is_none) {
        return Err(usage(format!(
            "no part covers pixel ({}, {}); the parts must tile the whole {width}x{height} frame",
            gap % width,
            gap / width
        )));
    }
    Ok(())
}

/// Copies every part's rows into a full-frame image with the first part's header.
fn assemble(parts: &[FlatImage]) -> Result<FlatImage> {
    let usage = |msg: String| Error::Usage(msg);
    let Some(first) = parts.first() else {
        return Err(usage("there are no parts to merge".into()));
    };
    let display = first.attributes.display_window;
    let (width, height) = (display.size.0, display.size.1);
    let mut list = x::SmallVec::new();
    for (c, channel) in first.layer_data.channel_data.list.iter().enumerate() {
        let mut samples = match &channel.sample_data {
            x::FlatSamples::F16(_) => x::FlatSamples::F16(vec![x::f16::ZERO; width * height]),
            x::FlatSamples::F32(_) => x::FlatSamples::F32(vec![0.0; width * height]),
            x::FlatSamples::U32(_) => x::FlatSamples::U32(vec![0; width * height]),
        };
        for part in parts {
            let position = part.layer_data.attributes.layer_position;
            let (x0, y0) = (
                (position.0 - display.position.0) as usize,
                (position.1 - display.position.1) as usize,
            );
            let w = part.layer_data.size.0;
            let source = &part.layer_data.channel_data.list[c].sample_data;
            for row in 0..part.layer_data.size.1 {
                let (from, to) = (row * w, (y0 + row) * width + x0);
                match (&mut samples, source) {
                    (x::FlatSamples::F16(d), x::FlatSamples::F16(s)) => {
                        d[to..to + w].copy_from_slice(&s[from..from + w])
                    }
                    (x::FlatSamples::F32(d), x::FlatSamples::F32(s)) => {
                        d[to..to + w].copy_from_slice(&s[from..from + w])
                    }
                    (x::FlatSamples::U32(d), x::FlatSamples::U32(s)) => {
                        d[to..to + w].copy_from_slice(&s[from..from + w])
                    }
                    _ => return Err(usage("pixel types differ between parts".into())),
                }
            }
        }
        let mut merged = channel.clone();
        merged.sample_data = samples;
        list.push(merged);
    }
    let mut attributes = first.layer_data.attributes.clone();
    attributes.layer_position = display.position;
    let layer = x::Layer::new(
        (width, height),
        attributes,
        first.layer_data.encoding,
        x::AnyChannels::sort(list),
    );
    Ok(x::Image::new(first.attributes.clone(), layer))
}

/// How `part` was rendered differently from `first`, from the render identity whitted
/// records in every EXR (`render/identity`, `render/scene` and the recorded command), or
/// `None` when they are parts of one render. Files without an identity (from elsewhere) are
/// only compared by their display window and channels.
fn render_difference(first: &FlatImage, part: &FlatImage) -> Option<String> {
    let identity = |p: &FlatImage| text_attribute(p, "render/identity");
    match (identity(first), identity(part)) {
        (None, None) => return None,
        (Some(a), Some(b)) if a == b => return None,
        (Some(_), None) | (None, Some(_)) => {
            return Some("only one of them records a whitted render identity".into())
        }
        _ => {}
    }
    if text_attribute(first, "render/scene") != text_attribute(part, "render/scene") {
        return Some("rendered from a different scene file".into());
    }
    let options = |p: &FlatImage| -> Vec<String> {
        let comments = p.layer_data.attributes.comments.as_ref();
        let text = comments.map(openexr::text).unwrap_or_default();
        let command = text.split_once("command: ").map_or("", |(_, c)| c);
        // The scene is compared by content above, not by the path it was read from.
        command
            .split(" --")
            .skip(1)
            .map(|o| format!("--{o}"))
            .filter(|o| !o.starts_with("--input "))
            .collect()
    };
    let (a, b) = (options(first), options(part));
    let name = |o: &str| o.split(' ').next().unwrap_or_default().to_string();
    let names: Vec<String> = a.iter().chain(&b).map(|o| name(o)).collect();
    for option in names {
        let value = |list: &[String]| {
            list.iter()
                .find(|o| name(o) == option)
                .cloned()
                .unwrap_or_else(|| format!("no {option}"))
        };
        let (x, y) = (value(&a), value(&b));
        if x != y {
            return Some(format!("`{y}` where the first part has `{x}`"));
        }
    }
    Some("their render identities differ".into())
}

/// A text attribute of a part's header.
fn text_attribute(part: &FlatImage, name: &str) -> Option<String> {
    part.layer_data
        .attributes
        .other
        .iter()
        .chain(part.attributes.other.iter())
        .find(|(key, _)| **key == *name)
        .and_then(|(_, value)| match value {
            x::AttributeValue::Text(t) => Some(openexr::text(t)),
            _ => None,
        })
}

#[cfg(test)]
mod tests {
    #[test]
    fn no_parts_is_an_error_not_a_panic() {
        let err = super::merge(&[], &[]).expect_err("nothing to merge");
        assert!(err.to_string().contains("no parts"), "{err}");
    }
}
