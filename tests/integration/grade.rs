//! `whitted grade`: a synthetic class built from the Java fixture's mistakes, stages and pairs
//! (tests/java/submission: a submission's Plane.java and Renderer.java, compiled against
//! skeleton/), in a Moodle-shaped zip with blind-marking and 3.x folder names; each student
//! named in class.csv and mistakes.csv, moodle.csv read back, a rerun that runs nothing, and
//! the class page in Chromium. Hostile submissions each get their status with nothing
//! escaping the sandbox and no process left (tests/integration/grade_hostile.rs).

use std::io::Write;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::*;
use crate::view::Browser;

/// The fixture's two files with `bugs` switched on in the source (as a student's code has
/// them), not by a property the grader would have to pass.
pub fn submission(bugs: &[&str]) -> (String, String) {
    let dir = root().join("tests/java/submission/gfx/tick2");
    let plane = std::fs::read_to_string(dir.join("Plane.java")).expect("Plane.java");
    let renderer = std::fs::read_to_string(dir.join("Renderer.java")).expect("Renderer.java");
    let baked = renderer.replace(
        "System.getProperty(\"bug\", \"\")",
        &format!("\"{}\"", bugs.join(",")),
    );
    assert_ne!(
        baked, renderer,
        "the fixture reads its mistakes from one place"
    );
    (plane, baked)
}

/// A submission's Renderer.java with `code` run first thing in `render`.
pub fn hostile(code: &str) -> (String, String) {
    let (plane, renderer) = submission(&[]);
    let marker = "public BufferedImage render(Scene scene) {";
    assert!(renderer.contains(marker));
    (
        plane,
        renderer.replace(marker, &format!("{marker}\n{code}\n")),
    )
}

/// `whitted grade ARGS` in `dir`.
pub fn grade(dir: &Path, args: &[&str]) -> std::process::Output {
    let mut all = vec!["grade", "-q"];
    all.extend_from_slice(args);
    whitted(dir, &all)
}

/// A CSV file's rows of fields (quotes and doubled quotes, CRLF), as a spreadsheet reads it.
pub fn read_csv(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).expect("csv");
    let mut rows = Vec::new();
    let (mut row, mut field, mut quoted, mut chars) =
        (Vec::new(), String::new(), false, text.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', true) => quoted = false,
            ('"', false) if field.is_empty() => quoted = true,
            (',', false) => row.push(std::mem::take(&mut field)),
            ('\r', false) => {}
            ('\n', false) => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (c, _) => field.push(c),
        }
    }
    rows
}

/// The rows of a CSV as maps from its header's names.
pub fn records(path: &Path) -> Vec<std::collections::BTreeMap<String, String>> {
    let rows = read_csv(path);
    let header = rows[0].clone();
    rows[1..]
        .iter()
        .map(|r| header.iter().cloned().zip(r.iter().cloned()).collect())
        .collect()
}

/// The synthetic class: (folder name in the zip, Moodle id, the mistakes it is built with,
/// what class.csv must name).
fn class() -> Vec<(String, String, Vec<&'static str>, &'static str)> {
    let students: [(&[&str], &str); 22] = [
        (&[], ""),
        (&[], ""),
        (&["no-shadows"], "no-shadows"),
        (&["no-ambient"], "no-ambient"),
        (&["no-falloff"], "no-falloff"),
        (&["diffuse-no-colour"], "diffuse-no-colour"),
        (&["specular-object-colour"], "specular-object-colour"),
        (&["reflection-wrong-sign"], "reflection-wrong-sign"),
        (&["reflection-unweighted"], "reflection-unweighted"),
        (&["shadow-any-hit"], "shadow-any-hit"),
        (&["first-light-only"], "first-light-only"),
        (&["last-light-wins"], "last-light-wins"),
        (&["bounces-plus-one"], "bounces-plus-one"),
        (&["plane-behind"], "plane-behind"),
        // Stages not written yet.
        (&["planes-missing"], "planes-missing"),
        (&["lights-missing"], "lights-missing"),
        (&["reflection-missing"], "reflection-missing"),
        (&["reflection-ignored"], "reflection-ignored"),
        // Pairs.
        (
            &["no-shadows", "reflection-wrong-sign"],
            "no-shadows+reflection-wrong-sign",
        ),
        (
            &["no-ambient", "reflect-unclamped"],
            "reflect-unclamped+no-ambient",
        ),
        (
            &["planes-missing", "no-falloff"],
            "no-falloff+planes-missing",
        ),
        (
            &["reflection-missing", "no-shadows"],
            "no-shadows+reflection-missing",
        ),
    ];
    students
        .iter()
        .enumerate()
        .map(|(i, (bugs, named))| {
            let id = (31_000 + i).to_string();
            // Blind marking for some, Moodle 3.x's trailing `_` for others.
            let folder = match i % 3 {
                0 => format!("Participant_{id}_assignsubmission_file"),
                1 => format!("Student Number{i}_{id}_assignsubmission_file_"),
                _ => format!("Ada O'Brien-{i}_{id}_assignsubmission_file"),
            };
            (folder, id, bugs.to_vec(), *named)
        })
        .collect()
}

