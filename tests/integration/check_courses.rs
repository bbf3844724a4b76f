//! `whitted check --course YEAR --program` against a real Java Tick 1 of the later years
//! (`tests/java/.../tick1/Tick1.java`, written from docs/courses.md; its year is
//! `-Dcourse=YEAR`, its mistakes `-Dbug=ID`, written as students write them): the correct
//! program passes, each mistake is named first with the year's progress keys, the common
//! variant is named as both its mistakes, a Tick 1 program is never checked as 2016-17's
//! in silence, a student's own sphere arithmetic (`-Dsphere=geometric`) is no mistake, and
//! Tick 1*'s random soft shadows are called noise, not mistakes.

use serde_json::Value;

use crate::common::*;

/// Our Java Tick 1 of `course` with the mistakes `bugs`, as one --program string.
fn program(course: &str, bugs: &[&str]) -> String {
    program_with(course, "", bugs)
}

/// The same with the JVM options `flags` (`-Dsphere=geometric `, `-Dstar=soft-shadows `).
fn program_with(course: &str, flags: &str, bugs: &[&str]) -> String {
    java_program_with(Some(course), flags, bugs)
}

/// The JSON of `check --course course --program ...` and its exit status.
fn check(course: &str, bugs: &[&str]) -> (Value, Option<i32>) {
    check_json(course, &program(course, bugs))
}

/// The JSON of `check --course course --program program` and its exit status.
fn check_json(course: &str, program: &str) -> (Value, Option<i32>) {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = check_program(dir.path(), course, program, &["--json"]);
    let json: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("{program}: {}", stderr(&out)));
    (json, out.status.code())
}

/// `whitted check --course course --program program EXTRA...` in `dir`.
fn check_program(
    dir: &std::path::Path,
    course: &str,
    program: &str,
    extra: &[&str],
) -> std::process::Output {
    let mut args = vec!["check", "--course", course, "--program", program];
    args.extend_from_slice(extra);
    whitted(dir, &args)
}

/// The ids of the top diagnosis and of its twins.
fn top(json: &Value) -> Vec<Vec<String>> {
    let Some(first) = json["diagnosis"].get(0) else {
        return Vec::new();
    };
    let ids = |v: &Value| -> Vec<String> {
        v.as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|s| s.as_str().map(String::from))
                    .collect()
            })
            .unwrap_or_default()
    };
    let mut all = vec![ids(&first["bugs"])];
    if let Some(twins) = first["indistinguishable_from"].as_array() {
        all.extend(twins.iter().map(ids));
    }
    all
}

fn assert_named_first(course: &str, bugs: &[&str]) {
    let (json, status) = check(course, bugs);
    assert_names_first(course, bugs, &json, status);
}

/// That the check `json` (exit `status`) of a `course` program with `bugs` fails and names
/// them first, with the year's progress keys.
fn assert_names_first(course: &str, bugs: &[&str], json: &Value, status: Option<i32>) {
    assert_eq!(status, Some(1), "{course} {bugs:?} fails the suite");
    let mut wanted: Vec<String> = bugs.iter().map(|s| s.to_string()).collect();
    wanted.sort();
    let named = top(json);
    let found = named.iter().any(|ids| {
        let mut ids = ids.clone();
        ids.sort();
        ids == wanted
    });
    assert!(found, "{course} {bugs:?}: named {named:?}");
    assert_eq!(json["course"], course);
    let keys: Vec<&String> = json["progress"]
        .as_object()
        .expect("progress")
        .keys()
        .collect();
    for key in ["spheres", "shading", "planes", "shadows", "reflection"] {
        assert!(keys.iter().any(|k| *k == key), "{key} in {keys:?}");
    }
}

/// Every mistake the Java program makes (each shows on the year's suite).
const SHOWN: [&str; 28] = [
    "view-flipped",
    "no-shadow-bias",
    "no-reflection-bias",
    "plane-behind",
    "light-unnormalised",
    "no-falloff",
    "no-ambient",
    "diffuse-no-colour",
    "specular-object-colour",
    "first-light-only",
    "last-light-wins",
    "no-shadows",
    "shadow-any-hit",
    "reflection-wrong-sign",
    "reflection-unweighted",
    "rv-unclamped",
    "planes-missing",
    "reflection-ignored",
    "view-to-camera",
    "no-gate",
    "specular-white",
    "shadow-bias-along-l",
    "reflection-bias-along-n",
    "tonemap-missing",
    "tonemap-twice",
    "spheres-missing",
    "shading-missing",
    "background-changed",
];

#[test]
fn a_correct_program_of_each_later_year_passes() {
    for course in [
        "2017-18", "2018-19", "2019-20", "2020-21", "2021-22", "2023-24",
    ] {
        let (json, status) = check(course, &[]);
        assert_eq!(status, Some(0), "{course}: {json}");
        assert_eq!(json["passed"], true);
        assert_eq!(json["progress"]["reflection"], "done");
    }
}

#[test]
fn each_mistake_of_2021_22_is_named_first_first_half() {
    for bug in &SHOWN[..14] {
        assert_named_first("2021-22", &[bug]);
    }
}

