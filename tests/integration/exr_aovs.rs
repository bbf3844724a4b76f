//! The AOV EXR against docs/aovs.md, checked with OpenImageIO's `oiiotool`/`idiff`, the OpenEXR
//! reference library's Python binding, and the `exr` crate.
//!
//! Sums use idiff with `-fail 1e-6 -failrelative 1e-5` (a value fails only when it is off by
//! more than 1e-6 absolute and 1e-5 relative), the tolerance docs/aovs.md states.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::common::*;

/// tick2.xml rendered once at 2 bounces with every AOV, shared by the tests here.
fn tick2_exr() -> &'static Path {
    static EXR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    let (_, path) = EXR.get_or_init(|| {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = render_exr(dir.path(), &scene("tick2.xml"), "tick2.exr", &[]);
        (dir, path)
    });
    path
}

/// `oiiotool` selection of layer `name`'s R, G, B renamed to bare R, G, B.
fn rgb_of(name: &str) -> String {
    if name.is_empty() {
        "R,G,B".into()
    } else {
        format!("R={name}.R,G={name}.G,B={name}.B")
    }
}

/// Writes the sum of `layers` of `exr` (as bare RGB) to `out` with `oiiotool --add`.
fn oiio_sum(exr: &Path, layers: &[&str], out: &Path) {
    let mut args: Vec<String> = Vec::new();
    for (i, layer) in layers.iter().enumerate() {
        args.extend([s(exr).to_string(), "--ch".into(), rgb_of(layer)]);
        if i > 0 {
            args.push("--add".into());
        }
    }
    args.extend(["-d".into(), "float".into(), "-o".into(), s(out).to_string()]);
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = run_tool("oiiotool", &argv, exr.parent().expect("dir"));
    assert!(
        run.status.success(),
        "oiiotool {argv:?}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// Whether idiff finds `a` and `b` equal within the stated tolerance.
fn idiff_equal(a: &Path, b: &Path) -> bool {
    let run = idiff_aov(a, b);
    match run.status.code() {
        Some(0) => true,
        Some(1 | 2) => false,
        other => panic!(
            "idiff failed to compare ({other:?}): {}",
            String::from_utf8_lossy(&run.stderr)
        ),
    }
}

/// Asserts that the sum of `layers` equals the sum of `expected` layers (bare RGB for "").
fn assert_sum(exr: &Path, layers: &[&str], expected_exr: &Path, expected: &[&str], label: &str) {
    let dir = exr.parent().expect("dir");
    let lhs = dir.join(format!("{label}_lhs.exr"));
    let rhs = dir.join(format!("{label}_rhs.exr"));
    oiio_sum(exr, layers, &lhs);
    oiio_sum(expected_exr, expected, &rhs);
    assert!(
        idiff_equal(&lhs, &rhs),
        "{label}: {layers:?} != {expected:?}"
    );
}

/// `Stats Min` / `Stats Max` of some channels, per channel, from `oiiotool --printstats`.
fn oiio_stats(exr: &Path, channels: &str) -> (Vec<f64>, Vec<f64>) {
    let run = run_tool(
        "oiiotool",
        &[s(exr), "--ch", channels, "--printstats"],
        exr.parent().expect("dir"),
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    let numbers = |key: &str| -> Vec<f64> {
        let line = text
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .unwrap_or_else(|| panic!("{key} in {text}"));
        line.split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect()
    };
    (numbers("Stats Min:"), numbers("Stats Max:"))
}

fn contract_channels(lights: &[&str], bounces: u32) -> Vec<String> {
    let mut want: Vec<String> = [
        "R",
        "G",
        "B",
        "A",
        "Z",
        "N.X",
        "N.Y",
        "N.Z",
        "P.X",
        "P.Y",
        "P.Z",
        "objectid.X",
    ]
    .iter()
    .map(|c| c.to_string())
    .collect();
    let mut colour = vec![
        "direct",
        "reflected",
        "ambient",
        "diffuse",
        "specular",
        "background",
        "albedo",
    ]
    .into_iter()
    .map(String::from)
    .collect::<Vec<_>>();
    colour.extend((1..=bounces).map(|k| format!("reflected_{k}")));
    for l in lights {
        colour.push(format!("light_{l}"));
        colour.push(format!("unshadowed_{l}"));
        want.push(format!("shadow_{l}.Y"));
    }
    for layer in colour {
        want.extend(["R", "G", "B"].iter().map(|c| format!("{layer}.{c}")));
    }
    want.sort();
    want
}

#[test]
fn oiiotool_reports_exactly_the_contract_channels() {
    let mut tick2 = oiio_channels(tick2_exr());
    tick2.sort();
    assert_eq!(tick2, contract_channels(&["0", "1"], 2));

    let dir = tempfile::tempdir().expect("tempdir");
    let exr = render_exr(
        dir.path(),
        &scene("coloured_lights.xml"),
        "three.exr",
        &["--bounces", "3"],
    );
    let mut three = oiio_channels(&exr);
    three.sort();
    assert_eq!(three, contract_channels(&["red", "green", "blue"], 3));
}

#[test]
fn the_openexr_reference_library_sees_the_same_channels() {
    let script = "import sys, OpenEXR\n\
                  f = OpenEXR.File(sys.argv[1], separate_channels=True)\n\
                  print(','.join(sorted(f.channels().keys())))\n\
                  print(len(f.parts))";
    let run = run_tool("python", &["-c", script, s(tick2_exr())], &root());
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let out = String::from_utf8_lossy(&run.stdout).into_owned();
    let mut lines = out.lines();
    let openexr: Vec<String> = lines
        .next()
        .expect("channels")
        .split(',')
        .map(String::from)
        .collect();
    let mut oiio = oiio_channels(tick2_exr());
    oiio.sort();
    assert_eq!(openexr, oiio);
    assert_eq!(lines.next(), Some("1"), "one part");
}

#[test]
fn invariants_1_to_5_hold_under_oiiotool() {
    let exr = tick2_exr();
    assert_sum(exr, &["direct", "reflected"], exr, &[""], "inv1");
    assert_sum(
        exr,
        &["reflected_1", "reflected_2"],
        exr,
        &["reflected"],
        "inv2",
    );
    assert_sum(
        exr,
        &["ambient", "light_0", "light_1", "background"],
        exr,
        &[""],
        "inv3",
    );
    assert_sum(
        exr,
        &["ambient", "diffuse", "specular", "background"],
        exr,
        &[""],
        "inv4",
    );
    for light in ["0", "1"] {
        let dir = exr.parent().expect("dir");
        let diff = dir.join(format!("inv5_{light}.exr"));
        let run = run_tool(
            "oiiotool",
            &[
                s(exr),
                "--ch",
                &rgb_of(&format!("unshadowed_{light}")),
                s(exr),
                "--ch",
                &rgb_of(&format!("light_{light}")),
                "--sub",
                "-o",
                s(&diff),
            ],
            dir,
        );
        assert!(run.status.success());
        let (min, max) = oiio_stats(&diff, "R,G,B");
        assert!(
            min.iter().all(|&m| m >= 0.0),
            "unshadowed_{light} - light_{light} min {min:?}"
        );
        assert!(
            max.iter().all(|&m| m > 0.0),
            "shadows of light {light} remove something: {max:?}"
        );
    }
}

#[test]
fn the_sums_can_fail() {
    // A wrong sum must be caught by the same machinery, or the checks above prove nothing.
    let exr = tick2_exr();
    let dir = exr.parent().expect("dir");
    oiio_sum(exr, &["direct"], &dir.join("only_direct.exr"));
    oiio_sum(exr, &[""], &dir.join("beauty_only.exr"));
    assert!(!idiff_equal(
        &dir.join("only_direct.exr"),
        &dir.join("beauty_only.exr")
    ));
}

#[test]
fn invariant_6_no_shadows_beauty_is_the_unshadowed_sum() {
    let dir = tempfile::tempdir().expect("tempdir");
    let no_shadows = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "noshadow.exr",
        &["--no-shadows"],
    );
    assert_sum(
        tick2_exr(),
        &["ambient", "unshadowed_0", "unshadowed_1", "background"],
        &no_shadows,
        &[""],
        "inv6",
    );
    // Without shadows nothing is occluded.
    let (_, max) = oiio_stats(&no_shadows, "shadow_0.Y,shadow_1.Y");
    assert_eq!(max, [0.0, 0.0]);
}

#[test]
fn invariant_7_bounces_0_has_no_reflection() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "b0.exr",
        &["--bounces", "0"],
    );
    let (min, max) = oiio_stats(&exr, "reflected.R,reflected.G,reflected.B");
    assert_eq!((min, max), (vec![0.0; 3], vec![0.0; 3]));
    assert_sum(&exr, &["direct"], &exr, &[""], "inv7");
    assert!(!oiio_channels(&exr)
        .iter()
        .any(|c| c.starts_with("reflected_")));
}