/// Moodle's zip of `students`: each student's files in a project layout of their own, one
/// of them as a zip inside the folder.
fn moodle_zip(path: &Path, students: &[(String, String, Vec<&str>, &str)]) {
    let file = std::fs::File::create(path).expect("zip");
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default();
    for (i, (folder, _, bugs, _)) in students.iter().enumerate() {
        let (plane, renderer) = submission(bugs);
        if i == 4 {
            // A student who zipped their project.
            let mut inner = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
            for (name, text) in [("Plane.java", &plane), ("Renderer.java", &renderer)] {
                inner
                    .start_file(format!("tick2/src/gfx/tick2/{name}"), options)
                    .expect("entry");
                inner.write_all(text.as_bytes()).expect("write");
            }
            let bytes = inner.finish().expect("inner zip").into_inner();
            zip.start_file(format!("{folder}/project.zip"), options)
                .expect("entry");
            zip.write_all(&bytes).expect("write");
            continue;
        }
        let layout = ["src/gfx/tick2", "gfx/tick2", ""][i % 3];
        for (name, text) in [("Plane.java", &plane), ("Renderer.java", &renderer)] {
            let path = [folder.as_str(), layout, name]
                .iter()
                .filter(|p| !p.is_empty())
                .cloned()
                .collect::<Vec<_>>()
                .join("/");
            zip.start_file(path, options).expect("entry");
            if i == 1 {
                // Saved by a Windows editor: a byte order mark, which javac alone rejects.
                zip.write_all(b"\xEF\xBB\xBF").expect("write");
            }
            zip.write_all(text.as_bytes()).expect("write");
        }
    }
    zip.finish().expect("zip");
}

fn result_json(out: &Path, id: &str) -> Value {
    let text = std::fs::read_to_string(out.join("students").join(id).join("result.json"))
        .expect("result.json");
    serde_json::from_str(&text).expect("json")
}

fn modified(path: &Path) -> std::time::SystemTime {
    std::fs::metadata(path)
        .and_then(|m| m.modified())
        .expect("mtime")
}

