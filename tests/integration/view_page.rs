//! The viewer's page in headless Chromium, feature by feature: zoom about the cursor (and on a
//! HiDPI screen), the error metrics against the numbers, a PNG, the tone maps against the CLI,
//! a check's two ray trees on a click, and --watch. The README's viewer pictures are the
//! screenshots these tests take (tools/figures sets WHITTED_SCREENSHOTS to docs/).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use crate::common::*;
use crate::view::{small_render, Browser, Viewer};

fn bytes(v: &Value) -> Vec<u8> {
    v.as_array()
        .expect("bytes")
        .iter()
        .map(|b| b.as_u64().expect("a byte") as u8)
        .collect()
}

/// An error metric of image value a against reference value b, as docs/view.md defines it.
type Metric = fn(f64, f64) -> f64;

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The tick PNG of tick2.xml at 160x120, with `extra` options, as `dir/name`.
fn tick_png(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let tick2 = scene("tick2.xml");
    let mut args = vec![
        "-i",
        s(&tick2),
        "-o",
        name,
        "--width",
        "160",
        "--height",
        "120",
    ];
    args.extend_from_slice(extra);
    let run = whitted(dir, &args);
    assert!(run.status.success(), "{}", stderr(&run));
    dir.join(name)
}

/// The RGB bytes of the page's full-resolution image, as shown now.
fn page_rgb(browser: &Browser) -> Vec<u8> {
    let rgba = bytes(&browser.script("return window.whitted.pixels()", json!([])));
    rgba.chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
}

#[test]
fn zooming_keeps_the_pixel_under_the_cursor_and_shows_each_pixels_values() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = small_render(dir.path());
    let viewer = Viewer::start(dir.path(), &exr);
    let browser = Browser::start();
    browser.open(viewer.url());
    let view = |b: &Browser| b.script("return window.whitted.view()", json!([]));
    let before = view(&browser);
    let (z0, x0, y0) = (
        number(&before["zoom"]),
        number(&before["x"]),
        number(&before["y"]),
    );
    let under = |b: &Browser, cx: f64, cy: f64| {
        b.script(
            "return window.whitted.imageAt(arguments[0], arguments[1])",
            json!([cx, cy]),
        )
    };
    let (cx, cy) = (300.0, 200.0);
    let pixel_before = under(&browser, cx, cy);
    // A real wheel event on the canvas: deltaY -600 is a factor 2^(600/300) = 4.
    browser.script(
        "const c = document.getElementById('canvas'), r = c.getBoundingClientRect(); \
         c.dispatchEvent(new WheelEvent('wheel', {clientX: r.left + arguments[0], \
           clientY: r.top + arguments[1], deltaY: -600, bubbles: true, cancelable: true}));",
        json!([cx, cy]),
    );
    let after = view(&browser);
    let z1 = number(&after["zoom"]);
    assert!((z1 - 4.0 * z0).abs() < 1e-9 * z1, "zoom {z0} -> {z1}");
    // The image point under the cursor stays there: x0 + cx / z0 = x1 + cx / z1.
    let (x1, y1) = (x0 + cx / z0 - cx / z1, y0 + cy / z0 - cy / z1);
    assert!((number(&after["x"]) - x1).abs() < 1e-9, "{after}");
    assert!((number(&after["y"]) - y1).abs() < 1e-9, "{after}");
    assert_eq!(under(&browser, cx, cy), pixel_before);
    for (px, py) in [(10.0, 20.0), (611.0, 333.0)] {
        let expected = json!([(x1 + px / z1).floor(), (y1 + py / z1).floor()]);
        let got = under(&browser, px, py);
        assert_eq!(
            got.as_array()
                .map(|a| a.iter().map(number).collect::<Vec<_>>()),
            expected.as_array().map(|a| a.iter().map(number).collect()),
            "the pixel under ({px}, {py})"
        );
    }

    // Close up, a pixel is a flat block of its own colour, its values written inside it.
    let full = page_rgb(&browser);
    browser.script("return window.whitted.goTo(40, 70)", json!([]));
    let centre = browser.script("return window.whitted.canvasAt(40, 70)", json!([]));
    let (cx, cy) = (number(&centre[0]), number(&centre[1]));
    let zoom = number(&view(&browser)["zoom"]);
    let expected = &full[(70 * 160 + 40) * 3..][..3];
    for (dx, dy) in [(-0.45, -0.45), (0.45, -0.45), (-0.45, 0.45), (0.45, 0.45)] {
        let at = browser.canvas_pixel(cx + dx * zoom, cy + dy * zoom);
        assert_eq!(&at[..], expected, "corner ({dx}, {dy}) of pixel (40, 70)");
    }
    let text_drawn = (-10..=10).any(|d| {
        browser.canvas_pixel(cx + f64::from(d), cy)[..] != *expected
            || browser.canvas_pixel(cx + f64::from(d), cy - 8.0)[..] != *expected
    });
    assert!(text_drawn, "the pixel's values are written in it");
    browser.screenshot("viewer_zoom.png");

    // The shortcuts: `?` lists them, `f` fits again, `e` is half a stop up, `]` the next layer.
    let key = |k: &str| {
        browser.script(
            "document.dispatchEvent(new KeyboardEvent('keydown', {key: arguments[0], bubbles: true}))",
            json!([k]),
        );
    };
    key("?");
    let rows = browser.script(
        "return document.getElementById('help').hidden ? -1 :            document.querySelectorAll('#shortcuts tr').length",
        json!([]),
    );
    assert!(number(&rows) >= 10.0, "the ? overlay: {rows}");
    key("Escape");
    key("f");
    browser.wait_for(
        &format!("Math.abs(window.whitted.view().zoom - {z0}) < 1e-9"),
        "f fits again",
    );
    key("e");
    let exposure = browser.script(
        "return document.getElementById('exposure').value",
        json!([]),
    );
    assert_eq!(exposure, "0.5");
    key("]");
    browser.wait_for(
        "document.querySelector('nav figure.selected').dataset.layer !== 'beauty'",
        "] selects the next layer",
    );
    browser.assert_no_errors();
}

