//! Hostile inputs and outputs around the renderer: bad images (tests/bad_images/, made by
//! tools/bad_images.py), every reading subcommand under a 4 GiB address-space limit, special
//! and linked outputs, signals, and a standard output that is closed, full or goes away.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::*;

/// Runs `whitted args` in `dir` under `ulimit -v` (KiB), as the hostile-input checks do.
fn limited(dir: &Path, kib: u64, args: &[&str]) -> std::process::Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("sh runs")
}

/// No whitted temporary file is left in `dir`.
fn assert_no_temp_files(dir: &Path) {
    let left: Vec<String> = std::fs::read_dir(dir)
        .expect("ls")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".whitted-"))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}

/// Whether `message` matches `pattern`, where `{any}` matches any text.
fn matches(pattern: &str, message: &str) -> bool {
    let parts: Vec<&str> = pattern.split("{any}").collect();
    let mut rest = message;
    for (i, part) in parts.iter().enumerate() {
        match rest.find(part) {
            Some(at) if i > 0 || at == 0 => rest = &rest[at + part.len()..],
            _ => return false,
        }
    }
    parts.len() > 1 || rest.is_empty()
}

#[test]
fn every_bad_image_gives_its_expected_message_and_writes_nothing() {
    let corpus = root().join("tests/bad_images");
    let dir = tempfile::tempdir().expect("tempdir");
    let mut checked = 0;
    for entry in std::fs::read_dir(&corpus).expect("tests/bad_images") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "expected") {
            continue;
        }
        let file = path.to_str().expect("utf-8").to_string();
        let expected_path = PathBuf::from(format!("{file}.expected"));
        let expected = std::fs::read_to_string(&expected_path)
            .unwrap_or_else(|e| panic!("{}: {e}", expected_path.display()));
        let mut lines = expected.lines();
        let command = lines
            .next()
            .expect("a command line")
            .replace("{file}", &file);
        let message = lines.next().expect("a message").replace("{file}", &file);
        let args: Vec<&str> = command.split(' ').collect();
        let run = limited(dir.path(), 4 << 20, &args);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{command}: {err}");
        assert!(
            matches(&message, err.trim_end()),
            "{command}:\n  expected {message}\n  got      {err}"
        );
        // Every reading subcommand refuses it the same way, without a panic or an abort.
        for other in [
            vec!["info", file.as_str()],
            vec!["diff", file.as_str(), file.as_str()],
            vec!["tonemap", file.as_str(), "-o", "t.png"],
            vec!["sheet", file.as_str(), "-o", "s.png"],
            vec!["merge", file.as_str(), "-o", "m.exr"],
        ] {
            let run = limited(dir.path(), 4 << 20, &other);
            let code = run.status.code();
            assert!(matches!(code, Some(0..=2)), "{other:?}: {:?}", run.status);
            assert!(!stderr(&run).contains("panicked"), "{other:?}");
        }
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} bad images");
    for written in ["merged.exr", "m.exr"] {
        assert!(!dir.path().join(written).exists(), "{written} was written");
    }
    assert_no_temp_files(dir.path());
}

#[test]
fn device_and_directory_inputs_are_refused_at_once() {
    let dir = tempfile::tempdir().expect("tempdir");
    let started = Instant::now();
    let run = whitted(dir.path(), &["info", "/dev/zero"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("not an image whitted reads"));
    assert!(started.elapsed() < Duration::from_secs(5));
    let run = whitted(dir.path(), &["info", "."]);
    assert!(
        stderr(&run).contains("it is a directory"),
        "{}",
        stderr(&run)
    );
}

#[test]
fn many_channels_take_linear_time() {
    // 100,000 one-pixel channels: grouping and statistics must not be quadratic.
    let dir = tempfile::tempdir().expect("tempdir");
    let script = root().join("tools/bad_images.py");
    let make = format!(
        "import sys; sys.path.insert(0, {:?}); import bad_images as b; \
         open('wide.exr', 'wb').write(b.exr_1x1([('c%06d' % i, 1) for i in range(100000)]))",
        script.parent().expect("tools").display().to_string()
    );
    let run = run_tool("python", &["-c", &make], dir.path());
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let started = Instant::now();
    let run = whitted(dir.path(), &["info", "--json", "wide.exr"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    assert_eq!(json["channels"].as_array().map(Vec::len), Some(100_000));
    assert!(
        started.elapsed() < Duration::from_secs(30),
        "{:?}",
        started.elapsed()
    );
}

#[test]
fn an_address_space_limit_is_a_clear_error_not_an_abort() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = limited(
        dir.path(),
        1 << 20,
        &[
            // Streamed in strips: only rows this wide need more than the limit.
            "render", "--width", "65535", "--height", "65535", "--exr", "big.exr", "-o", "big.png",
        ],
    );
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: cannot allocate") && err.contains("is available"),
        "{err}"
    );
    assert!(!dir.path().join("big.exr").exists() && !dir.path().join("big.png").exists());
}

/// A 12000 x 12000 PNG of one grey (the reference of a lights-only scene would do): 432 MB of
/// pixels in under 1 MB of file.
fn png_bomb(path: &Path) {
    let file = std::fs::File::create(path).expect("create");
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), 12000, 12000);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().expect("header");
    let mut stream = writer.stream_writer().expect("stream");
    let row = vec![25u8; 12000 * 3];
    for _ in 0..12000 {
        std::io::Write::write_all(&mut stream, &row).expect("row");
    }
    stream.finish().expect("finish");
}