#[test]
fn a_class_is_graded_named_written_up_and_rerun_for_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let students = class();
    let zip = d.join("submissions.zip");
    moodle_zip(&zip, &students);
    let out = d.join("out");
    let run = grade(d, &["submissions.zip", "-o", "out", "--timeout", "30"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let said = String::from_utf8_lossy(&run.stdout).to_string();
    assert!(said.contains("22 students: 22 graded"), "{said}");
    assert!(said.trim_end().ends_with("index.html"), "{said}");

    // class.csv names each student's mistake.
    let rows = records(&out.join("class.csv"));
    assert_eq!(rows.len(), students.len());
    let misnamed: Vec<String> = students
        .iter()
        .filter_map(|(_, id, bugs, named)| {
            let row = rows.iter().find(|r| &r["id"] == id)?;
            (&row["diagnosis"] != named).then(|| format!("{bugs:?} named {}", row["diagnosis"]))
        })
        .collect();
    assert!(misnamed.is_empty(), "{misnamed:#?}");
    for (folder, id, bugs, _) in &students {
        let row = rows
            .iter()
            .find(|r| &r["id"] == id)
            .expect("the student's row");
        assert_eq!(row["status"], "graded", "{folder}");
        // The course's five cases count; whitted's two diagnostic scenes inform only.
        assert_eq!(row["cases"], "5", "{folder}: {row:?}");
        if bugs.is_empty() {
            assert_eq!(row["passed"], "5", "{folder}: {row:?}");
        }
        let all_pass = row["passed"] == "5";
        assert_eq!(row["grade"], if all_pass { "100" } else { "0" });
        if folder.starts_with("Participant") {
            assert_eq!(row["name"], "Participant");
        }
        let page = std::fs::read_to_string(out.join("students").join(id).join("report.html"))
            .expect("report.html");
        assert!(
            page.matches("progress: ").count() <= 1,
            "{folder}: progress twice"
        );
    }

    // mistakes.csv counts them.
    let mistakes = records(&out.join("mistakes.csv"));
    for (id, kind, students_with) in [
        ("no-shadows", "unfinished stage", "3"),
        ("planes-missing", "unfinished stage", "2"),
        ("reflection-wrong-sign", "mistake", "2"),
        ("no-falloff", "mistake", "2"),
    ] {
        let row = mistakes.iter().find(|r| r["id"] == id).expect(id);
        assert_eq!(
            (row["kind"].as_str(), row["students"].as_str()),
            (kind, students_with),
            "{id}"
        );
    }

    // moodle.csv, read back as Moodle's import reads it: by Identifier, grade with feedback.
    let moodle = records(&out.join("moodle.csv"));
    assert_eq!(moodle.len(), students.len());
    for (_, id, bugs, named) in &students {
        let row = moodle
            .iter()
            .find(|r| r["Identifier"] == format!("Participant {id}"))
            .expect("a worksheet row");
        if bugs.is_empty() {
            assert_eq!(row["Grade"], "100");
        }
        assert_eq!(row["Maximum Grade"], "100");
        assert!(!row["Last modified (grade)"].is_empty());
        let feedback = &row["Feedback comments"];
        match named.is_empty() {
            true => assert_eq!(feedback, "passes all 5 graded cases"),
            false => assert!(
                feedback.contains(named.split('+').next().unwrap_or("")),
                "{feedback}"
            ),
        }
    }

    // result.json in Gradescope's shape.
    let (_, id, bugs, _) = &students[2];
    let result = result_json(&out, id);
    assert_eq!(result["score"], 0.0);
    let tests = result["tests"].as_array().expect("tests");
    assert_eq!(tests.len(), 7);
    for test in tests {
        for field in ["name", "score", "max_score", "status", "output", "tags"] {
            assert!(!test[field].is_null(), "{field}: {test}");
        }
        if test["status"] == "failed" {
            assert_eq!(test["tags"][0], bugs[0]);
        }
    }
    assert_eq!(result["extra_data"]["status"], "graded");
    assert_eq!(result["extra_data"]["progress"]["shadows"], "missing");
    let report = std::fs::read_to_string(out.join("students").join(id).join("report.html"))
        .expect("report.html");
    assert!(report.contains("data:image/png;base64,") && report.contains("no-shadows"));
    let png = read_png(&out.join("students").join(id).join("report.png"));
    assert!(png.width > 300 && png.height > 100);

    // A rerun grades no one: every result is kept as it was.
    let before = modified(&out.join("students").join(id).join("result.json"));
    let rerun = grade(d, &["submissions.zip", "-o", "out"]);
    assert!(rerun.status.success(), "{}", stderr(&rerun));
    let said = String::from_utf8_lossy(&rerun.stdout).to_string();
    assert!(said.contains("graded now 0, already graded 22"), "{said}");
    assert_eq!(
        modified(&out.join("students").join(id).join("result.json")),
        before
    );

    // The class page, offline, in a real browser.
    let browser = Browser::start();
    let index: PathBuf = out.join("index.html").canonicalize().expect("index.html");
    browser.navigate(&format!("file://{}", index.display()));
    let page = browser.script(
        "return {rows: document.querySelectorAll('#students tr').length - 1, \
                 bars: document.querySelectorAll('#mistakes rect').length, \
                 scenes: document.querySelectorAll('#scenes rect').length, \
                 links: [...document.querySelectorAll('#students a')].map(a => a.getAttribute('href')), \
                 identical: [...document.querySelectorAll('#identical li')].map(l => l.textContent), \
                 settings: document.getElementById('settings').textContent, \
                 totals: document.getElementById('totals').textContent}",
        serde_json::json!([]),
    );
    assert_eq!(page["rows"], students.len());
    let distinct: std::collections::BTreeSet<&str> = students
        .iter()
        .flat_map(|(_, _, _, named)| named.split('+'))
        .filter(|n| !n.is_empty())
        .collect();
    assert_eq!(page["bars"], distinct.len());
    assert_eq!(page["scenes"], 7);
    // The two correct students hand in the same files (one saved with a byte order mark).
    let identical = page["identical"].as_array().expect("identical");
    assert_eq!(identical.len(), 1, "{identical:?}");
    let group = identical[0].as_str().expect("text");
    assert!(
        group.contains("31000") && group.contains("31001"),
        "{group}"
    );
    let settings = page["settings"].as_str().expect("settings");
    assert!(
        settings.contains("Skeleton: whitted") && settings.contains("pass-fail over 5"),
        "{settings}"
    );
    let full_marks = rows.iter().filter(|r| r["grade"] == "100").count();
    assert!(full_marks >= 2);
    assert!(page["totals"]
        .as_str()
        .expect("totals")
        .contains(&format!("{full_marks} pass every graded case")));
    for link in page["links"].as_array().expect("links") {
        let target = out.join(link.as_str().expect("href"));
        assert!(target.is_file(), "{}", target.display());
    }
}

#[test]
fn one_project_with_hidden_scenes_and_a_fractional_grade() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (plane, renderer) = submission(&["planes-missing"]);
    let package = d.join("tick2-project/src/gfx/tick2");
    std::fs::create_dir_all(&package).expect("mkdir");
    std::fs::write(package.join("Plane.java"), plane).expect("write");
    std::fs::write(package.join("Renderer.java"), renderer).expect("write");
    // A hidden scene without planes: a program without planes renders it right.
    let hidden = d.join("hidden");
    std::fs::create_dir_all(&hidden).expect("mkdir");
    std::fs::write(
        hidden.join("hidden_b1.xml"),
        "<scene>\n  <point-light x=\"1\" y=\"2\" z=\"1\" colour=\"#FFFFFF\" intensity=\"80\"/>\n  \
         <sphere x=\"0\" y=\"0\" z=\"4\" radius=\"1\" colour=\"#3060E0\"/>\n  \
         <sphere x=\"0.8\" y=\"0.6\" z=\"2.8\" radius=\"0.3\" colour=\"#E0E0E0\"/>\n</scene>\n",
    )
    .expect("write");
    let run = grade(
        d,
        &[
            "tick2-project",
            "-o",
            "out",
            "--scenes",
            "hidden",
            "--grade",
            "fraction",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let result = result_json(&d.join("out"), "tick2-project");
    let tests = result["tests"].as_array().expect("tests");
    assert_eq!(tests.len(), 8);
    assert_eq!(tests[7]["name"], "hidden_b1.xml -b 1");
    assert_eq!(tests[7]["status"], "passed", "{}", tests[7]);
    // The course's five cases and the hidden one count, one each; the diagnostic two weigh 0.
    let counted: Vec<&Value> = tests.iter().filter(|t| t["max_score"] != 0.0).collect();
    assert_eq!(counted.len(), 6);
    let passed = counted.iter().filter(|t| t["status"] == "passed").count();
    let expected = (10000.0 * passed as f64 / 6.0).round() / 100.0;
    assert_eq!(result["score"].as_f64(), Some(expected));
    assert_eq!(result["extra_data"]["diagnosis"][0], "planes-missing");
    // A scene the course's loader could not read is refused before anyone is graded.
    std::fs::write(hidden.join("broken_b2.xml"), "<scene><sphear/></scene>").expect("write");
    let refused = grade(d, &["tick2-project", "-o", "out2", "--scenes", "hidden"]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(
        stderr(&refused).contains("broken_b2.xml"),
        "{}",
        stderr(&refused)
    );
    assert!(!d.join("out2/class.csv").exists());
}

/// A folder of students named `names`, each built with the fixture and `code` run first in
/// `render` (None: the plain fixture).
fn folder_class(root: &Path, students: &[(&str, Option<&str>)]) {
    for (name, code) in students {
        let (plane, renderer) = match code {
            Some(code) => hostile(code),
            None => submission(&[]),
        };
        let dir = root.join(name).join("gfx/tick2");
        std::fs::create_dir_all(&dir).expect("mkdir");
        std::fs::write(dir.join("Plane.java"), plane).expect("write");
        std::fs::write(dir.join("Renderer.java"), renderer).expect("write");
    }
}

#[test]
fn rerun_failed_grades_only_timeouts_and_ctrl_c_keeps_finished_students() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // Sleeps in the suite's first case only (the one at 0 bounces), so the timeout can be far
    // longer than a case takes on a loaded machine without making the test slow: a fine
    // student that timed out would be rerun too, and the counts below would be wrong.
    let sleeper = "if (bounces == 0) try { Thread.sleep(Long.MAX_VALUE); } \
                   catch (InterruptedException e) {}";
    folder_class(
        &d.join("class"),
        &[("a-fine", None), ("b-sleeps", Some(sleeper))],
    );
    let first = grade(d, &["class", "-o", "out", "--timeout", "15", "-j", "1"]);
    assert!(first.status.success(), "{}", stderr(&first));
    let rows = records(&d.join("out/class.csv"));
    assert_eq!(rows.len(), 2);
    let fine = result_json(&d.join("out"), "a-fine");
    assert_eq!(fine["extra_data"]["failed"], false, "{fine}");
    let slept = result_json(&d.join("out"), "b-sleeps");
    let cases = &slept["extra_data"]["check"]["cases"];
    assert_eq!(cases[0]["status"], "timeout");
    assert_ne!(cases[1]["status"], "timeout", "{}", cases[1]);
    assert_eq!(slept["extra_data"]["failed"], true);
    // --rerun failed: only the student whose cases timed out.
    let again = grade(
        d,
        &["class", "-o", "out", "--timeout", "15", "--rerun", "failed"],
    );
    assert!(again.status.success(), "{}", stderr(&again));
    let said = String::from_utf8_lossy(&again.stdout).to_string();
    assert!(said.contains("graded now 1, already graded 1"), "{said}");

    // Ctrl-C while the sleeper runs: the student finished before it is kept, exit 130, no
    // JVM left, no work folder left behind, and the next run grades only what is left.
    let tmp = d.join("tmp");
    std::fs::create_dir_all(&tmp).expect("tmp");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args([
            "grade",
            "-q",
            "class",
            "-o",
            "out2",
            "--timeout",
            "60",
            "-j",
            "1",
        ])
        .current_dir(d)
        .env("TMPDIR", &tmp)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("grade starts");
    let finished = d.join("out2/students/a-fine/result.json");
    let started = std::time::Instant::now();
    while !finished.exists() {
        assert!(
            started.elapsed().as_secs() < 120,
            "the first student never finished"
        );
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    // The sleeper's cases are running now.
    std::thread::sleep(std::time::Duration::from_secs(3));
    let _ = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    let status = child.wait().expect("wait");
    assert_eq!(status.code(), Some(130));
    assert!(finished.is_file());
    assert!(!d.join("out2/students/b-sleeps/result.json").exists());
    let left: Vec<_> = std::fs::read_dir(&tmp).expect("tmp").flatten().collect();
    assert!(
        left.is_empty(),
        "left behind: {:?}",
        left.iter().map(|e| e.path()).collect::<Vec<_>>()
    );
    std::thread::sleep(std::time::Duration::from_millis(300));
    let jvms = std::fs::read_dir("/proc")
        .expect("proc")
        .flatten()
        .filter(|e| {
            std::fs::read(e.path().join("cmdline")).is_ok_and(|c| {
                let c = String::from_utf8_lossy(&c);
                c.contains("gfx.tick2.Tick2") && c.contains(&*tmp.to_string_lossy())
            })
        })
        .count();
    assert_eq!(jvms, 0, "a JVM outlived Ctrl-C");
    let resumed = grade(d, &["class", "-o", "out2", "--timeout", "15"]);
    assert!(resumed.status.success(), "{}", stderr(&resumed));
    let said = String::from_utf8_lossy(&resumed.stdout).to_string();
    assert!(said.contains("graded now 1, already graded 1"), "{said}");
}

/// javac of `sources` into `d/out`.
fn javac(d: &Path, out: &str, sources: Vec<PathBuf>) {
    let javac = std::process::Command::new("javac")
        .args(["-proc:none", "-d", out])
        .args(&sources)
        .current_dir(d)
        .output()
        .expect("javac");
    assert!(javac.status.success(), "{}", stderr(&javac));
}

/// The `.java` files of `dir`.
fn java_files(dir: PathBuf) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .expect("dir")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "java"))
        .collect()
}