#[test]
fn a_hidpi_screen_gets_one_image_pixel_per_screen_pixel_at_one_to_one() {
    // A whole ratio (most HiDPI laptops) and a fractional one (many Windows ones).
    for ratio in [2.0, 1.5] {
        on_a_screen_of_ratio(ratio);
    }
}

fn on_a_screen_of_ratio(ratio: f64) {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = small_render(dir.path());
    let viewer = Viewer::start(dir.path(), &exr);
    let browser = Browser::start_scaled(ratio);
    browser.open(viewer.url());
    // The canvas holds the screen's pixels: `ratio` times its CSS size, nothing scaled by the
    // browser.
    let sizes = browser.script(
        "const c = document.getElementById('canvas'), b = c.getBoundingClientRect(); \
         return [window.devicePixelRatio, c.width, b.width, c.height, b.height]",
        json!([]),
    );
    let s: Vec<f64> = sizes
        .as_array()
        .expect("sizes")
        .iter()
        .map(number)
        .collect();
    assert_eq!(s[0], ratio, "the screen's pixel ratio");
    assert!(
        (s[1] - ratio * s[2]).abs() <= 1.0 && (s[3] - ratio * s[4]).abs() <= 1.0,
        "{s:?}"
    );
    // So does the histogram.
    browser.wait_for(
        "!!document.querySelector('canvas.histogram')",
        "the histogram",
    );
    let histogram = browser.script(
        "const c = document.querySelector('canvas.histogram'); \
         return [c.width, c.getBoundingClientRect().width]",
        json!([]),
    );
    assert_eq!(number(&histogram[0]), (256.0 * ratio).round());
    assert_eq!(number(&histogram[1]), 256.0);

    // 1:1 is exactly one image pixel per screen pixel: neighbouring canvas pixels show
    // neighbouring image pixels, each its own colour.
    browser.script("return window.whitted.actualSize()", json!([]));
    let view = browser.script("return window.whitted.view()", json!([]));
    assert_eq!(number(&view["zoom"]), 1.0);
    let full = page_rgb(&browser);
    let under = |cx: f64, cy: f64| {
        let p = browser.script(
            "return window.whitted.imageAt(arguments[0], arguments[1])",
            json!([cx, cy]),
        );
        (number(&p[0]) as usize, number(&p[1]) as usize)
    };
    let (mx, my) = ((s[1] / 2.0).floor(), (s[3] / 2.0).floor());
    let (x0, y0) = under(mx + 0.5, my + 0.5);
    for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (7.0, 5.0)] {
        let (cx, cy) = (mx + dx, my + dy);
        let (x, y) = under(cx + 0.5, cy + 0.5);
        assert_eq!(
            (x, y),
            (x0 + dx as usize, y0 + dy as usize),
            "canvas ({cx}, {cy})"
        );
        let expected = &full[(y * 160 + x) * 3..][..3];
        assert_eq!(
            &browser.canvas_pixel(cx, cy)[..],
            expected,
            "image pixel ({x}, {y})"
        );
    }

    // The wheel, at a CSS point, zooms about the screen pixel under it.
    let (css_x, css_y) = (150.0, 100.0);
    let scale = s[1] / s[2];
    let before = under(scale * css_x, scale * css_y);
    browser.script(
        "const c = document.getElementById('canvas'), r = c.getBoundingClientRect(); \
         return new Promise((done) => { c.dispatchEvent(new WheelEvent('wheel', {clientX: \
           r.left + arguments[0], clientY: r.top + arguments[1], deltaY: -600, bubbles: true, \
           cancelable: true})); setTimeout(done, 0); })",
        json!([css_x, css_y]),
    );
    assert_eq!(
        number(&browser.script("return window.whitted.view().zoom", json!([]))),
        4.0
    );
    assert_eq!(under(scale * css_x, scale * css_y), before);

    // Values are written from 48 CSS pixels an image pixel: 48 x ratio screen pixels.
    browser.script("return window.whitted.goTo(40, 70)", json!([]));
    let zoom = number(&browser.script("return window.whitted.view().zoom", json!([])));
    assert_eq!(zoom, 48.0 * ratio);
    let centre = browser.script("return window.whitted.canvasAt(40, 70)", json!([]));
    let (cx, cy) = (number(&centre[0]), number(&centre[1]));
    let expected = &full[(70 * 160 + 40) * 3..][..3];
    assert_eq!(
        &browser.canvas_pixel(cx - 0.45 * zoom, cy - 0.45 * zoom)[..],
        expected
    );
    let text_drawn = (-20..=20).any(|d| {
        browser.canvas_pixel(cx + f64::from(d), cy)[..] != *expected
            || browser.canvas_pixel(cx + f64::from(d), cy - 16.0)[..] != *expected
    });
    assert!(text_drawn, "the pixel's values are written in it");
    browser.assert_no_errors();
}

