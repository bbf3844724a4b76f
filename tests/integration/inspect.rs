//! `whitted info`, `diff` and `sheet` against files whose contents the tests know.

use std::path::{Path, PathBuf};

use crate::common::*;
use exr::prelude::{self as x, WritableImage as _};

/// A copy of the tick2 reference EXR with channel `Z` changed by +0.5 at `pixels`.
fn tampered(dir: &Path, pixels: &[(usize, usize)]) -> PathBuf {
    let source = read_exr(&reference("exr/tick2.exr"));
    let mut channels = x::SmallVec::new();
    for (name, samples) in source.channels {
        let samples = match (name.as_str(), samples) {
            ("Z", x::FlatSamples::F32(mut v)) => {
                for &(px, py) in pixels {
                    v[py * source.width + px] += 0.5;
                }
                x::FlatSamples::F32(v)
            }
            (_, other) => other,
        };
        channels.push(x::AnyChannel::new(name.as_str(), samples));
    }
    let image = x::Image::from_channels(
        (source.width, source.height),
        x::AnyChannels::sort(channels),
    );
    let path = dir.join("tampered.exr");
    image.write().to_file(&path).expect("write tampered EXR");
    path
}

fn json(out: &std::process::Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}): {}", String::from_utf8_lossy(&out.stdout)))
}

#[test]
fn diff_of_identical_files_passes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let golden = reference("exr/tick2.exr");
    let run = whitted(dir.path(), &["diff", s(&golden), s(&golden)]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(String::from_utf8_lossy(&run.stdout).contains("PASS: all 20 layers within tolerance"));
    let png = reference("tick2_b2.png");
    let run = whitted(
        dir.path(),
        &["diff", s(&png), s(&reference("tick2_reference.png"))],
    );
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stdout)
    );
}

#[test]
fn diff_reports_the_layer_count_and_coordinates_of_a_known_change() {
    let dir = tempfile::tempdir().expect("tempdir");
    let changed = tampered(dir.path(), &[(3, 4), (100, 20), (159, 119)]);
    let golden = reference("exr/tick2.exr");
    let heatmap = dir.path().join("heat.png");
    let run = whitted(
        dir.path(),
        &[
            "diff",
            s(&changed),
            s(&golden),
            "--json",
            "--heatmap",
            s(&heatmap),
        ],
    );
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let report = json(&run);
    assert_eq!(report["passed"], false);
    let layers = report["layers"].as_array().expect("layers");
    let failing: Vec<&serde_json::Value> = layers.iter().filter(|l| l["passed"] == false).collect();
    assert_eq!(failing.len(), 1, "only Z differs");
    let z = failing[0];
    assert_eq!(z["layer"], "Z");
    assert_eq!(z["failing"], 3);
    assert_eq!(
        z["first_failing"],
        serde_json::json!([[3, 4], [100, 20], [159, 119]])
    );
    assert_eq!(z["max_abs"].as_f64(), Some(0.5));

    // The heat map marks exactly those pixels as failing (red channel full).
    let heat = read_png(&heatmap);
    assert_eq!((heat.width, heat.height), (160, 120));
    let failing_pixels: Vec<(usize, usize)> = (0..160 * 120)
        .filter(|&i| heat.data[i * 3] == 255)
        .map(|i| (i % 160, i / 160))
        .collect();
    assert_eq!(failing_pixels, [(3, 4), (100, 20), (159, 119)]);

    // The table says the same for a person.
    let run = whitted(dir.path(), &["diff", s(&changed), s(&golden)]);
    let table = String::from_utf8_lossy(&run.stdout).into_owned();
    let z_row = table.lines().find(|l| l.starts_with("Z ")).expect("Z row");
    assert!(z_row.contains("(3, 4) (100, 20) (159, 119)"), "{z_row}");
    assert!(table.contains("FAIL: 1 of 20 layers differ"), "{table}");

    // Restricted to other layers, or with a loose enough tolerance, it passes.
    let run = whitted(
        dir.path(),
        &["diff", s(&changed), s(&golden), "--layers", "beauty,direct"],
    );
    assert_eq!(run.status.code(), Some(0));
    let run = whitted(
        dir.path(),
        &["diff", s(&changed), s(&golden), "--abs", "0.6"],
    );
    assert_eq!(run.status.code(), Some(0));
}

#[test]
fn diff_refuses_what_it_cannot_compare() {
    let dir = tempfile::tempdir().expect("tempdir");
    let golden = reference("exr/tick2.exr");
    let small = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "small.exr",
        &["--width", "80", "--height", "60"],
    );
    let beauty_only = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "beauty.exr",
        &["--width", "160", "--height", "120", "--aovs", "beauty"],
    );
    let (png, xml) = (reference("tick2_b2.png"), scene("tick2.xml"));
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["diff", s(&small), s(&golden)],
            "display windows differ",
        ),
        (
            vec!["diff", s(&beauty_only), s(&golden)],
            "missing from the first image",
        ),
        (
            vec!["diff", s(&golden), s(&golden), "--layers", "nope"],
            "layer `nope` is missing",
        ),
        (vec!["diff", s(&golden), "missing.exr"], "cannot read"),
        (vec!["diff", s(&golden), s(&png)], "display-referred image"),
        (
            vec!["diff", s(&golden), s(&xml)],
            "not an image whitted reads",
        ),
    ];
    for (args, phrase) in cases {
        let run = whitted(dir.path(), &args);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(phrase), "{args:?}: `{phrase}` not in {err}");
    }
}

