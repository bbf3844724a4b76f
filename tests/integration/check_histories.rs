//! `whitted check --course YEAR --program` on Tick 1 work in progress, commit by commit, as a
//! student writes it: the three files as the course's zip ships them, then written one stage
//! after another (whitted's finished Tick 1 with the edits of `tests/java/tick1-mistakes.txt`:
//! the zip's stubs of the stages left unwritten, the mistakes made; tick1_fixture.rs), on
//! whitted's clean-room skeleton of the year, sometimes edited as students edit it (the
//! loader's plane materials, 2023-24's BumpySphere that does not compile) and a Tick 1* program. Each commit states the truth: every stage's state, the entries that
//! must be named, the ones the rest of the program makes impossible, and what the summary says.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::*;
use crate::tick1_fixture::{fixture_file, shipped_file};
use whitted_core::course::Course;

/// The student's crsid in these histories.
const CRSID: &str = "hc321";

/// One of the student's three files at a commit.
#[derive(Clone, Copy, PartialEq)]
enum Src {
    /// As the course's zip ships it: its TODO not written.
    Shipped,
    /// Written (with the commit's flags).
    Written,
}

/// What a student changed outside their three files, or how the classes came out.
#[derive(Clone, Copy, PartialEq)]
enum Edit {
    None,
    /// `SceneLoader` builds planes with Plane's own 3-argument constructor: the plane's
    /// materials are then 2017-18's class constants (kD .6, kS 0), not the loader's.
    PlaneMaterials,
    /// 2023-24's BumpySphere as shipped does not compile; the IDE wrote every other class.
    BumpySphereUncompiled,
    /// The same Tick 1* code left in package `tick1`.
    StarUnnamed,
}

/// One commit of a history and the truth about it.
struct Commit {
    name: &'static str,
    sphere: Src,
    plane: Src,
    renderer: Src,
    /// The fixture's flags baked into the written files (stages left out, mistakes made).
    flags: &'static [&'static str],
    edit: Edit,
    /// Each stage's state, in the order spheres, shading, planes, shadows, reflection.
    progress: [&'static str; 5],
    /// Entries the top diagnosis must hold.
    named: &'static [&'static str],
}

use Src::{Shipped, Written};

/// The history every year shares: the untouched zip to the shadows written with any hit.
const HISTORY: [Commit; 7] = [
    Commit {
        name: "untouched skeleton",
        sphere: Shipped,
        plane: Shipped,
        renderer: Shipped,
        flags: &[],
        edit: Edit::None,
        progress: [
            "missing",
            "not-reached",
            "missing",
            "not-reached",
            "not-reached",
        ],
        named: &["spheres-missing", "planes-missing"],
    },
    Commit {
        name: "spheres only",
        sphere: Written,
        plane: Shipped,
        renderer: Shipped,
        flags: &[],
        edit: Edit::None,
        progress: ["done", "missing", "missing", "not-reached", "missing"],
        named: &["shading-missing", "planes-missing"],
    },
    Commit {
        name: "spheres and planes, no shading",
        sphere: Written,
        plane: Written,
        renderer: Shipped,
        flags: &[],
        edit: Edit::None,
        progress: ["done", "missing", "done", "not-reached", "missing"],
        named: &["shading-missing"],
    },
    Commit {
        name: "shading without shadows",
        sphere: Written,
        plane: Written,
        renderer: Written,
        flags: &["no-shadows", "reflection-ignored"],
        edit: Edit::None,
        progress: ["done", "done", "done", "missing", "missing"],
        named: &["no-shadows", "reflection-ignored"],
    },
    Commit {
        // The shadow test written (with any hit) while illuminate's placeholder still returns
        // the flat colour: no light is shaded, so no shadow can show.
        name: "shadows half-written behind the placeholder",
        sphere: Written,
        plane: Written,
        renderer: Written,
        flags: &["shading-missing", "shadow-any-hit", "reflection-ignored"],
        edit: Edit::None,
        progress: ["done", "missing", "done", "not-reached", "missing"],
        named: &["shading-missing"],
    },
    Commit {
        name: "shadows with any hit",
        sphere: Written,
        plane: Written,
        renderer: Written,
        flags: &["shadow-any-hit", "reflection-ignored"],
        edit: Edit::None,
        progress: ["done", "done", "done", "mistaken", "missing"],
        named: &["shadow-any-hit", "reflection-ignored"],
    },
    Commit {
        name: "edited loader, shadows with any hit, no reflection",
        sphere: Written,
        plane: Written,
        renderer: Written,
        flags: &["shadow-any-hit", "reflection-ignored"],
        edit: Edit::PlaneMaterials,
        progress: ["done", "done", "done", "mistaken", "missing"],
        named: &["shadow-any-hit", "reflection-ignored"],
    },
];

