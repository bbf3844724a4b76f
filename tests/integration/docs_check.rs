//! docs/check.md's opening examples run as written: the ```sh block at its top, line by line,
//! in a folder that has what the lines name (a 2021-22 Tick 1 project in IntelliJ's layout with
//! its shadows not written, the course's 2021-24 `test1.xml`, an image of it rendered at 0
//! bounces, the 2016-17 `output.png`). Each line must give a verdict (exit 0 or 1): a usage
//! error or a missing file (exit 2) fails the test.

use std::process::Command;

use crate::check_project::{project, Layout};
use crate::common::*;

/// The first ```sh block of `text`, one command a line (comments kept: bash drops them).
fn first_sh_block(text: &str) -> Vec<String> {
    text.split("```sh\n")
        .nth(1)
        .and_then(|rest| rest.split("\n```").next())
        .expect("docs/check.md has a ```sh block")
        .lines()
        .map(str::to_string)
        .collect()
}

#[test]
fn the_opening_examples_of_docs_check_md_run_as_written() {
    let doc = std::fs::read_to_string(root().join("docs/check.md")).expect("docs/check.md");
    let lines = first_sh_block(&doc);
    assert!(lines.len() >= 5, "{lines:?}");
    assert!(
        lines[0].starts_with("whitted check my-tick1"),
        "Tick 1 first: {}",
        lines[0]
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    project(d, "my-tick1", "2021-22", Layout::IntelliJ, &["no-shadows"]);
    std::fs::copy(
        root().join("scenes/courses/2021-24/test1.xml"),
        d.join("test1.xml"),
    )
    .expect("test1.xml");
    let made = whitted(
        d,
        &[
            "render",
            "--course",
            "2021-22",
            "-i",
            "test1.xml",
            "-b",
            "0",
            "-o",
            "mine.png",
            "-q",
        ],
    );
    assert!(made.status.success(), "{}", stderr(&made));
    let made = whitted(d, &["-o", "output.png", "-q"]);
    assert!(made.status.success(), "{}", stderr(&made));
    let bin = std::path::Path::new(env!("CARGO_BIN_EXE_whitted"))
        .parent()
        .expect("bin folder")
        .to_path_buf();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for line in &lines {
        let run = Command::new("bash")
            .args(["-c", line])
            .env("PATH", &path)
            .current_dir(d)
            .output()
            .expect("bash runs");
        let code = run.status.code();
        assert!(
            matches!(code, Some(0 | 1)),
            "`{line}` exited {code:?}:\n{}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(!run.stdout.is_empty(), "`{line}` printed nothing");
    }
    assert!(d.join("report.html").exists());
}
