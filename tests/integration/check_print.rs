//! How `whitted check` prints its one result: the default text fits one screen (at most 30
//! lines) and `--verbose` gives the detail; every command it prints runs as printed from the
//! directory the check ran in; `--report x.html` is one self-contained page with the images
//! inline and every string escaped, in image and in `--program` mode.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::*;

/// The default text's most lines.
const SCREEN: usize = 30;

fn stdout(run: &Output) -> String {
    String::from_utf8_lossy(&run.stdout).into_owned()
}

/// The commands a text prints (after "rerun it: ", "check it: ", "its worst pixel: ", or on
/// a line of their own under "the worst pixel ..."), in order.
pub fn commands(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for line in text.lines().map(str::trim) {
        for label in ["rerun it: ", "check it: ", "its worst pixel: "] {
            if let Some(command) = line.strip_prefix(label) {
                found.push(command.to_string());
            }
        }
        if line.starts_with("whitted ") {
            found.push(line.to_string());
        }
    }
    found
}

/// Runs `command` through sh in `dir`, its `whitted` the binary under test.
pub fn run_as_printed(dir: &Path, command: &str) -> Output {
    let command = match command.strip_prefix("whitted ") {
        Some(rest) => format!("{} {rest}", env!("CARGO_BIN_EXE_whitted")),
        None => command.to_string(),
    };
    Command::new("sh")
        .args(["-c", &command])
        .current_dir(dir)
        .output()
        .expect("sh runs")
}

/// Runs each printed command in `dir`, in order, as printed: a `whitted check` of a failing
/// case exits 1 (the case still fails), everything else 0.
pub fn assert_every_command_runs(dir: &Path, printed: &[String]) {
    for command in printed {
        let run = run_as_printed(dir, command);
        let expected = if command.starts_with("whitted check ") {
            1
        } else {
            0
        };
        assert_eq!(
            run.status.code(),
            Some(expected),
            "{command}: {}",
            stderr(&run)
        );
    }
}

/// The checks every report page passes: a page of its own, images inline (the full images and
/// the enlarged worst region of each failing case), nothing of `raw` unescaped.
fn assert_page(html: &str, failing: usize, raw: &str, escaped: &str) {
    assert!(html.starts_with("<!doctype html"), "{}", &html[..80]);
    assert!(html.trim_end().ends_with("</html>"));
    let images = html.matches("<img ").count();
    assert_eq!(
        images,
        6 * failing,
        "three images and three zooms a failing case"
    );
    assert_eq!(
        html.matches("src=\"data:image/png;base64,").count(),
        images,
        "every image inline"
    );
    assert_eq!(html.matches("enlarged\"").count(), 3 * failing);
    assert!(!html.contains(raw), "`{raw}` unescaped");
    assert!(html.contains(escaped), "`{escaped}` missing");
    assert!(!html.contains("<script"));
}

#[test]
fn a_failing_image_fits_one_screen_and_verbose_gives_the_detail() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // The acceptance check: a 2021-22 render at 0 bounces checked against 2 bounces, on a
    // scene named as the user gave it (here relative, with a `<` to escape).
    let scene = root().join("scenes/courses/2021-24/test1.xml");
    std::fs::copy(&scene, d.join("a<b.xml")).expect("scene");
    let render = whitted(
        d,
        &[
            "render",
            "--course",
            "2021-22",
            "-i",
            "a<b.xml",
            "-b",
            "0",
            "-o",
            "t1_b0.png",
            "-q",
        ],
    );
    assert!(render.status.success(), "{}", stderr(&render));
    let check = [
        "check",
        "t1_b0.png",
        "-i",
        "a<b.xml",
        "-b",
        "2",
        "--course",
        "2021-22",
    ];
    let run = whitted(d, &[&check[..], &["--report", "r.html"]].concat());
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let text = stdout(&run);
    assert!(text.lines().count() <= SCREEN, "{text}");
    assert!(!text.contains("DIR/"), "{text}");
    assert!(text.contains("progress: ") && text.contains("1. reflection-ignored"));
    assert!(text.contains("fix: "), "the finding with its fix: {text}");
    assert!(
        commands(&text).is_empty(),
        "commands are --verbose's: {text}"
    );
    let html = std::fs::read_to_string(d.join("r.html")).expect("r.html");
    assert_page(&html, 1, "a<b.xml", "a&lt;b.xml");
    assert!(html.contains("reflection-ignored") && html.contains("fix: "));

    // --verbose: what the images cannot tell, and the explain commands, which run as printed.
    let run = whitted(d, &[&check[..], &["--verbose"]].concat());
    let verbose = stdout(&run);
    assert!(verbose.lines().count() > text.lines().count(), "{verbose}");
    assert!(
        verbose.contains("the images cannot tell whether"),
        "{verbose}"
    );
    let printed = commands(&verbose);
    assert_eq!(printed.len(), 2, "{verbose}");
    for command in &printed {
        let run = run_as_printed(d, command);
        assert!(run.status.success(), "{command}: {}", stderr(&run));
    }
    assert!(stdout(&run_as_printed(d, &printed[1])).contains("reflection-ignored"));
    // The JSON still has every fact.
    let run = whitted(d, &[&check[..], &["--json"]].concat());
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    assert_eq!(json["diagnosis"][0]["bugs"][0], "reflection-ignored");
    assert_eq!(json["course"], "2021-22");
    assert_eq!(json["scene"], "a<b.xml");
}