#[test]
fn fixnan_error_passes_and_nothing_is_non_finite() {
    let exr = tick2_exr();
    let dir = exr.parent().expect("dir");
    let run = run_tool(
        "oiiotool",
        &[s(exr), "--fixnan", "error", "-o", s(&dir.join("fixed.exr"))],
        dir,
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let run = run_tool("oiiotool", &[s(exr), "--printstats"], dir);
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    for key in ["Stats NanCount:", "Stats InfCount:"] {
        let line = text
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .expect(key);
        assert!(line.split_whitespace().all(|n| n == "0"), "{key} {line}");
    }
}

#[test]
fn header_attributes_are_present_and_correct() {
    use exr::prelude::AttributeValue;
    let exr = read_exr(tick2_exr());
    let text = |v: &Option<exr::prelude::Text>| v.as_ref().map(|t| t.to_string());
    assert_eq!(
        text(&exr.layer.software_name),
        Some(format!("whitted {}", env!("CARGO_PKG_VERSION")))
    );
    let comments = text(&exr.layer.comments).expect("comments");
    assert!(
        comments.contains("tick2.xml") && comments.contains("--bounces 2"),
        "{comments}"
    );
    assert!(exr.layer.layer_name.is_none(), "no part name");
    assert!(
        exr.layer.capture_date.is_none(),
        "no date unless --stamp-date"
    );
    let c = exr.image.chromaticities.expect("chromaticities");
    assert_eq!(
        (c.red.0, c.red.1, c.green.0, c.green.1),
        (0.64, 0.33, 0.30, 0.60)
    );
    assert_eq!(
        (c.blue.0, c.blue.1, c.white.0, c.white.1),
        (0.15, 0.06, 0.3127, 0.3290)
    );
    let world_to_camera = exr.layer.world_to_camera.expect("worldToCamera");
    assert_eq!(
        world_to_camera,
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    );
    assert!(exr.layer.world_to_normalized_device.is_some());
    let other = |name: &str| {
        exr.layer
            .other
            .iter()
            .chain(exr.image.other.iter())
            .find(|(k, _)| **k == *name)
            .map(|(_, v)| v.clone())
            .unwrap_or_else(|| panic!("attribute {name} missing"))
    };
    assert_eq!(
        other("colorInteropID"),
        AttributeValue::Text("lin_rec709_scene".into())
    );
    assert_eq!(other("render/bounces"), AttributeValue::I32(2));
    assert_eq!(other("render/spp"), AttributeValue::I32(1));
    assert_eq!(other("render/shadows"), AttributeValue::I32(1));
    assert_eq!(other("render/lights"), AttributeValue::Text("0,1".into()));
    assert_eq!(other("render/zMiss"), AttributeValue::F32(1e10));
    match other("render/invariants") {
        AttributeValue::Text(t) => assert!(t.to_string().contains("RGB = direct + reflected")),
        v => panic!("render/invariants is {v:?}"),
    }
    // Stored the way docs/aovs.md asks: float, scanlines, ZIP, increasing lines.
    let meta = exr::meta::MetaData::read_from_file(tick2_exr(), false).expect("meta");
    let header = &meta.headers[0];
    assert_eq!(header.compression, exr::prelude::Compression::ZIP16);
    assert_eq!(header.blocks, exr::meta::BlockDescription::ScanLines);
    assert_eq!(header.line_order, exr::prelude::LineOrder::Increasing);
    assert_eq!(
        header.shared_attributes.display_window,
        header.data_window()
    );
    assert!(header
        .channels
        .list
        .iter()
        .all(|c| c.sample_type == exr::prelude::SampleType::F32));
    // Linear data, never flagged as perceptually encoded.
    let flagged: Vec<String> = header
        .channels
        .list
        .iter()
        .filter(|c| c.quantize_linearly)
        .map(|c| c.name.to_string())
        .collect();
    assert!(flagged.is_empty(), "pLinear on {flagged:?}");
}

#[test]
fn stamp_date_adds_a_capture_date() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "dated.exr",
        &[
            "--stamp-date",
            "--aovs",
            "beauty",
            "--width",
            "32",
            "--height",
            "24",
        ],
    );
    let date = read_exr(&exr)
        .layer
        .capture_date
        .expect("capDate")
        .to_string();
    assert_eq!(date.len(), "YYYY:MM:DD hh:mm:ss".len(), "{date}");
    assert_eq!(&date[4..5], ":");
}

