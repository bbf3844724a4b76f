//! `whitted grade --course YEAR` on whitted's clean-room skeleton of the year (docs/grade.md,
//! "The Tick 1 skeleton's API"): classes of every API group, each student in the package of
//! their own user id (`uk.ac.cam.cl.gfxintro.<crsid>.tick1`), handing in Plane, Renderer and
//! Sphere, as real submissions arrive (a whole IDE project with the course's classes and an
//! edited Tick1.java, a Maven tree in a zip, a Tick 1* project). The submissions are whitted's
//! finished Tick 1 with a student's mistakes edited in (tick1_fixture.rs), selected for each
//! year's API.

use std::path::Path;

use serde_json::Value;

use crate::common::*;
use crate::grade::{grade, records};
use crate::tick1_fixture::fixture;

/// The submission's three files for 2021-22 in package `crsid`, with `bugs` baked in.
fn submission(crsid: &str, bugs: &[&str]) -> Vec<(&'static str, String)> {
    fixture("2021-22", crsid, bugs)
}

/// Writes a student's folder: their files under `layout` (`{crsid}` replaced).
fn student(class: &Path, folder: &str, files: &[(&str, String)], layout: &str, crsid: &str) {
    let dir = class.join(folder).join(layout.replace("{crsid}", crsid));
    std::fs::create_dir_all(&dir).expect("folder");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write");
    }
}

/// `whitted grade class -o out --course course` in `dir`: the year's default skeleton.
fn grade_year(dir: &Path, course: &str) -> std::process::Output {
    grade(dir, &["class", "-o", "out", "--course", course])
}

fn result_json(out: &Path, id: &str) -> Value {
    let text = std::fs::read(out.join("students").join(id).join("result.json")).expect("result");
    serde_json::from_slice(&text).expect("json")
}

#[test]
fn a_later_class_with_a_package_each_is_graded_named_and_written_up() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let tree = "src/uk/ac/cam/cl/gfxintro/{crsid}/tick1";
    // (Moodle folder, crsid, mistakes, layout, what class.csv names)
    let students: [(&str, &str, &[&str], &str, &str); 6] = [
        ("Ada_41001_assignsubmission_file", "ab123", &[], tree, ""),
        (
            "Ben_41002_assignsubmission_file",
            "cd456",
            &["no-gate", "reflection-bias-along-n"],
            "tick1/uk/ac/cam/cl/gfxintro/{crsid}/tick1",
            "no-gate+reflection-bias-along-n",
        ),
        (
            "Cy_41003_assignsubmission_file",
            "ef789",
            &["spheres-missing"],
            tree,
            "spheres-missing",
        ),
        (
            "Di_41004_assignsubmission_file",
            "gh012",
            &["shading-missing"],
            "",
            "shading-missing",
        ),
        (
            "Ed_41005_assignsubmission_file",
            "ij345",
            &["specular-white"],
            tree,
            "specular-white",
        ),
        (
            "Flo_41006_assignsubmission_file",
            "kl678",
            &["background-changed"],
            tree,
            "background-changed",
        ),
    ];
    for (folder, crsid, bugs, layout, _) in &students {
        student(&class, folder, &submission(crsid, bugs), layout, crsid);
    }
    // A package that is no Java name cannot be a main class on a command line.
    let mut bad = submission("mn901", &[]);
    for (_, text) in &mut bad {
        *text = text.replace("gfxintro.mn901.tick1;", "gfxintro.mn-901.tick1;");
    }
    student(
        &class,
        "Gus_41007_assignsubmission_file",
        &bad,
        tree,
        "mn901",
    );
    let out = dir.path().join("out");
    let run = grade_year(dir.path(), "2021-22");
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let rows = records(&out.join("class.csv"));
    assert_eq!(rows.len(), 7, "{rows:?}");
    for (folder, crsid, _, _, named) in &students {
        let id = folder.split('_').nth(1).expect("id");
        let row = rows.iter().find(|r| r["id"] == id).expect("row");
        assert_eq!(row["status"], "graded", "{crsid}: {row:?}");
        assert_eq!(row["diagnosis"], *named, "{crsid}: {row:?}");
        if named.is_empty() {
            assert_eq!(row["passed"], row["cases"], "{row:?}");
        } else {
            assert_ne!(row["passed"], row["cases"], "{row:?}");
        }
        // Each student's own main class ran, at the year's size.
        let json = result_json(&out, id);
        let check = &json["extra_data"]["check"];
        // (The program as the check names it: a case's rerun command is given only where the
        // suite's scenes were written, which grade does not do.)
        let main = format!("java uk.ac.cam.cl.gfxintro.{crsid}.tick1.Tick1");
        let program = check["program"].as_str().expect("program");
        assert!(program.starts_with(&main), "{program}");
        assert!(check["cases"][0]["reproduce"]["run"].is_null(), "{check}");
        assert_eq!(check["cases"][0]["width"], 800);
    }
    let gus = rows.iter().find(|r| r["id"] == "41007").expect("row");
    assert_eq!(gus["status"], "error", "{gus:?}");
    let gus = std::fs::read_to_string(out.join("students/41007/report.html")).expect("report");
    assert!(gus.contains("not a plain Java package name"), "{gus}");
    // The common variant is said to be one (docs/courses.md).
    let ben = std::fs::read_to_string(out.join("students/41002/report.html")).expect("report");
    assert!(ben.contains("common variant"), "{ben}");
    assert!(ben.contains("Tick 1 (2021-22)"), "{ben}");
    let index = std::fs::read_to_string(out.join("index.html")).expect("index");
    assert!(index.contains("Tick 1 (2021-22): the class"), "{index}");
    assert!(index.contains("Course: 2021-22."), "{index}");
}

