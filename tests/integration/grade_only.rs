//! `whitted grade --only ID` into a fresh OUTDIR: the students it did not grade get no grade
//! in the worksheet (Moodle's own worksheet leaves an ungraded student's blank, and its import
//! skips a blank grade), never a 0 that an upload would give the whole class; the closing
//! lines say how many were not graded and how to grade them. The class is two students
//! whose submissions hold Plane.java alone, so that no program is compiled or run.

use crate::common::*;
use crate::grade::{grade, records};

#[test]
fn a_partial_run_writes_no_grade_for_the_students_it_did_not_grade() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    for folder in [
        "Ann Able_71001_assignsubmission_file_",
        "Ben Baker_71002_assignsubmission_file_",
    ] {
        let student = d.join("class").join(folder);
        std::fs::create_dir_all(&student).expect("folder");
        std::fs::write(student.join("Plane.java"), "class Plane {}\n").expect("write");
    }
    let run = grade(d, &["class", "-o", "out", "--only", "71001"]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let said = String::from_utf8_lossy(&run.stdout).to_string();
    assert!(said.contains("1 not graded by this run"), "{said}");
    assert!(
        said.contains("grade them with `whitted grade class -o out`"),
        "{said}"
    );

    let out = d.join("out");
    let moodle = records(&out.join("moodle.csv"));
    let row = |id: &str| {
        moodle
            .iter()
            .find(|r| r["Identifier"] == format!("Participant {id}"))
            .expect("row")
            .clone()
    };
    // The student graded has their grade (no-files: 0) and its feedback.
    assert_eq!(row("71001")["Grade"], "0", "{moodle:?}");
    assert!(row("71001")["Feedback comments"].starts_with("no Renderer.java"));
    // The other has the row Moodle's worksheet gives an ungraded student.
    let ben = row("71002");
    assert_eq!(ben["Grade"], "", "{ben:?}");
    assert_eq!(ben["Feedback comments"], "", "{ben:?}");
    assert_eq!(ben["Last modified (grade)"], "", "{ben:?}");
    assert_eq!(ben["Status"], "not-graded", "{ben:?}");
    let class = records(&out.join("class.csv"));
    let ben = class.iter().find(|r| r["id"] == "71002").expect("row");
    assert_eq!(
        (ben["grade"].as_str(), ben["status"].as_str()),
        ("", "not-graded")
    );
    assert!(
        !out.join("students/71002").exists(),
        "nothing written of Ben"
    );

    // A run without --only grades him, and leaves no one ungraded.
    let all = grade(d, &["class", "-o", "out"]);
    assert_eq!(all.status.code(), Some(0), "{}", stderr(&all));
    let said = String::from_utf8_lossy(&all.stdout).to_string();
    assert!(!said.contains("not graded"), "{said}");
    let moodle = records(&out.join("moodle.csv"));
    assert!(moodle.iter().all(|r| r["Grade"] == "0"), "{moodle:?}");
}
