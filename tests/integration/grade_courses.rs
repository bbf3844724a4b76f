//! `whitted grade --course 2021-22`: a class of the later years, each student in the package
//! of their own user id (`uk.ac.cam.cl.gfxintro.<crsid>.tick1`), handing in Plane, Renderer
//! and Sphere. The skeleton is `tests/java/tick1-skeleton`, a Tick 1 skeleton of whitted's own
//! API (not the course's, which the specs do not give), in the course's placeholder package
//! `...gfxintro.crsid.tick1`; the submissions (`tests/java/tick1-submission`) are written
//! against it the way students write (the plane's stored normal trusted, the far root taken).

use std::path::Path;

use serde_json::Value;

use crate::common::*;
use crate::grade::{grade, records};

/// The submission's three files in package `crsid`, with `bugs` baked into Renderer.java.
fn submission(crsid: &str, bugs: &[&str]) -> Vec<(&'static str, String)> {
    let dir = root().join("tests/java/tick1-submission");
    ["Plane.java", "Renderer.java", "Sphere.java"]
        .into_iter()
        .map(|name| {
            let text = std::fs::read_to_string(dir.join(name)).expect("source");
            let text = text.replace(
                "package uk.ac.cam.cl.gfxintro.crsid.tick1;",
                &format!("package uk.ac.cam.cl.gfxintro.{crsid}.tick1;"),
            );
            let text = text.replace(
                "System.getProperty(\"bug\", \"\")",
                &format!("\"{}\"", bugs.join(",")),
            );
            (name, text)
        })
        .collect()
}

/// Writes a student's folder: their files under `layout` (`{crsid}` replaced).
fn student(class: &Path, folder: &str, files: &[(&str, String)], layout: &str, crsid: &str) {
    let dir = class.join(folder).join(layout.replace("{crsid}", crsid));
    std::fs::create_dir_all(&dir).expect("folder");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write");
    }
}

fn skeleton() -> String {
    root()
        .join("tests/java/tick1-skeleton")
        .display()
        .to_string()
}

/// `whitted grade class -o out --course course --skeleton SKELETON` in `dir`.
fn grade_year(dir: &Path, course: &str, skeleton: &str) -> std::process::Output {
    let args = [
        "class",
        "-o",
        "out",
        "--course",
        course,
        "--skeleton",
        skeleton,
    ];
    grade(dir, &args)
}

fn result_json(out: &Path, id: &str) -> Value {
    let text = std::fs::read(out.join("students").join(id).join("result.json")).expect("result");
    serde_json::from_slice(&text).expect("json")
}

