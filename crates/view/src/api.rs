//! The viewer's answers: the page, the image's description, layers (whole or by tile, the
//! image's, the reference's or an error metric's), statistics, a pixel's values and ray trees,
//! the check's report, for a request already parsed and checked (`view::request`). A pure
//! function from what is loaded and the request to the reply; nothing is read from disk.
//! While the first load still runs, only the page and the version (with what is being read)
//! are answered.

use serde_json::json;

use super::content::Content;
use super::metric::Metric;
use super::planes::{differing_pixels, Missing, Planes, Which};
use super::request::ApiRequest;
use super::{stats, text, Reply};
use whitted_check::explain::{explain, json::to_json};
use whitted_core::aov;
use whitted_core::memory;
use whitted_io::input::Image;

const PAGE: &str = include_str!("page/index.html");
const STYLE: &str = include_str!("page/style.css");
/// The page's script, one concept a file, in the order they depend on each other.
const SCRIPTS: [&str; 9] = [
    include_str!("page/tonemap.js"),
    include_str!("page/colormap.js"),
    include_str!("page/viewport.js"),
    include_str!("page/panels.js"),
    include_str!("page/trees.js"),
    include_str!("page/state.js"),
    include_str!("page/pixels.js"),
    include_str!("page/controls.js"),
    include_str!("page/app.js"),
];

/// Samples a side of a tile: 256 x 256 x 4 channels is 1 MiB of f32s.
pub const TILE: usize = 256;

/// What the server holds: its first load still running, or what the latest load gave.
#[derive(Clone)]
pub enum State {
    /// Reading `what` since `started` (a large EXR takes seconds: the page shows this meanwhile).
    Opening {
        what: String,
        started: std::time::Instant,
    },
    Open(Snapshot),
}

/// What one load gave, and how many loads there were.
#[derive(Clone)]
pub struct Snapshot {
    pub content: std::sync::Arc<Content>,
    pub version: u64,
    /// Why the last reload failed, if it did (the content is then the one before).
    pub problem: Option<String>,
    /// Whether the files are watched (`--watch`): the page polls for reloads only then.
    pub watching: bool,
}

impl Snapshot {
    /// The first load's.
    pub fn first(content: Content, watching: bool) -> Snapshot {
        Snapshot {
            watching,
            content: std::sync::Arc::new(content),
            version: 1,
            problem: None,
        }
    }
}

fn json_reply(value: &serde_json::Value) -> Reply {
    (200, "application/json", value.to_string().into_bytes())
}

/// One document with its style and script inline: every request carries the token.
fn page() -> Reply {
    (
        200,
        "text/html; charset=utf-8",
        PAGE.replace("/*STYLE*/", STYLE)
            .replace("/*SCRIPT*/", &SCRIPTS.concat())
            .into_bytes(),
    )
}

/// The reply to `request`.
pub fn respond(state: &State, request: &ApiRequest) -> Reply {
    let now = match state {
        State::Open(now) => now,
        State::Opening { what, started } => return opening(what, *started, request),
    };
    let content = &now.content;
    match request {
        ApiRequest::Page => page(),
        ApiRequest::Image => json_reply(&describe(now)),
        ApiRequest::Version => json_reply(&json!({
            "open": true,
            "version": now.version,
            "problem": now.problem,
            "watching": now.watching,
        })),
        ApiRequest::Check => match &content.check {
            Some(report) => json_reply(report),
            None => text(404, "not in check mode"),
        },
        ApiRequest::Layer {
            which,
            name,
            step,
            tile,
        } => match planes(content, *which, name) {
            Ok(planes) => layer_bytes(&planes, *step, *tile),
            Err(refusal) => refusal,
        },
        ApiRequest::Stats { which, name } => match planes(content, *which, name) {
            Ok(planes) => {
                let mut s = stats::statistics(&planes);
                s["differing_pixels"] = json!(differing_pixels(
                    &content.main,
                    content.reference.as_ref(),
                    name
                ));
                json_reply(&s)
            }
            Err(refusal) => refusal,
        },
        ApiRequest::Pixel { x, y } => {
            let image = &content.main;
            if *x < image.width && *y < image.height {
                json_reply(&json!({
                    "values": pixel(image, *x, *y),
                    "reference": content.reference.as_ref().map(|r| pixel(r, *x, *y)),
                }))
            } else {
                text(404, "no such pixel")
            }
        }
        ApiRequest::Trees { x, y } => trees(content, *x, *y),
    }
}