#[test]
fn a_png_bomb_is_refused_by_check_before_its_buffers_are_allocated() {
    let dir = tempfile::tempdir().expect("tempdir");
    let bomb = dir.path().join("bomb.png");
    png_bomb(&bomb);
    assert!(std::fs::metadata(&bomb).expect("bomb").len() < 8 << 20);
    // 1.5 GiB: the decode fits; the check's renders at this size (6 GiB) do not. (With --view
    // the URL may come first, when reading took longer than the viewer waits before serving.)
    for extra in [&[][..], &["--json"], &["--view", "--no-browser"]] {
        let mut args = vec!["check", "bomb.png"];
        args.extend_from_slice(extra);
        let run = limited(dir.path(), 1536 << 10, &args);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{extra:?}: {err}");
        assert!(
            err.contains("cannot allocate")
                && err.contains("12000x12000")
                && err.contains("is available"),
            "{extra:?}: {err}"
        );
    }
}

#[test]
fn outputs_that_are_inputs_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "a.exr",
        &["--width", "32", "--height", "24"],
    );
    let before = std::fs::read(&exr).expect("read");
    std::os::unix::fs::symlink("a.exr", dir.path().join("link.exr")).expect("symlink");
    for args in [
        vec!["tonemap", "a.exr", "-o", "a.exr"],
        vec!["sheet", "a.exr", "-o", "./a.exr"],
        vec!["diff", "a.exr", "a.exr", "--heatmap", "link.exr"],
        vec!["merge", "a.exr", "-o", "link.exr"],
    ] {
        let run = whitted(dir.path(), &args);
        assert_eq!(run.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&run).contains("is the input"),
            "{args:?}: {}",
            stderr(&run)
        );
    }
    assert_eq!(std::fs::read(&exr).expect("read"), before);
    assert_no_temp_files(dir.path());
}