/// The course's camera ray for pixel (x, y), computed here independently of the renderer.
fn camera_ray(x: u32, y: u32, width: u32, height: u32) -> [f64; 3] {
    let w = 2.0 * (22.5f64).to_radians().tan();
    let h = w / (f64::from(width) / f64::from(height));
    let step = w / f64::from(width);
    let (px, py) = (
        (step - w) / 2.0 + f64::from(x) * step,
        (step + h) / 2.0 - f64::from(y) * step,
    );
    let len = (px * px + py * py + 1.0).sqrt();
    [px / len, py / len, 1.0 / len]
}

#[test]
fn data_layers_hold_hand_computed_geometry() {
    // Object 1: a floor at y = -2 facing up; object 2: a unit sphere at (0, 0, 5).
    let dir = tempfile::tempdir().expect("tempdir");
    let scene_file = write_scene(
        dir.path(),
        "geometry.xml",
        r##"<scene>
  <point-light x="0" y="5" z="0" colour="#FFFFFF"/>
  <plane x="0" y="-2" z="0" nx="0" ny="1" nz="0" colour="#336699"/>
  <sphere x="0" y="0" z="5" radius="1" colour="#CC8844"/>
</scene>"##,
    );
    let (width, height) = (160, 120);
    let exr = render_exr(
        dir.path(),
        &scene_file,
        "g.exr",
        &["--width", "160", "--height", "120"],
    );
    let exr = read_exr(&exr);
    let close = |a: f32, b: f64, what: &str| {
        assert!(
            (f64::from(a) - b).abs() <= 1e-5 * (1.0 + b.abs()),
            "{what}: {a} vs {b}"
        )
    };

    // A pixel near the centre hits the sphere: s = D.C - sqrt((D.C)^2 - (|C|^2 - 1)).
    let (x, y) = (82, 57);
    let d = camera_ray(x, y, width, height);
    let dc = 5.0 * d[2];
    let t = dc - (dc * dc - 24.0).sqrt();
    let p = [t * d[0], t * d[1], t * d[2]];
    let (x, y) = (x as usize, y as usize);
    close(exr.at("Z", x, y), p[2], "sphere Z");
    close(exr.at("P.X", x, y), p[0], "sphere P.X");
    close(exr.at("P.Y", x, y), p[1], "sphere P.Y");
    close(exr.at("N.X", x, y), p[0], "sphere N.X");
    close(exr.at("N.Z", x, y), p[2] - 5.0, "sphere N.Z");
    close(exr.at("objectid.X", x, y), 2.0, "sphere id");
    close(exr.at("albedo.R", x, y), 204.0 / 255.0, "sphere albedo");

    // The bottom-left pixel hits the floor: s = -2 / D.y.
    let (x, y) = (0, 119);
    let d = camera_ray(x, y, width, height);
    let t = -2.0 / d[1];
    let (x, y) = (x as usize, y as usize);
    close(exr.at("Z", x, y), t * d[2], "floor Z");
    close(exr.at("P.X", x, y), t * d[0], "floor P.X");
    close(exr.at("P.Y", x, y), -2.0, "floor P.Y");
    close(exr.at("N.Y", x, y), 1.0, "floor N.Y");
    close(exr.at("objectid.X", x, y), 1.0, "floor id");

    // The top-left pixel looks up into the background: data layers are 0 there, and Z is
    // "far".
    assert_eq!(exr.at("Z", 0, 0), 1e10, "Z on a miss");
    for c in [
        "N.X",
        "N.Y",
        "N.Z",
        "P.X",
        "P.Y",
        "P.Z",
        "objectid.X",
        "albedo.R",
    ] {
        assert_eq!(exr.at(c, 0, 0), 0.0, "{c} on a miss");
    }
    assert_eq!(exr.at("A", 0, 0), 1.0);
    close(exr.at("R", 0, 0), 0.1, "background");
}