#[test]
fn each_error_metric_at_a_pixel_is_the_number_and_the_differing_pixels_are_counted() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = small_render(d);
    let other = render_exr(
        d,
        &scene("tick2.xml"),
        "other.exr",
        &["--width", "160", "--height", "120", "--no-shadows"],
    );
    let (a, b) = (read_exr(&exr), read_exr(&other));
    // The pixel where the shadow changes red the most.
    let (x, y) = (0..160 * 120)
        .map(|p| (p % 160, p / 160))
        .max_by(|&(x, y), &(u, v)| {
            let d = |x, y| (a.at("R", x, y) - b.at("R", x, y)).abs();
            d(x, y).total_cmp(&d(u, v))
        })
        .expect("pixels");
    let differing = (0..160 * 120)
        .filter(|p| {
            ["R", "G", "B", "A"]
                .iter()
                .any(|c| a.at(c, p % 160, p / 160) != b.at(c, p % 160, p / 160))
        })
        .count();
    assert!(differing > 0);
    let viewer = Viewer::start_with(d, &[s(&exr), "--reference", s(&other)]);
    let browser = Browser::start();
    browser.open(viewer.url());
    let metrics: [(&str, Metric); 5] = [
        ("error", |a, b| a - b),
        ("absolute-error", |a, b| (a - b).abs()),
        ("squared-error", |a, b| (a - b) * (a - b)),
        ("relative-absolute-error", |a, b| {
            (a - b).abs() / (b.abs() + 0.01)
        }),
        ("relative-squared-error", |a, b| {
            (a - b) * (a - b) / (b * b + 0.01)
        }),
    ];
    for (name, metric) in metrics {
        let shown = browser.script(
            "return window.whitted.setCompare(arguments[0]) \
               .then(() => window.whitted.valueAt(arguments[1], arguments[2]))",
            json!([name, x, y]),
        );
        for (i, c) in ["R", "G", "B"].iter().enumerate() {
            let expected = metric(f64::from(a.at(c, x, y)), f64::from(b.at(c, x, y))) as f32;
            assert_eq!(
                number(&shown[i]),
                f64::from(expected),
                "{name} {c} at ({x}, {y})"
            );
        }
    }
    browser.wait_for(
        "document.getElementById('differing').textContent.length > 0",
        "the differing-pixel count",
    );
    let count = browser.script(
        "return document.getElementById('differing').textContent",
        json!([]),
    );
    assert!(
        count
            .as_str()
            .is_some_and(|t| t.starts_with(&format!("{differing} of 19200"))),
        "{count}, expected {differing}"
    );
    browser.script(
        "return window.whitted.setCompare('relative-absolute-error')",
        json!([]),
    );
    browser.wait_for("!document.getElementById('scale').hidden", "the scale bar");
    browser.screenshot("viewer_error.png");
    browser.assert_no_errors();
}

