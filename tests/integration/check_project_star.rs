//! `whitted check DIR` on a Tick 1* project that fails (docs/check.md, "From your project
//! folder"): its random image cannot be compared pixel for pixel with a second render, so the
//! failing case is rendered again on the student's own files among the year's classes and the
//! two verdicts are compared. Our Java Tick 1* (tests/java/tick1star, option 2 done) on
//! whitted's clean-room 2023-24 skeleton is the project, at 2023-24's reduced 160x120; the
//! edit is a real student's: the loader gives planes no specular term (kS 0, the course's
//! 1.2). In the loader, the year's loader gives another verdict and the loader is named; the
//! same image made by the student's own Renderer, with the year's loader, gives the same
//! verdict on the year's classes, and nothing is said of a course class.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::*;
use crate::star_programs::{compiled, Done, PACKAGE, YEAR};

/// Our Java Tick 1* (option 2) as a project folder `d/name` of sources alone, with `file`
/// (a file of its package) edited by `edit`; returns the folder.
fn project(d: &Path, name: &str, file: &str, edit: &dyn Fn(&str) -> String) -> PathBuf {
    let root = d.join(name);
    std::fs::create_dir_all(&root).expect("project");
    compiled(&root, PACKAGE, Done::Distributed, "");
    std::fs::remove_dir_all(root.join("classes")).expect("classes");
    let path = root.join("src").join(PACKAGE.replace('.', "/")).join(file);
    let text = std::fs::read_to_string(&path).expect("source");
    let edited = edit(&text);
    assert_ne!(edited, text, "{file} not edited");
    std::fs::write(&path, edited).expect("write");
    root
}

/// `whitted check --course 2023-24 DIR` in `d`: its exit status, stdout's notes, stderr.
fn check(d: &Path, root: &Path) -> (Option<i32>, String, Vec<String>, String) {
    let out: Output = whitted(d, &["check", "--course", YEAR, s(root)]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let notes = text
        .lines()
        .filter(|l| l.starts_with("note:"))
        .map(str::to_string)
        .collect();
    (out.status.code(), text, notes, stderr(&out))
}

/// The year's SceneLoader with a plane's kS 0 where the year's is 1.2, the real edit.
fn planes_without_specular(loader: &str) -> String {
    let plane = loader.find("new Plane(").expect("the loader makes planes");
    let (before, after) = loader.split_at(plane);
    format!(
        "{before}{}",
        after.replacen("number(e, \"kS\", 1.2)", "0", 1)
    )
}

#[test]
fn a_tick1_star_project_s_edited_loader_is_named_by_its_verdict() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let root = project(d, "loader", "SceneLoader.java", &planes_without_specular);
    let started = std::time::Instant::now();
    let (status, out, notes, err) = check(d, &root);
    eprintln!(
        "check of the edited loader: {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert_eq!(status, Some(1), "{out}\n{err}");
    // The members are the year's: only the second render can tell.
    assert!(
        !notes
            .iter()
            .any(|n| n.contains("it has") || n.contains("it lacks")),
        "{out}"
    );
    let said = notes.join("\n");
    assert!(
        notes.iter().any(|n| n.contains(
            "your project's image of distributed.xml is judged not-a-draw, but your \
             Sphere.java, Plane.java, Renderer.java and BumpySphere.java among 2023-24's own \
             classes render one judged course-draw"
        )),
        "{out}\n{err}"
    );
    assert!(
        notes.iter().any(|n| n.contains(
            "SceneLoader.java is not 2023-24's: with your SceneLoader.java among 2023-24's own \
             classes, your Sphere.java, Plane.java, Renderer.java and BumpySphere.java render \
             distributed.xml judged not-a-draw, as your project does"
        )),
        "{said}\n{err}"
    );
    assert_eq!(notes.len(), 2, "{said}");
    // Each render said before it starts, with why.
    assert_eq!(
        err.matches("rendering distributed.xml again").count(),
        1,
        "{err}"
    );
    assert!(
        err.contains("rendering distributed.xml with your SceneLoader.java among 2023-24's own classes (try 1 of at most 3)"),
        "{err}"
    );
}

#[test]
fn the_same_image_from_the_student_s_renderer_with_the_year_s_loader_names_no_class() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let renderer = |text: &str| {
        text.replacen(
            "double k_s = object.getPhong_kS();",
            "double k_s = object instanceof Plane ? 0 : object.getPhong_kS();",
            1,
        )
    };
    let root = project(d, "renderer", "Renderer.java", &renderer);
    let started = std::time::Instant::now();
    let (status, out, notes, err) = check(d, &root);
    eprintln!(
        "check of the edited renderer: {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert_eq!(status, Some(1), "{out}\n{err}");
    assert!(
        out.contains("not a draw of the course's distribution"),
        "{out}"
    );
    // Rendered again, and judged alike: nothing to say of a course class.
    assert!(err.contains("rendering distributed.xml again"), "{err}");
    assert!(notes.is_empty(), "{out}\n{err}");
}
