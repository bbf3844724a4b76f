//! The viewer's answers: the page, the image's description, each layer's values and a
//! pixel's, for a request already parsed and checked (`view::request`). A pure function from
//! request to reply; nothing is read from disk.

use serde_json::json;

use super::request::{ApiRequest, Which};
use super::{text, Reply, Served};
use crate::aov;
use crate::input::Image;
use crate::memory;

const PAGE: &str = include_str!("page/index.html");
const SCRIPT: &str = include_str!("page/app.js");
const STYLE: &str = include_str!("page/style.css");

/// The reply to `request`.
pub fn respond(served: &Served, request: &ApiRequest) -> Reply {
    match request {
        // One document with its style and script inline: every request carries the token.
        ApiRequest::Page => (
            200,
            "text/html; charset=utf-8",
            PAGE.replace("/*STYLE*/", STYLE)
                .replace("/*SCRIPT*/", SCRIPT)
                .into_bytes(),
        ),
        ApiRequest::Image => (
            200,
            "application/json",
            describe(served).to_string().into_bytes(),
        ),
        ApiRequest::Layer { which, name, step } => {
            let image = match which {
                Which::Main => Some(&served.main),
                Which::Reference => served.reference.as_ref(),
            };
            match image {
                Some(image) => layer_bytes(image, name, *step),
                None => text(404, "no reference image"),
            }
        }
        ApiRequest::Pixel { x, y } => {
            let image = &served.main;
            if *x < image.width && *y < image.height {
                (
                    200,
                    "application/json",
                    pixel(image, *x, *y).to_string().into_bytes(),
                )
            } else {
                text(404, "no such pixel")
            }
        }
    }
}

/// Every layer's values at pixel (x, y), for the probe.
fn pixel(image: &Image, x: usize, y: usize) -> serde_json::Value {
    let p = y * image.width + x;
    let layers: serde_json::Map<String, serde_json::Value> = image
        .layers()
        .iter()
        .map(|layer| {
            let values: Vec<f64> = layer
                .channels
                .iter()
                .map(|&i| f64::from(image.channels[i].values[p]))
                .collect();
            (layer.name.clone(), json!(values))
        })
        .collect();
    serde_json::Value::Object(layers)
}

/// The image's size and layers (name, channels, role), its lights, and whether a reference
/// of the same size is there.
fn describe(served: &Served) -> serde_json::Value {
    let image = &served.main;
    let layers: Vec<serde_json::Value> = image
        .layers()
        .iter()
        .map(|layer| {
            let channels: Vec<&str> = layer
                .channels
                .iter()
                .map(|&i| crate::input::suffix(&image.channels[i].name))
                .collect();
            let role = match aov::role_of_layer(&layer.name) {
                Some(aov::Role::Colour) => "colour",
                Some(aov::Role::Mask) => "mask",
                Some(aov::Role::Normal) => "normal",
                Some(aov::Role::ObjectId) => "id",
                Some(aov::Role::Data) => "data",
                None if image.is_colour(layer) => "colour",
                None => "data",
            };
            json!({ "name": layer.name, "channels": channels, "role": role })
        })
        .collect();
    let lights: Vec<String> = image
        .colour_layers()
        .into_iter()
        .filter_map(|l| aov::light_of_layer(&l).map(str::to_string))
        .collect();
    let reference = served
        .reference
        .as_ref()
        .is_some_and(|r| (r.width, r.height) == (image.width, image.height));
    json!({
        "width": image.width,
        "height": image.height,
        "layers": layers,
        "lights": lights,
        "reference": reference,
    })
}

/// A layer's values, pixel-major, its channels in display order, little-endian f32; with
/// `step` > 1 every step-th pixel of every step-th row (`width / step` by `height / step`, for
/// thumbnails), so a 4K image's page never needs every layer whole. 404 for no such layer,
/// 503 when the reply does not fit in the memory this process may use.
fn layer_bytes(image: &Image, name: &str, step: usize) -> Reply {
    let Some(layer) = image.layers().into_iter().find(|l| l.name == name) else {
        return text(404, "no such layer");
    };
    let channels: Vec<&[f32]> = layer
        .channels
        .iter()
        .map(|&i| image.channels[i].values.as_slice())
        .collect();
    let (width, height) = (image.width / step, image.height / step);
    let size = (width as u64)
        .saturating_mul(height as u64)
        .saturating_mul(4 * channels.len() as u64);
    if let Err(e) = memory::check(size, memory::available_bytes(), "the layer") {
        return text(503, &format!("service unavailable: {e}"));
    }
    let mut bytes = Vec::new();
    if bytes.try_reserve_exact(size as usize).is_err() {
        return text(503, "service unavailable: not enough memory for the layer");
    }
    for y in 0..height {
        for x in 0..width {
            let p = y * step * image.width + x * step;
            for c in &channels {
                bytes.extend_from_slice(&c[p].to_le_bytes());
            }
        }
    }
    (200, "application/octet-stream", bytes)
}