/// The skeleton and the fixture's two files (`Plane.java` maybe replaced), compiled into `d/out`.
fn compile_submission(d: &Path, out: &str, plane: Option<&str>) {
    let mut sources = java_files(root().join("skeleton/gfx/tick2"));
    let fixture = root().join("tests/java/submission/gfx/tick2");
    sources.push(fixture.join("Renderer.java"));
    match plane {
        Some(text) => {
            let path = d.join(format!("{out}-Plane/gfx/tick2/Plane.java"));
            std::fs::create_dir_all(path.parent().expect("parent")).expect("mkdir");
            std::fs::write(&path, text).expect("write");
            sources.push(path);
        }
        None => sources.push(fixture.join("Plane.java")),
    }
    javac(d, out, sources);
}

/// The pixels `java -cp classes gfx.tick2.Tick2` writes for `scene` at `bounces`.
fn java_render(d: &Path, classes: &str, bug: &str, scene: &Path, bounces: &str) -> Vec<u8> {
    let out = format!("{classes}-out.png");
    let run = std::process::Command::new("java")
        .arg(format!("-Dbug={bug}"))
        .args(["-cp", classes, "gfx.tick2.Tick2", "--input"])
        .arg(scene)
        .args(["--output", &out, "--bounces", bounces])
        .current_dir(d)
        .stdout(std::process::Stdio::null())
        .output()
        .expect("java");
    assert!(run.status.success(), "{}", stderr(&run));
    read_png(&d.join(out)).data
}

