//! Every class of bad input in scene-format.md and cli.md: exit status 2, one located line on
//! stderr, no panic, and no output file.

mod common;

use common::*;

/// (file name, content, expected `line:col`, a phrase the message must contain)
const BAD_SCENES: &[(&str, &str, &str, &str)] = &[
    ("empty.xml", "", "1:1", "the file is empty"),
    ("blank.xml", "  \n\n", "1:1", "the file is empty"),
    ("not_xml.xml", "<scene>\n  <sphere colour=\"#FF0000\">\n</scene>\n", "3:1", "not well-formed XML"),
    ("unclosed.xml", "<scene>\n  <sphere colour=\"#FF0000\"/>\n", "1:1", "<scene> is never closed"),
    ("bad_quote.xml", "<scene>\n  <sphere colour=#FF0000/>\n</scene>", "2:", "not well-formed XML"),
    ("wrong_root.xml", "<world>\n  <sphere colour=\"#FF0000\"/>\n</world>\n", "1:1", "root element is <world>, expected <scene>"),
    ("two_roots.xml", "<scene/>\n<scene/>\n", "2:1", "a second root element"),
    ("text.xml", "<scene>\n  sphere please\n</scene>\n", "2:3", "unexpected text"),
    ("unknown_element.xml", "<scene>\n  <sphear colour=\"#FF0000\"/>\n</scene>\n", "2:3", "did you mean <sphere>?"),
    ("nested.xml", "<scene>\n  <sphere colour=\"#FF0000\">\n    <plane ny=\"1\" colour=\"#FF0000\"/>\n  </sphere>\n</scene>\n", "3:5", "nested inside <sphere>"),
    ("misspelt_attr.xml", "<scene>\n  <sphere x=\"0\" color=\"#FF0000\"/>\n</scene>\n", "2:17", "did you mean `colour`?"),
    ("unknown_attr.xml", "<scene>\n  <plane ny=\"1\" shininess=\"3\" colour=\"#FF0000\"/>\n</scene>\n", "2:17", "unknown attribute `shininess`"),
    ("duplicate_attr.xml", "<scene>\n  <sphere x=\"0\" x=\"1\" colour=\"#FF0000\"/>\n</scene>\n", "2:17", "duplicate attribute `x`"),
    ("missing_colour.xml", "<scene>\n  <sphere x=\"0\"/>\n</scene>\n", "2:3", "needs a `colour` attribute"),
    ("short_colour.xml", "<scene>\n  <sphere colour=\"#FFF\"/>\n</scene>\n", "2:11", "#RRGGBB"),
    ("named_colour.xml", "<scene>\n  <sphere colour=\"red\"/>\n</scene>\n", "2:11", "#RRGGBB"),
    ("bad_hex.xml", "<scene>\n  <sphere colour=\"#GGGGGG\"/>\n</scene>\n", "2:11", "#RRGGBB"),
    ("bad_number.xml", "<scene>\n  <sphere y=\"abc\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "`y` must be a number"),
    ("nan.xml", "<scene>\n  <sphere x=\"NaN\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "finite"),
    ("infinite.xml", "<scene>\n  <sphere z=\"1e999\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "finite"),
    ("zero_radius.xml", "<scene>\n  <sphere radius=\"0\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "`radius` must be > 0"),
    ("neg_radius.xml", "<scene>\n  <sphere radius=\"-1\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "`radius` must be > 0"),
    ("zero_normal.xml", "<scene>\n  <plane nx=\"0\" ny=\"0\" nz=\"0\" colour=\"#FF0000\"/>\n</scene>\n", "2:3", "zero length"),
    ("tiny_normal.xml", "<scene>\n  <plane ny=\"1e-300\" colour=\"#FF0000\"/>\n</scene>\n", "2:3", "zero length"),
    ("neg_intensity.xml", "<scene>\n  <point-light intensity=\"-5\" colour=\"#FF0000\"/>\n</scene>\n", "2:16", "`intensity` must be >= 0"),
    ("reflectivity.xml", "<scene>\n  <sphere reflectivity=\"1.01\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "between 0 and 1"),
    ("neg_reflectivity.xml", "<scene>\n  <sphere reflectivity=\"-0.1\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "between 0 and 1"),
    ("neg_kd.xml", "<scene>\n  <sphere kD=\"-1\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "`kD` must be >= 0"),
    ("neg_ks.xml", "<scene>\n  <sphere kS=\"-1\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "`kS` must be >= 0"),
    ("neg_n.xml", "<scene>\n  <sphere n=\"-2\" colour=\"#FF0000\"/>\n</scene>\n", "2:11", "`n` must be >= 0"),
    ("two_ambient.xml", "<scene>\n  <ambient-light colour=\"#111111\"/>\n  <ambient-light colour=\"#222222\"/>\n</scene>\n", "3:3", "a second <ambient-light>"),
    ("dup_light_name.xml", "<scene>\n  <point-light name=\"key\" colour=\"#FFFFFF\"/>\n  <point-light name=\"key\" colour=\"#FFFFFF\"/>\n</scene>\n", "3:16", "duplicate light name `key`"),
    ("bad_light_name.xml", "<scene>\n  <point-light name=\"key light\" colour=\"#FFFFFF\"/>\n</scene>\n", "2:16", "light name `key light`"),
    ("long_light_name.xml", "<scene>\n  <point-light name=\"a23456789012345678\" colour=\"#FFFFFF\"/>\n</scene>\n", "2:16", "at most 16 characters"),
];

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

#[test]
fn every_bad_scene_is_a_located_error_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (name, text, at, phrase) in BAD_SCENES {
        std::fs::write(dir.path().join(name), text).expect("write scene");
        let out = format!("{name}.png");
        assert_clean_failure(
            dir.path(),
            &["--input", name, "--output", &out],
            &format!("{name}:{at}"),
            phrase,
        );
        assert!(!dir.path().join(&out).exists(), "{name}: output written");
    }
    // Nothing but the scenes themselves: no temporary files left behind.
    let files = std::fs::read_dir(dir.path()).expect("ls").count();
    assert_eq!(files, BAD_SCENES.len());
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
        assert_clean_failure(dir.path(), args, "error:", phrase);
    }
    assert!(!dir.path().join("output.png").exists());
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