#[test]
fn shadow_masks_mark_the_light_that_is_blocked() {
    // A floor lit by two lights; a sphere on the line from floor point (1, -1, 5) to the left
    // light blocks it there, while the right light still reaches that point.
    let dir = tempfile::tempdir().expect("tempdir");
    let scene_file = write_scene(
        dir.path(),
        "masks.xml",
        r##"<scene>
  <point-light x="-3" y="3" z="5" colour="#FFFFFF" name="left"/>
  <point-light x="3" y="3" z="5" colour="#FFFFFF" name="right"/>
  <sphere x="-1" y="1" z="5" radius="0.5" colour="#FFFFFF"/>
  <plane x="0" y="-1" z="0" nx="0" ny="1" nz="0" colour="#808080"/>
</scene>"##,
    );
    let exr = render_exr(
        dir.path(),
        &scene_file,
        "m.exr",
        &["--width", "160", "--height", "120"],
    );
    let exr = read_exr(&exr);
    // (1, -1, 5) projects to x_plane = 0.2, y_plane = -0.2: pixel (118.6, 98.9) at 160x120.
    let (x, y) = (118, 98);
    assert_eq!(exr.at("P.Y", x, y), -1.0, "the pixel sees the floor");
    assert_eq!(exr.at("shadow_left.Y", x, y), 1.0);
    assert_eq!(exr.at("shadow_right.Y", x, y), 0.0);
    assert_eq!(exr.at("light_left.R", x, y), 0.0);
    assert!(exr.at("unshadowed_left.R", x, y) > 0.0);
    assert!(exr.at("light_right.R", x, y) > 0.0);
    // The mirror-image point (-1, -1, 5) is lit by the left light: masks are 0 there.
    let (x, y) = (41, 98);
    assert_eq!(exr.at("shadow_left.Y", x, y), 0.0);
}

