//! What a Tick 1* program's check leaves the student (docs/tick1star.md, "Checking a Tick 1*
//! program"): `--suite-dir` writes the handout's scenes it ran (bump.xml, its map,
//! distributed.xml), never over other files; each option's rerun and check commands appear in
//! the text and the JSON, and run as printed; `--report` shows each option's image (option 1's
//! beside the render it was compared with); `--verbose` adds the numbers behind each verdict.
//! Our Java Tick 1* (tests/java/tick1star) is the program, at 2023-24's reduced 160x120.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

use crate::common::*;
use crate::star_programs::{compiled, Done, PACKAGE, YEAR};
use whitted_core::star::bump::PARAMETRISATIONS;
use whitted_core::star::BumpMistake;

/// `whitted check --course 2023-24 --program PROGRAM EXTRA...` in `d`.
fn check(d: &Path, program: &str, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["check", "--course", YEAR, "--program", program];
    args.extend(extra);
    whitted(d, &args)
}

/// Runs a printed command line from `d`: a `whitted` one as the built binary.
fn run_line(d: &Path, line: &str) -> std::process::Output {
    let words = whitted_check::check::program::words(line).expect("a shell line");
    match words[0].as_str() {
        "whitted" => {
            let rest: Vec<&str> = words[1..].iter().map(String::as_str).collect();
            whitted(d, &rest)
        }
        program => Command::new(program)
            .args(&words[1..])
            .current_dir(d)
            .output()
            .expect("the rerun command starts"),
    }
}

/// `html` with each inline image's data cut, for a failing assertion's message.
fn readable(html: &str) -> String {
    html.split("src=\"data:")
        .enumerate()
        .map(|(i, part)| match (i, part.split_once('"')) {
            (0, _) | (_, None) => part.to_string(),
            (_, Some((_, rest))) => format!("src=\"...\"{rest}"),
        })
        .collect()
}

/// How many `<img` tags `html` holds.
fn images(html: &str) -> usize {
    html.matches("<img").count()
}

#[test]
fn the_suite_dir_holds_what_a_tick1_star_program_ran_and_each_printed_command_runs() {
    let d = tempfile::tempdir().expect("tempdir");
    let program = compiled(d.path(), PACKAGE, Done::Bump, "");
    let out = check(
        d.path(),
        &program,
        &["--suite-dir", "suite", "--verbose", "--report", "r.html"],
    );
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(0), "{text}{}", stderr(&out));
    // What was run, not the Tick 1 suite.
    let suite = d.path().join("suite");
    let mut written: Vec<String> = std::fs::read_dir(&suite)
        .expect("suite")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(written, ["bump.xml", "bumpmap.png", "distributed.xml"]);
    let handout = root().join("crates/check/scenes/tick1star");
    let read = |p: &Path| std::fs::read(p).expect("read");
    assert_eq!(
        read(&suite.join("bumpmap.png")),
        read(&handout.join("bumpmap.png"))
    );
    assert_eq!(
        read(&suite.join("distributed.xml")),
        read(&handout.join("distributed.xml"))
    );
    // The map is named by its whole path: found from the student's folder and beside it.
    let bump = std::fs::read_to_string(suite.join("bump.xml")).expect("bump.xml");
    let map = suite.join("bumpmap.png");
    assert!(
        bump.contains(&format!("bump-map=\"{}\"", s(&map))),
        "{bump}"
    );
    // --verbose: each option's commands and numbers.
    let tried = PARAMETRISATIONS.len() * (1 + BumpMistake::ALL.len());
    assert!(text.contains(&format!("renders tried: {tried} ")), "{text}");
    for line in [
        "rerun it: ",
        " --input suite/bump.xml --output bump_b2.png --bounces 2 --resolution 160x120",
        "check it: whitted check bump_b2.png -b 2 --course 2023-24 --star bump",
        "check it: whitted check distributed_b2.png -b 2 --course 2023-24 --star distributed",
        "image: 160x120",
        "closest: the handout's method under y-zx, ",
        "scene: suite/distributed.xml",
    ] {
        assert!(text.contains(line), "{line:?} in\n{text}");
    }
    assert!(!text.contains("--suite-dir DIR"), "{text}");
    // The report: option 1's image, the render it was compared with and their difference
    // (whole and enlarged); option 2's image (the option not done: nothing to compare).
    let html = std::fs::read_to_string(d.path().join("r.html")).expect("report");
    assert!(
        html.contains("the handout's method under parametrisation y-zx"),
        "{}",
        readable(&html)
    );
    let bump_block = &html[html.find("<h2>bump.xml -b 2").expect("bump block")..];
    let (bump_block, distributed_block) = bump_block
        .split_once("<h2>distributed.xml -b 2")
        .expect("distributed block");
    assert!(
        (3..=6).contains(&images(bump_block)),
        "{}",
        readable(bump_block)
    );
    assert!(
        bump_block.contains("alt=\"the reference\""),
        "{}",
        readable(bump_block)
    );
    assert_eq!(
        images(distributed_block),
        1,
        "{}",
        readable(distributed_block)
    );
    assert!(
        distributed_block.contains("option 2 not done"),
        "{}",
        readable(distributed_block)
    );
    // The JSON: the same commands, and each runs as printed from the student's folder.
    let out = check(d.path(), &program, &["--suite-dir", "suite", "--json"]);
    let json: Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", stderr(&out)));
    let cases = json["cases"].as_array().expect("cases");
    assert_eq!(cases.len(), 2, "{json}");
    for (case, option, verdict) in [
        (&cases[0], "bump", "bump-correct"),
        (&cases[1], "distributed", "option-not-done"),
    ] {
        let reproduce = &case["reproduce"];
        assert_eq!(reproduce["scene"], format!("suite/{option}.xml"), "{case}");
        assert_eq!(reproduce["scene_written"], true, "{case}");
        let rerun = reproduce["run"].as_str().expect("run");
        assert!(rerun.starts_with("java "), "{rerun}");
        let checked = reproduce["check"].as_str().expect("check");
        assert_eq!(
            checked,
            format!("whitted check {option}_b2.png -b 2 --course 2023-24 --star {option}")
        );
        let ran = run_line(d.path(), rerun);
        assert!(ran.status.success(), "{rerun}: {}", stderr(&ran));
        let judged = run_line(d.path(), &format!("{checked} --json"));
        let judged: Value = serde_json::from_slice(&judged.stdout).expect("json");
        assert_eq!(judged["tick1_star"]["verdict"], verdict, "{judged}");
    }
}