/// The reply while the first load runs (the server holds other requests until it ends, so
/// this 503 is only for one that waited its limit out).
fn opening(what: &str, started: std::time::Instant, request: &ApiRequest) -> Reply {
    match request {
        ApiRequest::Page => page(),
        ApiRequest::Version => json_reply(&json!({
            "open": false,
            "version": 0,
            "problem": null,
            "reading": what,
            "seconds": started.elapsed().as_secs_f64(),
        })),
        _ => text(503, &format!("still reading {what}: ask again shortly")),
    }
}

fn planes<'a>(content: &'a Content, which: Which, name: &str) -> Result<Planes<'a>, Reply> {
    Planes::of(&content.main, content.reference.as_ref(), which, name).map_err(|m| match m {
        Missing::Layer => text(404, "no such layer"),
        Missing::Reference => text(404, "no reference image"),
    })
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

/// The ray trees of pixel (x, y): the course's, and the top-ranked mistake's in check mode.
fn trees(content: &Content, x: usize, y: usize) -> Reply {
    let Some(tracer) = &content.tracer else {
        return text(
            404,
            "no scene to trace: give the scene with -i, or view a whitted EXR of the embedded scene",
        );
    };
    let at = |v: usize, origin: u32| u32::try_from(v).ok()?.checked_add(origin);
    let (Some(x), Some(y)) = (at(x, tracer.origin[0]), at(y, tracer.origin[1])) else {
        return text(404, "no such pixel");
    };
    if x >= tracer.frame.width || y >= tracer.frame.height {
        return text(404, "no such pixel");
    }
    let rules = tracer.frame.course.rules();
    let reference = match explain(&rules, &tracer.scene, &tracer.frame, x, y) {
        Ok(e) => to_json(&e, &tracer.scene, whitted_check::mistakes::Mistakes::NONE),
        Err(e) => return text(400, &e.to_string()),
    };
    let mistake = if tracer.mistakes.is_empty() {
        serde_json::Value::Null
    } else {
        let frame = tracer.mistakes.frame_spec(&tracer.frame);
        match explain(
            &whitted_check::mistakes::Variant::from(tracer.mistakes).in_course(tracer.frame.course),
            &tracer.scene,
            &frame,
            x,
            y,
        ) {
            Ok(e) => to_json(&e, &tracer.scene, tracer.mistakes),
            Err(e) => return text(400, &e.to_string()),
        }
    };
    json_reply(&json!({ "reference": reference, "mistake": mistake }))
}

/// The image's size and layers (name, channels, role), its lights, and what else the page can
/// ask for: a reference, the error metrics, ray trees, a check report.
fn describe(now: &Snapshot) -> serde_json::Value {
    let content = &now.content;
    let image = &content.main;
    let layers: Vec<serde_json::Value> = image
        .layers()
        .iter()
        .map(|layer| {
            let channels: Vec<&str> = layer
                .channels
                .iter()
                .map(|&i| whitted_io::input::suffix(&image.channels[i].name))
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
            // Grouped by what aov.rs knows of the name; a name whitted never writes goes
            // with the colour terms or the data by its channels.
            let group = aov::group_of_layer(&layer.name).unwrap_or(match role {
                "colour" => "effects",
                _ => "data",
            });
            json!({ "name": layer.name, "channels": channels, "role": role, "group": group })
        })
        .collect();
    let lights: Vec<String> = image
        .colour_layers()
        .into_iter()
        .filter_map(|l| aov::light_of_layer(&l).map(str::to_string))
        .collect();
    // The tone map the image's course year writes its PNG with: what the page starts on.
    // Only where the page starts: a year this version does not know starts on `tick`.
    let course = image.course(std::path::Path::new("")).ok();
    let tonemap = match course.map(|c| c.tonemap()) {
        Some(whitted_core::tonemap::ToneMap::Sigmoid) => "sigmoid",
        _ => "tick",
    };
    json!({
        "width": image.width,
        "height": image.height,
        "tonemap": tonemap,
        "layers": layers,
        "lights": lights,
        "reference": content.reference.is_some(),
        "metrics": Metric::ALL.map(Metric::name),
        "tile": TILE,
        "trees": content.tracer.is_some(),
        "check": content.check.is_some(),
        "labels": content.labels,
        "version": now.version,
        "problem": now.problem,
        "watching": now.watching,
    })
}