#[test]
fn aovs_selects_layers_and_rejects_unknown_names() {
    let dir = tempfile::tempdir().expect("tempdir");
    let small = ["--width", "32", "--height", "24"];
    let mut args = vec!["--aovs", "direct,shadow_1,Z"];
    args.extend_from_slice(&small);
    let exr = render_exr(dir.path(), &scene("tick2.xml"), "some.exr", &args);
    let mut names = read_exr(&exr).names();
    names.sort();
    assert_eq!(
        names,
        [
            "A",
            "B",
            "G",
            "R",
            "Z",
            "direct.B",
            "direct.G",
            "direct.R",
            "shadow_1.Y"
        ]
    );

    let mut args = vec!["--aovs", "beauty"];
    args.extend_from_slice(&small);
    let exr = render_exr(dir.path(), &scene("tick2.xml"), "beauty.exr", &args);
    assert_eq!(read_exr(&exr).names().len(), 4);

    let run = whitted(
        dir.path(),
        &["render", "--exr", "bad.exr", "--aovs", "direct,shadw_0"],
    );
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("unknown AOV layer `shadw_0`") && err.contains("did you mean `shadow_0`?"),
        "{err}"
    );
    assert!(
        err.contains("light_1") && err.contains("reflected_2"),
        "lists valid names: {err}"
    );
    assert!(!dir.path().join("bad.exr").exists());
}

