//! `whitted grade` on Tick 1* hand-ins of one file, as the handout asks students to submit
//! (docs/tick1star.md: `BumpySphere.java` for option 1, `Renderer.java` for option 2, with a
//! screenshot): grade completes them with whitted's finished Tick 1 (`skeleton/tick1/finished`)
//! and judges the option; a plain Tick 1 file alone is still `no-files`, said why. The option-1
//! file is `tests/java/tick1star-handin/BumpySphere.java`, written as a student writes it.

use std::path::Path;

use serde_json::Value;

use crate::common::*;
use crate::grade::{grade, records};
use crate::tick1_fixture::fixture;

/// The hand-in's BumpySphere.java in `package`, with `edit` applied to its text.
fn bumpy_sphere(package: &str, edit: &dyn Fn(String) -> String) -> String {
    let path = root().join("tests/java/tick1star-handin/BumpySphere.java");
    let text = std::fs::read_to_string(path).expect("fixture");
    edit(text.replace(
        "package uk.ac.cam.cl.gfxintro.crsid.tick1star;",
        &format!("package {package};"),
    ))
}

fn hand_in(class: &Path, folder: &str, files: &[(&str, String)]) {
    let dir = class.join(folder);
    std::fs::create_dir_all(&dir).expect("folder");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write");
    }
}

fn result_json(out: &Path, id: &str) -> Value {
    let text = std::fs::read(out.join("students").join(id).join("result.json")).expect("result");
    serde_json::from_slice(&text).expect("json")
}

/// Each case's (name, verdict) of a Tick 1* run.
fn verdicts(json: &Value) -> Vec<(String, String)> {
    json["extra_data"]["check"]["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .map(|c| {
            (
                c["case"].as_str().unwrap_or("").to_string(),
                c["tick1_star"]["verdict"]
                    .as_str()
                    .unwrap_or("")
                    .to_string(),
            )
        })
        .collect()
}

