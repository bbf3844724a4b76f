//! An image as named float channels grouped into layers: the common form in which `tonemap`,
//! `info`, `diff` and `sheet` see EXRs and PNGs.

use std::collections::HashMap;

use glam::DVec3;

use crate::aov;

/// One channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Full name: `R`, `Z`, `direct.G`, ...
    pub name: String,
    /// As stored: `half`, `float`, `uint` (EXR) or `uint8`, `uint16` (PNG).
    pub pixel_type: &'static str,
    /// Row-major over the data window. PNG values are scaled to [0, 1].
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
    Exr,
    Png,
}

/// A decoded image file.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub format: Format,
    pub width: usize,
    pub height: usize,
    pub channels: Vec<Channel>,
    /// Header attributes as text, sorted by name (empty for PNGs).
    pub attributes: Vec<(String, String)>,
}

impl Image {
    pub fn channel(&self, name: &str) -> Option<&Channel> {
        self.channels.iter().find(|c| c.name == name)
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
            width: 1,
            height: 1,
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