#[test]
fn half_clamps_colour_layers_and_keeps_data_layers_float() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene_file = write_scene(
        dir.path(),
        "bright.xml",
        r##"<scene>
  <point-light x="0" y="0" z="0" colour="#FFFFFF" intensity="1e12"/>
  <sphere x="0" y="0" z="5" radius="1" colour="#FFFFFF"/>
</scene>"##,
    );
    let exr = render_exr(
        dir.path(),
        &scene_file,
        "h.exr",
        &["--half", "--width", "32", "--height", "24"],
    );
    let image = read_exr(&exr);
    let (x, y) = (16, 12);
    assert_eq!(image.at("R", x, y), 65504.0, "clamped to the largest half");
    assert_eq!(image.at("direct.G", x, y), 65504.0);
    for (name, samples) in &image.channels {
        let is_data = ["Z", "N.", "P.", "albedo.", "objectid.", "shadow_"]
            .iter()
            .any(|p| name.starts_with(p));
        match samples {
            exr::prelude::FlatSamples::F16(v) => {
                assert!(!is_data, "{name} should stay float");
                assert!(v.iter().all(|h| h.is_finite()), "{name} has Inf");
            }
            exr::prelude::FlatSamples::F32(_) => assert!(is_data, "{name} should be half"),
            exr::prelude::FlatSamples::U32(_) => panic!("{name} is u32"),
        }
    }
    let (_, max) = oiio_stats(&exr, "R,G,B");
    assert!(max.iter().all(|&m| m == 65504.0), "{max:?}");
}

#[test]
fn every_compression_stores_the_same_pixels() {
    let dir = tempfile::tempdir().expect("tempdir");
    let base = ["--width", "48", "--height", "36"];
    let reference = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "none.exr",
        &[&base[..], &["--compression", "none"]].concat(),
    );
    for c in ["rle", "zips", "zip", "piz"] {
        let exr = render_exr(
            dir.path(),
            &scene("tick2.xml"),
            &format!("{c}.exr"),
            &[&base[..], &["--compression", c]].concat(),
        );
        let run = run_tool(
            "idiff",
            &["-fail", "0", "-warn", "0", s(&reference), s(&exr)],
            dir.path(),
        );
        assert_eq!(
            run.status.code(),
            Some(0),
            "{c}: {}",
            String::from_utf8_lossy(&run.stdout)
        );
    }
}

#[test]
fn exr_bytes_are_identical_for_any_thread_count_and_output_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let one = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "one.exr",
        &["--threads", "1"],
    );
    let two = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "two.exr",
        &["--threads", "2"],
    );
    assert!(std::fs::read(one).expect("read") == std::fs::read(two).expect("read"));
    assert!(
        std::fs::read(tick2_exr()).expect("read")
            == std::fs::read(dir.path().join("one.exr")).expect("read")
    );
}

