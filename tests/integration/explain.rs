//! `whitted explain`: a pixel's ray tree whose beauty is what `render` stores, with the shadow
//! tests spelled out.

use crate::common::*;

#[test]
fn explained_beauty_is_what_render_stores() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let tick2 = scene("tick2.xml");
    let exr = render_exr(d, &tick2, "t.exr", &["--width", "160", "--height", "120"]);
    let exr = read_exr(&exr);
    let mut in_shadow = 0;
    for (x, y) in [(0, 0), (60, 75), (80, 60), (100, 50), (40, 90), (159, 119)] {
        let pixel = format!("{x},{y}");
        let run = whitted(
            d,
            &[
                "explain",
                "-i",
                tick2.to_str().expect("utf-8"),
                "--pixel",
                &pixel,
                "--width",
                "160",
                "--height",
                "120",
                "--json",
            ],
        );
        assert!(run.status.success(), "{}", stderr(&run));
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
        for (c, name) in ["R", "G", "B"].iter().enumerate() {
            let stored = f64::from(exr.at(name, x as usize, y as usize));
            assert_eq!(
                json["beauty"][c].as_f64(),
                Some(stored),
                "({x}, {y}) {name}"
            );
        }
        let vertices = json["vertices"].as_array().expect("vertices");
        in_shadow += vertices
            .iter()
            .flat_map(|v| v["lights"].as_array().cloned().unwrap_or_default())
            .filter(|l| l["in_shadow"] == true && l["occluder"]["object"].is_u64())
            .count();
        if let Some(first) = vertices.first() {
            assert_eq!(
                first["object"].as_f64(),
                Some(f64::from(exr.at("objectid.X", x as usize, y as usize)))
            );
        }
    }
    assert!(in_shadow > 0, "no shadowed light among the pixels");
    // The tree spells out the shadow tests.
    let run = whitted(d, &["explain", "--pixel", "250,300"]);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("blocked by object 2 (sphere)"), "{text}");
    assert!(text.contains("max(0, N.L) ="), "{text}");
    assert!(text.contains("fold (far end first)"), "{text}");
    let run = whitted(d, &["explain", "--pixel", "640,0"]);
    assert_eq!(run.status.code(), Some(2));
}

#[test]
fn explain_traces_a_mistake_as_the_program_with_it_would() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let json = |args: &[&str]| -> serde_json::Value {
        let mut all = vec!["explain", "--pixel", "250,300", "--json"];
        all.extend_from_slice(args);
        let run = whitted(d, &all);
        assert!(run.status.success(), "{}", stderr(&run));
        serde_json::from_slice(&run.stdout).expect("json")
    };
    let course = json(&[]);
    let flawed = json(&["--bug", "no-ambient", "--bug", "no-shadow-bias"]);
    assert_eq!(
        flawed["bugs"],
        serde_json::json!(["no-ambient", "no-shadow-bias"])
    );
    let (c, f) = (&course["vertices"][0], &flawed["vertices"][0]);
    assert_ne!(c["ambient"], serde_json::json!([0.0, 0.0, 0.0]));
    assert_eq!(f["ambient"], serde_json::json!([0.0, 0.0, 0.0]));
    // The shadow ray as spawned: P + EPSILON L for the course, P itself without the bias.
    assert_ne!(c["lights"][0]["shadow_origin"], c["P"]);
    assert_eq!(f["lights"][0]["shadow_origin"], f["P"]);
    // One bounce fewer: the chain stops a vertex earlier.
    let short = json(&["--bug", "bounces-minus-one", "-b", "1"]);
    assert_eq!(short["vertices"].as_array().map(Vec::len), Some(1));
    let run = whitted(d, &["explain", "--pixel", "1,1", "--bug", "no-ambeint"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("did you mean `no-ambient`"),
        "{}",
        stderr(&run)
    );
}

/// Under a later year the tree is that year's: its beauty is what `render --course` stores, and
/// a light the N.L gate keeps out has no terms and no shadow ray.
#[test]
fn a_later_year_s_tree_is_that_year_s_render() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let test2 = scene("courses/2021-24/test2.xml");
    let course = ["--course", "2021-22", "--width", "160", "--height", "120"];
    let exr = read_exr(&render_exr(d, &test2, "t.exr", &course));
    let mut gated = 0;
    for (x, y) in [(80, 10), (20, 100), (80, 60), (120, 70)] {
        let pixel = format!("{x},{y}");
        let mut args = vec!["explain", "-i", s(&test2), "--pixel", &pixel, "--json"];
        args.extend(course);
        let run = whitted(d, &args);
        assert!(run.status.success(), "{}", stderr(&run));
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
        for (c, name) in ["R", "G", "B"].iter().enumerate() {
            let stored = f64::from(exr.at(name, x as usize, y as usize));
            assert_eq!(
                json["beauty"][c].as_f64(),
                Some(stored),
                "({x}, {y}) {name}"
            );
        }
        let lights = json["vertices"][0]["lights"].as_array().expect("lights");
        for light in lights.iter().filter(|l| l["reaches"] == false) {
            gated += 1;
            assert_eq!(light["shadow_tested"], false, "{light}");
            assert_eq!(
                light["diffuse"],
                serde_json::json!([0.0, 0.0, 0.0]),
                "{light}"
            );
        }
    }
    // Light 0 sits above the ceiling plane: the ceiling's lower side never sees it.
    assert!(gated > 0);
    // A mistake of the year's catalogue is traced under the year's rules; one that is the
    // year's own rule is refused, clearly.
    let traced = whitted(
        d,
        &[
            "explain", "--pixel", "400,300", "--course", "2020-21", "--bug", "no-gate", "--json",
        ],
    );
    assert!(traced.status.success(), "{}", stderr(&traced));
    let refused = whitted(
        d,
        &[
            "explain",
            "--pixel",
            "1,1",
            "--course",
            "2020-21",
            "--bug",
            "view-from-ray-origin",
        ],
    );
    assert_eq!(refused.status.code(), Some(2));
    let message = stderr(&refused);
    assert!(
        message.contains("--bug view-from-ray-origin") && message.contains("2020-21"),
        "{message}"
    );
    assert_eq!(message.trim().lines().count(), 1);
}
