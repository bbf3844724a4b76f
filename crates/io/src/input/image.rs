//! An image as named float channels grouped into layers: the common form in which `tonemap`,
//! `info`, `diff` and `sheet` see EXRs, PNGs, JPEGs, TIFFs and Radiance HDRs.

use std::collections::HashMap;

use glam::DVec3;

use crate::input::attribute::Attribute;
use crate::output::exr::COURSE_ATTRIBUTE;
use whitted_core::aov;
use whitted_core::course::Course;

/// One channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Full name: `R`, `Z`, `direct.G`, ...
    pub name: String,
    /// As stored: `half`, `float`, `uint` (EXR), `uint8`, `uint16` (PNG, JPEG, TIFF) or
    /// `float` (HDR, float TIFF).
    pub pixel_type: &'static str,
    /// Row-major over the data window. Integer samples are scaled to [0, 1].
    pub values: Vec<f32>,
}

/// A group of channels sharing a layer name (`direct` for `direct.R/G/B`), with the bare
/// beauty channels `R G B A` called `beauty`.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    pub name: String,
    /// Indices into `Image::channels`, in display order (R G B A, X Y Z, then the rest).
    pub channels: Vec<usize>,
}

/// The file formats `input::read` understands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// OpenEXR: linear, scene-referred, any channels (read with the `exr` crate).
    Exr,
    /// Display-referred rasters read with the `image` crate.
    Png,
    Jpeg,
    Tiff,
    /// Radiance RGBE: linear floats.
    Hdr,
}

/// A rectangle of pixel coordinates, both corners inclusive (as OpenEXR states windows).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window {
    pub min: [i64; 2],
    pub max: [i64; 2],
}

impl Window {
    /// The window of a `width` x `height` image whose top-left pixel is `origin`.
    pub fn at(origin: [i64; 2], width: usize, height: usize) -> Self {
        Window {
            min: origin,
            max: [origin[0] + width as i64 - 1, origin[1] + height as i64 - 1],
        }
    }
}

impl std::fmt::Display for Window {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "({}, {}) - ({}, {})",
            self.min[0], self.min[1], self.max[0], self.max[1]
        )
    }
}

/// One decoded image (one part of a multi-part OpenEXR file).
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub format: Format,
    /// The part's name in a multi-part OpenEXR file.
    pub part: Option<String>,
    pub width: usize,
    pub height: usize,
    /// Where the pixels are: `width` x `height` from `data_window.min`.
    pub data_window: Window,
    /// The frame they belong to (the same as the data window for whole images).
    pub display_window: Window,
    pub channels: Vec<Channel>,
    /// Header attributes, sorted by name (empty for raster formats).
    pub attributes: Vec<(String, Attribute)>,
}

impl Image {
    /// Everything but the pixels: the same image with no channels.
    pub fn clone_header(&self) -> Image {
        Image {
            format: self.format,
            part: self.part.clone(),
            width: self.width,
            height: self.height,
            data_window: self.data_window,
            display_window: self.display_window,
            channels: Vec::new(),
            attributes: self.attributes.clone(),
        }
    }

    pub fn channel(&self, name: &str) -> Option<&Channel> {
        self.channels.iter().find(|c| c.name == name)
    }

    pub fn attribute(&self, name: &str) -> Option<&Attribute> {
        self.attributes
            .iter()
            .find_map(|(n, a)| (n == name).then_some(a))
    }

    /// The course year a whitted EXR was rendered under (`render/course`; none recorded is
    /// the default 2016-17). A year this version does not know is an error naming the file
    /// read from `path`.
    pub fn course(&self, path: &std::path::Path) -> whitted_core::Result<Course> {
        let unknown = |msg: String| whitted_core::Error::Exr {
            path: path.to_path_buf(),
            msg,
        };
        match self.attribute(COURSE_ATTRIBUTE) {
            None => Ok(Course::default()),
            Some(Attribute::Text(name)) => Course::from_name(name).ok_or_else(|| {
                unknown(format!(
                    "its {COURSE_ATTRIBUTE} is '{name}', which is none of {}",
                    Course::names()
                ))
            }),
            Some(other) => Err(unknown(format!(
                "its {COURSE_ATTRIBUTE} is not text: {other}"
            ))),
        }
    }