/// Blocks are compressed in the background and finish in any order; they must still be
/// written in order: one-line blocks (many per strip) and a height that leaves a short last
/// strip, on one to three threads.
#[test]
fn background_compression_writes_blocks_in_order_for_any_thread_count() {
    let dir = tempfile::tempdir().expect("tempdir");
    let render = |threads: &str, compression: &str| {
        let name = format!("t{threads}{compression}.exr");
        let args = [
            "--threads",
            threads,
            "--compression",
            compression,
            "--width",
            "97",
            "--height",
            "203",
        ];
        render_exr(dir.path(), &scene("tick2.xml"), &name, &args)
    };
    let bytes = |path: PathBuf| std::fs::read(path).expect("read");
    let one = bytes(render("1", "zips"));
    assert!(one == bytes(render("2", "zips")));
    assert!(one == bytes(render("3", "zips")));
    let zips = read_exr(&dir.path().join("t1zips.exr"));
    let none = read_exr(&render("3", "none"));
    assert_eq!((zips.width, zips.height), (97, 203));
    for y in 0..203 {
        for x in 0..97 {
            for c in ["R", "Z", "direct.G"] {
                assert_eq!(
                    zips.at(c, x, y).to_bits(),
                    none.at(c, x, y).to_bits(),
                    "{c} {x},{y}"
                );
            }
        }
    }
}

#[test]
fn tick_tone_map_of_the_exr_beauty_is_the_tick_png() {
    // Invariant 8: within 1 LSB, and only where f32 storage rounds across a step: there the
    // stored value lies within half an f32 ulp of a step k/255 (no share is promised).
    let exr = read_exr(tick2_exr());
    let png = read_png(&reference("tick2_b2.png"));
    let channels = if png.color == png::ColorType::Rgba {
        4
    } else {
        3
    };
    let mut off_by_one = 0;
    for y in 0..exr.height {
        for x in 0..exr.width {
            for (c, name) in ["R", "G", "B"].iter().enumerate() {
                let v = f64::from(exr.at(name, x, y));
                let byte = (255.0 * v.clamp(0.0, 1.0)) as i32;
                let want = i32::from(png.data[(y * exr.width + x) * channels + c]);
                assert!(
                    (byte - want).abs() <= 1,
                    "({x}, {y}) {name}: {byte} vs {want}"
                );
                if byte != want {
                    let stored = exr.at(name, x, y);
                    let half_ulp = f64::from(f32::from_bits(stored.to_bits() + 1) - stored) / 2.0;
                    let scaled = 255.0 * f64::from(stored);
                    assert!(
                        (scaled - scaled.round()).abs() <= 255.0 * half_ulp,
                        "({x}, {y}) {name}: {stored} is off by one but not at a step"
                    );
                    off_by_one += 1;
                }
            }
        }
    }
    eprintln!("{off_by_one} values off by one, each at a quantisation step");
}