#[test]
fn a_bumpy_sphere_handed_in_alone_is_judged_on_whitted_finished_tick1() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    // Right, in the handout's tick1star package.
    let right = bumpy_sphere("uk.ac.cam.cl.gfxintro.ab123.tick1star", &|t| t);
    hand_in(
        &class,
        "Ann Able_61001_assignsubmission_file_",
        &[("BumpySphere.java", right)],
    );
    // The relief inverted (the handout's "most common mistake"), left in the Tick 1 package:
    // a BumpySphere alone is Tick 1* whatever its package.
    let inverted = bumpy_sphere("uk.ac.cam.cl.gfxintro.cd456.tick1", &|t| {
        t.replace("scale(Bu)", "scale(-Bu)")
            .replace("scale(Bv)", "scale(-Bv)")
    });
    hand_in(
        &class,
        "Ben Baker_61002_assignsubmission_file_",
        &[("BumpySphere.java", inverted)],
    );
    // Slow, as a program of hundreds of rays a pixel is: ten seconds of CPU before it renders,
    // more than the sandbox's CPU limit of twice `--timeout` (2 s here) and 5 s, but well
    // within the minutes a Tick 1* case of a year's own size is given: it is judged, not killed.
    let slow = bumpy_sphere("uk.ac.cam.cl.gfxintro.gh012.tick1star", &|t| {
        t.replace(
            "        super(position, radius, colour);\n",
            "        super(position, radius, colour);\n        \
             java.lang.management.ThreadMXBean cpu = \
             java.lang.management.ManagementFactory.getThreadMXBean();\n        \
             double spin = 0;\n        \
             while (cpu.getCurrentThreadCpuTime() < 10_000_000_000L) spin += Math.sqrt(spin + 1);\n        \
             if (spin < 0) System.out.println(spin);\n",
        )
    });
    assert!(slow.contains("ThreadMXBean"), "the spin is written in");
    hand_in(
        &class,
        "Dee Dale_61004_assignsubmission_file_",
        &[("BumpySphere.java", slow)],
    );
    // A Tick 1 Renderer alone is no Tick 1* hand-in: the Tick 1 needs all three files.
    let renderer = fixture("2021-22", "ef789", &[])
        .into_iter()
        .filter(|(name, _)| *name == "Renderer.java")
        .collect::<Vec<_>>();
    hand_in(&class, "Cy Cole_61003_assignsubmission_file_", &renderer);
    let run = grade(
        dir.path(),
        &[
            "class",
            "-o",
            "out",
            "--course",
            "2021-22",
            "--timeout",
            "300",
        ],
    );
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let out = dir.path().join("out");
    let rows = records(&out.join("class.csv"));
    let row = |id: &str| rows.iter().find(|r| r["id"] == id).expect("row").clone();

    let ann = result_json(&out, "61001");
    assert_eq!(row("61001")["status"], "graded", "{rows:?}");
    assert_eq!(row("61001")["grade"], "100", "{rows:?}");
    assert_eq!(
        verdicts(&ann),
        [
            ("bump.xml -b 2".to_string(), "bump-correct".to_string()),
            (
                "distributed.xml -b 2".to_string(),
                "option-not-done".to_string()
            )
        ]
    );
    let feedback = ann["extra_data"]["feedback"].as_str().expect("feedback");
    assert!(feedback.starts_with("Tick 1* accepted"), "{feedback}");
    assert!(feedback.contains("parametrisation y-zx"), "{feedback}");
    assert!(
        feedback.contains(
            "whitted's finished Tick 1 in place of Plane.java, Renderer.java, Sphere.java"
        ),
        "{feedback}"
    );
    let notes = ann["extra_data"]["notes"].to_string();
    assert!(notes.contains("BumpySphere.java alone"), "{notes}");
    // Recognised as a hand-in, whatever its package says.
    assert_eq!(
        ann["extra_data"]["check"]["tick1_star"]["seen"], "hand-in",
        "{}",
        ann["extra_data"]["check"]["tick1_star"]
    );
    // Its page shows each option's image with the option's verdict, as `check --report` does.
    let page = std::fs::read_to_string(out.join("students/61001/report.html")).expect("report");
    let bump_heading = "<h2>bump.xml -b 2: option 1, bump mapping</h2>\n";
    let verdict = page
        .split_once(bump_heading)
        .and_then(|(_, after)| after.split_once("</p>"))
        .map(|(verdict, _)| verdict)
        .expect("option 1's block");
    assert!(
        verdict.starts_with("<p class=\"pass\">") && verdict.contains("y-zx"),
        "{verdict}"
    );
    assert!(page.contains("<h2>distributed.xml -b 2: option 2,"));
    assert_eq!(
        page.matches("alt=\"your image\"").count(),
        2,
        "each option's image"
    );
    // Its sheet has a row per option: the image's tiles (800x600 shown a third the size, at
    // most 320 wide: 266x200), not the 160x120 blank tiles of a student with no image.
    let sheet = read_png(&out.join("students/61001/report.png"));
    let (tile_w, tile_h) = (800 / 3, 600 / 3);
    assert_eq!(
        sheet.width,
        3 * tile_w + 4 * 8,
        "tiles of the options' images"
    );
    let pixel = |x: u32, y: u32| {
        let i = 3 * (y * sheet.width + x) as usize;
        [sheet.data[i], sheet.data[i + 1], sheet.data[i + 2]]
    };
    // The first tile starts below the headings, at (8, 26).
    let first_tile_lit = (0..tile_h)
        .flat_map(|y| (0..tile_w).map(move |x| (x + 8, y + 26)))
        .any(|(x, y)| pixel(x, y) != [0; 3] && pixel(x, y) != [24; 3]);
    assert!(first_tile_lit, "the bump image is drawn on the sheet");

    let ben = result_json(&out, "61002");
    assert_eq!(row("61002")["status"], "graded", "{rows:?}");
    assert_eq!(row("61002")["grade"], "0", "{rows:?}");
    let bump = &ben["extra_data"]["check"]["cases"][0]["tick1_star"];
    assert_eq!(bump["verdict"], "bump-mistake", "{bump}");
    assert!(
        bump["line"].as_str().expect("line").contains("inverted"),
        "{bump}"
    );
    // Recognised by what it is, not by a package it does not have.
    let report = std::fs::read_to_string(out.join("students/61002/report.html")).expect("report");
    assert!(
        report.contains("a hand-in of its option&#39;s file")
            || report.contains("a hand-in of its option's file"),
        "{report}"
    );
    assert!(!report.contains("its package is tick1star"), "{report}");
    assert_eq!(ben["extra_data"]["check"]["tick1_star"]["seen"], "hand-in");
    // The failed option's verdict and its images: the render it was compared with beside it.
    assert!(
        report.contains("<p class=\"fail\">") && report.contains("inverted"),
        "the verdict on the page"
    );
    assert!(
        report.contains("the handout&#39;s method under parametrisation")
            || report.contains("the handout's method under parametrisation"),
        "the reference beside the image"
    );

    let dee = result_json(&out, "61004");
    assert_eq!(row("61004")["grade"], "100", "{rows:?}");
    assert_eq!(verdicts(&dee)[0].1, "bump-correct", "{dee}");

    assert_eq!(row("61003")["status"], "no-files", "{rows:?}");
    let cy = result_json(&out, "61003");
    let said = cy["extra_data"]["feedback"].as_str().expect("feedback");
    assert!(
        said.starts_with("no Plane.java in the submission (it holds Renderer.java only)"),
        "{said}"
    );
    assert!(said.contains("Tick 1* hand-in of one file"), "{said}");
}
