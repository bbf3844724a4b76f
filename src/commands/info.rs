//! `whitted info FILE.exr [--json]`: what is in an image file, and the range of every layer.

use serde_json::json;

use crate::cli::InfoArgs;
use crate::error::Result;
use crate::input::{Image, Layer};

/// Statistics over the finite values of a group of channels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    pub non_finite: usize,
}

impl Stats {
    /// Over all `values` of all `channels`; min, max and mean are 0 when nothing is finite.
    pub fn of<'a>(channels: impl IntoIterator<Item = &'a [f32]>) -> Self {
        let (mut min, mut max, mut sum, mut finite, mut non_finite) =
            (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0usize, 0usize);
        for values in channels {
            for &v in values {
                if v.is_finite() {
                    let v = f64::from(v);
                    min = min.min(v);
                    max = max.max(v);
                    sum += v;
                    finite += 1;
                } else {
                    non_finite += 1;
                }
            }
        }
        if finite == 0 {
            return Stats {
                min: 0.0,
                max: 0.0,
                mean: 0.0,
                non_finite,
            };
        }
        Stats {
            min,
            max,
            mean: sum / finite as f64,
            non_finite,
        }
    }

    pub fn of_layer(image: &Image, layer: &Layer) -> Self {
        Self::of(
            layer
                .channels
                .iter()
                .map(|&i| image.channels[i].values.as_slice()),
        )
    }
}

pub fn run(args: &InfoArgs) -> Result<()> {
    let image = Image::read(&args.input)?;
    let text = if args.json {
        // serde_json cannot fail to print a Value it built itself.
        serde_json::to_string_pretty(&to_json(&image, &args.input.display().to_string()))
            .unwrap_or_default()
    } else {
        table(&image, &args.input.display().to_string())
    };
    println!("{text}");
    Ok(())
}

fn channel_names(image: &Image, layer: &Layer) -> Vec<String> {
    layer
        .channels
        .iter()
        .map(|&i| image.channels[i].name.clone())
        .collect()
}

fn pixel_types(image: &Image, layer: &Layer) -> String {
    let mut types: Vec<&str> = layer
        .channels
        .iter()
        .map(|&i| image.channels[i].pixel_type)
        .collect();
    types.dedup();
    types.join("/")
}

pub fn to_json(image: &Image, file: &str) -> serde_json::Value {
    let layers: Vec<serde_json::Value> = image
        .layers()
        .iter()
        .map(|layer| {
            let stats = Stats::of_layer(image, layer);
            json!({
                "name": layer.name,
                "channels": channel_names(image, layer),
                "type": pixel_types(image, layer),
                "min": stats.min,
                "max": stats.max,
                "mean": stats.mean,
                "non_finite": stats.non_finite,
            })
        })
        .collect();
    let channels: Vec<serde_json::Value> = image
        .channels
        .iter()
        .map(|c| json!({ "name": c.name, "type": c.pixel_type }))
        .collect();
    let attributes: serde_json::Map<String, serde_json::Value> = image
        .attributes
        .iter()
        .map(|(k, v)| (k.clone(), json!(v)))
        .collect();
    json!({
        "file": file,
        "format": format!("{:?}", image.format).to_lowercase(),
        "width": image.width,
        "height": image.height,
        "channels": channels,
        "layers": layers,
        "attributes": attributes,
    })
}

fn table(image: &Image, file: &str) -> String {
    let layers = image.layers();
    let mut out = format!(
        "{file}: {} x {}, {} channels in {} layers\n\n",
        image.width,
        image.height,
        image.channels.len(),
        layers.len()
    );
    out += &format!(
        "{:<18} {:<22} {:<6} {:>12} {:>12} {:>12} {:>10}\n",
        "layer", "channels", "type", "min", "max", "mean", "non-finite"
    );
    for layer in &layers {
        let stats = Stats::of_layer(image, layer);
        let suffixes: Vec<&str> = layer
            .channels
            .iter()
            .map(|&i| crate::input::image::suffix(&image.channels[i].name))
            .collect();
        out += &format!(
            "{:<18} {:<22} {:<6} {:>12} {:>12} {:>12} {:>10}\n",
            layer.name,
            suffixes.join(" "),
            pixel_types(image, layer),
            number(stats.min),
            number(stats.max),
            number(stats.mean),
            stats.non_finite
        );
    }
    if !image.attributes.is_empty() {
        out += "\nheader:\n";
        for (name, value) in &image.attributes {
            out += &format!("  {name}: {value}\n");
        }
    }
    out.trim_end().to_string()
}

/// A compact, readable number: 4 significant digits, scientific when far from 1.
pub fn number(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_skip_non_finite_values() {
        let values = [1.0f32, -2.0, f32::NAN, 4.0, f32::INFINITY];
        let s = Stats::of([&values[..]]);
        assert_eq!((s.min, s.max, s.mean, s.non_finite), (-2.0, 4.0, 1.0, 2));
        let empty = Stats::of([&[f32::NAN][..]]);
        assert_eq!((empty.min, empty.non_finite), (0.0, 1));
    }

    #[test]
    fn numbers_are_compact() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.12345), "0.1235");
        assert_eq!(number(12.5), "12.50");
        assert_eq!(number(1.5e-7), "1.500e-7");
    }
}