#[test]
fn a_random_tick1_star_submission_is_not_reproducible_rather_than_diagnosed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let files = submission("op234", &["star-soft-shadows"]);
    student(&class, "op234", &files, "", "op234");
    let run = grade_year(dir.path(), "2021-22");
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let json = result_json(&dir.path().join("out"), "op234");
    let check = &json["extra_data"]["check"];
    assert_eq!(
        check["not_reproducible"]["seen"], "two-runs-differ",
        "{check}"
    );
    let report =
        std::fs::read_to_string(dir.path().join("out/students/op234/report.html")).expect("report");
    assert!(report.contains("not reproducible"), "{report}");
}

/// `--skeleton DIR` overrides the default: the course's 2023-24 classes as shipped (BumpySphere's
/// getNormalAt without its return) do not compile, and the report says the skeleton is at fault.
#[test]
fn a_given_skeleton_overrides_the_default_and_one_that_does_not_compile_is_named() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let files = fixture("2023-24", "qr567", &[]);
    student(&class, "qr567", &files, "", "qr567");
    let broken = dir.path().join("broken");
    let course = whitted_core::course::Course::from_name("2023-24").expect("course");
    for (path, bytes) in whitted_grade::clean_room_skeleton(course, None).expect("skeleton") {
        let text = String::from_utf8(bytes).expect("utf-8");
        let text = text.replace("return new Vector3(0);", "new Vector3(0);");
        let path = broken.join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, text).expect("write");
    }
    let args = [
        "class",
        "-o",
        "out",
        "--course",
        "2023-24",
        "--skeleton",
        s(&broken),
    ];
    let run = grade(dir.path(), &args);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let rows = records(&dir.path().join("out/class.csv"));
    assert_eq!(rows[0]["status"], "compile-error", "{rows:?}");
    let report =
        std::fs::read_to_string(dir.path().join("out/students/qr567/report.html")).expect("report");
    assert!(report.contains("BumpySphere.java"), "{report}");
    assert!(report.contains("missing return statement"), "{report}");
    assert!(report.contains("the skeleton"), "{report}");
    // The same student on the default skeleton of the year compiles and passes.
    let run = grade(
        dir.path(),
        &["class", "-o", "default", "--course", "2023-24"],
    );
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let rows = records(&dir.path().join("default/class.csv"));
    assert_eq!(rows[0]["status"], "graded", "{rows:?}");
    assert_eq!(rows[0]["passed"], rows[0]["cases"], "{rows:?}");
}

/// A project as a student's IDE has it: the course's classes beside their three files, an edited
/// Tick1.java and Tick1Tests.java, compiled classes, scenes; all under `top`.
fn ide_project(class: &Path, folder: &str, year: &str, crsid: &str, bugs: &[&str], top: &str) {
    let course = whitted_core::course::Course::from_name(year).expect("course");
    let package = format!("uk.ac.cam.cl.gfxintro.{crsid}.tick1");
    let root = class.join(folder).join(top);
    for (path, bytes) in
        whitted_grade::clean_room_skeleton(course, Some(&package)).expect("skeleton")
    {
        let text = String::from_utf8(bytes).expect("utf-8");
        // Six of eleven real solutions change Tick1's defaults; a few break it outright.
        let text = text.replace("\"tick1.xml\"", "\"scenes/test1.xml\"");
        let path = root.join("src").join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, text).expect("write");
    }
    student(
        &class.join(folder),
        top,
        &fixture(year, crsid, bugs),
        &format!("src/uk/ac/cam/cl/gfxintro/{crsid}/tick1"),
        crsid,
    );
    for (path, text) in [
        (".idea/misc.xml", "<project version=\"4\"/>"),
        ("tick1.iml", "<module type=\"JAVA_MODULE\"/>"),
        ("scenes/test1.xml", "<scene/>"),
        (
            &format!("out/production/tick1/uk/ac/cam/cl/gfxintro/{crsid}/tick1/Tick1.class")
                as &str,
            "\u{cafe}",
        ),
    ] {
        let path = root.join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, text).expect("write");
    }
}

