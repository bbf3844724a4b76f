//! The same command gives the same bytes, whatever the thread count or destination.

use crate::common::*;

#[test]
fn png_is_byte_identical_for_one_and_two_threads() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = scene("tick2.xml");
    let scene = scene.to_str().expect("utf-8 path");
    let mut outputs = Vec::new();
    for threads in ["1", "2", "3"] {
        let out = format!("t{threads}.png");
        let run = whitted(
            dir.path(),
            &[
                "render",
                "-q",
                "-i",
                scene,
                "-o",
                &out,
                "--threads",
                threads,
            ],
        );
        assert!(run.status.success(), "{}", stderr(&run));
        outputs.push(std::fs::read(dir.path().join(out)).expect("read"));
    }
    assert!(outputs.windows(2).all(|w| w[0] == w[1]));
}

#[test]
fn dash_writes_the_same_png_to_stdout_and_nothing_else() {
    let dir = tempfile::tempdir().expect("tempdir");
    let to_file = whitted(dir.path(), &["-q", "-o", "file.png"]);
    assert!(to_file.status.success());
    let to_stdout = whitted(dir.path(), &["-q", "-o", "-"]);
    assert!(to_stdout.status.success());
    assert_eq!(
        to_stdout.stdout,
        std::fs::read(dir.path().join("file.png")).expect("read")
    );
    assert!(to_stdout.stderr.is_empty());
    assert_eq!(std::fs::read_dir(dir.path()).expect("ls").count(), 1);
}

#[test]
fn summary_goes_to_stderr_and_quiet_silences_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = whitted(
        dir.path(),
        &["--width", "64", "--height", "48", "-o", "s.png"],
    );
    assert!(run.status.success());
    assert!(run.stdout.is_empty());
    let err = stderr(&run);
    assert!(err.contains("64x48") && err.contains("rays"), "{err}");
    let run = whitted(
        dir.path(),
        &["--width", "64", "--height", "48", "-o", "s.png", "--quiet"],
    );
    assert!(run.stderr.is_empty() && run.stdout.is_empty());
}

#[test]
fn other_sizes_keep_the_field_of_view() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = whitted(
        dir.path(),
        &["-q", "--width", "320", "--height", "120", "-o", "wide.png"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let png = read_png(&dir.path().join("wide.png"));
    assert_eq!((png.width, png.height), (320, 120));
}