#[test]
fn diff_of_different_pngs_fails() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = whitted(
        dir.path(),
        &[
            "diff",
            s(&reference("tick2_b1.png")),
            s(&reference("tick2_b2.png")),
            "--json",
        ],
    );
    assert_eq!(run.status.code(), Some(1));
    let report = json(&run);
    assert_eq!(report["layers"][0]["layer"], "beauty");
    assert!(report["layers"][0]["failing"].as_u64().expect("count") > 1000);
}

#[test]
fn info_json_describes_what_the_file_holds() {
    let dir = tempfile::tempdir().expect("tempdir");
    let golden = reference("exr/tick2.exr");
    let run = whitted(dir.path(), &["info", s(&golden), "--json"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let info = json(&run);
    assert_eq!(
        (info["width"].as_u64(), info["height"].as_u64()),
        (Some(160), Some(120))
    );

    let exr = read_exr(&golden);
    let mut channels: Vec<String> = info["channels"]
        .as_array()
        .expect("channels")
        .iter()
        .map(|c| c["name"].as_str().expect("name").to_string())
        .collect();
    channels.sort();
    let mut expected = exr.names();
    expected.sort();
    assert_eq!(channels, expected);

    let layers = info["layers"].as_array().expect("layers");
    assert_eq!(layers.len(), 20);
    let layer = |name: &str| {
        layers
            .iter()
            .find(|l| l["name"] == name)
            .unwrap_or_else(|| panic!("{name}"))
    };
    assert_eq!(
        layer("beauty")["channels"],
        serde_json::json!(["R", "G", "B", "A"])
    );
    assert_eq!(layer("shadow_0")["type"], "float");
    // Statistics equal what the file holds, computed here independently.
    let z: Vec<f64> = (0..160 * 120)
        .map(|i| f64::from(exr.at("Z", i % 160, i / 160)))
        .collect();
    let (min, max) = z
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    let mean = z.iter().sum::<f64>() / z.len() as f64;
    assert_eq!(layer("Z")["min"].as_f64(), Some(min));
    assert_eq!(layer("Z")["max"].as_f64(), Some(max));
    assert!((layer("Z")["mean"].as_f64().expect("mean") - mean).abs() < 1e-9);
    assert_eq!(layer("Z")["non_finite"], 0);
    let objectid = layer("objectid");
    assert_eq!(
        (objectid["min"].as_f64(), objectid["max"].as_f64()),
        (Some(1.0), Some(4.0))
    );
    assert_eq!(info["attributes"]["render/lights"], "0,1");
    assert_eq!(info["attributes"]["colorInteropID"], "lin_rec709_scene");

    let table = whitted(dir.path(), &["info", s(&golden)]);
    let text = String::from_utf8_lossy(&table.stdout).into_owned();
    assert!(
        text.starts_with(&format!(
            "{}: 160 x 120, 53 channels in 20 layers",
            golden.display()
        )),
        "{text}"
    );
    assert!(text
        .lines()
        .any(|l| l.starts_with("shadow_1") && l.contains("Y") && l.contains("float")));
}

#[test]
fn sheet_has_one_distinct_tile_per_layer() {
    let dir = tempfile::tempdir().expect("tempdir");
    let golden = reference("exr/tick2.exr");
    let run = whitted(
        dir.path(),
        &["sheet", s(&golden), "-o", "sheet.png", "--tile-width", "80"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let sheet = read_png(&dir.path().join("sheet.png"));
    // 20 layers in 4 columns of 80x60 tiles, 24-pixel captions and 8-pixel margins.
    let (columns, rows, tile_w, tile_h, caption, margin) = (4, 5, 80, 60, 24, 8);
    assert_eq!(
        sheet.width as usize,
        columns * tile_w + (columns + 1) * margin
    );
    assert_eq!(
        sheet.height as usize,
        rows * (tile_h + caption) + (rows + 1) * margin
    );
    let tile = |i: usize| -> Vec<u8> {
        let (x0, y0) = (
            margin + (i % columns) * (tile_w + margin),
            margin + (i / columns) * (tile_h + caption + margin) + caption,
        );
        (y0..y0 + tile_h)
            .flat_map(|y| {
                let start = (y * sheet.width as usize + x0) * 3;
                sheet.data[start..start + tile_w * 3].to_vec()
            })
            .collect()
    };
    let tiles: Vec<Vec<u8>> = (0..20).map(tile).collect();
    for (i, a) in tiles.iter().enumerate() {
        assert!(a.iter().any(|&v| v != a[0]), "tile {i} is flat");
        for (j, b) in tiles.iter().enumerate().skip(i + 1) {
            assert_ne!(a, b, "tiles {i} and {j} are identical");
        }
    }
    // A chosen subset, in the given order.
    let run = whitted(
        dir.path(),
        &[
            "sheet",
            s(&golden),
            "-o",
            "some.png",
            "--layers",
            "Z,beauty",
            "--columns",
            "2",
            "--tile-width",
            "80",
        ],
    );
    assert!(run.status.success());
    let some = read_png(&dir.path().join("some.png"));
    assert_eq!((some.width, some.height), (2 * 80 + 3 * 8, 60 + 24 + 2 * 8));
    let run = whitted(
        dir.path(),
        &["sheet", s(&golden), "-o", "bad.png", "--layers", "nope"],
    );
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("no layer `nope`"));
    assert!(!dir.path().join("bad.png").exists());
}
