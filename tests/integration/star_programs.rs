//! Tick 1* programs run as programs (docs/check.md "Tick 1*", docs/grade.md "Tick 1*"): by
//! `check --program`, `check DIR` and `grade`, each runs the handout's two scenes once and
//! judges each image by its option: a program that did both options has a random bump image,
//! judged as a draw of the bumped scene; a program that did one renders the other option's
//! scene with its Tick 1 renderer, which is that option not done, and fine. Our Java Tick 1*
//! (tests/java/tick1star, on whitted's clean-room 2023-24 skeleton) is the program, at 2023-24's
//! reduced 160x120.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::common::*;
use crate::grade::{grade, records};
use crate::tick1_fixture::fixture_file;

pub(crate) const YEAR: &str = "2023-24";

fn course() -> whitted_core::course::Course {
    whitted_core::course::Course::from_name(YEAR).expect("course")
}

/// How a student's Tick 1* is written.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Done {
    /// Both options: the Tick 1* Renderer and BumpySphere.
    Both,
    /// Option 1 only: the Tick 1 Renderer and the Tick 1* BumpySphere.
    Bump,
    /// Option 2 only: the Tick 1* Renderer and a BumpySphere that returns the smooth normal.
    Distributed,
    /// Neither: the Tick 1 Renderer and the skeleton's stub BumpySphere.
    Neither,
}

/// The student's files in package `package`: the Tick 1 fixture's Sphere and Plane, and the
/// Renderer and BumpySphere `done` says (None: the skeleton's).
fn files(package: &str, done: Done) -> Vec<(&'static str, String)> {
    let star = |name: &str| {
        let path = root().join("tests/java/tick1star").join(name);
        let text = std::fs::read_to_string(path).expect("fixture");
        whitted_grade::for_year(&text, course()).expect("template")
    };
    let tick1 = |name: &str| fixture_file(name, YEAR, "crsid", &[]);
    let mut files = vec![
        ("Sphere.java", tick1("Sphere.java")),
        ("Plane.java", tick1("Plane.java")),
    ];
    files.push(match done {
        Done::Both | Done::Distributed => ("Renderer.java", star("Renderer.java")),
        Done::Bump | Done::Neither => ("Renderer.java", tick1("Renderer.java")),
    });
    match done {
        Done::Both | Done::Bump => files.push(("BumpySphere.java", star("BumpySphere.java"))),
        Done::Distributed => files.push((
            "BumpySphere.java",
            star("BumpySphere.java").replacen(
                "public Vector3 getNormalAt(Vector3 position) {",
                "public Vector3 getNormalAt(Vector3 position) {\n        \
                 if (position != null) return super.getNormalAt(position);",
                1,
            ),
        )),
        Done::Neither => {}
    }
    files
        .into_iter()
        .map(|(name, text)| {
            let text = text
                .replace(
                    "package uk.ac.cam.cl.gfxintro.crsid.tick1star;",
                    &format!("package {package};"),
                )
                .replace(
                    "package uk.ac.cam.cl.gfxintro.crsid.tick1;",
                    &format!("package {package};"),
                );
            (name, text)
        })
        .collect()
}

/// The skeleton and `files` compiled into `d/classes`; the program's command line with the
/// JVM options `flags`.
pub(crate) fn compiled(d: &Path, package: &str, done: Done, flags: &str) -> String {
    let src = d.join("src");
    let classes = d.join("classes");
    let folder = src.join(package.replace('.', "/"));
    std::fs::create_dir_all(&folder).expect("folder");
    std::fs::create_dir_all(&classes).expect("classes");
    for (path, bytes) in
        whitted_grade::clean_room_skeleton(course(), Some(package)).expect("skeleton")
    {
        write_file(&src.join(path), bytes);
    }
    for (name, text) in files(package, done) {
        std::fs::write(folder.join(name), text).expect("write");
    }
    let paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .expect("folder")
        .flatten()
        .map(|e| e.path())
        .collect();
    javac_into(&classes, &paths);
    format!(
        "java -Djava.awt.headless=true {flags} -cp '{}' {package}.Tick1",
        s(&classes)
    )
}

/// `check --course 2023-24 --json --program PROGRAM` in `d`: per case (verdict, line), exit.
fn check_program(d: &Path, program: &str) -> (Vec<(String, String)>, Option<i32>) {
    let out = whitted(
        d,
        &["check", "--course", YEAR, "--json", "--program", program],
    );
    let json: Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", stderr(&out)));
    (verdicts(&json), out.status.code())
}