#[test]
fn a_png_opens_with_its_own_bytes_and_the_tone_maps_are_the_clis() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let png = tick_png(d, "mine.png", &[]);
    let viewer = Viewer::start(d, &png);
    let browser = Browser::start();
    browser.open(viewer.url());
    assert_eq!(page_rgb(&browser), read_png(&png).data, "the PNG's bytes");
    drop(viewer);

    let exr = small_render(d);
    let viewer = Viewer::start(d, &exr);
    browser.open(viewer.url());
    for op in [
        "tick", "clamp", "reinhard", "aces", "agx", "neutral", "sigmoid",
    ] {
        browser.script(
            "return window.whitted.setToneMap(arguments[0], 0.7)",
            json!([op]),
        );
        let page = page_rgb(&browser);
        let out = format!("{op}.png");
        let run = whitted(
            d,
            &[
                "tonemap",
                s(&exr),
                "-o",
                &out,
                "--tonemap",
                op,
                "--exposure",
                "0.7",
            ],
        );
        assert!(run.status.success(), "{}", stderr(&run));
        let cli = read_png(&d.join(&out)).data;
        let worst = cli
            .iter()
            .zip(&page)
            .map(|(a, b)| a.abs_diff(*b))
            .max()
            .expect("bytes");
        assert!(
            worst <= 1,
            "{op}: the page differs from the CLI by {worst} LSB"
        );
    }
    browser.assert_no_errors();
}

#[test]
fn check_view_serves_the_check_and_a_click_shows_both_ray_trees() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let student = tick_png(d, "student.png", &["--no-shadows"]);
    let tick2 = scene("tick2.xml");
    // `whitted check student.png -i tick2.xml --view --no-browser`: the URL is the first line.
    let viewer = Viewer::check(d, &[s(&student), "-i", s(&tick2)]);
    // The token is needed; the report names the mistake.
    let host = format!("127.0.0.1:{}", viewer.port);
    let bare = |path: &str| crate::view::http(viewer.port, "GET", path, &host, None).0;
    for path in ["/", "/api/check", "/api/trees?x=1&y=1", "/api/version"] {
        assert_eq!(bare(path), 403, "{path} without the token");
    }
    assert_eq!(viewer.get("/").0, 200);
    let report = viewer.json("/api/check");
    assert_eq!(report["verdict"], "differs");
    assert_eq!(report["diagnosis"][0]["bugs"], json!(["no-shadows"]));
    let trees = viewer.json("/api/trees?x=40&y=70");
    assert_eq!(trees["mistake"]["bugs"], json!(["no-shadows"]));
    assert_eq!(trees["reference"]["pixel"], json!([40, 70]));

    let browser = Browser::start();
    browser.open(viewer.url());
    browser.wait_for(
        "!document.getElementById('check-panel').hidden",
        "the check panel",
    );
    let [x, y] = [
        number(&report["worst_pixel"][0]),
        number(&report["worst_pixel"][1]),
    ];
    // A real click (press and release without moving) on that pixel of the canvas.
    browser.script(
        "const c = document.getElementById('canvas'), r = c.getBoundingClientRect(); \
         const [cx, cy] = window.whitted.canvasAt(arguments[0], arguments[1]); \
         const at = {clientX: r.left + cx, clientY: r.top + cy, bubbles: true}; \
         c.dispatchEvent(new MouseEvent('mousedown', at)); \
         c.dispatchEvent(new MouseEvent('mouseup', at));",
        json!([x, y]),
    );
    browser.wait_for(
        "document.querySelectorAll('#trees .tree').length === 2",
        "two ray trees",
    );
    let titles = browser.script(
        "return Array.from(document.querySelectorAll('#trees .tree h3'), h => h.textContent)",
        json!([]),
    );
    assert_eq!(titles, json!(["reference", "top mistake: no-shadows"]));
    let differing = browser.script(
        "return Array.from(document.querySelectorAll('#trees .tree:last-child tr.differs'), \
           r => r.dataset.key)",
        json!([]),
    );
    let keys: Vec<&str> = differing
        .as_array()
        .expect("keys")
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert!(
        keys.iter().any(|k| k.ends_with(".shadow")),
        "a shadow row differs: {keys:?}"
    );
    browser.screenshot("viewer_check.png");
    browser.assert_no_errors();
}

