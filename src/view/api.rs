//! The viewer's HTTP routes: the page, the image's description, and each layer's values.
//! Every request is checked first: Host must be this loopback address and port, the token must
//! match; anything else is 403, and any other path 404. Nothing is read from disk.

use serde_json::json;
use tiny_http::{Header, Request, Response};

use super::Served;
use crate::aov;
use crate::input::Image;

const PAGE: &str = include_str!("page/index.html");
const SCRIPT: &str = include_str!("page/app.js");
const STYLE: &str = include_str!("page/style.css");

/// Answers one request.
pub fn respond(served: &Served, request: Request) {
    let (status, kind, body) = route(served, &request);
    let mut response = Response::from_data(body).with_status_code(status);
    for (name, value) in [
        ("Content-Type", kind),
        ("Cache-Control", "no-store"),
        ("X-Content-Type-Options", "nosniff"),
    ] {
        if let Ok(header) = Header::from_bytes(name, value) {
            response.add_header(header);
        }
    }
    // A client that went away is not the server's problem.
    let _ = request.respond(response);
}

type Reply = (u16, &'static str, Vec<u8>);

fn text(status: u16, message: &str) -> Reply {
    (
        status,
        "text/plain; charset=utf-8",
        message.as_bytes().to_vec(),
    )
}

fn route(served: &Served, request: &Request) -> Reply {
    let host = request
        .headers()
        .iter()
        .find(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str().to_string());
    let allowed = [
        format!("127.0.0.1:{}", served.port),
        format!("localhost:{}", served.port),
    ];
    if !host.is_some_and(|h| allowed.contains(&h)) {
        return text(403, "forbidden: not the viewer's loopback address");
    }
    let (path, query) = request.url().split_once('?').unwrap_or((request.url(), ""));
    let param = |key: &str| {
        query
            .split('&')
            .filter_map(|kv| kv.split_once('='))
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.to_string())
    };
    if param("token").as_deref() != Some(served.token.as_str()) {
        return text(403, "forbidden: missing or wrong token");
    }
    match path {
        // One document with its style and script inline: every request carries the token.
        "/" => (
            200,
            "text/html; charset=utf-8",
            PAGE.replace("/*STYLE*/", STYLE)
                .replace("/*SCRIPT*/", SCRIPT)
                .into_bytes(),
        ),
        "/api/image" => (
            200,
            "application/json",
            describe(served).to_string().into_bytes(),
        ),
        "/api/layer" => {
            let image = match param("which").as_deref() {
                Some("reference") => served.reference.as_ref(),
                _ => Some(&served.main),
            };
            let step = param("step").and_then(|s| s.parse().ok()).unwrap_or(1usize);
            match (image, param("name")) {
                (Some(image), Some(name)) => match layer_bytes(image, &name, step.max(1)) {
                    Some(bytes) => (200, "application/octet-stream", bytes),
                    None => text(404, "no such layer"),
                },
                _ => text(404, "no such image or layer"),
            }
        }
        "/api/pixel" => {
            let coordinate = |key: &str| param(key).and_then(|v| v.parse::<usize>().ok());
            match (coordinate("x"), coordinate("y")) {
                (Some(x), Some(y)) if x < served.main.width && y < served.main.height => (
                    200,
                    "application/json",
                    pixel(&served.main, x, y).to_string().into_bytes(),
                ),
                _ => text(404, "no such pixel"),
            }
        }
        _ => text(404, "not found"),
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
        .filter_map(|l| l.strip_prefix("light_").map(str::to_string))
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
/// thumbnails), so a 4K image's page never needs every layer whole.
fn layer_bytes(image: &Image, name: &str, step: usize) -> Option<Vec<u8>> {
    let layer = image.layers().into_iter().find(|l| l.name == name)?;
    let channels: Vec<&[f32]> = layer
        .channels
        .iter()
        .map(|&i| image.channels[i].values.as_slice())
        .collect();
    let (width, height) = (image.width / step, image.height / step);
    let mut bytes = Vec::with_capacity(width * height * channels.len() * 4);
    for y in 0..height {
        for x in 0..width {
            let p = y * step * image.width + x * step;
            for c in &channels {
                bytes.extend_from_slice(&c[p].to_le_bytes());
            }
        }
    }
    Some(bytes)
}