#[test]
fn special_files_are_written_through_and_links_are_kept() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // A character device made here (like /dev/null): written through, never replaced.
    let mknod = Command::new("mknod")
        .args(["null", "c", "1", "3"])
        .current_dir(d)
        .status()
        .expect("mknod runs");
    assert!(mknod.success(), "mknod needs root, as CI has");
    let run = whitted(d, &["-q", "-o", "null", "--width", "16", "--height", "12"]);
    assert!(run.status.success(), "{}", stderr(&run));
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(d.join("null"))
        .expect("meta")
        .file_type()
        .is_char_device());

    // /dev/stdout, whose link in /proc is not a path: written through to the pipe.
    let piped = Command::new("sh")
        .arg("-c")
        .arg("\"$0\" -q -o /dev/stdout --width 16 --height 12 | wc -c")
        .arg(env!("CARGO_BIN_EXE_whitted"))
        .current_dir(d)
        .output()
        .expect("sh");
    let bytes: usize = String::from_utf8_lossy(&piped.stdout)
        .trim()
        .parse()
        .expect("a count");
    assert!(bytes > 100, "{bytes} bytes through /dev/stdout");

    // A full device: an error, and the device stays.
    let run = whitted(
        d,
        &["-q", "-o", "/dev/full", "--width", "16", "--height", "12"],
    );
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(std::fs::symlink_metadata("/dev/full")
        .expect("meta")
        .file_type()
        .is_char_device());

    // A FIFO: written through to its reader.
    let fifo = Command::new("mkfifo")
        .arg("pipe")
        .current_dir(d)
        .status()
        .expect("mkfifo");
    assert!(fifo.success());
    let reader = Command::new("cat")
        .arg("pipe")
        .current_dir(d)
        .stdout(Stdio::piped())
        .spawn()
        .expect("cat");
    let run = whitted(d, &["-q", "-o", "pipe", "--width", "16", "--height", "12"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let got = reader.wait_with_output().expect("cat output");
    assert!(
        got.stdout.starts_with(b"\x89PNG"),
        "{} bytes",
        got.stdout.len()
    );
    assert!(std::fs::symlink_metadata(d.join("pipe"))
        .expect("meta")
        .file_type()
        .is_fifo());

    // A symlink: the file it points to is replaced, the link stays a link.
    std::fs::create_dir(d.join("real")).expect("mkdir");
    std::fs::write(d.join("real/out.png"), b"old").expect("write");
    std::os::unix::fs::symlink("real/out.png", d.join("out.png")).expect("symlink");
    let run = whitted(
        d,
        &["-q", "-o", "out.png", "--width", "16", "--height", "12"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(std::fs::symlink_metadata(d.join("out.png"))
        .expect("meta")
        .file_type()
        .is_symlink());
    assert!(std::fs::read(d.join("real/out.png"))
        .expect("read")
        .starts_with(b"\x89PNG"));
    assert_no_temp_files(d);
    assert_no_temp_files(&d.join("real"));
}

/// Starts a render long enough to interrupt, sends `signal` (twice if `twice`), and returns
/// its exit code; the previous output must survive and no temporary file remain.
fn interrupted_render(signal: &str, twice: bool) -> Option<i32> {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("out.exr"), b"previous").expect("write");
    let mut child = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args([
            "render", "-q", "--width", "2000", "--height", "1500", "--spp", "64", "--exr",
            "out.exr", "-o", "out.png",
        ])
        .current_dir(dir.path())
        .stderr(Stdio::null())
        .spawn()
        .expect("whitted starts");
    std::thread::sleep(Duration::from_millis(700));
    let pid = child.id().to_string();
    let sent = Instant::now();
    for _ in 0..(1 + usize::from(twice)) {
        Command::new("kill")
            .args([&format!("-{signal}"), &pid])
            .status()
            .expect("kill");
    }
    let status = child.wait().expect("wait");
    assert!(
        sent.elapsed() < Duration::from_secs(2),
        "took {:?}",
        sent.elapsed()
    );
    assert_eq!(
        std::fs::read(dir.path().join("out.exr")).expect("kept"),
        b"previous"
    );
    assert!(!dir.path().join("out.png").exists());
    assert_no_temp_files(dir.path());
    status.code()
}

#[test]
fn signals_stop_cleanly_with_128_plus_the_signal() {
    assert_eq!(interrupted_render("INT", false), Some(130));
    assert_eq!(interrupted_render("TERM", false), Some(143));
    assert_eq!(interrupted_render("HUP", false), Some(129));
    assert_eq!(interrupted_render("QUIT", false), Some(131));
    assert_eq!(interrupted_render("TERM", true), Some(143));
}

#[test]
fn standard_output_that_goes_away_is_quiet_and_closed_or_full_is_an_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    render_exr(
        dir.path(),
        &scene("tick2.xml"),
        "a.exr",
        &["--width", "32", "--height", "24"],
    );
    let shell = |script: &str| {
        Command::new("sh")
            .arg("-c")
            .arg(script)
            .arg(env!("CARGO_BIN_EXE_whitted"))
            .current_dir(dir.path())
            .output()
            .expect("sh")
    };
    // The reader stops after one line: whitted's own status survives, nothing on stderr.
    let run = shell("\"$0\" info a.exr | head -1 >/dev/null; echo \"${PIPESTATUS:-0}\"");
    assert!(run.status.success());
    for script in [
        "\"$0\" info a.exr | true",
        "\"$0\" diff --json a.exr a.exr | true",
    ] {
        let run = shell(&format!("{script}; exit 0"));
        assert!(
            !String::from_utf8_lossy(&run.stderr).contains("panicked"),
            "{script}"
        );
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(["diff", "a.exr", "a.exr"])
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait");
    assert_eq!(out.status.code(), Some(0), "diff keeps its verdict");
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    for script in [
        "exec \"$0\" info a.exr >&-",
        "exec \"$0\" info a.exr >/dev/full",
    ] {
        let run = shell(script);
        assert_eq!(run.status.code(), Some(2), "{script}");
        assert!(String::from_utf8_lossy(&run.stderr).contains("standard output"));
    }
    // Python's subprocess.DEVNULL opens /dev/null read-write, as Rust's runtime reopens a
    // closed descriptor: that is not a closed standard output.
    let run = shell("exec \"$0\" info a.exr 1<>/dev/null");
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}