/// Replaces `path` by `new` as a program that writes its output elsewhere and renames it does.
fn replace(new: &Path, path: &Path) {
    std::fs::rename(new, path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

#[test]
fn watch_reloads_a_rewritten_image_and_rechecks_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let shown = tick_png(d, "shown.png", &[]);
    let viewer = Viewer::start_with(d, &[s(&shown), "--watch"]);
    let browser = Browser::start();
    browser.open(viewer.url());
    assert_eq!(page_rgb(&browser), read_png(&shown).data);
    assert_eq!(
        browser.script("return window.whitted.following", json!([])),
        json!(true)
    );
    let new = tick_png(d, "new.png", &["--no-shadows"]);
    let expected = read_png(&new).data;
    // Rewritten in place, as a student's program writes its PNG.
    std::fs::write(&shown, std::fs::read(&new).expect("read")).expect("rewrite");
    browser.wait_for("window.whitted.reloads >= 1", "the page reloads");
    assert_eq!(page_rgb(&browser), expected);
    browser.assert_no_errors();
    drop(viewer);

    // In check mode the check runs again: the wrong image, then the right one.
    let checked = tick_png(d, "checked.png", &["--no-shadows"]);
    let viewer = Viewer::check(d, &[s(&checked), "--watch"]);
    assert_eq!(viewer.json("/api/check")["verdict"], "differs");
    let right = tick_png(d, "right.png", &[]);
    replace(&right, &checked);
    let started = Instant::now();
    while viewer.json("/api/version")["version"] == 1 {
        assert!(started.elapsed() < Duration::from_secs(60), "no reload");
        std::thread::sleep(Duration::from_millis(100));
    }
    assert_eq!(viewer.json("/api/check")["verdict"], "identical");
    // A truncated file is reported, and the last good check stays.
    std::fs::write(&checked, b"\x89PNG\r\n\x1a\n").expect("truncate");
    while viewer.json("/api/version")["problem"].is_null() {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "no problem reported"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    assert_eq!(viewer.json("/api/check")["verdict"], "identical");
}

#[test]
fn an_exr_of_a_known_scene_shows_its_ray_tree_and_another_scene_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let run = whitted(
        d,
        &[
            "render", "-q", "--no-png", "--exr", "tick.exr", "--width", "80", "--height", "60",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let exr = d.join("tick.exr");
    // The embedded scene needs no -i.
    let viewer = Viewer::start(d, &exr);
    assert_eq!(viewer.json("/api/image")["trees"], true);
    let trees = viewer.json("/api/trees?x=20&y=30");
    assert!(trees["mistake"].is_null());
    let explained = whitted(
        d,
        &[
            "explain", "--pixel", "20,30", "--width", "80", "--height", "60", "--json",
        ],
    );
    let expected: Value = serde_json::from_slice(&explained.stdout).expect("explain --json");
    assert_eq!(trees["reference"], expected, "the tree is explain's");
    assert_eq!(viewer.get("/api/trees?x=80&y=0").0, 404);
    drop(viewer);
    // Rendered without shadows: the trees are traced so, as the header's own attribute says.
    let run = whitted(
        d,
        &[
            "render",
            "-q",
            "--no-png",
            "--exr",
            "flat.exr",
            "--width",
            "80",
            "--height",
            "60",
            "--no-shadows",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let viewer = Viewer::start(d, &d.join("flat.exr"));
    let flat = viewer.json("/api/trees?x=20&y=30");
    let light = &flat["reference"]["vertices"][0]["lights"][0];
    assert_eq!(light["shadow_tested"], false, "{light}");
    drop(viewer);
    // A farm node's region: its pixel (0, 0) is the frame's (20, 30).
    let run = whitted(
        d,
        &[
            "render",
            "-q",
            "--no-png",
            "--exr",
            "part.exr",
            "--width",
            "80",
            "--height",
            "60",
            "--region",
            "20,30,60,50",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let viewer = Viewer::start(d, &d.join("part.exr"));
    assert_eq!(viewer.json("/api/trees?x=0&y=0")["reference"], expected);
    drop(viewer);
    // Another scene than the recorded one would explain another image.
    let refused = whitted(
        d,
        &[
            "view",
            s(&exr),
            "-i",
            s(&scene("cast_shadow.xml")),
            "--no-browser",
        ],
    );
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    assert!(
        stderr(&refused).contains("was not rendered from"),
        "{}",
        stderr(&refused)
    );
    assert!(refused.stdout.is_empty());
}

#[test]
fn a_long_first_load_opens_the_page_at_once_and_says_what_it_reads() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // A 4K student image with one bounce too few: checking it (the reference and the
    // diagnosis, at 4K) takes seconds, longer than the viewer keeps its URL back.
    let run = whitted(
        d,
        &[
            "-q", "-o", "big.png", "-b", "1", "--width", "3840", "--height", "2160",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let browser = Browser::start();
    let viewer = Viewer::check(d, &["big.png", "--watch"]);
    let version = viewer.json("/api/version");
    assert_eq!(
        version["open"], false,
        "the URL came before the check: {version}"
    );
    assert_eq!(version["reading"], "big.png (and checking it)");
    // Rewritten while the first load runs: --watch looked before it, and sees the change.
    std::fs::copy(d.join("big.png"), d.join("again.png")).expect("copy");
    replace(&d.join("again.png"), &d.join("big.png"));
    browser.session("POST", "/url", Some(json!({"url": viewer.url()})));
    browser.wait_for(
        "document.getElementById('status').textContent.startsWith('reading big.png')",
        "the page says what it reads",
    );
    // A request that needs the check waits for it, and gets what it would have got later.
    let image = viewer.json("/api/image");
    assert_eq!(
        (&image["width"], &image["check"]),
        (&json!(3840), &json!(true))
    );
    assert_eq!(viewer.json("/api/version")["open"], true);
    assert_eq!(viewer.json("/api/check")["verdict"], "differs");
    browser.wait_for(
        "!!(window.whitted && window.whitted.ready)",
        "the page is ready",
    );
    // The image rewritten during the first load is checked again once it has ended.
    let started = Instant::now();
    while viewer.json("/api/version")["version"] != 2 {
        assert!(started.elapsed() < Duration::from_secs(60), "no reload");
        std::thread::sleep(Duration::from_millis(200));
    }
    browser.wait_for(
        "window.whitted.reloads === 1",
        "the page follows the reload",
    );
    browser.assert_no_errors();
}

#[test]
fn watch_reports_a_pipe_and_a_truncated_jpeg_and_reloads_the_next_good_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let shown = tick_png(d, "shown.png", &[]);
    let viewer = Viewer::start_with(d, &[s(&shown), "--watch"]);
    let started = Instant::now();
    let wait_for = |what: &str, done: &dyn Fn(&Value) -> bool| loop {
        let version = viewer.json("/api/version");
        if done(&version) {
            return version;
        }
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "{what}: {version}"
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    // A pipe renamed over the watched file: said, never opened (an open would block).
    let fifo = d.join("fifo");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo")
        .success());
    replace(&fifo, &shown);
    let version = wait_for("the pipe reported", &|v| !v["problem"].is_null());
    assert!(
        version["problem"]
            .as_str()
            .is_some_and(|p| p.contains("not a regular file")),
        "{version}"
    );
    // A good PNG renamed over the pipe is reloaded.
    let good = tick_png(d, "good.png", &["--no-shadows"]);
    replace(&good, &shown);
    wait_for("the good file reloaded", &|v| {
        v["version"].as_u64().is_some_and(|n| n >= 2) && v["problem"].is_null()
    });
    let image = viewer.json("/api/image");
    assert_eq!(image["width"], read_png(&shown).width, "{image}");
    drop(viewer);

    // A JPEG caught 60% written (the writer paused): reported, not shown with grey rows.
    let jpeg = root().join("reference/specular_test_correct_solution.jpg");
    let whole = std::fs::read(&jpeg).expect("jpeg");
    let watched = d.join("shown.jpg");
    std::fs::write(&watched, &whole).expect("jpeg");
    let viewer = Viewer::start_with(d, &[s(&watched), "--watch"]);
    std::fs::write(&watched, &whole[..whole.len() * 6 / 10]).expect("half");
    let started = Instant::now();
    loop {
        let version = viewer.json("/api/version");
        if let Some(problem) = version["problem"].as_str() {
            assert!(problem.contains("truncated JPEG"), "{problem}");
            assert_eq!(version["version"], 1, "the last good image stays");
            break;
        }
        assert!(started.elapsed() < Duration::from_secs(60), "{version}");
        std::thread::sleep(Duration::from_millis(100));
    }
}