/// Each case's Tick 1* verdict and line, in case order.
fn verdicts(check: &Value) -> Vec<(String, String)> {
    check["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .map(|c| {
            let star = &c["tick1_star"];
            (
                star["verdict"].as_str().unwrap_or("none").to_string(),
                star["line"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect()
}

pub(crate) const PACKAGE: &str = "uk.ac.cam.cl.gfxintro.ab123.tick1star";

#[test]
fn both_options_pass_for_two_seeds_and_a_bump_mistake_is_named() {
    let d = tempfile::tempdir().expect("tempdir");
    for seed in [601, 602] {
        let program = compiled(d.path(), PACKAGE, Done::Both, &format!("-Dseed={seed}"));
        let (cases, status) = check_program(d.path(), &program);
        assert_eq!(cases[0].0, "bump-draw", "seed {seed}: {cases:?}");
        assert!(cases[0].1.contains("parametrisation y-zx"), "{cases:?}");
        assert_eq!(cases[1].0, "course-draw", "seed {seed}: {cases:?}");
        assert_eq!(status, Some(0), "{cases:?}");
    }
    let program = compiled(
        d.path(),
        PACKAGE,
        Done::Both,
        "-Dseed=603 -Dbump=y-zx,inverted",
    );
    let (cases, status) = check_program(d.path(), &program);
    assert_eq!(cases[0].0, "bump-draw-mistake", "{cases:?}");
    assert!(cases[0].1.contains("bump-inverted"), "{cases:?}");
    assert_eq!(status, Some(1));
}

#[test]
fn one_option_is_enough_and_the_other_is_said_not_done() {
    let d = tempfile::tempdir().expect("tempdir");
    // Option 1 only: distributed.xml is the Tick 1 render.
    let program = compiled(d.path(), PACKAGE, Done::Bump, "");
    let (cases, status) = check_program(d.path(), &program);
    assert_eq!(cases[0].0, "bump-correct", "{cases:?}");
    assert_eq!(cases[1].0, "option-not-done", "{cases:?}");
    assert!(
        cases[1]
            .1
            .contains("option 2 not done (hard shadows, no depth of field"),
        "{cases:?}"
    );
    assert!(
        cases[1].1.contains("fine, one option is enough"),
        "{cases:?}"
    );
    assert_eq!(status, Some(0), "{cases:?}");
    // Option 2 only: bump.xml has a smooth sphere, soft shadows and depth of field on.
    let e = tempfile::tempdir().expect("tempdir");
    let program = compiled(e.path(), PACKAGE, Done::Distributed, "-Dseed=604");
    let (cases, status) = check_program(e.path(), &program);
    assert_eq!(cases[0].0, "option-not-done", "{cases:?}");
    assert!(cases[0].1.contains("option 1 not done"), "{cases:?}");
    assert_eq!(cases[1].0, "course-draw", "{cases:?}");
    assert_eq!(status, Some(0), "{cases:?}");
    // Neither: the Tick 1 renderer with the skeleton's stub, which is no Tick 1*.
    let f = tempfile::tempdir().expect("tempdir");
    let program = compiled(f.path(), PACKAGE, Done::Neither, "");
    let (cases, status) = check_program(f.path(), &program);
    assert_eq!(cases[0].0, "option-not-done", "{cases:?}");
    assert_eq!(cases[1].0, "option-not-done", "{cases:?}");
    assert!(cases[1].1.contains("Tick 1* needs one of"), "{cases:?}");
    assert_eq!(status, Some(1), "{cases:?}");
}

#[test]
fn a_single_image_of_the_tick1_renderer_is_the_option_not_done() {
    let d = tempfile::tempdir().expect("tempdir");
    compiled(d.path(), PACKAGE, Done::Bump, "");
    let handout = root().join("crates/check/scenes/tick1star");
    for file in ["distributed.xml", "bump.xml", "bumpmap.png"] {
        std::fs::copy(handout.join(file), d.path().join(file)).expect("copy");
    }
    let java = |scene: &str, out: &str| {
        Command::new("java")
            .arg("-Djava.awt.headless=true")
            .arg("-cp")
            .arg(d.path().join("classes"))
            .arg(format!("{PACKAGE}.Tick1"))
            .args(["-i", scene, "-o", out, "-b", "2", "-r", "160x120"])
            .current_dir(d.path())
            .output()
            .expect("java")
    };
    let run = java("distributed.xml", "sharp.png");
    assert!(run.status.success(), "{}", stderr(&run));
    let out = whitted(
        d.path(),
        &[
            "check",
            "--course",
            YEAR,
            "--star",
            "distributed",
            "sharp.png",
        ],
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("option 2 not done"), "{text}{}", stderr(&out));
    assert_eq!(out.status.code(), Some(0));
    // Its bump image, with no -i: the handout's scene, judged by option 1.
    let run = java("bump.xml", "bump.png");
    assert!(run.status.success(), "{}", stderr(&run));
    let out = whitted(
        d.path(),
        &[
            "check", "--course", YEAR, "--star", "bump", "--json", "bump.png",
        ],
    );
    let json: Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(json["tick1_star"]["verdict"], "bump-correct", "{json}");
}

#[test]
fn the_skeleton_s_flat_bump_stub_is_option_1_not_done_with_or_without_i() {
    // A real 2021-22 student's bump.png from the skeleton's getNormalAt (the zero vector) was
    // "option 1 not done" (exit 0) without -i, and a made-up mistake (exit 1) with -i bump.xml.
    let d = tempfile::tempdir().expect("tempdir");
    compiled(d.path(), PACKAGE, Done::Neither, "");
    let handout = root().join("crates/check/scenes/tick1star");
    for file in ["bump.xml", "bumpmap.png"] {
        std::fs::copy(handout.join(file), d.path().join(file)).expect("copy");
    }
    let run = Command::new("java")
        .arg("-Djava.awt.headless=true")
        .arg("-cp")
        .arg(d.path().join("classes"))
        .arg(format!("{PACKAGE}.Tick1"))
        .args([
            "-i", "bump.xml", "-o", "flat.png", "-b", "2", "-r", "160x120",
        ])
        .current_dir(d.path())
        .output()
        .expect("java");
    assert!(run.status.success(), "{}", stderr(&run));
    for with_input in [false, true] {
        let mut args = vec!["check", "--course", YEAR, "--star", "bump", "flat.png"];
        if with_input {
            args.extend(["-i", "bump.xml"]);
        }
        let out = whitted(d.path(), &args);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            text.contains("option 1 not done"),
            "-i {with_input}: {text}{}",
            stderr(&out)
        );
        assert!(!text.contains("nearest"), "-i {with_input}: {text}");
        assert_eq!(out.status.code(), Some(0), "-i {with_input}: {text}");
    }
}

#[test]
fn check_dir_runs_a_tick1_star_project_s_options_not_the_suite() {
    let d = tempfile::tempdir().expect("tempdir");
    let project = d.path().join("project");
    std::fs::create_dir_all(&project).expect("project");
    compiled(&project, PACKAGE, Done::Bump, "");
    std::fs::remove_dir_all(project.join("classes")).expect("classes");
    let out = whitted(d.path(), &["check", "--course", YEAR, "--json", "project"]);
    let json: Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", stderr(&out)));
    let names: Vec<&str> = json["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .map(|c| c["case"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(names, ["bump.xml -b 2", "distributed.xml -b 2"], "{json}");
    let cases = verdicts(&json);
    assert_eq!(cases[0].0, "bump-correct", "{cases:?}");
    assert_eq!(cases[1].0, "option-not-done", "{cases:?}");
    assert_eq!(out.status.code(), Some(0), "{json}");
}

/// A Tick 1* project whose bump mapping has a mistake (written into its BumpySphere, as a
/// student's is: no JVM option) fails option 1 by name, and the report says nothing of its
/// course classes: a second render of a Tick 1* case on the year's Tick 1 classes (which lack
/// the student's BumpySphere, and whose random images differ run to run) would blame them.
#[test]
fn a_tick1_star_project_s_bump_mistake_blames_no_course_class() {
    let d = tempfile::tempdir().expect("tempdir");
    let project = d.path().join("project");
    std::fs::create_dir_all(&project).expect("project");
    compiled(&project, PACKAGE, Done::Bump, "");
    std::fs::remove_dir_all(project.join("classes")).expect("classes");
    let bumpy = project
        .join("src")
        .join(PACKAGE.replace('.', "/"))
        .join("BumpySphere.java");
    let text = std::fs::read_to_string(&bumpy).expect("BumpySphere");
    let edited = text.replace(
        r#"System.getProperty("bump", "y-zx")"#,
        r#"System.getProperty("bump", "y-zx,inverted")"#,
    );
    assert_ne!(edited, text, "the fixture's default moved");
    std::fs::write(&bumpy, edited).expect("write");
    let out = whitted(d.path(), &["check", "--course", YEAR, "--json", "project"]);
    let json: Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", stderr(&out)));
    let cases = verdicts(&json);
    assert_eq!(cases[0].0, "bump-mistake", "{cases:?}");
    assert!(cases[0].1.contains("bump-inverted"), "{cases:?}");
    assert_eq!(out.status.code(), Some(1), "{json}");
    let notes = json["project"]["notes"].to_string();
    for blame in ["otherwise than", "writes no image", "is not 2023-24's"] {
        assert!(!notes.contains(blame), "{blame}: {notes}");
    }
}

/// A student's folder of a Moodle class: `files` under the course's package folder.
fn student(class: &Path, folder: &str, package: &str, files: &[(&str, String)]) {
    let dir = class
        .join(folder)
        .join("src")
        .join(package.replace('.', "/"));
    std::fs::create_dir_all(&dir).expect("folder");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write");
    }
}

#[test]
fn grade_judges_a_tick1_star_class_by_its_options() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    // (Moodle folder, package, what was done)
    let students = [
        (
            "Ada_61001_assignsubmission_file",
            "uk.ac.cam.cl.gfxintro.ab123.tick1star",
            Done::Both,
        ),
        // Recognised by its Renderer's ray counts, in the Tick 1 package; its BumpySphere is
        // taken, since the submission is Tick 1*.
        (
            "Ben_61002_assignsubmission_file",
            "uk.ac.cam.cl.gfxintro.cd456.tick1",
            Done::Distributed,
        ),
        (
            "Cy_61003_assignsubmission_file",
            "uk.ac.cam.cl.gfxintro.ef789.tick1star",
            Done::Neither,
        ),
    ];
    for (folder, package, done) in students {
        student(&class, folder, package, &files(package, done));
    }
    let run = grade(
        dir.path(),
        &["class", "-o", "out", "--course", YEAR, "--timeout", "60"],
    );
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let out = dir.path().join("out");
    let rows = records(&out.join("class.csv"));
    assert_eq!(rows.len(), 3, "{rows:?}");
    let result = |id: &str| -> Value {
        let text =
            std::fs::read(out.join("students").join(id).join("result.json")).expect("result");
        serde_json::from_slice(&text).expect("json")
    };
    for (id, accepted, first, second) in [
        ("61001", true, "bump-draw", "course-draw"),
        ("61002", true, "option-not-done", "course-draw"),
        ("61003", false, "option-not-done", "option-not-done"),
    ] {
        let json = result(id);
        let check = &json["extra_data"]["check"];
        let cases = verdicts(check);
        assert_eq!(
            cases.len(),
            2,
            "{id}: the options' scenes, not the suite: {cases:?}"
        );
        assert_eq!(
            (cases[0].0.as_str(), cases[1].0.as_str()),
            (first, second),
            "{id}: {cases:?}"
        );
        let feedback = json["output"].as_str().expect("output");
        assert!(
            feedback.contains("option 1, bump mapping"),
            "{id}: {feedback}"
        );
        assert!(
            feedback.contains("option 2, soft shadows and depth of field"),
            "{id}: {feedback}"
        );
        assert!(!feedback.contains("graded cases"), "{id}: {feedback}");
        let score = json["score"].as_f64().expect("score");
        match accepted {
            true => {
                assert!(feedback.starts_with("Tick 1* accepted"), "{id}: {feedback}");
                assert_eq!(score, 100.0, "{id}");
            }
            false => {
                assert!(
                    feedback.starts_with("Tick 1* not accepted"),
                    "{id}: {feedback}"
                );
                assert_eq!(score, 0.0, "{id}");
            }
        }
        let report = std::fs::read_to_string(out.join("students").join(id).join("report.html"))
            .expect("report");
        assert!(report.contains("judged by its option"), "{id}: {report}");
        assert!(!report.contains("timeout"), "{id}: {report}");
    }
    let ben = result("61002");
    assert!(
        ben["output"]
            .as_str()
            .is_some_and(|o| o.contains("fine, one option is enough")),
        "{ben}"
    );
}