/// The samples a layer reply holds, (x0, y0, columns, rows), or None for no such tile.
fn grid(
    w: usize,
    h: usize,
    step: usize,
    tile: Option<(usize, usize)>,
) -> Option<(usize, usize, usize, usize)> {
    match tile {
        // The same grid as the tiles': every sample at x = i * step < width.
        None => Some((0, 0, w.div_ceil(step), h.div_ceil(step))),
        Some((tx, ty)) => {
            let origin = |t: usize| t.checked_mul(TILE).and_then(|t| t.checked_mul(step));
            match (origin(tx), origin(ty)) {
                (Some(x0), Some(y0)) if x0 < w && y0 < h => Some((
                    x0,
                    y0,
                    TILE.min((w - x0).div_ceil(step)),
                    TILE.min((h - y0).div_ceil(step)),
                )),
                _ => None,
            }
        }
    }
}

/// At most how many bytes the reply to `request` holds, known before it is computed, so that
/// the server can charge it against what unsent replies may hold (`admission.rs`). Only a
/// layer's values can be large; everything else counts as a nominal 64 KiB.
pub fn reply_bytes(state: &State, request: &ApiRequest) -> u64 {
    const SMALL: u64 = 64 << 10;
    let (
        State::Open(now),
        ApiRequest::Layer {
            which,
            name,
            step,
            tile,
        },
    ) = (state, request)
    else {
        return SMALL;
    };
    let Ok(planes) = planes(&now.content, *which, name) else {
        return SMALL;
    };
    match grid(planes.width, planes.height, *step, *tile) {
        Some((_, _, columns, rows)) => (columns as u64)
            .saturating_mul(rows as u64)
            .saturating_mul(4 * planes.count() as u64)
            .max(SMALL),
        None => SMALL,
    }
}