/// The streamed writer against OpenEXR's own reader: every codec, half colour layers, a data
/// window that is a region, and a height that is no multiple of a strip or a block, read by
/// the reference library to exactly the values of the uncompressed file.
#[test]
fn the_openexr_library_reads_every_codec_to_the_same_values() {
    let dir = tempfile::tempdir().expect("tempdir");
    let base = ["--width", "53", "--height", "150", "--region", "3,5,50,147"];
    let mut files = Vec::new();
    for half in [false, true] {
        for c in ["none", "rle", "zips", "zip", "piz"] {
            let name = format!("{c}{}.exr", if half { "-half" } else { "" });
            let mut args = [&base[..], &["--compression", c]].concat();
            if half {
                args.push("--half");
            }
            files.push(render_exr(dir.path(), &scene("tick2.xml"), &name, &args));
        }
    }
    let script = "import sys, OpenEXR, numpy\n\
                  def read(p):\n\
                  \x20   f = OpenEXR.File(p, separate_channels=True)\n\
                  \x20   return {k: numpy.asarray(c.pixels) for k, c in f.channels().items()}\n\
                  for group in (sys.argv[1:6], sys.argv[6:11]):\n\
                  \x20   first = read(group[0])\n\
                  \x20   assert len(first) == 53, len(first)\n\
                  \x20   assert first['R'].shape == (142, 47), first['R'].shape\n\
                  \x20   for p in group[1:]:\n\
                  \x20       other = read(p)\n\
                  \x20       assert other.keys() == first.keys(), p\n\
                  \x20       for k in first:\n\
                  \x20           assert numpy.array_equal(first[k], other[k]), (p, k)\n\
                  print('ok')";
    let mut args = vec!["-c", script];
    args.extend(files.iter().map(|f| s(f)));
    let run = run_tool("python", &args, dir.path());
    assert_eq!(
        String::from_utf8_lossy(&run.stdout).trim(),
        "ok",
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// A later year's render: its layers still add up to the beauty (the N.L gate and the
/// doubled light colour land in the light and specular layers, not in a layer of their own),
/// the header names the year, and `tonemap` of the EXR gives the year's PNG.
#[test]
fn a_later_year_s_layers_add_up_and_its_header_names_the_year() {
    use exr::prelude::AttributeValue;
    let dir = tempfile::tempdir().expect("tempdir");
    let exr_path = render_exr(
        dir.path(),
        &scene("courses/2021-24/test1.xml"),
        "y.exr",
        &["--course", "2021-22"],
    );
    let png = whitted(
        dir.path(),
        &[
            "render",
            "--course",
            "2021-22",
            "-i",
            s(&scene("courses/2021-24/test1.xml")),
            "-o",
            "render.png",
        ],
    );
    assert!(png.status.success(), "{}", stderr(&png));
    assert_sum(&exr_path, &["direct", "reflected"], &exr_path, &[""], "y1");
    assert_sum(
        &exr_path,
        &["ambient", "light_0", "light_1", "background"],
        &exr_path,
        &[""],
        "y3",
    );
    assert_sum(
        &exr_path,
        &["ambient", "diffuse", "specular", "background"],
        &exr_path,
        &[""],
        "y4",
    );
    let exr = read_exr(&exr_path);
    assert_eq!((exr.width, exr.height), (800, 600));
    let course = exr
        .layer
        .other
        .iter()
        .chain(exr.image.other.iter())
        .find(|(k, _)| **k == *"render/course")
        .map(|(_, v)| v.clone());
    assert_eq!(course, Some(AttributeValue::Text("2021-22".into())));
    // The background is the year's 0.001 (times the mirrors' r = 0.3 on the way) where a ray
    // leaves the scene, 0.1 in 2016-17.
    let mut seen: Vec<f32> = (0..exr.height)
        .flat_map(|y| (0..exr.width).map(move |x| (x, y)))
        .map(|(x, y)| exr.at("background.R", x, y))
        .filter(|&v| v > 0.0)
        .collect();
    seen.sort_by(f32::total_cmp);
    seen.dedup();
    // test1's plane fills the frame: rays leave the scene after one or two mirrors.
    let shares: Vec<f64> = seen.iter().map(|&v| f64::from(v) / 0.001).collect();
    assert_eq!(shares.len(), 2, "{seen:?}");
    assert!(
        (shares[0] - 0.09).abs() < 1e-6 && (shares[1] - 0.3).abs() < 1e-6,
        "{seen:?}"
    );
    // The year's tone map is what `tonemap` applies to this EXR by default.
    let run = whitted(dir.path(), &["tonemap", s(&exr_path), "-o", "again.png"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(
        read_png(&dir.path().join("again.png")).data,
        read_png(&dir.path().join("render.png")).data
    );
    // A 2016-17 file records no year: its header is as it was before there were years.
    let old = read_exr(tick2_exr());
    assert!(!old
        .layer
        .other
        .iter()
        .chain(old.image.other.iter())
        .any(|(k, _)| *k == *"render/course"));
}
