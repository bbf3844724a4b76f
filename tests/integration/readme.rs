//! Every shell example in README.md runs as written: each ```sh block, in order, in one
//! temporary directory that has the repository's `scenes/` and `reference/`, with the built
//! `whitted` and OpenImageIO's `oiiotool` on PATH.
//!
//! The students' blocks that `cd my-tick1` run in a Tick 1 project folder of 2021-22 made as
//! a student has it (IntelliJ's layout, whitted's clean-room classes, the three files with one
//! mistake, no shadows), beside the others.
//!
//! Two lines of the first block are the repository's own commands and are not run again
//! here: `tools/test` is the command running this very test, and `cargo run --release [--]`
//! runs the binary under test with the same arguments, which is what is run in its place.

use std::path::Path;
use std::process::Command;

use crate::check_project::{project, Layout};
use crate::common::*;

/// The student's project the README's Tick 1 examples run in: `d/my-tick1`.
fn student_project(d: &Path) {
    project(d, "my-tick1", "2021-22", Layout::IntelliJ, &["no-shadows"]);
    // What `project` leaves beside it to build it from is not the student's.
    let _ = std::fs::remove_dir_all(d.join("my-tick1-skeleton"));
}

/// The ```sh blocks of the README, in order.
fn shell_blocks(readme: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in readme.lines() {
        match (&mut current, line.trim_end()) {
            (None, "```sh") => current = Some(String::new()),
            (Some(block), "```") => {
                blocks.push(std::mem::take(block));
                current = None;
            }
            (Some(block), line) => {
                block.push_str(line);
                block.push('\n');
            }
            (None, _) => {}
        }
    }
    blocks
}

/// The block as it runs here (see the module comment for the two repository commands).
fn runnable(block: &str) -> String {
    block
        .lines()
        .filter(|l| !l.trim_start().starts_with("tools/test"))
        .map(|l| {
            l.replacen("cargo run --release --", "whitted", 1).replacen(
                "cargo run --release",
                "whitted",
                1,
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn link(from: &Path, to: &Path) {
    std::os::unix::fs::symlink(from, to)
        .unwrap_or_else(|e| panic!("{} -> {}: {e}", to.display(), from.display()));
}

#[test]
fn every_readme_example_runs_as_written() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let blocks = shell_blocks(&readme);
    assert!(blocks.len() >= 8, "only {} shell blocks", blocks.len());
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    for name in ["scenes", "reference"] {
        link(&root().join(name), &d.join(name));
    }
    student_project(d);
    let bin = d.join(".bin");
    std::fs::create_dir(&bin).expect("mkdir");
    link(
        Path::new(env!("CARGO_BIN_EXE_whitted")),
        &bin.join("whitted"),
    );
    link(&tool("oiiotool"), &bin.join("oiiotool"));
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for block in &blocks {
        let script = runnable(block);
        let run = Command::new("bash")
            .args(["-euo", "pipefail", "-c", &script])
            .env("PATH", &path)
            .current_dir(d)
            .output()
            .expect("bash runs");
        assert!(
            run.status.success(),
            "README example failed:\n{script}\n{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    for made in [
        "output.png",
        "tick1.png",
        "my-tick1/report.html",
        "floor.png",
        "shadow.png",
        "frame.exr",
        "light0.exr",
        "sheet.png",
        "where.png",
        "mine.png",
        "whitted.bash",
        "whitted.1",
        "tick2_agx.png",
        "key.png",
    ] {
        let meta = std::fs::metadata(d.join(made)).unwrap_or_else(|_| panic!("{made} missing"));
        assert!(meta.len() > 0, "{made} is empty");
    }
}

/// The students' examples (the blocks of "For students" that run `whitted check`) run from a
/// student's own directory: no `scenes/` of this repository beside them.
#[test]
fn the_students_check_examples_run_from_any_directory() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let students = readme
        .split("## For students")
        .nth(1)
        .and_then(|s| s.split("\n## ").next())
        .expect("the For students section");
    let blocks: Vec<String> = shell_blocks(students)
        .into_iter()
        .filter(|b| b.contains("whitted check"))
        .collect();
    assert!(!blocks.is_empty(), "no check example");
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    student_project(d);
    let bin = d.join(".bin");
    std::fs::create_dir(&bin).expect("mkdir");
    link(
        Path::new(env!("CARGO_BIN_EXE_whitted")),
        &bin.join("whitted"),
    );
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for block in &blocks {
        let run = Command::new("bash")
            .args(["-euo", "pipefail", "-c", block])
            .env("PATH", &path)
            .current_dir(d)
            .output()
            .expect("bash runs");
        assert!(
            run.status.success(),
            "README example failed outside the repository:\n{block}\n{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    assert!(d.join("check.json").exists());
    assert!(d.join("my-tick1/report.html").exists());
}