/// A layer's values, pixel-major, its channels in display order, little-endian f32; with
/// `step` > 1 every step-th pixel of every step-th row (`ceil(width / step)` by
/// `ceil(height / step)`: a step larger than the image still gives its first pixel).
/// With a tile (tx, ty), only the `TILE` x `TILE` block of those samples there (fewer at the
/// right and bottom edges: the samples at x = (tx * TILE + i) * step < width), so that a
/// zoomed-in page fetches the full resolution of what it shows and nothing else. 404 for no
/// such layer or tile, 503 when the reply does not fit in the memory this process may use.
fn layer_bytes(planes: &Planes, step: usize, tile: Option<(usize, usize)>) -> Reply {
    let Some((x0, y0, columns, rows)) = grid(planes.width, planes.height, step, tile) else {
        return text(404, "no such tile");
    };
    let w = planes.width;
    let size = (columns as u64)
        .saturating_mul(rows as u64)
        .saturating_mul(4 * planes.count() as u64);
    if let Err(e) = memory::check(size, memory::available_bytes(), "the layer") {
        return text(503, &format!("service unavailable: {e}"));
    }
    let mut bytes = Vec::new();
    if bytes.try_reserve_exact(size as usize).is_err() {
        return text(503, "service unavailable: not enough memory for the layer");
    }
    for row in 0..rows {
        for column in 0..columns {
            let p = (y0 + row * step) * w + x0 + column * step;
            for c in 0..planes.count() {
                bytes.extend_from_slice(&planes.value(c, p).to_le_bytes());
            }
        }
    }
    (200, "application/octet-stream", bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use whitted_io::input::raster;

    fn snapshot() -> State {
        let main = raster::rgb8(300, 2, &vec![51; 300 * 2 * 3]);
        let reference = raster::rgb8(300, 2, &vec![102; 300 * 2 * 3]);
        State::Open(Snapshot {
            content: std::sync::Arc::new(Content {
                main,
                reference: Some(reference),
                tracer: None,
                check: None,
                labels: ["a.png".into(), "b.png".into()],
            }),
            version: 1,
            problem: None,
            watching: false,
        })
    }

    fn floats(bytes: &[u8]) -> Vec<f32> {
        bytes
            .chunks(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    }

    #[test]
    fn tiles_hold_the_samples_of_their_block_and_metrics_the_metric() {
        let now = snapshot();
        let layer = |which, step, tile| {
            respond(
                &now,
                &ApiRequest::Layer {
                    which,
                    name: "beauty".into(),
                    step,
                    tile,
                },
            )
        };
        // 300 wide: tile 0 has 256 columns, tile 1 the 44 left; at step 2, one tile of 150.
        assert_eq!(layer(Which::Main, 1, Some((0, 0))).2.len(), 256 * 2 * 3 * 4);
        assert_eq!(layer(Which::Main, 1, Some((1, 0))).2.len(), 44 * 2 * 3 * 4);
        assert_eq!(layer(Which::Main, 2, Some((0, 0))).2.len(), 150 * 3 * 4);
        assert_eq!(layer(Which::Main, 2, Some((1, 0))).0, 404);
        assert_eq!(layer(Which::Main, 1, Some((usize::MAX, 0))).0, 404);
        let squared = floats(&layer(Which::Metric(Metric::SquaredError), 1, Some((1, 0))).2);
        let (a, b) = (51.0_f32 / 255.0, 102.0_f32 / 255.0);
        assert_eq!(squared[0], Metric::SquaredError.apply(a, b));
        let reference = floats(&layer(Which::Reference, 1, None).2);
        assert_eq!(reference[0], b);
        // Whole layers sample the tiles' grid: 300 at step 7 is 43 columns (x = 0 .. 294), and
        // a step wider than the image still gives its first pixel.
        assert_eq!(layer(Which::Main, 7, None).2.len(), 43 * 3 * 4);
        assert_eq!(layer(Which::Main, 7, Some((0, 0))).2.len(), 43 * 3 * 4);
        let wide = layer(Which::Main, 1000, None);
        assert_eq!((wide.0, wide.2.len()), (200, 3 * 4));
    }

    #[test]
    fn statistics_count_the_differing_pixels_and_trees_need_a_scene() {
        let now = snapshot();
        let (status, _, body) = respond(
            &now,
            &ApiRequest::Stats {
                which: Which::Metric(Metric::Error),
                name: "beauty".into(),
            },
        );
        assert_eq!(status, 200);
        let s: serde_json::Value = serde_json::from_slice(&body).expect("json");
        assert_eq!(s["differing_pixels"], 600);
        assert_eq!(
            s["channels"][0]["max"],
            f64::from(Metric::Error.apply(0.2, 0.4))
        );
        assert_eq!(respond(&now, &ApiRequest::Trees { x: 0, y: 0 }).0, 404);
        assert_eq!(respond(&now, &ApiRequest::Check).0, 404);
        let missing = ApiRequest::Stats {
            which: Which::Main,
            name: "nothing".into(),
        };
        assert_eq!(respond(&now, &missing).0, 404);
    }

    #[test]
    fn while_the_first_load_runs_only_the_page_and_the_version_answer() {
        let opening = State::Opening {
            what: "big.exr".into(),
            started: std::time::Instant::now(),
        };
        assert_eq!(respond(&opening, &ApiRequest::Page).0, 200);
        let (status, _, body) = respond(&opening, &ApiRequest::Version);
        assert_eq!(status, 200);
        let v: serde_json::Value = serde_json::from_slice(&body).expect("json");
        assert_eq!(
            (&v["open"], &v["reading"]),
            (&json!(false), &json!("big.exr"))
        );
        for request in [
            ApiRequest::Image,
            ApiRequest::Check,
            ApiRequest::Pixel { x: 0, y: 0 },
            ApiRequest::Trees { x: 0, y: 0 },
        ] {
            let (status, _, body) = respond(&opening, &request);
            assert_eq!(status, 503);
            assert!(String::from_utf8_lossy(&body).contains("still reading big.exr"));
        }
        let (_, _, body) = respond(&snapshot(), &ApiRequest::Version);
        let v: serde_json::Value = serde_json::from_slice(&body).expect("json");
        assert_eq!((&v["open"], &v["version"]), (&json!(true), &json!(1)));
    }
}