#[test]
fn a_later_class_with_a_package_each_is_graded_named_and_written_up() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let tree = "src/uk/ac/cam/cl/gfxintro/{crsid}/tick1";
    // (Moodle folder, crsid, mistakes, layout, what class.csv names)
    let students: [(&str, &str, &[&str], &str, &str); 6] = [
        ("Ada_41001_assignsubmission_file", "ab123", &[], tree, ""),
        (
            "Ben_41002_assignsubmission_file",
            "cd456",
            &["no-gate", "reflection-bias-along-n"],
            "tick1/uk/ac/cam/cl/gfxintro/{crsid}/tick1",
            "no-gate+reflection-bias-along-n",
        ),
        (
            "Cy_41003_assignsubmission_file",
            "ef789",
            &["spheres-missing"],
            tree,
            "spheres-missing",
        ),
        (
            "Di_41004_assignsubmission_file",
            "gh012",
            &["shading-missing"],
            "",
            "shading-missing",
        ),
        (
            "Ed_41005_assignsubmission_file",
            "ij345",
            &["specular-white"],
            tree,
            "specular-white",
        ),
        (
            "Flo_41006_assignsubmission_file",
            "kl678",
            &["background-changed"],
            tree,
            "background-changed",
        ),
    ];
    for (folder, crsid, bugs, layout, _) in &students {
        student(&class, folder, &submission(crsid, bugs), layout, crsid);
    }
    // A package that is no Java name cannot be a main class on a command line.
    let mut bad = submission("mn901", &[]);
    for (_, text) in &mut bad {
        *text = text.replace("gfxintro.mn901.tick1;", "gfxintro.mn-901.tick1;");
    }
    student(
        &class,
        "Gus_41007_assignsubmission_file",
        &bad,
        tree,
        "mn901",
    );
    let out = dir.path().join("out");
    let run = grade_year(dir.path(), "2021-22", &skeleton());
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let rows = records(&out.join("class.csv"));
    assert_eq!(rows.len(), 7, "{rows:?}");
    for (folder, crsid, _, _, named) in &students {
        let id = folder.split('_').nth(1).expect("id");
        let row = rows.iter().find(|r| r["id"] == id).expect("row");
        assert_eq!(row["status"], "graded", "{crsid}: {row:?}");
        assert_eq!(row["diagnosis"], *named, "{crsid}: {row:?}");
        if named.is_empty() {
            assert_eq!(row["passed"], row["cases"], "{row:?}");
        } else {
            assert_ne!(row["passed"], row["cases"], "{row:?}");
        }
        // Each student's own main class ran, at the year's size.
        let json = result_json(&out, id);
        let check = &json["extra_data"]["check"];
        let main = format!("java uk.ac.cam.cl.gfxintro.{crsid}.tick1.Tick1 ");
        let run = check["cases"][0]["reproduce"]["run"].as_str().expect("run");
        assert!(run.starts_with(&main), "{run}");
        assert_eq!(check["cases"][0]["width"], 800);
    }
    let gus = rows.iter().find(|r| r["id"] == "41007").expect("row");
    assert_eq!(gus["status"], "error", "{gus:?}");
    let gus = std::fs::read_to_string(out.join("students/41007/report.html")).expect("report");
    assert!(gus.contains("not a plain Java package name"), "{gus}");
    // The common variant is said to be one (docs/courses.md).
    let ben = std::fs::read_to_string(out.join("students/41002/report.html")).expect("report");
    assert!(ben.contains("common variant"), "{ben}");
    assert!(ben.contains("Tick 1 (2021-22)"), "{ben}");
    let index = std::fs::read_to_string(out.join("index.html")).expect("index");
    assert!(index.contains("Tick 1 (2021-22): the class"), "{index}");
    assert!(index.contains("Course: 2021-22."), "{index}");
}

#[test]
fn a_random_tick1_star_submission_is_not_reproducible_rather_than_diagnosed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let files = submission("op234", &["star-soft-shadows"]);
    student(&class, "op234", &files, "", "op234");
    let run = grade_year(dir.path(), "2021-22", &skeleton());
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let json = result_json(&dir.path().join("out"), "op234");
    let check = &json["extra_data"]["check"];
    assert_eq!(
        check["not_reproducible"]["seen"], "two-runs-differ",
        "{check}"
    );
    let report =
        std::fs::read_to_string(dir.path().join("out/students/op234/report.html")).expect("report");
    assert!(report.contains("not reproducible"), "{report}");
}

#[test]
fn a_later_year_needs_its_skeleton_and_one_that_does_not_compile_is_named() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    student(&class, "qr567", &submission("qr567", &[]), "", "qr567");
    let run = grade(dir.path(), &["class", "-o", "out", "--course", "2021-22"]);
    assert_eq!(run.status.code(), Some(2));
    let said = stderr(&run);
    assert!(said.contains("needs --skeleton DIR"), "{said}");
    assert!(!dir.path().join("out/class.csv").exists());
    // 2023-24's BumpySphere as shipped: getNormalAt without its return.
    let broken = dir.path().join("broken");
    let from = root().join("tests/java/tick1-skeleton/src/uk/ac/cam/cl/gfxintro/crsid/tick1");
    std::fs::create_dir_all(&broken).expect("folder");
    for entry in std::fs::read_dir(&from).expect("skeleton").flatten() {
        let text = std::fs::read_to_string(entry.path()).expect("source");
        let text = text.replace(
            "return super.getNormalAt(position);",
            "super.getNormalAt(position);",
        );
        std::fs::write(broken.join(entry.file_name()), text).expect("write");
    }
    let run = grade_year(dir.path(), "2023-24", broken.to_str().expect("utf-8"));
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let rows = records(&dir.path().join("out/class.csv"));
    assert_eq!(rows[0]["status"], "compile-error", "{rows:?}");
    let report =
        std::fs::read_to_string(dir.path().join("out/students/qr567/report.html")).expect("report");
    assert!(report.contains("BumpySphere.java"), "{report}");
    assert!(report.contains("missing return statement"), "{report}");
    assert!(report.contains("the skeleton"), "{report}");
}