/// The pixels `whitted render` writes for `scene` at `bounces`: the course's image.
fn whitted_render(d: &Path, scene: &Path, bounces: &str) -> Vec<u8> {
    let run = whitted(
        d,
        &["-q", "-i", s(scene), "-b", bounces, "-o", "whitted.png"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    read_png(&d.join("whitted.png")).data
}

#[test]
fn the_fixture_as_two_files_on_the_skeleton_renders_the_single_file_fixture_s_bytes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    compile_submission(d, "submission", None);
    javac(
        d,
        "single",
        vec![root().join("tests/java/gfx/tick2/Tick2.java")],
    );
    let mirrors = root().join("scenes/check/mirrors.xml");
    let tick2 = root().join("scenes/tick2.xml");
    for (bug, scene, bounces) in [
        ("", &tick2, "2"),
        ("", &mirrors, "3"),
        ("reflection-wrong-sign", &mirrors, "3"),
        ("plane-behind", &mirrors, "3"),
        ("no-falloff", &tick2, "2"),
        ("view-from-ray-origin", &mirrors, "3"),
        ("reflect-unclamped,no-shadow-bias", &tick2, "2"),
        ("planes-missing,bounces-minus-one", &tick2, "2"),
    ] {
        let ours = java_render(d, "submission", bug, scene, bounces);
        let theirs = java_render(d, "single", bug, scene, bounces);
        assert!(
            ours == theirs,
            "-Dbug={bug} on {}: the pixels differ",
            scene.display()
        );
    }
}

/// Real students' Plane.java trusts the course's loader: it keeps the normal as given. On
/// the skeleton such a submission renders the course's images (whitted's, which match the
/// course's reference), and each documented behaviour of the course's loader (docs/grade.md,
/// "The clean-room skeleton") is rendered as whitted renders the scene that behaviour means.
#[test]
fn a_submission_that_trusts_the_course_s_loader_renders_the_course_s_images() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    // As the course's template has it, with the one line the handout asks for: no
    // normalising, no checks beyond the sign of s.
    let trusting = "package gfx.tick2;\n\npublic class Plane extends SceneObject {\n    \
        private final double PLANE_KD = 0.9;\n    private final double PLANE_KS = 0.0;\n    \
        private final double PLANE_N = 0.0;\n    private final double PLANE_REFLECTIVITY = 0.1;\n\n    \
        private Vector3 point;\n    private Vector3 normal;\n\n    \
        public Plane(Vector3 point, Vector3 normal, Vector3 colour) {\n        \
        this.point = point;\n        this.normal = normal;\n        this.colour = colour;\n        \
        this.phong_kD = PLANE_KD;\n        this.phong_kS = PLANE_KS;\n        \
        this.phong_n = PLANE_N;\n        this.reflectivity = PLANE_REFLECTIVITY;\n    }\n\n    \
        public RaycastHit intersectionWith(Ray ray) {\n        Vector3 O = ray.getOrigin();\n        \
        Vector3 D = ray.getDirection();\n        Vector3 Q = this.point;\n        \
        Vector3 N = this.normal;\n        double s = Q.subtract(O).dot(N) / D.dot(N);\n        \
        if (s < 0) return new RaycastHit();\n        \
        return new RaycastHit(this, s, O.add(D.scale(s)), N);\n    }\n\n    \
        public Vector3 getNormalAt(Vector3 position) {\n        return normal;\n    }\n}\n";
    compile_submission(d, "trusting", Some(trusting));
    compile_submission(d, "fixture", None);
    for (scene, bounces) in [
        (root().join("scenes/tick2.xml"), "2"),
        (root().join("scenes/tick2.xml"), "0"),
        (root().join("scenes/check/mirrors.xml"), "3"),
        (root().join("scenes/specular_test.xml"), "2"),
    ] {
        let course = whitted_render(d, &scene, bounces);
        for classes in ["trusting", "fixture"] {
            let theirs = java_render(d, classes, "", &scene, bounces);
            assert!(
                theirs == course,
                "{classes} on {} -b {bounces}: not the course's image",
                scene.display()
            );
        }
    }
    // The course loader's behaviours, each beside the strict scene it amounts to.
    let quirks = write_scene(
        d,
        "quirks.xml",
        "<scene>\n  <ambient-light colour=\"#101010\"/>\n  <group>\n    \
         <point-light x=\"1\" y=\"up\" z=\"1\" colour=\"#FFFFFF.\" intensity=\"\"/>\n  \
         </group>\n  <sphere x=\" 0.2 \" y=\"0\" z=\"4\" radius=\"1\" colour=\"#3060e0\"/>\n  \
         <plane x=\"0\" y=\"-1\" z=\"0\" nx=\"0\" ny=\"4.22\" nz=\"-2.18\" colour=\"#22AA22\"/>\n  \
         <widget size=\"3\"/>\n  <ambient-light colour=\"#555555\"/>\n</scene>\n",
    );
    let strict = write_scene(
        d,
        "strict.xml",
        "<scene>\n  <point-light x=\"1\" y=\"0\" z=\"1\" colour=\"#FFFFFF\" intensity=\"100\"/>\n  \
         <sphere x=\"0.2\" y=\"0\" z=\"4\" radius=\"1\" colour=\"#3060E0\"/>\n  \
         <plane x=\"0\" y=\"-1\" z=\"0\" nx=\"0\" ny=\"4.22\" nz=\"-2.18\" colour=\"#22AA22\"/>\n  \
         <ambient-light colour=\"#555555\"/>\n</scene>\n",
    );
    let course = whitted_render(d, &strict, "2");
    for classes in ["trusting", "fixture"] {
        let theirs = java_render(d, classes, "", &quirks, "2");
        assert!(theirs == course, "{classes}: the loader's rules differ");
    }
}

