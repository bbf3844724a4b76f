//! Regression tools as CI and people use them: `diff` sees moved images and every part of a
//! file, has idiff-style thresholds, reads the course's JPEGs; `info --json` is typed;
//! completions and the manual page exist.

use std::path::{Path, PathBuf};

use crate::common::*;

fn oiiotool(dir: &Path, args: &[&str]) {
    let run = run_tool("oiiotool", args, dir);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// A small render of tick2 with every AOV.
fn small_exr(dir: &Path) -> PathBuf {
    render_exr(
        dir,
        &scene("tick2.xml"),
        "a.exr",
        &["--width", "32", "--height", "24"],
    )
}

#[test]
fn a_moved_image_is_a_difference_with_both_windows_reported() {
    let dir = tempfile::tempdir().expect("tempdir");
    small_exr(dir.path());
    oiiotool(
        dir.path(),
        &["a.exr", "--origin", "+10+10", "-o", "moved.exr"],
    );
    let run = whitted(dir.path(), &["diff", "moved.exr", "a.exr"]);
    let out = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(1), "{out}");
    assert!(
        out.contains("data windows differ: (10, 10) - (41, 33) vs (0, 0) - (31, 23)"),
        "{out}"
    );
    // A different frame cannot be compared at all.
    let other = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "b.exr",
        &["--width", "16", "--height", "12"],
    );
    let run = whitted(dir.path(), &["diff", s(&other), "a.exr"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("display windows differ"),
        "{}",
        stderr(&run)
    );
}

#[test]
fn every_part_of_a_multi_part_file_is_compared() {
    let dir = tempfile::tempdir().expect("tempdir");
    small_exr(dir.path());
    let d = dir.path();
    oiiotool(d, &["a.exr", "--ch", "R,G,B,A", "-o", "rgba.exr"]);
    oiiotool(d, &["rgba.exr", "--addc", "0,0,0.25,0", "-o", "bluer.exr"]);
    oiiotool(d, &["rgba.exr", "rgba.exr", "--siappend", "-o", "same.exr"]);
    oiiotool(
        d,
        &["rgba.exr", "bluer.exr", "--siappend", "-o", "changed.exr"],
    );
    let run = whitted(d, &["diff", "same.exr", "same.exr"]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let run = whitted(d, &["diff", "--json", "changed.exr", "same.exr"]);
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    let parts = json["parts"].as_array().expect("parts");
    assert_eq!(parts.len(), 2);
    assert_eq!(parts[0]["passed"], true);
    assert_eq!(parts[1]["passed"], false);
    // Different numbers of parts cannot be compared.
    let run = whitted(d, &["diff", "rgba.exr", "same.exr"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("1 and 2 parts"), "{}", stderr(&run));
}

#[test]
fn thresholds_allow_share_count_hard_limit_and_warnings() {
    let dir = tempfile::tempdir().expect("tempdir");
    small_exr(dir.path());
    let d = dir.path();
    // One pixel of the beauty changed.
    oiiotool(d, &["a.exr", "--ch", "R,G,B,A", "-o", "rgba.exr"]);
    oiiotool(
        d,
        &[
            "rgba.exr",
            "--fill:color=0.5,0.5,0.5,1",
            "1x1+5+5",
            "-o",
            "pixel.exr",
        ],
    );
    let code = |extra: &[&str]| {
        let mut args = vec!["diff", "pixel.exr", "rgba.exr"];
        args.extend_from_slice(extra);
        let run = whitted(d, &args);
        (
            run.status.code(),
            String::from_utf8_lossy(&run.stdout).into_owned(),
        )
    };
    let json: serde_json::Value = serde_json::from_str(&code(&["--json"]).1).expect("json");
    let changed = json["layers"][0]["max_abs"].as_f64().expect("max_abs");
    assert!(changed > 0.01, "{changed}");
    let (half, double) = ((changed / 2.0).to_string(), (changed * 2.0).to_string());
    assert_eq!(code(&[]).0, Some(1), "one changed pixel fails by default");
    assert_eq!(
        code(&["--fail-percent", "1"]).0,
        Some(0),
        "1% of 768 allows 7"
    );
    assert_eq!(code(&["--allow-failures", "1"]).0, Some(0));
    assert_eq!(
        code(&["--allow-failures", "1", "--hard-fail", &half]).0,
        Some(1)
    );
    let (status, out) = code(&["--abs", &double, "--warn", &half]);
    assert_eq!(status, Some(0), "{out}");
    assert!(out.contains("PASS with 1 warnings"), "{out}");
}

#[test]
fn a_student_png_is_compared_with_the_course_jpeg() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("mine.png");
    let render = whitted(
        dir.path(),
        &["-q", "-i", s(&scene("specular_test.xml")), "-o", s(&png)],
    );
    assert!(render.status.success());
    let jpeg = reference("specular_test_correct_solution.jpg");
    let run = whitted(dir.path(), &["diff", "--json", s(&png), s(&jpeg)]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    let beauty = &json["layers"][0];
    let psnr = beauty["psnr"].as_f64().expect("a PSNR");
    assert!((30.0..60.0).contains(&psnr), "PSNR {psnr}");
    // JPEG noise fails the default tolerance; a tolerance for it passes.
    assert_eq!(run.status.code(), Some(1));
    let run = whitted(
        dir.path(),
        &[
            "diff",
            s(&png),
            s(&jpeg),
            "--abs",
            "0.06",
            "--rel",
            "0",
            "--fail-percent",
            "1",
        ],
    );
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stdout)
    );
    // The contact sheet reads rasters too, and shows their display values as they are.
    let sheet = whitted(dir.path(), &["sheet", s(&jpeg), "-o", "sheet.png"]);
    assert!(sheet.status.success(), "{}", stderr(&sheet));
    let tile = read_png(&dir.path().join("sheet.png"));
    let distinct: std::collections::HashSet<&[u8]> = tile.data.chunks(3).collect();
    assert!(distinct.len() > 50, "{} colours", distinct.len());
    let info = whitted(dir.path(), &["info", "--json", s(&jpeg)]);
    let info: serde_json::Value = serde_json::from_slice(&info.stdout).expect("json");
    assert_eq!(
        (info["format"].as_str(), info["width"].as_u64()),
        (Some("jpeg"), Some(640))
    );
}

