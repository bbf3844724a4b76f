//! An attempt of a project, run as `whitted grade` runs one student of a class: their `.java`
//! files in a folder of Moodle's shape, compiled against the year's skeleton and run over the
//! suite in grade's sandbox (bubblewrap, seccomp, a memory cgroup), checked, and written up.
//! The grade output is kept in the attempt's folder (`graded/`), where the staff's export
//! takes it from without running anything again.

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::store::{Outcome, Student};
use whitted_check::check::pass_rule::{Allowance, PassRule};
use whitted_check::mistakes::Stage;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_grade::{Grading, Limits, Options, Rerun, Watch};

/// The folder of an attempt's sources, and of its grade output.
pub const SOURCES: &str = "src";
pub const GRADED: &str = "graded";

/// How a program is run: grade's defaults (`whitted grade --timeout 60 --memory 1024`).
#[derive(Debug, Clone, Copy)]
pub struct Run {
    pub course: Course,
    pub limits: Limits,
}

impl Run {
    pub fn new(course: Course, seconds: u64) -> Run {
        Run {
            course,
            limits: Limits {
                memory_mib: 1024,
                seconds,
            },
        }
    }
}

/// Grades the sources in `attempt/src` for `student`; the outcome, or why it could not run
/// (no JDK, no bubblewrap: the service's own trouble, said as such).
/// `watch` is told of each step as it happens.
pub fn run(attempt: &Path, student: &Student, how: Run, watch: Option<Watch>) -> Result<Outcome> {
    let submissions = tempfile::Builder::new()
        .prefix("whitted-serve-")
        .tempdir()
        .map_err(|e| Error::Environment(format!("cannot create a temporary folder: {e}")))?;
    let folder = submissions.path().join(moodle_folder(student));
    copy_sources(&attempt.join(SOURCES), &folder)?;
    let outdir = attempt.join(GRADED);
    // A run the service was killed in left part of an output: this run starts it again.
    if outdir.exists() {
        std::fs::remove_dir_all(&outdir).map_err(|e| Error::io(&outdir, "cannot remove", e))?;
    }
    let options = Options {
        submissions: submissions.path().to_path_buf(),
        outdir: outdir.clone(),
        skeleton: None,
        course: how.course,
        scenes: None,
        jobs: 1,
        limits: how.limits,
        rerun: Some(Rerun::All),
        no_sandbox: false,
        grading: Grading::PassFail,
        rule: PassRule {
            tolerance: 2,
            allowance: Allowance::NONE,
        },
        count_diagnostic: false,
        rubric: None,
        only: Vec::new(),
        show_hidden: false,
        part: None,
        quiet: true,
        watch,
    };
    whitted_grade::run(&options)?;
    outcome(&graded_student(&outdir)?, how.course)
}

/// The folder Moodle's "Download all submissions" gives the student, which grade reads the
/// id and name from (a numeric id) or takes as the id (any other).
fn moodle_folder(student: &Student) -> String {
    let numeric = student.id.bytes().all(|b| b.is_ascii_digit());
    let name: String = student
        .name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == ' ' {
                c
            } else {
                '_'
            }
        })
        .collect();
    match (numeric, name.trim().is_empty()) {
        (true, false) => format!("{}_{}_assignsubmission_file_", name.trim(), student.id),
        (true, true) => format!("Participant_{}_assignsubmission_file_", student.id),
        (false, _) => student.id.clone(),
    }
}

fn copy_sources(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).map_err(|e| Error::io(to, "cannot create", e))?;
    let entries = std::fs::read_dir(from).map_err(|e| Error::io(from, "cannot read", e))?;
    for entry in entries.flatten() {
        let target = to.join(entry.file_name());
        std::fs::copy(entry.path(), &target).map_err(|e| Error::io(&target, "cannot write", e))?;
    }
    Ok(())
}

/// The progress line in the handout's order of its stages (spheres, planes or shading...,
/// as `check` prints it), not the alphabetical order of the result's keys.
fn progress_line(stages: &serde_json::Map<String, Value>, course: Course) -> String {
    let order = Stage::of(course);
    let rank = |key: &str| {
        order
            .iter()
            .position(|s| s.key(course) == key)
            .unwrap_or(order.len())
    };
    let mut keys: Vec<&String> = stages.keys().collect();
    keys.sort_by_key(|k| rank(k));
    let parts: Vec<String> = keys
        .iter()
        .map(|k| format!("{k} {}", stages[k.as_str()].as_str().unwrap_or("")))
        .collect();
    format!("progress: {}", parts.join("; "))
}

/// The one student's folder under `outdir/students`.
pub fn graded_student(outdir: &Path) -> Result<PathBuf> {
    let students = outdir.join("students");
    std::fs::read_dir(&students)
        .map_err(|e| Error::io(&students, "cannot read", e))?
        .flatten()
        .map(|e| e.path())
        .find(|p| p.join("result.json").is_file())
        .ok_or_else(|| Error::Environment(format!("{}: no result was written", students.display())))
}

/// The outcome `result.json` and `report.html` in `dir` say.
fn outcome(dir: &Path, course: Course) -> Result<Outcome> {
    let read = |name: &str| {
        let path = dir.join(name);
        std::fs::read(&path).map_err(|e| Error::io(&path, "cannot read", e))
    };
    let result: Value = serde_json::from_slice(&read("result.json")?)
        .map_err(|e| Error::Environment(format!("{}: {e}", dir.display())))?;
    let report = String::from_utf8_lossy(&read("report.html")?).into_owned();
    let extra = &result["extra_data"];
    let (passed, cases) = (extra["passed"].as_u64(), extra["cases"].as_u64());
    let status = extra["status"].as_str().unwrap_or("error");
    let verdict = match (passed, cases) {
        (Some(p), Some(c)) if c > 0 => format!("{p} of {c} cases pass ({status})"),
        _ => status.to_string(),
    };
    let progress = extra["progress"]
        .as_object()
        .map(|stages| progress_line(stages, course))
        .unwrap_or_default();
    Ok(Outcome {
        passed: extra["grade"].as_f64().is_some_and(|g| g >= 100.0),
        verdict,
        mistake: extra["diagnosis"][0].as_str().map(str::to_string),
        finding: super::images::for_the_web(extra["feedback"].as_str().unwrap_or("")),
        progress,
        report: serde_json::to_string(&[report]).unwrap_or_default(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn student(id: &str, name: &str) -> Student {
        Student {
            number: 1,
            id: id.into(),
            name: name.into(),
            email: String::new(),
            secret: None,
            csrf: String::new(),
        }
    }

    #[test]
    fn progress_follows_the_handout() {
        let stages: serde_json::Map<String, Value> = serde_json::from_str(
            r#"{"planes": "done", "reflection": "not written yet", "shading": "done",
                "shadows": "done", "spheres": "done"}"#,
        )
        .expect("json");
        assert_eq!(
            progress_line(&stages, Course::Y2023),
            "progress: spheres done; shading done; planes done; shadows done; \
             reflection not written yet"
        );
    }

    #[test]
    fn the_folder_is_moodles_shape_for_a_numeric_id_and_the_id_otherwise() {
        assert_eq!(
            moodle_folder(&student("1201", "Ada Lovelace")),
            "Ada Lovelace_1201_assignsubmission_file_"
        );
        assert_eq!(
            moodle_folder(&student("1202", "")),
            "Participant_1202_assignsubmission_file_"
        );
        assert_eq!(moodle_folder(&student("ab123", "A/B")), "ab123");
    }
}