/// Each API group's class graded on its default skeleton, as submissions arrive: whole IDE
/// projects carrying the course's classes and an edited Tick1.java, a Maven tree zipped inside
/// the Moodle folder with a second copy of a file, and a Tick 1* project.
#[test]
fn every_api_group_is_graded_on_its_own_skeleton_as_submissions_arrive() {
    for (year, bugs, width) in [
        ("2017-18", &["specular-white"][..], 640),
        ("2018-19", &["no-shadows"][..], 640),
        ("2023-24", &["view-to-camera"][..], 800),
    ] {
        let dir = tempfile::tempdir().expect("tempdir");
        let class = dir.path().join("class");
        ide_project(
            &class,
            "Ada_51001_assignsubmission_file",
            year,
            "ab123",
            &[],
            "tick1",
        );
        // A Maven project zipped, with an old copy of Renderer.java left at the top.
        let maven = dir.path().join("maven");
        let tree = "src/main/java/uk/ac/cam/cl/gfxintro/cd456/tick1";
        student(
            &maven,
            "project",
            &fixture(year, "cd456", bugs),
            tree,
            "cd456",
        );
        std::fs::write(maven.join("project/pom.xml"), "<project/>").expect("pom");
        let folder = class.join("Ben_51002_assignsubmission_file");
        std::fs::create_dir_all(&folder).expect("folder");
        zip_folder(&maven.join("project"), &folder.join("project.zip"));
        let old = fixture(year, "cd456", &["shading-missing"]);
        std::fs::write(folder.join("Renderer.java"), &old[1].1).expect("old copy");
        if year == "2023-24" {
            // Tick 1*: random soft shadows in its own package.
            let star: Vec<(&str, String)> = fixture(year, "ef789", &["star-soft-shadows"])
                .into_iter()
                .map(|(name, text)| (name, text.replace(".ef789.tick1;", ".ef789.tick1star;")))
                .collect();
            student(
                &class,
                "Cy_51003_assignsubmission_file",
                &star,
                "src/uk/ac/cam/cl/gfxintro/ef789/tick1star",
                "ef789",
            );
        }
        let run = grade_year(dir.path(), year);
        assert_eq!(run.status.code(), Some(0), "{year}: {}", stderr(&run));
        let out = dir.path().join("out");
        let rows = records(&out.join("class.csv"));
        assert_eq!(
            rows.len(),
            if year == "2023-24" { 3 } else { 2 },
            "{year}: {rows:?}"
        );
        let ada = rows.iter().find(|r| r["id"] == "51001").expect("Ada");
        assert_eq!(ada["status"], "graded", "{year}: {ada:?}");
        assert_eq!(ada["diagnosis"], "", "{year}: {ada:?}");
        assert_eq!(ada["passed"], ada["cases"], "{year}: {ada:?}");
        let ben = rows.iter().find(|r| r["id"] == "51002").expect("Ben");
        assert_eq!(ben["status"], "graded", "{year}: {ben:?}");
        assert_eq!(ben["diagnosis"], bugs.join("+"), "{year}: {ben:?}");
        let json = result_json(&out, "51002");
        let check = &json["extra_data"]["check"];
        assert_eq!(check["cases"][0]["width"], width, "{year}");
        let report =
            std::fs::read_to_string(out.join("students/51001/report.html")).expect("report");
        assert!(
            report.contains("Tick1.java"),
            "{year}: the ignored classes are said: {report}"
        );
        let ben = std::fs::read_to_string(out.join("students/51002/report.html")).expect("report");
        assert!(ben.contains("Renderer.java"), "{year}: {ben}");
        // In the year's own words: no 2016-17 names.
        assert!(
            !ben.contains("inShadow stays false") && !ben.contains("|X - P|"),
            "{year}: {ben}"
        );
        if year == "2018-19" {
            assert!(ben.contains("no shadow ray is cast"), "{ben}");
        }
        let index = std::fs::read_to_string(out.join("index.html")).expect("index");
        assert!(
            index.contains(&format!("clean-room {year} skeleton")),
            "{year}: {index}"
        );
        if year == "2023-24" {
            let cy = rows.iter().find(|r| r["id"] == "51003").expect("Cy");
            let report =
                std::fs::read_to_string(out.join("students/51003/report.html")).expect("report");
            assert!(report.contains("Tick 1*"), "{cy:?}: {report}");
            assert!(!report.contains("timeout"), "{report}");
        }
    }
}