    /// The channels grouped into layers, in name order with `beauty` first.
    pub fn layers(&self) -> Vec<Layer> {
        // Indexed by name, so that files with many channels take linear time.
        let mut layers: Vec<Layer> = Vec::new();
        let mut index: HashMap<&str, usize> = HashMap::new();
        for (i, channel) in self.channels.iter().enumerate() {
            let name = aov::layer_of_channel(&channel.name);
            match index.get(name) {
                Some(&l) => layers[l].channels.push(i),
                None => {
                    index.insert(name, layers.len());
                    layers.push(Layer {
                        name: name.to_string(),
                        channels: vec![i],
                    });
                }
            }
        }
        for layer in &mut layers {
            layer.channels.sort_by_key(|&i| {
                (
                    suffix_rank(&self.channels[i].name),
                    self.channels[i].name.clone(),
                )
            });
        }
        layers.sort_by_key(|l| (l.name != "beauty", l.name.clone()));
        layers
    }

    /// Names of the layers that have R, G and B channels.
    pub fn colour_layers(&self) -> Vec<String> {
        self.layers()
            .into_iter()
            .filter(|l| self.is_colour(l))
            .map(|l| l.name)
            .collect()
    }

    /// The layer's channels that statistics are taken over: R, G, B for a colour layer (alpha
    /// is not colour), every channel otherwise.
    pub fn statistics_channels(&self, layer: &Layer) -> Vec<usize> {
        if !self.is_colour(layer) {
            return layer.channels.clone();
        }
        layer
            .channels
            .iter()
            .copied()
            .filter(|&i| ["R", "G", "B"].contains(&suffix(&self.channels[i].name)))
            .collect()
    }

    /// Whether `layer` has R, G and B channels.
    pub fn is_colour(&self, layer: &Layer) -> bool {
        ["R", "G", "B"].iter().all(|c| {
            layer
                .channels
                .iter()
                .any(|&i| suffix(&self.channels[i].name) == *c)
        })
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
                let what = if self.layers().iter().any(|l| l.name == name) {
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

/// `direct.R` -> `R`; bare names are their own suffix.
pub fn suffix(channel: &str) -> &str {
    channel.rsplit_once('.').map_or(channel, |(_, s)| s)
}

fn suffix_rank(channel: &str) -> usize {
    ["R", "G", "B", "A", "X", "Y", "Z"]
        .iter()
        .position(|s| *s == suffix(channel))
        .unwrap_or(7)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel(name: &str) -> Channel {
        Channel {
            name: name.into(),
            pixel_type: "float",
            values: vec![0.0],
        }
    }

    #[test]
    fn channels_group_into_layers_in_display_order() {
        let image = Image {
            format: Format::Exr,
            part: None,
            width: 1,
            height: 1,
            data_window: Window::at([0, 0], 1, 1),
            display_window: Window::at([0, 0], 1, 1),
            channels: [
                "A",
                "B",
                "G",
                "R",
                "Z",
                "N.X",
                "N.Z",
                "N.Y",
                "direct.B",
                "direct.G",
                "direct.R",
                "shadow_key.Y",
            ]
            .iter()
            .map(|n| channel(n))
            .collect(),
            attributes: vec![],
        };
        let layers = image.layers();
        let names: Vec<&str> = layers.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(names, ["beauty", "N", "Z", "direct", "shadow_key"]);
        let beauty: Vec<&str> = layers[0]
            .channels
            .iter()
            .map(|&i| image.channels[i].name.as_str())
            .collect();
        assert_eq!(beauty, ["R", "G", "B", "A"]);
        let n: Vec<&str> = layers[1]
            .channels
            .iter()
            .map(|&i| image.channels[i].name.as_str())
            .collect();
        assert_eq!(n, ["N.X", "N.Y", "N.Z"]);
        assert_eq!(image.colour_layers(), ["beauty", "direct"]);
        assert!(image
            .colour_layer("Z")
            .unwrap_err()
            .contains("not a colour layer"));
        assert!(image
            .colour_layer("nope")
            .unwrap_err()
            .contains("no layer `nope`"));
    }
}