/// Entries no commit of these histories makes: none may be named, at any rank. Each is a
/// mistake in code the student has not written (reflection) or did not get wrong.
const NEVER: [&str; 9] = [
    "view-to-camera",
    "no-reflection-bias",
    "reflection-bias-along-n",
    "reflection-wrong-sign",
    "reflection-unweighted",
    "bounces-plus-one",
    "bounces-minus-one",
    "no-shadow-bias",
    "shadow-bias-along-l",
];

fn course(year: &str) -> Course {
    Course::from_name(year).expect("course")
}

/// The package of the commit's classes: tick1 (a Tick 1* program in tick1star is check_star.rs's).
fn package() -> String {
    format!("uk.ac.cam.cl.gfxintro.{CRSID}.tick1")
}

/// One of the student's files at `commit`, as `year`'s student has it.
fn student_file(name: &str, src: Src, year: &str, commit: &Commit) -> String {
    let text = match src {
        Written => {
            let mut flags: Vec<&str> = commit.flags.to_vec();
            if commit.edit == Edit::StarUnnamed {
                flags.extend(["star-soft-shadows", "star-depth-of-field"]);
            }
            fixture_file(name, year, "crsid", &flags)
        }
        Shipped => shipped_file(name, year, "crsid"),
    };
    text.replace(
        "package uk.ac.cam.cl.gfxintro.crsid.tick1;",
        &format!("package {};", package()),
    )
}

/// The loader with planes built by Plane's own 3-argument constructor (the class's material
/// constants), as a student editing it while working might leave it.
fn planes_with_class_defaults(loader: &str) -> String {
    let start = loader
        .find("scene.addObject(new Plane(")
        .expect("the loader builds planes");
    let end = start + loader[start..].find("));").expect("the call ends");
    format!(
        "{}scene.addObject(new Plane(position(e), normal(e), colour(e){}",
        &loader[..start],
        &loader[end..]
    )
}

/// `commit` of `year` compiled into `dir`: the classes folder.
fn compile(dir: &Path, year: &str, commit: &Commit) -> PathBuf {
    let src = dir.join("src");
    let classes = dir.join("classes");
    std::fs::create_dir_all(&classes).expect("classes");
    let package = package();
    let folder = package.replace('.', "/");
    let skeleton = whitted_grade::clean_room_skeleton(course(year), Some(&package))
        .expect("skeleton")
        .into_iter()
        .map(|(path, bytes)| {
            let text = String::from_utf8(bytes).expect("utf-8 source");
            let text = match commit.edit {
                Edit::PlaneMaterials if path.ends_with("/SceneLoader.java") => {
                    planes_with_class_defaults(&text)
                }
                _ => text,
            };
            (path, text)
        });
    let theirs = [
        ("Sphere.java", commit.sphere),
        ("Plane.java", commit.plane),
        ("Renderer.java", commit.renderer),
    ]
    .map(|(name, s)| {
        (
            format!("{folder}/{name}"),
            student_file(name, s, year, commit),
        )
    });
    let mut paths = Vec::new();
    for (path, text) in skeleton.chain(theirs) {
        let path = src.join(path);
        write_file(&path, text);
        paths.push(path);
    }
    javac_into(&classes, &paths);
    if commit.edit == Edit::BumpySphereUncompiled {
        // The IDE compiled every class but the one with errors.
        std::fs::remove_file(classes.join(&folder).join("BumpySphere.class"))
            .expect("BumpySphere.class");
    }
    classes
}

