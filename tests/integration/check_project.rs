//! `whitted check DIR`: project folders built the way students have them (IntelliJ's `src/`
//! with `.idea/` and `out/`, Maven's `src/main/java/`, a plain folder), each from whitted's
//! clean-room skeleton of a year (`whitted grade --write-skeleton`) with `crsid` renamed as
//! every student renames it, and the student's three files (whitted's finished Tick 1, edited:
//! tick1_fixture.rs; 2016-17: the Tick 2 skeleton and `tests/java/submission`). Each asserts
//! the year found and why, the exit status, and what is said up front about the project.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::*;
use crate::tick1_fixture::fixture;

/// How a project's folder is laid out.
#[derive(Clone, Copy)]
pub enum Layout {
    /// IntelliJ: `src/<package>/`, `.idea/`, a module file and stale classes in `out/`.
    IntelliJ,
    /// Maven: `pom.xml`, `src/main/java/<package>/`, `target/classes/`.
    Maven,
    /// Everything in one folder, package lines and all.
    Plain,
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `year`'s clean-room skeleton with `crsid` renamed to `ab123`, and the fixture's three files
/// with `bugs`, laid out as `layout` in `d/name`; returns the project's folder and the folder
/// of its sources.
pub fn project(
    d: &Path,
    name: &str,
    year: &str,
    layout: Layout,
    bugs: &[&str],
) -> (PathBuf, PathBuf) {
    let skeleton = d.join(format!("{name}-skeleton"));
    let wrote = whitted(
        d,
        &[
            "grade",
            "--write-skeleton",
            "--course",
            year,
            "-o",
            s(&skeleton),
        ],
    );
    assert!(wrote.status.success(), "{}", stderr(&wrote));
    let shipped = skeleton.join("src/uk/ac/cam/cl/gfxintro/crsid/tick1");
    let package = "uk/ac/cam/cl/gfxintro/ab123/tick1";
    let root = d.join(name);
    let sources = match layout {
        Layout::IntelliJ => root.join("src").join(package),
        Layout::Maven => root.join("src/main/java").join(package),
        Layout::Plain => root.clone(),
    };
    std::fs::create_dir_all(&sources).expect("sources");
    for entry in std::fs::read_dir(&shipped).expect("skeleton") {
        let path = entry.expect("entry").path();
        let text = std::fs::read_to_string(&path).expect("read");
        let renamed = text.replace("gfxintro.crsid.tick1", "gfxintro.ab123.tick1");
        std::fs::write(sources.join(path.file_name().expect("name")), renamed).expect("write");
    }
    for (file, text) in fixture(year, "ab123", bugs) {
        std::fs::write(sources.join(file), text).expect("write");
    }
    match layout {
        Layout::IntelliJ => {
            std::fs::create_dir_all(root.join(".idea")).expect(".idea");
            std::fs::write(root.join(".idea/misc.xml"), "<project version=\"4\"/>").expect("w");
            std::fs::write(root.join(format!("{name}.iml")), "<module/>").expect("w");
            // A stale build of another year's copy: never read as sources.
            let out = root.join("out/production").join(name).join(package);
            std::fs::create_dir_all(&out).expect("out");
            std::fs::write(out.join("Tick1.class"), b"\xCA\xFE\xBA\xBE").expect("w");
            std::fs::write(out.join("Tick1.java"), "not java").expect("w");
        }
        Layout::Maven => {
            std::fs::write(root.join("pom.xml"), "<project/>").expect("pom");
            std::fs::create_dir_all(root.join("target/classes")).expect("target");
        }
        Layout::Plain => {}
    }
    (root, sources)
}

/// `whitted check args...` in `dir`, with `TMPDIR` set to `tmp` (so that what it leaves there
/// can be seen).
fn check_in(dir: &Path, tmp: &Path, args: &[&str]) -> Output {
    std::fs::create_dir_all(tmp).expect("tmp");
    Command::new(env!("CARGO_BIN_EXE_whitted"))
        .arg("check")
        .args(args)
        .current_dir(dir)
        .env("TMPDIR", tmp)
        .output()
        .expect("whitted runs")
}

fn assert_empty(tmp: &Path) {
    let left: Vec<PathBuf> = std::fs::read_dir(tmp)
        .expect("tmp")
        .flatten()
        .map(|e| e.path())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

/// A 2021-22 IntelliJ project passes, its year read from its classes and said with why; a copy
/// of the main class elsewhere is said; the compiled classes are gone afterwards. `--course`
/// overrides the year and says the project disagrees.
#[test]
fn a_2021_22_intellij_project_passes_with_its_year_and_why_and_course_overrides() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (root, sources) = project(d, "tick1", "2021-22", Layout::IntelliJ, &[]);
    std::fs::create_dir_all(root.join("backup")).expect("backup");
    std::fs::copy(sources.join("Tick1.java"), root.join("backup/Tick1.java")).expect("copy");
    let tmp = d.join("tmp");
    let run = check_in(d, &tmp, &["tick1"]);
    let (out, err) = (stdout(&run), stderr(&run));
    assert_eq!(run.status.code(), Some(0), "{out}\n{err}");
    assert!(
        out.contains(
            "course: 2021-22, because Tick1.java renders 800x600 and ColorRGB has power()/inv() \
             but no isZero()"
        ),
        "{out}"
    );
    assert!(
        out.contains(
            "project: uk.ac.cam.cl.gfxintro.ab123.tick1.Tick1 in \
             tick1/src/uk/ac/cam/cl/gfxintro/ab123/tick1, compiled by javac"
        ),
        "{out}"
    );
    assert!(
        !out.contains("note:"),
        "the year's own classes: nothing to say\n{out}"
    );
    assert!(
        err.contains(
            "2 copies of Tick1.java: using tick1/src/uk/ac/cam/cl/gfxintro/ab123/tick1/Tick1.java"
        ) && err.contains("not tick1/backup/Tick1.java"),
        "{err}"
    );
    assert_empty(&tmp);

    let run = check_in(d, &tmp, &["tick1", "--course", "2023-24", "--json"]);
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    assert_eq!(json["course"], "2023-24");
    assert!(json.get("course_chosen_because").is_none(), "{json}");
    let notes = json["project"]["notes"].to_string();
    assert!(
        notes.contains("look like 2021-22's") && notes.contains("checked as 2023-24"),
        "{notes}"
    );
    // 2023-24's program takes -r, which a 2021-22 Tick1 refuses.
    assert!(json["cases"][0]["status"] == "crashed", "{json}");
    assert_empty(&tmp);
}

/// A 2017-18 Maven project and a 2023-24 plain folder (checked from inside it, with no
/// argument) pass, each year said with the clues that tell it.
#[test]
fn a_2017_18_maven_project_and_a_2023_24_plain_folder_pass_with_their_years() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    project(d, "maven", "2017-18", Layout::Maven, &[]);
    let run = check_in(d, &d.join("tmp"), &["maven"]);
    let out = stdout(&run);
    assert_eq!(run.status.code(), Some(0), "{out}\n{}", stderr(&run));
    assert!(
        out.contains(
            "course: 2017-18, because Tick1.java renders 640x480 and ColorRGB has no power()/inv()"
        ),
        "{out}"
    );
    assert!(
        out.contains("in maven/src/main/java/uk/ac/cam/cl/gfxintro/ab123/tick1"),
        "{out}"
    );

