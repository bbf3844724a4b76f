//! Reads any scanline or tiled OpenEXR file's first part into f32 channels, for the
//! subcommands that work on existing renders (`tonemap`, and the inspection tools).

use std::path::Path;

use exr::prelude::{self as x, ReadChannels as _, ReadLayers as _};
use glam::DVec3;

use crate::error::{Error, Result};

/// One channel of an EXR.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    pub name: String,
    /// `half`, `float` or `uint`, as stored.
    pub pixel_type: &'static str,
    /// Row-major over the data window.
    pub values: Vec<f32>,
}

/// The first part of an EXR file, decoded.
#[derive(Debug, Clone, PartialEq)]
pub struct ExrImage {
    pub width: usize,
    pub height: usize,
    /// Sorted by name, as stored.
    pub channels: Vec<Channel>,
    /// Header attributes as `name = value` text, sorted by name.
    pub attributes: Vec<(String, String)>,
}

impl ExrImage {
    pub fn read(path: &Path) -> Result<Self> {
        let fail = |msg: String| Error::Exr {
            path: path.to_path_buf(),
            msg,
        };
        let image = x::read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
            .map_err(|e| match e {
                x::Error::Io(io) => fail(format!("cannot read: {io}")),
                other => fail(format!("not a readable OpenEXR file ({other})")),
            })?;
        let layer = image.layer_data;
        let channels = layer
            .channel_data
            .list
            .into_iter()
            .map(|c| {
                let (pixel_type, values) = match c.sample_data {
                    x::FlatSamples::F16(v) => ("half", v.iter().map(|h| h.to_f32()).collect()),
                    x::FlatSamples::F32(v) => ("float", v),
                    x::FlatSamples::U32(v) => ("uint", v.iter().map(|&u| u as f32).collect()),
                };
                Channel {
                    name: c.name.to_string(),
                    pixel_type,
                    values,
                }
            })
            .collect();
        let mut attributes: Vec<(String, String)> =
            header_text(&image.attributes, &layer.attributes);
        attributes.sort();
        Ok(ExrImage {
            width: layer.size.0,
            height: layer.size.1,
            channels,
            attributes,
        })
    }

    pub fn channel(&self, name: &str) -> Option<&Channel> {
        self.channels.iter().find(|c| c.name == name)
    }

    /// Layer names that have R, G and B channels; `beauty` stands for the bare `R G B`.
    pub fn colour_layers(&self) -> Vec<String> {
        let mut layers: Vec<String> = self
            .channels
            .iter()
            .filter_map(|c| c.name.strip_suffix('R'))
            .filter(|prefix| {
                self.channel(&format!("{prefix}G")).is_some()
                    && self.channel(&format!("{prefix}B")).is_some()
            })
            .map(|prefix| match prefix.strip_suffix('.') {
                Some(layer) => layer.to_string(),
                None if prefix.is_empty() => "beauty".to_string(),
                None => prefix.to_string(),
            })
            .collect();
        layers.sort();
        layers
    }

    /// The pixels of colour layer `name` (`beauty` for the bare `R G B`), row-major.
    pub fn colour_layer(&self, name: &str) -> std::result::Result<Vec<DVec3>, String> {
        let prefix = if name == "beauty" || name.is_empty() {
            String::new()
        } else {
            format!("{name}.")
        };
        let get = |c: &str| self.channel(&format!("{prefix}{c}"));
        match (get("R"), get("G"), get("B")) {
            (Some(r), Some(g), Some(b)) => Ok(r
                .values
                .iter()
                .zip(&g.values)
                .zip(&b.values)
                .map(|((&r, &g), &b)| DVec3::new(f64::from(r), f64::from(g), f64::from(b)))
                .collect()),
            _ => {
                let exists = self
                    .channels
                    .iter()
                    .any(|c| c.name == name || c.name.starts_with(&format!("{name}.")));
                let what = if exists {
                    format!("layer `{name}` is not a colour layer (it has no R, G, B channels)")
                } else {
                    format!("no layer `{name}` in the file")
                };
                Err(format!(
                    "{what}; colour layers: {}",
                    self.colour_layers().join(", ")
                ))
            }
        }
    }
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