/// `check --course year --program 'java -cp classes PACKAGE.Tick1' --json EXTRA...` on
/// `commit`: the JSON, its exit status and the text report of the same run's words.
fn check(year: &str, commit: &Commit, extra: &[&str]) -> (Value, Option<i32>) {
    let dir = tempfile::tempdir().expect("tempdir");
    let classes = compile(dir.path(), year, commit);
    let program = format!(
        "java -Djava.awt.headless=true -cp '{}' {}.Tick1",
        s(&classes),
        package()
    );
    let mut args = vec!["check", "--course", year, "--program", &program, "--json"];
    args.extend_from_slice(extra);
    let out = whitted(dir.path(), &args);
    let json: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("{year} {}: {}", commit.name, stderr(&out)));
    (json, out.status.code())
}

/// Every id any diagnosis of `json` names, and every number fit's name.
fn every_name(json: &Value) -> Vec<String> {
    let mut names = Vec::new();
    for d in json["diagnosis"].as_array().into_iter().flatten() {
        for id in d["bugs"].as_array().into_iter().flatten() {
            names.extend(id.as_str().map(String::from));
        }
    }
    names
}

fn ids(v: &Value) -> Vec<String> {
    v.as_array()
        .into_iter()
        .flatten()
        .filter_map(|s| s.as_str().map(String::from))
        .collect()
}

/// Checks `commit` of `year` against its truth.
fn holds(year: &str, commit: &Commit) {
    let (json, status) = check(year, commit, &[]);
    let what = format!("{year} {}", commit.name);
    assert_eq!(status, Some(1), "{what}: {json}");
    let progress = &json["progress"];
    let keys = ["spheres", "shading", "planes", "shadows", "reflection"];
    let states: Vec<&str> = keys
        .iter()
        .map(|k| progress[k].as_str().unwrap_or("?"))
        .collect();
    assert_eq!(states, commit.progress, "{what}: {}", json["summary"]);
    let top = json["diagnosis"]
        .get(0)
        .unwrap_or_else(|| panic!("{what}: no diagnosis: {json}"));
    let mut named = vec![ids(&top["bugs"])];
    named.extend(
        top["indistinguishable_from"]
            .as_array()
            .into_iter()
            .flatten()
            .map(ids),
    );
    assert!(
        named
            .iter()
            .any(|set| commit.named.iter().all(|id| set.iter().any(|n| n == id))),
        "{what}: top {named:?}, wanted {:?}: {}",
        commit.named,
        json["summary"]
    );
    let names = every_name(&json);
    for never in NEVER {
        assert!(
            !names.iter().any(|n| n == never),
            "{what}: {never} named in {names:?}: {}",
            json["summary"]
        );
    }
    // A stage not reached is never said to be done, nor to have a mistake.
    let summary = json["summary"].to_string();
    for (key, state) in keys.iter().zip(commit.progress) {
        if state == "not-reached" {
            assert!(
                summary.contains(&format!("{key} not reached")),
                "{what}: {summary}"
            );
        }
    }
}

#[test]
fn a_2019_20_history_is_told_stage_by_stage() {
    for commit in &HISTORY[..4] {
        holds("2019-20", commit);
    }
}

#[test]
fn a_2019_20_history_is_told_stage_by_stage_later() {
    for commit in &HISTORY[4..] {
        holds("2019-20", commit);
    }
}

#[test]
fn a_2023_24_history_is_told_stage_by_stage() {
    for commit in &HISTORY[..4] {
        holds("2023-24", commit);
    }
}

