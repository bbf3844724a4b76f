//! A Tick 1* bump image drawn with both options on (soft shadows and depth of field, so
//! random), checked with `-i bump.xml` as without it (docs/check.md, "Tick 1*"): option 1's one
//! judge (`bump_judge.rs`) reads it as a draw of the bumped scene, whichever way it came. At
//! 160x120 under 2023-24; whitted's own draw is the correct student, our Java Tick 1*
//! (`check_star.rs`) the one with an inverted relief.

use std::path::Path;

use serde_json::Value;

use crate::check_star::java_image;
use crate::common::*;

const YEAR: &str = "2023-24";

/// The handout's bump.xml and its map, copied into `d`.
fn handout(d: &Path) {
    let handout = root().join("crates/check/scenes/tick1star");
    for file in ["bump.xml", "bumpmap.png"] {
        std::fs::copy(handout.join(file), d.join(file)).expect("copy");
    }
}

/// whitted's draw of bump.xml with both options on, seed `seed`, at 160x120, to `out`.
fn both_options_draw(d: &Path, seed: u32, out: &str) {
    let seed = seed.to_string();
    let run = whitted(
        d,
        &[
            "render",
            "-q",
            "--course",
            YEAR,
            "-i",
            "bump.xml",
            "-o",
            out,
            "--width",
            "160",
            "--height",
            "120",
            "--soft-shadows",
            "--dof",
            "--sampling",
            "course",
            "--seed",
            &seed,
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
}

/// `check --course 2023-24 ARGS --json`: its JSON and exit.
fn check_json(d: &Path, args: &[&str]) -> (Value, Option<i32>) {
    let mut all = vec!["check", "--course", YEAR, "--json"];
    all.extend(args);
    let out = whitted(d, &all);
    let json: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("{args:?}: {}", stderr(&out)));
    (json, out.status.code())
}

/// `check --course 2023-24 ARGS`: its text and exit.
fn check_text(d: &Path, args: &[&str]) -> (String, Option<i32>) {
    let mut all = vec!["check", "--course", YEAR];
    all.extend(args);
    let out = whitted(d, &all);
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        out.status.code(),
    )
}

#[test]
fn a_both_options_draw_passes_with_i_bump_xml_as_without_it() {
    let d = tempfile::tempdir().expect("tempdir");
    handout(d.path());
    both_options_draw(d.path(), 11, "draw.png");
    let (json, status) = check_json(d.path(), &["-i", "bump.xml", "draw.png"]);
    assert_eq!(status, Some(0), "{json}");
    assert_eq!(json["passed"], true, "{json}");
    let draw = &json["bump_draw"];
    assert_eq!(draw["verdict"], "bump-draw", "{json}");
    assert_eq!(draw["parametrisation"], "y-zx", "{json}");
    assert_eq!(draw["mistake"], Value::Null, "{json}");
    assert_eq!(draw["passes"], true, "{json}");
    let statistic = draw["statistic"].as_f64().expect("statistic");
    assert!((0.8..=1.45).contains(&statistic), "{statistic}");
    assert_eq!(json["bump"], Value::Null, "{json}");
    assert_eq!(json["star_not_done"], Value::Null, "{json}");
    // Without -i, the handout's scene judged as a program's image is: the same verdict.
    let (star, status) = check_json(d.path(), &["--star", "bump", "draw.png"]);
    assert_eq!(status, Some(0), "{star}");
    assert_eq!(star["tick1_star"]["verdict"], draw["verdict"], "{star}");
    let fit = &star["tick1_star"]["fits"][0];
    assert_eq!(fit["parametrisation"], "y-zx", "{star}");
    assert_eq!(fit["statistic"].as_f64(), Some(statistic), "{star}");
    // The text says the draw, and no Tick 1 diagnosis or worst pixel to trace.
    let (text, status) = check_text(d.path(), &["-i", "bump.xml", "draw.png"]);
    assert_eq!(status, Some(0), "{text}");
    for words in [
        "bump.xml, 160x120, 2 bounces: bump-draw",
        "progress: option 1 (bump mapping) done;",
        "one draw of the handout's bump mapping under parametrisation y-zx",
    ] {
        assert!(text.contains(words), "{words}: {text}");
    }
    for contradiction in ["diagnosis:", "differs (tolerance", "trace the worst pixel"] {
        assert!(!text.contains(contradiction), "{contradiction}: {text}");
    }
    // The report page's heading is the text's: the verdict, not the bytes' comparison.
    let (_, status) = check_text(
        d.path(),
        &["-i", "bump.xml", "--report", "r.html", "draw.png"],
    );
    assert_eq!(status, Some(0));
    let page = std::fs::read_to_string(d.path().join("r.html")).expect("report");
    assert!(
        page.contains("<strong>passes</strong>: bump.xml, 160x120, 2 bounces: bump-draw"),
        "{page}"
    );
    assert!(!page.contains("differs (tolerance"), "{page}");
}

#[test]
fn a_both_options_draw_with_an_inverted_relief_fails_naming_it_with_where_and_fix() {
    let d = tempfile::tempdir().expect("tempdir");
    let image = java_image(
        d.path(),
        "bump.xml",
        &["-Dbump=y-zx,inverted", "-Dseed=611"],
        "160x120",
        "inv.png",
    );
    let (json, status) = check_json(d.path(), &["-i", "bump.xml", s(&image)]);
    assert_eq!(status, Some(1), "{json}");
    assert_eq!(json["passed"], false, "{json}");
    let draw = &json["bump_draw"];
    assert_eq!(draw["verdict"], "bump-draw-mistake", "{json}");
    assert_eq!(draw["mistake"], "bump-inverted", "{json}");
    assert_eq!(draw["parametrisation"], "y-zx", "{json}");
    assert_eq!(draw["where"], "BumpySphere.getNormalAt", "{json}");
    assert!(
        draw["fix"]
            .as_str()
            .is_some_and(|f| f.starts_with("flip the sign")),
        "{json}"
    );
    let (statistic, correct) = (
        draw["statistic"].as_f64(),
        draw["statistic_correct"].as_f64(),
    );
    assert!(
        statistic
            .zip(correct)
            .is_some_and(|(m, c)| m <= 1.45 && c > 1.45),
        "{json}"
    );
    let (star, _) = check_json(d.path(), &["--star", "bump", s(&image)]);
    assert_eq!(star["tick1_star"]["verdict"], "bump-draw-mistake", "{star}");
    let (text, status) = check_text(d.path(), &["-i", "bump.xml", s(&image)]);
    assert_eq!(status, Some(1), "{text}");
    for words in [
        "bump.xml, 160x120, 2 bounces: bump-draw-mistake",
        "progress: option 1 (bump mapping) with a mistake",
        "a draw of bump-inverted under parametrisation y-zx",
        "where: BumpySphere.getNormalAt",
        "fix: flip the sign of the perturbation",
    ] {
        assert!(text.contains(words), "{words}: {text}");
    }
}