#[test]
fn each_mistake_of_2021_22_is_named_first_second_half() {
    for bug in &SHOWN[14..] {
        assert_named_first("2021-22", &[bug]);
    }
}

#[test]
fn the_mistakes_that_differ_between_years_are_named_in_their_year() {
    for bug in [
        "shadow-bias-along-n",
        "no-gate",
        "tonemap-twice",
        "view-to-camera",
    ] {
        assert_named_first("2019-20", &[bug]);
    }
    for bug in [
        "view-to-camera",
        "specular-white",
        "reflection-bias-along-n",
    ] {
        assert_named_first("2017-18", &[bug]);
    }
    // 2018-19: 2017-18's loader (planes with the Plane class's kD .6) under 2019-20's rules.
    for bug in ["shadow-bias-along-n", "no-gate", "tonemap-missing"] {
        assert_named_first("2018-19", &[bug]);
    }
    // 2023-24: the shadow ray along N is the rule, as from 2020-21.
    for bug in ["shadow-bias-along-l", "background-changed"] {
        assert_named_first("2023-24", &[bug]);
    }
}

#[test]
fn the_common_variant_is_named_as_both_its_mistakes() {
    assert_named_first("2021-22", &["no-gate", "reflection-bias-along-n"]);
    let (json, _) = check("2021-22", &["no-gate", "reflection-bias-along-n"]);
    let summary = json["summary"].to_string();
    assert!(
        summary.contains("common variant") && summary.contains("may accept"),
        "{summary}"
    );
    let (alone, _) = check("2021-22", &["no-gate"]);
    assert!(!alone["summary"].to_string().contains("common variant"));
}

#[test]
fn a_tick1_program_is_not_checked_as_2016_17_in_silence() {
    let dir = tempfile::tempdir().expect("tempdir");
    let program = program("2021-22", &[]);
    let out = whitted(dir.path(), &["check", "--program", &program]);
    assert_eq!(out.status.code(), Some(2));
    let message = stderr(&out);
    assert!(
        message.contains("Tick 1") && message.contains("2017-18") && message.contains("2023-24"),
        "{message}"
    );
    assert_eq!(message.trim().lines().count(), 1, "{message}");
}

#[test]
fn an_800x600_image_is_checked_as_2021_22_and_says_why() {
    let dir = tempfile::tempdir().expect("tempdir");
    let reference = root().join("reference/courses/2021-24/test1_reference.png");
    let out = whitted(dir.path(), &["check", reference.to_str().expect("utf-8")]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("course: 2021-22") && l.contains("800x600")),
        "{text}"
    );
    // A scene two years with different rules ship, at their shared size: refused.
    let scene = root().join("scenes/courses/2019-20/test2.xml");
    let image = root().join("reference/courses/2019-20/test2_reference.png");
    let out = whitted(
        dir.path(),
        &[
            "check",
            image.to_str().expect("utf-8"),
            "-i",
            scene.to_str().expect("utf-8"),
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--course with one of 2019-20 and 2020-21"));
}

/// From 2017-18 students write the sphere intersection themselves, in arithmetic of their
/// own, so every hit's last bits differ from the course's quadratic. Written so, a correct
/// program still passes every case identically, and the shadow and mirror acne that hinge on
/// those bits are still named.
#[test]
fn a_student_s_own_sphere_arithmetic_neither_is_a_mistake_nor_hides_one() {
    let geometric = |bugs: &[&str]| program_with("2021-22", "-Dsphere=geometric ", bugs);
    let (json, status) = check_json("2021-22", &geometric(&[]));
    assert_eq!(status, Some(0), "{json}");
    let cases = json["cases"].as_array().expect("cases");
    assert_eq!(cases.len(), 6);
    for case in cases {
        assert_eq!(case["verdict"], "identical", "{case}");
    }
    for bug in ["no-shadow-bias", "no-reflection-bias"] {
        let (json, status) = check_json("2021-22", &geometric(&[bug]));
        assert_names_first("2021-22", &[bug], &json, status);
    }
}

#[test]
fn tick1_star_s_random_soft_shadows_are_noise_not_mistakes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let program = program_with("2021-22", "-Dstar=soft-shadows ", &[]);
    let out = check_program(dir.path(), "2021-22", &program, &["--json"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let json: Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(
        json["not_reproducible"]["seen"], "two-runs-differ",
        "{json}"
    );
    assert!(json["diagnosis"].as_array().is_some_and(|d| d.is_empty()));
    assert!(json["summary"].to_string().contains("not reproducible"));
}

#[test]
fn suite_dir_writes_the_year_s_own_scenes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let program = program("2021-22", &["no-ambient"]);
    let out = check_program(
        dir.path(),
        "2021-22",
        &program,
        &["--suite-dir", "suite", "--verbose"],
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let test1 = std::fs::read(dir.path().join("suite/test1.xml")).expect("test1.xml");
    let ours = std::fs::read(root().join("crates/check/scenes/courses/2021-24/test1.xml"))
        .expect("the year's test1");
    assert_eq!(test1, ours);
    assert!(!dir.path().join("suite/tick2.xml").exists());
    // The text's rerun lines point at the scenes written.
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("suite/test1.xml"), "{text}");
}