    let (plain, _) = project(d, "plain", "2023-24", Layout::Plain, &[]);
    let run = check_in(&plain, &d.join("tmp"), &[]);
    let out = stdout(&run);
    assert_eq!(run.status.code(), Some(0), "{out}\n{}", stderr(&run));
    assert!(
        out.contains(
            "course: 2023-24, because Tick1.java renders 800x600 and ColorRGB has isZero()"
        ),
        "{out}"
    );
    assert!(out.contains(" in ., compiled by javac"), "{out}");
}

/// 2019-20 and 2020-21 ship the same classes: the later is taken and that is said. A mistake
/// in the student's Renderer fails (exit 1) and is named, with nothing said of the course's
/// classes, which are the year's.
#[test]
fn a_2020_21_project_with_a_mistake_fails_and_the_years_its_classes_cannot_tell_are_said() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (root, _) = project(d, "p", "2020-21", Layout::IntelliJ, &["specular-white"]);
    let run = check_in(d, &d.join("tmp"), &[s(&root)]);
    let out = stdout(&run);
    assert_eq!(run.status.code(), Some(1), "{out}\n{}", stderr(&run));
    assert!(
        out.contains("course: 2020-21, because ")
            && out.contains("as in 2019-20 and 2020-21: their classes are the same, so the latest is taken (--course 2019-20"),
        "{out}"
    );
    assert!(out.contains("specular-white"), "{out}");
    assert!(!out.contains("note:"), "{out}");
}

