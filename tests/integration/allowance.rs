//! `--max-beyond`: the pixels a case may have beyond the channel tolerance (docs/check.md,
//! docs/grade.md). An image a handful of pixels off fails by default and passes with an
//! allowance, in `check` and in `grade`, and says how it passes; `grade --calibrate` counts,
//! from the results on disk, the students each (tolerance, allowance) passes.

use std::path::Path;

use serde_json::Value;

use crate::common::*;
use crate::grade::{grade, submission};
use whitted_check::check::renderer::Renderer;
use whitted_check::check::suite::cases;

/// Pixels the perturbed images and programs change, each by 8 in every channel.
const OFF: usize = 7;

/// The course's tick2.xml at 2 bounces as whitted renders it, with `OFF` pixels of row 10
/// changed by 8 in each channel, written to `path`.
fn few_pixels_off(path: &Path) {
    let case = cases()
        .into_iter()
        .find(|c| c.file == "tick2.xml" && c.bounces == 2)
        .expect("tick2.xml -b 2");
    let scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
    let renderer = Renderer::new(&scene, 640, 480, 2).expect("renderer");
    let mut image = renderer.reference().expect("image");
    for x in 10..10 + OFF {
        let i = 3 * (10 * 640 + x);
        for byte in &mut image.bytes[i..i + 3] {
            *byte ^= 8;
        }
    }
    let file = std::fs::File::create(path).expect("create");
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), 640, 480);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().expect("header");
    writer.write_image_data(&image.bytes).expect("data");
}

fn json(out: &std::process::Output) -> Value {
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

#[test]
fn check_passes_an_image_a_few_pixels_off_only_with_an_allowance_and_says_so() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    few_pixels_off(&d.join("off.png"));
    let strict = whitted(d, &["check", "off.png", "--json"]);
    assert_eq!(strict.status.code(), Some(1), "{}", stderr(&strict));
    let report = json(&strict);
    assert_eq!(report["verdict"], "differs");
    assert_eq!(report["pixels_beyond_tolerance"], OFF);
    assert_eq!(report["max_beyond"], "0");
    let allowed = whitted(d, &["check", "off.png", "--max-beyond", "10", "--json"]);
    assert_eq!(allowed.status.code(), Some(0), "{}", stderr(&allowed));
    let report = json(&allowed);
    assert_eq!(report["verdict"], "within-tolerance");
    assert_eq!(report["max_beyond"], "10");
    assert_eq!(report["pixels_allowed_beyond"], 10);
    assert_eq!(report["pixels_beyond_tolerance"], OFF);
    assert_eq!(
        report["verdict_text"],
        "within-tolerance (7 pixels beyond ±2, allowed up to 10)"
    );
    // One pixel fewer allowed than are off fails; 0.01% of 307200 is 30, which passes.
    let short = whitted(
        d,
        &["check", "off.png", "--max-beyond", &(OFF - 1).to_string()],
    );
    assert_eq!(short.status.code(), Some(1), "{}", stderr(&short));
    let share = whitted(d, &["check", "off.png", "--max-beyond", "0.01%", "--json"]);
    assert_eq!(share.status.code(), Some(0), "{}", stderr(&share));
    assert_eq!(json(&share)["pixels_allowed_beyond"], 30);
    // The text never calls it plainly within the tolerance.
    let text = whitted(d, &["check", "off.png", "--max-beyond", "10"]);
    let text = String::from_utf8_lossy(&text.stdout);
    let first = text.lines().next().unwrap_or_default();
    assert_eq!(
        first,
        "tick2.xml (embedded), 640x480, 2 bounces: within-tolerance (7 pixels beyond ±2, allowed up to 10) \
         (tolerance: 2 of 255 in a channel, but for at most 10 pixels)",
        "{text}"
    );
    for bad in ["-1", "1.5", "nan%", "101%", "5 %", "ten"] {
        let refused = whitted(d, &["check", "off.png", "--max-beyond", bad]);
        assert_eq!(refused.status.code(), Some(2), "--max-beyond {bad}");
        assert!(
            stderr(&refused).contains("--max-beyond"),
            "{bad}: {}",
            stderr(&refused)
        );
    }
}

/// A student's folder in `root`: the fixture with `bugs`, and `tail` run on the image just
/// before `render` returns it.
fn student(root: &Path, id: &str, bugs: &[&str], tail: &str) {
    let (plane, renderer) = submission(bugs);
    let end = "        return image;";
    assert!(
        renderer.contains(end),
        "the fixture's render ends as expected"
    );
    let renderer = renderer.replace(end, &format!("{tail}\n{end}"));
    let package = root.join(id).join("gfx/tick2");
    std::fs::create_dir_all(&package).expect("mkdir");
    std::fs::write(package.join("Plane.java"), plane).expect("write");
    std::fs::write(package.join("Renderer.java"), renderer).expect("write");
}

fn result(out: &Path, id: &str) -> Value {
    let path = out.join("students").join(id).join("result.json");
    serde_json::from_str(&std::fs::read_to_string(path).expect("result.json")).expect("json")
}

/// The cells of the calibration table's row for `tolerance`.
fn row<'a>(table: &'a str, tolerance: &str) -> Vec<&'a str> {
    table
        .lines()
        .find(|l| l.trim_start().starts_with(tolerance))
        .unwrap_or_else(|| panic!("no row {tolerance}: {table}"))
        .split_whitespace()
        .skip(1)
        .collect()
}