#[test]
fn a_suite_dir_with_other_files_of_those_names_is_refused_before_anything_runs() {
    let d = tempfile::tempdir().expect("tempdir");
    let suite = d.path().join("suite");
    std::fs::create_dir_all(&suite).expect("suite");
    std::fs::write(suite.join("distributed.xml"), "<scene/>").expect("write");
    // The program is never started: its command need not exist.
    let program = format!("java -cp missing {PACKAGE}.Tick1");
    let out = check(d.path(), &program, &["--suite-dir", "suite"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let message = stderr(&out);
    assert!(message.contains("exists with other content"), "{message}");
    assert_eq!(message.trim().lines().count(), 1, "{message}");
    assert!(out.stdout.is_empty());
    // Nothing written beside it, nothing replaced.
    let written: Vec<_> = std::fs::read_dir(&suite)
        .expect("suite")
        .flatten()
        .collect();
    assert_eq!(written.len(), 1, "{written:?}");
    assert_eq!(
        std::fs::read(suite.join("distributed.xml")).expect("read"),
        b"<scene/>"
    );
}

#[test]
fn a_draw_of_a_variant_shows_its_numbers_and_where_it_fits_worst() {
    let d = tempfile::tempdir().expect("tempdir");
    let program = compiled(
        d.path(),
        PACKAGE,
        Done::Distributed,
        "-Dseed=611 -Dsoft=light-size",
    );
    let out = check(d.path(), &program, &["--verbose", "--report", "r.html"]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(1), "{text}{}", stderr(&out));
    for line in [
        "mean z^2 of the image against each process tried (a draw is near 1):",
        "light-size",
        "(a draw)",
        "the course's process fits worst at x ",
        // No --suite-dir: no command, and the way to get them, once.
        "add --suite-dir DIR to write the handout's scenes (bump.xml, its map, distributed.xml)",
    ] {
        assert!(text.contains(line), "{line:?} in\n{text}");
    }
    assert!(!text.contains("rerun it:"), "{text}");
    let html = std::fs::read_to_string(d.path().join("r.html")).expect("report");
    let distributed = &html[html.find("<h2>distributed.xml -b 2").expect("block")..];
    assert!(
        distributed.contains("but of light-size"),
        "{}",
        readable(distributed)
    );
    assert_eq!(images(distributed), 2, "{}", readable(distributed));
    assert!(
        distributed.contains("where the course's process fits worst"),
        "{}",
        readable(distributed)
    );
    // One screen: what --verbose and --report add, said in a line.
    let out = check(d.path(), &program, &[]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        text.contains("--verbose adds the numbers behind each option's verdict"),
        "{text}"
    );
    assert!(
        text.contains("--report FILE.html shows the images"),
        "{text}"
    );
}

#[test]
fn a_tick1_star_project_s_suite_dir_holds_its_scenes_and_its_classes() {
    let d = tempfile::tempdir().expect("tempdir");
    let project = d.path().join("project");
    std::fs::create_dir_all(&project).expect("project");
    compiled(&project, PACKAGE, Done::Bump, "");
    std::fs::remove_dir_all(project.join("classes")).expect("classes");
    let out = whitted(
        d.path(),
        &[
            "check",
            "--course",
            YEAR,
            "--json",
            "--suite-dir",
            "suite",
            "project",
        ],
    );
    let json: Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|_| panic!("{}", stderr(&out)));
    let suite = d.path().join("suite");
    for file in ["bump.xml", "bumpmap.png", "distributed.xml", "classes"] {
        assert!(suite.join(file).exists(), "{file}: {json}");
    }
    assert!(!suite.join("test1.xml").exists());
    let rerun = json["cases"][0]["reproduce"]["run"].as_str().expect("run");
    assert!(rerun.starts_with("java -cp suite/classes "), "{rerun}");
    let ran = run_line(d.path(), rerun);
    assert!(ran.status.success(), "{rerun}: {}", stderr(&ran));
    assert!(d.path().join("bump_b2.png").is_file());
}