/// An edited SceneLoader (a public method added; colours divided by 200, not 255) is told up front, the
/// class named: by its members before the run, and by a render on the year's own classes
/// after a case fails.
#[test]
fn an_edited_scene_loader_is_told_up_front_with_the_class_named() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (root, sources) = project(d, "edited", "2021-22", Layout::IntelliJ, &[]);
    let loader = sources.join("SceneLoader.java");
    let text = std::fs::read_to_string(&loader).expect("loader");
    let edited = text.replace("/ 255.0", "/ 200.0").replacen(
        "    public Scene getScene() {",
        "    public int count() {\n        return 0;\n    }\n\n    public Scene getScene() {",
        1,
    );
    assert_ne!(edited, text);
    std::fs::write(&loader, edited).expect("write");
    let run = check_in(d, &d.join("tmp"), &[s(&root)]);
    let out = stdout(&run);
    assert_eq!(run.status.code(), Some(1), "{out}\n{}", stderr(&run));
    let notes: Vec<&str> = out.lines().filter(|l| l.starts_with("note:")).collect();
    assert!(
        notes.iter().any(|n| n
            .contains("SceneLoader.java is not 2021-22's: it has count() that 2021-22's has not")),
        "{out}"
    );
    assert!(
        notes.iter().any(
            |n| n.contains("with your SceneLoader.java among 2021-22's own classes")
                && n.contains("pixels differ")
        ),
        "{out}"
    );
    // Up front: the notes come before the cases.
    let first_case = out.find("test1.xml").expect("a case");
    assert!(out.find("note:").expect("a note") < first_case, "{out}");
    assert!(
        !notes
            .iter()
            .any(|n| n.contains("Camera") || n.contains("Tick1.java is")),
        "{out}"
    );
}

/// The 2023-24 skeleton as shipped (BumpySphere.getNormalAt with no return) does not compile:
/// javac's error and the cause, each said once, exit 2, nothing on stdout, nothing left behind.
#[test]
fn the_2023_24_bumpy_sphere_as_shipped_is_said_once_with_its_cause() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (_, sources) = project(d, "shipped", "2023-24", Layout::IntelliJ, &[]);
    let bumpy = sources.join("BumpySphere.java");
    let text = std::fs::read_to_string(&bumpy).expect("bumpy");
    let shipped = text.replace("return new Vector3(0);", "// TODO: the bump-mapped normal");
    assert_ne!(shipped, text);
    std::fs::write(&bumpy, shipped).expect("write");
    let tmp = d.join("tmp");
    let run = check_in(d, &tmp, &["shipped"]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(run.stdout.is_empty());
    assert_eq!(err.matches("missing return statement").count(), 1, "{err}");
    assert_eq!(
        err.matches("BumpySphere.getNormalAt has no return").count(),
        1,
        "{err}"
    );
    assert!(
        err.contains("shipped/src/uk/ac/cam/cl/gfxintro/ab123/tick1/BumpySphere.java:"),
        "{err}"
    );
    assert_eq!(
        err.matches("error:").count(),
        2,
        "ours and javac's one\n{err}"
    );
    assert_empty(&tmp);
}