#[test]
fn grade_fails_a_few_pixels_by_default_passes_them_with_an_allowance_and_calibrates() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let class = d.join("class");
    student(&class, "right", &[], "");
    let perturb = format!(
        "        for (int x = 10; x < {}; x++) image.setRGB(x, 10, image.getRGB(x, 10) ^ 0x080808);",
        10 + OFF
    );
    student(&class, "few", &[], &perturb);
    student(&class, "mistaken", &["no-ambient"], "");
    let run = grade(d, &["class", "-o", "out"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let out = d.join("out");
    let few = result(&out, "few");
    assert_eq!(few["score"], 0.0, "{few}");
    assert_eq!(few["extra_data"]["allowance"], "0");
    assert_eq!(result(&out, "right")["score"], 100.0);
    // Every case keeps its pixels beyond 0 to 8: seven pixels off by 8.
    let beyond = few["extra_data"]["beyond"].as_array().expect("beyond");
    assert_eq!(beyond.len(), few["tests"].as_array().expect("tests").len());
    assert_eq!(beyond[0]["case"], "tick2.xml -b 0");
    assert_eq!(beyond[0]["pixels"], 640 * 480);
    assert_eq!(
        beyond[0]["beyond_at"],
        serde_json::json!([OFF, OFF, OFF, OFF, OFF, OFF, OFF, OFF, 0])
    );

    // The calibration, from the results alone.
    let calibrated = grade(d, &["-o", "out", "--calibrate", "--max-beyond", "7"]);
    assert!(calibrated.status.success(), "{}", stderr(&calibrated));
    let table = String::from_utf8_lossy(&calibrated.stdout).into_owned();
    assert!(
        table.starts_with(
            "3 students with counts; as graded (±2, --max-beyond 0), 1 pass every counted case"
        ),
        "{table}"
    );
    let header: Vec<&str> = table
        .lines()
        .nth(3)
        .unwrap_or_default()
        .split_whitespace()
        .collect();
    assert_eq!(
        header,
        ["0", "5", "7", "10", "20", "50", "100", "0.1%", "1%"]
    );
    // "few" passes with 7 pixels allowed, or at ±8; "mistaken" by none of these.
    assert_eq!(
        row(&table, "±0 "),
        ["1", "1", "2", "2", "2", "2", "2", "2", "2"]
    );
    assert_eq!(
        row(&table, "±2*"),
        ["1*", "1", "2", "2", "2", "2", "2", "2", "2"]
    );
    assert_eq!(row(&table, "±8 "), ["2"; 9]);
    // Listed where it changes: 7 pixels at ±0, and ±8 with none.
    let through: Vec<&str> = table.lines().filter(|l| l.starts_with("  ±")).collect();
    assert_eq!(through.len(), 2, "{table}");
    assert!(
        through[0].starts_with("  ±0, --max-beyond 7: +1 ("),
        "{table}"
    );
    assert!(
        through[1].starts_with("  ±8, --max-beyond 0: +1 ("),
        "{table}"
    );
    assert!(through.iter().all(|l| l.ends_with("): few")), "{table}");
    assert!(!table.contains("mistaken"), "{table}");

    // Graded again with an allowance: the key changes, "few" passes and is told how.
    let run = grade(d, &["class", "-o", "out", "--max-beyond", "10"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let few = result(&out, "few");
    assert_eq!(few["score"], 100.0, "{few}");
    let extra = &few["extra_data"];
    assert_eq!(extra["allowance"], "10");
    assert!(
        extra["policy"]
            .as_str()
            .is_some_and(|p| p.ends_with("within 2 of 255 in a channel, but for at most 10 pixels")),
        "{extra}"
    );
    assert_eq!(
        extra["feedback"],
        "passes all 5 graded cases (5 of them only by the allowance: at most 10 pixels beyond ±2)"
    );
    assert!(
        few["tests"][0]["output"].as_str().is_some_and(
            |o| o.starts_with("within-tolerance (7 pixels beyond ±2, allowed up to 10)")
        ),
        "{}",
        few["tests"][0]
    );
    assert_eq!(result(&out, "mistaken")["score"], 0.0);
    for page in ["index.html", "students/few/report.html"] {
        let html = std::fs::read_to_string(out.join(page)).expect("page");
        assert!(html.contains("but for at most 10 pixels"), "{page}");
    }
    let moodle = std::fs::read_to_string(out.join("moodle.csv")).expect("moodle.csv");
    assert!(moodle.contains("only by the allowance"), "{moodle}");

    // A result an older whitted wrote, without the counts, is named and left out.
    let path = out.join("students/right/result.json");
    let mut old: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("read")).expect("json");
    old["extra_data"]
        .as_object_mut()
        .expect("extra_data")
        .remove("beyond");
    std::fs::write(&path, old.to_string()).expect("write");
    let calibrated = grade(d, &["-o", "out", "--calibrate"]);
    assert!(calibrated.status.success(), "{}", stderr(&calibrated));
    let table = String::from_utf8_lossy(&calibrated.stdout).into_owned();
    assert!(
        table.starts_with("2 students with counts; as graded (±2, --max-beyond 10), 1 pass"),
        "{table}"
    );
    assert!(
        table.contains("graded by an older whitted")
            && table.contains("--rerun all to count them): right"),
        "{table}"
    );
    // Nothing graded there: refused.
    let nothing = grade(d, &["-o", "elsewhere", "--calibrate"]);
    assert_eq!(nothing.status.code(), Some(2), "{}", stderr(&nothing));
    let bad = grade(d, &["class", "-o", "out2", "--max-beyond", "100.5%"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(!d.join("out2").exists());
}