/// `dir` zipped into `zip`, its files under the folder's own name.
fn zip_folder(dir: &Path, zip: &Path) {
    fn files(dir: &Path, into: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("folder").flatten() {
            match entry.file_type().expect("type").is_dir() {
                true => files(&entry.path(), into),
                false => into.push(entry.path()),
            }
        }
    }
    let mut paths = Vec::new();
    files(dir, &mut paths);
    paths.sort();
    let file = std::fs::File::create(zip).expect("zip");
    let mut writer = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default();
    for path in paths {
        let name = path
            .strip_prefix(dir.parent().expect("parent"))
            .expect("inside");
        writer
            .start_file(name.to_string_lossy(), options)
            .expect("entry");
        let bytes = std::fs::read(&path).expect("read");
        std::io::Write::write_all(&mut writer, &bytes).expect("write");
    }
    writer.finish().expect("finish");
}

/// A Tick 1* program too slow for the timeout (hundreds of rays a pixel) runs the handout's two
/// scenes, not the suite: two timeouts at most, never a row of them, and said to be Tick 1*.
#[test]
fn a_slow_tick1_star_project_is_one_timeout_and_said_to_be_tick1_star() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let star: Vec<(&str, String)> = fixture("2023-24", "gh012", &[])
        .into_iter()
        .map(|(name, text)| {
            let text = text.replace(".gh012.tick1;", ".gh012.tick1star;").replace(
                "public BufferedImage render(Scene scene) {",
                "public BufferedImage render(Scene scene) {\n        \
                 try { Thread.sleep(600000); } catch (InterruptedException e) { }",
            );
            (name, text)
        })
        .collect();
    student(
        &class,
        "gh012",
        &star,
        "src/uk/ac/cam/cl/gfxintro/gh012/tick1star",
        "gh012",
    );
    let started = std::time::Instant::now();
    let args = [
        "class",
        "-o",
        "out",
        "--course",
        "2023-24",
        "--timeout",
        "4",
    ];
    let run = grade(dir.path(), &args);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(
        started.elapsed() < std::time::Duration::from_secs(40),
        "{:?}",
        started.elapsed()
    );
    let json = result_json(&dir.path().join("out"), "gh012");
    let statuses: Vec<&str> = json["extra_data"]["check"]["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .map(|c| c["status"].as_str().expect("status"))
        .collect();
    // Its package says Tick 1*: the options' two scenes ran (together), not the suite.
    assert_eq!(statuses, ["timeout", "timeout"]);
    let report =
        std::fs::read_to_string(dir.path().join("out/students/gh012/report.html")).expect("report");
    assert!(report.contains("a Tick 1* program"), "{report}");
}

/// A later year's class graded without `--course` (2016-17's Tick 2, the default) would be
/// every student a compile error with grade 0, in a worksheet ready to upload: it is refused
/// before anyone is graded, naming the flag, and nothing is written.
#[test]
fn a_tick1_class_graded_without_its_year_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().expect("tempdir");
    let class = dir.path().join("class");
    let tree = "src/uk/ac/cam/cl/gfxintro/{crsid}/tick1";
    for (folder, crsid) in [
        ("Ada_41001_assignsubmission_file", "ab123"),
        ("Ben_41002_assignsubmission_file", "cd456"),
    ] {
        student(&class, folder, &submission(crsid, &[]), tree, crsid);
    }
    let out = grade(dir.path(), &["class", "-o", "out"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("2 of 2 submissions are Tick 1 hand-ins (students 41001, 41002")
            && stderr.contains("give --course YEAR, one of 2017-18"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(!dir.path().join("out").join("moodle.csv").exists());
    // With the year the same class is graded.
    let out = grade_year(dir.path(), "2021-22");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = records(&dir.path().join("out/class.csv"));
    assert!(rows.iter().all(|r| r["grade"] == "100"), "{rows:?}");
}
