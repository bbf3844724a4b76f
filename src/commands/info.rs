//! `whitted info FILE [--json]`: what is in an image file, and the range of every layer (the
//! JSON schema is docs/info-json.md).

use serde_json::json;

use crate::cli::InfoArgs;
use whitted_core::error::Result;
use whitted_core::numbers::{compact as number, finite_or_null};
use whitted_io::input::{self, Image, Layer, Window};
use whitted_io::output::stdout;
use whitted_io::stats::Stats;

pub fn run(args: &InfoArgs) -> Result<()> {
    let image = input::read(&args.input)?;
    let text = if args.json {
        // serde_json cannot fail to print a Value it built itself.
        serde_json::to_string_pretty(&to_json(&image, &args.input.display().to_string()))
            .unwrap_or_default()
    } else {
        table(&image, &args.input.display().to_string())
    };
    stdout::print_line(&text)
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
                "min": finite_or_null(stats.min),
                "max": finite_or_null(stats.max),
                "mean": finite_or_null(stats.mean),
                "non_finite": stats.non_finite(),
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
        .map(|(k, v)| (k.clone(), v.to_json()))
        .collect();
    let window = |w: Window| json!({ "min": w.min, "max": w.max });
    json!({
        "file": file,
        "format": format!("{:?}", image.format).to_lowercase(),
        "part": image.part,
        "width": image.width,
        "height": image.height,
        "data_window": window(image.data_window),
        "display_window": window(image.display_window),
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
            .map(|&i| input::suffix(&image.channels[i].name))
            .collect();
        out += &format!(
            "{:<18} {:<22} {:<6} {:>12} {:>12} {:>12} {:>10}\n",
            layer.name,
            suffixes.join(" "),
            pixel_types(image, layer),
            number(stats.min),
            number(stats.max),
            number(stats.mean),
            stats.non_finite()
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
