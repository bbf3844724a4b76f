//! Every class of bad input in docs/scene-format.md and docs/cli.md: exit status 2, one located line on
//! stderr, no panic, and no output file.

use crate::common::*;

fn assert_clean_failure(dir: &std::path::Path, args: &[&str], located: &str, phrase: &str) {
    let run = whitted(dir, args);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        !err.contains("panicked") && !err.contains("RUST_BACKTRACE"),
        "{err}"
    );
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected: {err}"
    );
    assert!(err.starts_with("error: "), "{err}");
    assert!(
        err.contains(located),
        "{args:?}: expected {located} in {err}"
    );
    assert!(
        err.contains(phrase),
        "{args:?}: expected `{phrase}` in {err}"
    );
}

/// `tests/bad_scenes/`: one scene per error class, each with the exact message it must give
/// in `<name>.expected` (`{file}` stands for the path as given on the command line).
#[test]
fn every_bad_scene_gives_its_expected_message_and_writes_nothing() {
    let corpus = root().join("tests/bad_scenes");
    let dir = tempfile::tempdir().expect("tempdir");
    let mut count = 0;
    let mut entries: Vec<_> = std::fs::read_dir(&corpus)
        .expect("corpus")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .collect();
    entries.sort();
    for scene in entries
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
    {
        let expected_file = scene.with_extension("expected");
        let expected = std::fs::read_to_string(&expected_file)
            .unwrap_or_else(|_| panic!("{} has no .expected file", scene.display()));
        let given = scene.to_str().expect("utf-8 path");
        let run = whitted(dir.path(), &["--input", given, "--output", "out.png"]);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{given}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert_eq!(
            err.trim_end(),
            expected.trim_end().replace("{file}", given),
            "{given}"
        );
        assert!(!dir.path().join("out.png").exists(), "{given} wrote a file");
        count += 1;
    }
    assert!(count >= 40, "only {count} bad scenes");
    assert_eq!(
        std::fs::read_dir(dir.path()).expect("ls").count(),
        0,
        "temporary files left"
    );
}

#[test]
fn unreadable_scene_files_are_clear_errors() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(
        dir.path().join("latin1.xml"),
        b"<scene>\n<!-- caf\xe9 -->\n</scene>",
    )
    .expect("write");
    std::fs::create_dir(dir.path().join("folder.xml")).expect("mkdir");
    assert_clean_failure(
        dir.path(),
        &["-i", "missing.xml", "-o", "a.png"],
        "missing.xml",
        "cannot read scene",
    );
    assert_clean_failure(
        dir.path(),
        &["-i", "folder.xml", "-o", "a.png"],
        "folder.xml",
        "cannot read scene",
    );
    assert_clean_failure(
        dir.path(),
        &["-i", "latin1.xml", "-o", "a.png"],
        "latin1.xml:2:9",
        "not valid UTF-8",
    );
    assert!(!dir.path().join("a.png").exists());
}

#[test]
fn bad_options_are_usage_errors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let cases: &[(&[&str], &str)] = &[
        (&["--bounces", "-1"], "bounces must be >= 0"),
        (&["-b", "x"], "whole number"),
        (&["--bounces", "1000"], "at most"),
        (&["--width", "0"], "between 1 and"),
        (&["--threads", "0"], "threads >= 1"),
        (&["--no-such-option"], "unexpected argument"),
        (&["render", "--colour"], "unexpected argument"),
    ];
    for (args, phrase) in cases {
        // clap's whole message: the error first, then the usage hint.
        let run = whitted(dir.path(), args);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.contains(phrase),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(!dir.path().join("output.png").exists());
}

#[test]
fn usage_errors_keep_what_clap_says() {
    let dir = tempfile::tempdir().expect("tempdir");
    let missing = stderr(&whitted(dir.path(), &["tonemap", "x.exr"]));
    assert!(
        missing.contains("required arguments were not provided") && missing.contains("--output"),
        "{missing}"
    );
    let values = stderr(&whitted(dir.path(), &["render", "--tonemap", "foo"]));
    assert!(
        values.contains("possible values: tick, clamp, reinhard, aces, agx, neutral"),
        "{values}"
    );
}

#[test]
fn unwritable_outputs_fail_before_rendering_and_leave_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::create_dir(dir.path().join("taken")).expect("mkdir");
    assert_clean_failure(
        dir.path(),
        &["-o", "no/such/dir/out.png"],
        "no/such/dir/out.png",
        "cannot write output",
    );
    assert_clean_failure(dir.path(), &["-o", "taken"], "taken", "it is a directory");
    assert_eq!(std::fs::read_dir(dir.path()).expect("ls").count(), 1);
}

#[test]
fn a_failed_render_keeps_the_previous_output() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(
        dir.path().join("bad.xml"),
        "<scene><sphere colour=\"#FFF\"/></scene>",
    )
    .expect("write");
    std::fs::write(dir.path().join("keep.png"), b"previous good output").expect("write");
    let run = whitted(dir.path(), &["-i", "bad.xml", "-o", "keep.png"]);
    assert_eq!(run.status.code(), Some(2));
    assert_eq!(
        std::fs::read(dir.path().join("keep.png")).expect("read"),
        b"previous good output"
    );
}

/// `check --report`'s format follows its extension (`.html` or `.png`): a report named
/// otherwise is refused before anything runs, never silently written under that name.
#[test]
fn a_check_report_neither_html_nor_png_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let image = reference("tick2_b2.png");
    for name in ["r", "r.pdf", "r.html.txt"] {
        let run = whitted(d, &["check", s(&image), "--report", name]);
        assert_eq!(run.status.code(), Some(2), "{name}");
        let message = stderr(&run);
        assert!(
            message.contains("REPORT.html") && message.contains("REPORT.png"),
            "{message}"
        );
        assert!(!d.join(name).exists(), "{name}");
    }
}