/// No main class: a clear message, exit 2; no argument outside a project: the usage, exit 2;
/// no javac: what to install, exit 2.
#[test]
fn no_main_class_and_no_javac_are_clear_errors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let empty = d.join("empty");
    std::fs::create_dir_all(empty.join("out")).expect("empty");
    std::fs::write(empty.join("out/Tick1.java"), "class Tick1 {}").expect("w");
    let run = check_in(d, &d.join("tmp"), &["empty"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("empty: no Tick1.java (Tick 1, 2017-18 on) or Tick2.java"),
        "{}",
        stderr(&run)
    );
    let run = check_in(&empty, &d.join("tmp"), &[]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("a project folder, or --program"),
        "{}",
        stderr(&run)
    );

    let (root, _) = project(d, "nojdk", "2021-22", Layout::Plain, &[]);
    let bin = d.join("bin");
    std::fs::create_dir_all(&bin).expect("bin");
    let java = std::env::split_paths(&std::env::var_os("PATH").expect("PATH"))
        .map(|p| p.join("java"))
        .find(|p| p.is_file())
        .expect("java on PATH");
    std::os::unix::fs::symlink(java, bin.join("java")).expect("link");
    let run = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(["check", s(&root)])
        .env("PATH", &bin)
        .output()
        .expect("runs");
    assert_eq!(run.status.code(), Some(2));
    let err = stderr(&run);
    assert!(
        err.contains("`javac` is not on PATH") && err.contains("install a JDK"),
        "{err}"
    );
}

/// 2016-17's Tick 2 project (gfx/tick2, Tick2.java): its year from the main class; passes.
#[test]
fn a_2016_17_tick2_project_is_checked_as_2016_17() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let tick2 = d.join("tick2");
    let wrote = whitted(
        d,
        &[
            "grade",
            "--write-skeleton",
            "--course",
            "2016-17",
            "-o",
            s(&tick2),
        ],
    );
    assert!(wrote.status.success(), "{}", stderr(&wrote));
    let package = tick2.join("src/gfx/tick2");
    assert!(package.join("Tick2.java").is_file());
    for file in ["Plane.java", "Renderer.java"] {
        std::fs::copy(
            root().join("tests/java/submission/gfx/tick2").join(file),
            package.join(file),
        )
        .expect("copy");
    }
    let run = check_in(d, &d.join("tmp"), &["tick2", "--json"]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("json");
    assert_eq!(json["course"], "2016-17");
    let why = json["course_chosen_because"].as_str().unwrap_or_default();
    assert!(
        why.contains("the main class is Tick2.java, the 2016-17 Tick 2"),
        "{why}"
    );
    assert_eq!(json["project"]["main_class"], "gfx.tick2.Tick2");
}

/// With `--suite-dir`, the rerun commands of a project's failing cases run as printed and run
/// what was checked: the build kept in `suite/classes`, never the IDE's `out/` (here a stale,
/// broken `Tick1.class`, as an IDE leaves one).
#[test]
fn a_project_s_rerun_commands_run_the_build_that_was_checked() {
    use crate::check_print::{assert_every_command_runs, commands};
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let (root, _) = project(d, "p", "2021-22", Layout::IntelliJ, &["no-ambient"]);
    let run = check_in(
        d,
        &d.join("tmp"),
        &[s(&root), "--suite-dir", "suite", "--verbose"],
    );
    let out = stdout(&run);
    assert_eq!(run.status.code(), Some(1), "{out}\n{}", stderr(&run));
    assert!(out.contains("java -cp suite/classes "), "{out}");
    assert!(!out.contains("out/production"), "{out}");
    let printed = commands(&out);
    assert!(printed.len() >= 6 * 2, "{out}");
    assert_every_command_runs(d, &printed);
}