/// Moodle both ways, the grading policy, hidden scenes and regrading one student: a class with
/// an online-text folder beside a file folder, a student with only online text, near-miss file
/// names, hidden scenes weighed by a rubric; then `--only` one student, and a late student graded
/// alone into the same output.
#[test]
fn moodle_round_trip_rubric_hidden_scenes_and_one_student_regraded() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (plane, renderer) = submission(&[]);
    let (bob_plane, bob_renderer) = submission(&["no-shadows"]);
    let file = std::fs::File::create(d.join("class.zip")).expect("zip");
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default();
    for (path, text) in [
        ("Ada Lovelace_101_assignsubmission_file_/Plane.java", &plane),
        (
            "Ada Lovelace_101_assignsubmission_file_/Renderer (1).java",
            &renderer,
        ),
        (
            "Ada Lovelace_101_assignsubmission_onlinetext_/onlinetext.html",
            &"<p>see my files</p>".to_string(),
        ),
        (
            "Bob Smith_102_assignsubmission_file_/src/gfx/tick2/plane.java",
            &bob_plane,
        ),
        (
            "Bob Smith_102_assignsubmission_file_/src/gfx/tick2/Renderer.java.txt",
            &bob_renderer,
        ),
        (
            "Cy_103_assignsubmission_onlinetext_/onlinetext.html",
            &"<p>forgot the files</p>".to_string(),
        ),
    ] {
        zip.start_file(path, options).expect("entry");
        zip.write_all(text.as_bytes()).expect("write");
    }
    zip.finish().expect("zip");
    let hidden = d.join("hidden");
    std::fs::create_dir_all(&hidden).expect("mkdir");
    // A colour no other scene has, to find the scene if it leaks.
    std::fs::write(
        hidden.join("hidden_b1.xml"),
        "<scene>\n  <point-light x=\"1\" y=\"2\" z=\"1\" colour=\"#FFFFFF\" intensity=\"80\"/>\n  \
         <sphere x=\"0\" y=\"0\" z=\"4\" radius=\"1\" colour=\"#123457\"/>\n</scene>\n",
    )
    .expect("write");
    std::fs::write(
        d.join("rubric.txt"),
        "# the course's weights\ntick2.xml -b 2   3\nhidden_b1.xml  1\n",
    )
    .expect("write");
    let args = [
        "class.zip",
        "-o",
        "out",
        "--scenes",
        "hidden",
        "--rubric",
        "rubric.txt",
        "--grade",
        "fraction",
    ];
    let run = grade(d, &args);
    assert!(run.status.success(), "{}", stderr(&run));
    let out = d.join("out");
    let rows = records(&out.join("class.csv"));
    let ids: Vec<&str> = rows.iter().map(|r| r["id"].as_str()).collect();
    assert_eq!(ids, ["101", "102", "103"]);

    // The online-text folders are ignored with a note; near-miss names taken with a warning.
    let ada = result_json(&out, "101");
    assert_eq!(ada["extra_data"]["status"], "graded");
    assert_eq!(ada["score"], 100.0, "{}", ada["output"]);
    let notes = ada["extra_data"]["notes"].to_string();
    assert!(notes.contains("onlinetext"), "{notes}");
    let warnings = ada["extra_data"]["warnings"].to_string();
    assert!(
        warnings.contains("Renderer (1).java was taken as Renderer.java"),
        "{warnings}"
    );
    let bob = result_json(&out, "102");
    assert_eq!(bob["extra_data"]["status"], "graded");
    assert_eq!(
        bob["extra_data"]["warnings"].as_array().map(Vec::len),
        Some(2)
    );
    let cy = result_json(&out, "103");
    assert_eq!(cy["extra_data"]["status"], "no-files");
    assert!(cy["extra_data"]["notes"].to_string().contains("onlinetext"));

    // The rubric: tick2 -b 2 weighs 3, the hidden scene 1, the rest nothing.
    let tests = bob["tests"].as_array().expect("tests");
    let weight = |name: &str| {
        tests
            .iter()
            .find(|t| t["name"] == name)
            .map(|t| t["max_score"].as_f64().expect("max_score"))
    };
    assert_eq!(weight("tick2.xml -b 2"), Some(3.0));
    assert_eq!(weight("hidden_b1.xml -b 1"), Some(1.0));
    assert_eq!(weight("tick2.xml -b 0"), Some(0.0));
    let earned: f64 = tests
        .iter()
        .map(|t| t["score"].as_f64().unwrap_or(0.0))
        .sum();
    assert_eq!(
        bob["score"].as_f64(),
        Some((10000.0 * earned / 4.0).round() / 100.0)
    );
    let policy = bob["extra_data"]["policy"].as_str().expect("policy");
    assert!(
        policy.contains("rubric.txt") && policy.contains("fraction"),
        "{policy}"
    );

    // The hidden scene never reaches a student: not its XML, not its images.
    let hidden_case = &bob["extra_data"]["check"]["cases"][7];
    assert_eq!(hidden_case["hidden"], true, "{hidden_case}");
    assert!(hidden_case.get("reproduce").is_none());
    for id in ["101", "102"] {
        let student = out.join("students").join(id);
        let report = std::fs::read_to_string(student.join("report.html")).expect("report");
        let result = std::fs::read_to_string(student.join("result.json")).expect("result");
        for text in [&report, &result] {
            assert!(!text.contains("123457"), "{id}: the hidden scene leaks");
        }
        assert!(
            !report.contains("<h2>hidden_b1.xml"),
            "{id}: hidden images shown"
        );
    }

    // The class page names the skeleton and the policy; feedback.zip is Moodle's layout.
    let index = std::fs::read_to_string(out.join("index.html")).expect("index");
    assert!(index.contains("Skeleton: whitted"), "{index}");
    assert!(index.contains("rubric.txt"));
    let feedback =
        zip::ZipArchive::new(std::fs::File::open(out.join("feedback.zip")).expect("zip"))
            .expect("a zip");
    let names: Vec<&str> = feedback.file_names().collect();
    for name in [
        "Ada Lovelace_101_assignsubmission_file_/report.html",
        "Bob Smith_102_assignsubmission_file_/report.html",
        "Cy_103_assignsubmission_file_/report.html",
    ] {
        assert!(names.contains(&name), "{name} in {names:?}");
    }

    // --only regrades one student and keeps the others' rows.
    let before = modified(&out.join("students/101/result.json"));
    let mut again = args.to_vec();
    again.extend(["--only", "102"]);
    let only = grade(d, &again);
    assert!(only.status.success(), "{}", stderr(&only));
    let said = String::from_utf8_lossy(&only.stdout).to_string();
    assert!(said.contains("graded now 1"), "{said}");
    assert_eq!(modified(&out.join("students/101/result.json")), before);
    assert_eq!(records(&out.join("class.csv")).len(), 3);
    let unknown = grade(d, &["class.zip", "-o", "out", "--only", "999"]);
    assert_eq!(unknown.status.code(), Some(2));

    // A late student graded alone into the same output joins the class.
    let late = d.join("late/Dee_104_assignsubmission_file_");
    std::fs::create_dir_all(&late).expect("mkdir");
    std::fs::write(late.join("Plane.java"), &plane).expect("write");
    std::fs::write(late.join("Renderer.java"), &renderer).expect("write");
    let mut alone = args.to_vec();
    alone[0] = "late";
    let run = grade(d, &alone);
    assert!(run.status.success(), "{}", stderr(&run));
    let ids: Vec<String> = records(&out.join("class.csv"))
        .iter()
        .map(|r| r["id"].clone())
        .collect();
    assert_eq!(ids, ["101", "102", "103", "104"]);
    assert_eq!(records(&out.join("moodle.csv")).len(), 4);
}