#[test]
fn a_2023_24_history_is_told_stage_by_stage_later() {
    for commit in &HISTORY[4..] {
        holds("2023-24", commit);
    }
}

/// The edited loader's planes differ from the course's in a way no entry catalogues: the
/// report says the difference is outside the catalogue and where it is, fits no number that
/// only one stage's share would support, and lists no weak candidate as a finding.
#[test]
fn an_edited_loader_is_said_to_be_outside_the_catalogue_and_located() {
    for year in ["2019-20", "2023-24"] {
        let (json, _) = check(year, &HISTORY[6], &[]);
        let summary = json["summary"].to_string();
        assert!(
            summary.contains("outside the catalogue"),
            "{year}: {summary}"
        );
        assert!(summary.contains("plane"), "{year}: {summary}");
        for p in json["parameters"].as_array().into_iter().flatten() {
            assert!(
                !matches!(p["name"].as_str(), Some("epsilon" | "reflectivity")),
                "{year}: {p}"
            );
        }
    }
}

/// 2023-24's zip does not compile (BumpySphere's stub has no return statement); an IDE
/// still writes every other class. Every case then fails alike: said once, with the class and
/// the known cause, and each case's own line stays short.
#[test]
fn a_2023_24_skeleton_that_did_not_compile_is_said_once() {
    let commit = Commit {
        name: "the zip as shipped, BumpySphere not compiled",
        sphere: Shipped,
        plane: Shipped,
        renderer: Shipped,
        flags: &[],
        edit: Edit::BumpySphereUncompiled,
        progress: ["unknown"; 5],
        named: &[],
    };
    let (json, status) = check("2023-24", &commit, &[]);
    assert_eq!(status, Some(1), "{json}");
    let cases = json["cases"].as_array().expect("cases");
    assert!(cases.iter().all(|c| c["status"] == "crashed"), "{json}");
    let summary: Vec<String> = ids(&json["summary"]);
    let about: Vec<&String> = summary
        .iter()
        .filter(|l| l.contains("BumpySphere"))
        .collect();
    assert_eq!(about.len(), 1, "{summary:?}");
    assert!(
        about[0].contains("did not compile") && about[0].contains("return"),
        "{summary:?}"
    );
    assert_eq!(json["missing_class"]["class"], "BumpySphere", "{json}");
    for case in cases {
        assert!(
            case["message"]
                .as_str()
                .is_some_and(|m| m.contains("BumpySphere")),
            "{case}"
        );
    }
}

/// A Tick 1* program (soft shadows and depth of field: hundreds of random rays a pixel) not in
/// a `tick1star` package runs out of time: said once at the top, what it is and what to do.
/// (One in the package runs the handout's scenes instead of the suite: check_star.rs.)
#[test]
fn a_tick1_star_program_is_said_to_be_one_at_the_top() {
    let commit = Commit {
        name: "Tick 1*",
        sphere: Written,
        plane: Written,
        renderer: Written,
        flags: &[],
        edit: Edit::StarUnnamed,
        progress: ["unknown"; 5],
        named: &[],
    };
    let (json, status) = check("2019-20", &commit, &["--timeout", "1"]);
    assert_eq!(status, Some(1), "{json}");
    let statuses: Vec<&str> = json["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .filter_map(|c| c["status"].as_str())
        .collect();
    assert!(
        statuses.iter().filter(|s| **s == "timeout").count() <= 2 && statuses.contains(&"not-run"),
        "{statuses:?}"
    );
    let summary: Vec<String> = ids(&json["summary"]);
    let star: Vec<&String> = summary.iter().filter(|l| l.contains("Tick 1*")).collect();
    assert_eq!(star.len(), 1, "{summary:?}");
    assert!(
        star[0].contains("--timeout") && star[0].contains("random"),
        "{summary:?}"
    );
    assert!(json["tick1_star"]["seen"].is_string(), "{json}");
}