#[test]
fn info_json_is_typed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = small_exr(dir.path());
    let run = whitted(dir.path(), &["info", "--json", s(&exr)]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    let attributes = &json["attributes"];
    assert_eq!(attributes["render/bounces"], 2);
    assert_eq!(attributes["render/spp"], 1);
    assert_eq!(attributes["render/zMiss"], 1e10);
    assert_eq!(
        attributes["dataWindow"],
        serde_json::json!({"min": [0, 0], "max": [31, 23]})
    );
    assert_eq!(json["display_window"]["max"], serde_json::json!([31, 23]));
    let matrix = attributes["worldToCamera"].as_array().expect("rows");
    assert_eq!(matrix.len(), 4);
    assert_eq!(matrix[0], serde_json::json!([1.0, 0.0, 0.0, 0.0]));
    // The beauty's statistics are over R, G, B: alpha (1 everywhere) is not colour.
    let read = read_exr(&exr);
    let mean: f64 = ["R", "G", "B"]
        .iter()
        .flat_map(|c| (0..32 * 24).map(move |i| (*c, i)))
        .map(|(c, i)| f64::from(read.at(c, i % 32, i / 32)))
        .sum::<f64>()
        / (3.0 * 32.0 * 24.0);
    let beauty = json["layers"]
        .as_array()
        .expect("layers")
        .iter()
        .find(|l| l["name"] == "beauty")
        .expect("beauty");
    assert!((beauty["mean"].as_f64().expect("mean") - mean).abs() < 1e-9);
}

#[test]
fn completions_and_the_manual_page_are_generated() {
    let dir = tempfile::tempdir().expect("tempdir");
    let bash = whitted(dir.path(), &["completions", "bash"]);
    assert!(bash.status.success());
    let script = String::from_utf8_lossy(&bash.stdout);
    assert!(
        script.contains("_whitted()") && script.contains("--tonemap"),
        "{script}"
    );
    let zsh = whitted(dir.path(), &["completions", "zsh"]);
    assert!(String::from_utf8_lossy(&zsh.stdout).contains("#compdef whitted"));
    let man = whitted(dir.path(), &["man"]);
    let page = String::from_utf8_lossy(&man.stdout);
    assert!(
        man.status.success() && page.contains(".TH whitted 1"),
        "{page}"
    );
    assert!(page.contains("merge"), "subcommands are listed");
    // Every page the SUBCOMMANDS section names is written with --dir.
    let pages = dir.path().join("man1");
    std::fs::create_dir(&pages).expect("dir");
    let run = whitted(dir.path(), &["man", "--dir", "man1"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let named: Vec<&str> = page
        .lines()
        .filter_map(|l| l.strip_suffix("(1)"))
        .filter(|l| l.starts_with("whitted"))
        .collect();
    assert!(named.len() >= 12, "{named:?}");
    for name in std::iter::once("whitted").chain(named.iter().copied()) {
        let file = pages.join(format!("{}.1", name.replace("\\-", "-")));
        let text =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert!(text.contains(".TH"), "{}", file.display());
    }
    let run = whitted(dir.path(), &["man", "--dir", "nowhere"]);
    assert_eq!(run.status.code(), Some(2));
}