/// A student's file that declares one of the skeleton's classes (a `Vector3` pasted into
/// Renderer.java, a `Tick2` of their own beside Plane): javac's first error is then in the
/// skeleton's file, and the report used to blame the skeleton given to grade. It names the
/// student's file and the class instead.
#[test]
fn a_submission_declaring_a_skeleton_class_is_told_so_not_blamed_on_the_skeleton() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (plane, renderer) = submission(&[]);
    let vector3 = format!("{renderer}\nclass Vector3 {{ double x, y, z; }}\n");
    let tick2 = format!("{plane}\nclass Tick2 {{ }}\n");
    for (id, files) in [
        ("vector3", (plane.clone(), vector3)),
        ("tick2", (tick2, renderer.clone())),
    ] {
        let dir = d.join("class").join(id).join("src/gfx/tick2");
        std::fs::create_dir_all(&dir).expect("mkdir");
        std::fs::write(dir.join("Plane.java"), files.0).expect("Plane.java");
        std::fs::write(dir.join("Renderer.java"), files.1).expect("Renderer.java");
    }
    let run = grade(d, &["class", "-o", "out", "--timeout", "30"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let out = d.join("out");
    for (id, file, class) in [
        ("vector3", "Renderer.java", "Vector3"),
        ("tick2", "Plane.java", "Tick2"),
    ] {
        let result = result_json(&out, id);
        assert_eq!(result["extra_data"]["status"], "compile-error", "{id}");
        let errors = result["extra_data"]["compile_errors"]
            .as_str()
            .expect("compile errors");
        let said = format!(
            "Your {file} declares class {class}, which the course's skeleton provides \
             ({class}.java): remove it from {file} and use the skeleton's."
        );
        assert!(errors.starts_with(&said), "{id}: {errors}");
        assert!(!errors.contains("may not compile"), "{id}: {errors}");
        // javac's own messages follow, and the report shows the sentence too.
        assert!(errors.contains("duplicate class"), "{id}: {errors}");
        let report = std::fs::read_to_string(out.join("students").join(id).join("report.html"))
            .expect("report");
        assert!(report.contains(&format!("Your {file} declares class {class}")));
    }
}