#[test]
fn a_failing_program_fits_one_screen_and_prints_no_command_that_cannot_run() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // A 2021-22 Tick 1 with a mistake: six cases, every one failing; `<b>` in its line.
    let program = java_program_with(Some("2021-22"), "-Dnote=<b> ", &["no-ambient"]);
    let check = [
        "check",
        "--course",
        "2021-22",
        "--program",
        program.as_str(),
    ];
    let run = whitted(d, &[&check[..], &["--report", "p.html"]].concat());
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let text = stdout(&run);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.len() <= SCREEN, "{text}");
    assert_eq!(lines.iter().filter(|l| l.contains(".xml -b ")).count(), 6);
    assert!(
        text.contains("1. no-ambient") && text.contains("fix: "),
        "{text}"
    );
    assert!(
        !text.contains("DIR/") && commands(&text).is_empty(),
        "{text}"
    );
    assert!(text.contains("--suite-dir DIR"), "{text}");
    let html = std::fs::read_to_string(d.join("p.html")).expect("p.html");
    assert_page(&html, 6, "-Dnote=<b>", "-Dnote=&lt;b&gt;");
    assert!(html.contains("<h2>test1.xml -b 0</h2>"));
    // Without the scenes, --verbose says once how to get them and prints no command.
    let run = whitted(d, &[&check[..], &["--verbose"]].concat());
    let verbose = stdout(&run);
    assert_eq!(
        verbose.matches("add --suite-dir DIR").count(),
        1,
        "{verbose}"
    );
    assert!(!verbose.contains("DIR/") && commands(&verbose).is_empty());
    let run = whitted(d, &[&check[..], &["--json"]].concat());
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    let reproduce = &json["cases"][0]["reproduce"];
    assert_eq!(
        (
            &reproduce["scene"],
            &reproduce["scene_written"],
            &reproduce["run"]
        ),
        (
            &serde_json::json!("test1.xml"),
            &serde_json::json!(false),
            &serde_json::Value::Null
        )
    );

    // With the scenes written, every command printed runs as printed, in order, from here.
    let run = whitted(
        d,
        &[&check[..], &["--suite-dir", "suite", "--verbose"]].concat(),
    );
    let verbose = stdout(&run);
    let printed = commands(&verbose);
    // Each case's run, check and one or two explains.
    assert!(printed.len() >= 6 * 3, "{verbose}");
    assert_every_command_runs(d, &printed);
    assert!(d.join("test1_b0.png").exists() && d.join("mirrors_b3.png").exists());
}

#[test]
fn a_report_not_written_leaves_nothing_behind() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    std::fs::write(d.join("r.html"), "mine").expect("an old report");
    // An image that cannot be read: exit 2, and the old report is as it was.
    std::fs::write(d.join("junk.png"), b"not a png").expect("junk");
    let run = whitted(d, &["check", "junk.png", "--report", "r.html"]);
    assert_eq!(run.status.code(), Some(2));
    assert_eq!(
        std::fs::read_to_string(d.join("r.html")).expect("r.html"),
        "mine"
    );
    let leftovers = std::fs::read_dir(d).expect("dir").count();
    assert_eq!(leftovers, 2, "no temporary file left");
}
