//! A project's run as a process of its own, `whitted serve run-attempt DIR`: what the service's
//! workers start on this machine, and what a Slurm job runs on a node (`--slurm`). The attempt's
//! folder carries everything between the two, so that nothing but the folder needs to be
//! shared with a node:
//! - `job.json`, written by the service: the year, the time limit, the student's id and name;
//! - `progress.json`, rewritten by the run at each step (compiling, case k of n, checking):
//!   what the attempt's live page shows;
//! - `outcome.json`, written by the run last, whole or not at all: the result, and the CPU
//!   time of everything the run started (`cpu.rs`).
//!
//! Its own process makes the CPU time countable (a cgroup of its own), keeps a crash of the
//! run from ending the service, and is the same run whether it is local or on the farm.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde_json::{json, Value};

use super::project::{self, Run};
use super::store::{Outcome, Student};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_grade::{Step, Watch};
use whitted_io::output::atomic::AtomicFile;

pub const JOB: &str = "job.json";
pub const PROGRESS: &str = "progress.json";
pub const OUTCOME: &str = "outcome.json";

/// What a run is asked: who, and how.
#[derive(Debug, Clone)]
pub struct Job {
    pub course: Course,
    pub seconds: u64,
    pub student: Student,
}

/// A finished run: its outcome and the CPU seconds of all it started (None: not measurable).
#[derive(Debug, Clone, PartialEq)]
pub struct Finished {
    pub outcome: Outcome,
    pub cpu: Option<f64>,
}

/// Prepares `dir` for a run of `job`: its job file, and no progress or outcome of an earlier
/// run (a run the service was killed in).
pub fn prepare(dir: &Path, job: &Job) -> Result<()> {
    for name in [PROGRESS, OUTCOME] {
        let path = dir.join(name);
        if path.exists() {
            std::fs::remove_file(&path).map_err(|e| Error::io(&path, "cannot remove", e))?;
        }
    }
    let text = json!({
        "course": job.course.name(),
        "seconds": job.seconds,
        "id": job.student.id,
        "name": job.student.name,
    });
    write_atomic(&dir.join(JOB), text.to_string().as_bytes())
}

/// `whitted serve run-attempt DIR`: runs the job in `dir` and writes its outcome. A failure of
/// the machine's (no JDK) is an outcome that says so; Err only when no outcome can be written.
pub fn run(dir: &Path) -> Result<()> {
    let job = read_job(dir)?;
    // A run the service started ends with it (a SIGKILL of the service leaves no run behind
    // to race the one its next start makes); under Slurm, with the job's step.
    let _ = rustix::process::set_parent_process_death_signal(Some(rustix::process::Signal::TERM));
    let account = super::cpu::Account::start();
    let progress = dir.join(PROGRESS);
    let watch = Watch(Arc::new(move |_: &str, step: Step| {
        // Progress is a courtesy: a write that fails loses a step, never the run.
        let _ = write_atomic(&progress, step_json(&step).to_string().as_bytes());
    }));
    let outcome = match project::run(
        dir,
        &job.student,
        Run::new(job.course, job.seconds),
        Some(watch),
    ) {
        Ok(outcome) => outcome,
        // Stopped by a signal (the service stopping, Slurm cancelling): no outcome, so that
        // the attempt runs again rather than be told it could not.
        Err(e @ Error::Interrupted { .. }) => return Err(e),
        Err(e) => not_run(&e),
    };
    let cpu = account.as_ref().and_then(super::cpu::Account::seconds);
    drop(account);
    write_atomic(&dir.join(OUTCOME), outcome_json(&outcome, cpu).as_bytes())
}

/// The outcome of a run the service could not make: said to the student as the service's.
pub fn not_run(e: &Error) -> Outcome {
    Outcome {
        passed: false,
        verdict: "not tested: the service could not run it".into(),
        mistake: None,
        finding: format!("The tester could not run this attempt: {e}. Tell the course staff."),
        progress: String::new(),
        report: "[]".into(),
    }
}

/// The run's outcome in `dir`, once it has written one.
pub fn finished(dir: &Path) -> Option<Finished> {
    let text = std::fs::read(dir.join(OUTCOME)).ok()?;
    let v: Value = serde_json::from_slice(&text).ok()?;
    let text = |key: &str| v[key].as_str().map(str::to_string);
    Some(Finished {
        outcome: Outcome {
            passed: v["passed"].as_bool()?,
            verdict: text("verdict")?,
            mistake: text("mistake"),
            finding: text("finding")?,
            progress: text("progress")?,
            report: text("report")?,
        },
        cpu: v["cpu_seconds"].as_f64(),
    })
}

/// The step the run in `dir` last said it is at.
pub fn progress(dir: &Path) -> Option<Value> {
    serde_json::from_slice(&std::fs::read(dir.join(PROGRESS)).ok()?).ok()
}

/// A step as the attempt's status gives it to the page.
pub fn step_json(step: &Step) -> Value {
    match step {
        Step::Compiling => json!({ "step": "compiling" }),
        Step::Running { case, index, of } => {
            json!({ "step": "running", "case": case, "index": index, "of": of })
        }
        Step::Checking { case, index, of } => {
            json!({ "step": "checking", "case": case, "index": index, "of": of })
        }
    }
}

fn outcome_json(outcome: &Outcome, cpu: Option<f64>) -> String {
    json!({
        "passed": outcome.passed,
        "verdict": outcome.verdict,
        "mistake": outcome.mistake,
        "finding": outcome.finding,
        "progress": outcome.progress,
        "report": outcome.report,
        "cpu_seconds": cpu,
    })
    .to_string()
}

fn read_job(dir: &Path) -> Result<Job> {
    let path = dir.join(JOB);
    let bad = |why: String| Error::Usage(format!("{}: {why}", path.display()));
    let text = std::fs::read(&path).map_err(|e| Error::io(&path, "cannot read", e))?;
    let v: Value = serde_json::from_slice(&text).map_err(|e| bad(e.to_string()))?;
    let course = v["course"]
        .as_str()
        .and_then(Course::from_name)
        .ok_or_else(|| bad("no course year in it".into()))?;
    let text = |key: &str| v[key].as_str().unwrap_or("").to_string();
    Ok(Job {
        course,
        seconds: v["seconds"]
            .as_u64()
            .ok_or_else(|| bad("no time limit in it".into()))?,
        student: Student {
            number: 0,
            id: text("id"),
            name: text("name"),
            email: String::new(),
            secret: None,
            csrf: String::new(),
        },
    })
}

fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut file = AtomicFile::create(path)?;
    file.file()
        .write_all(bytes)
        .map_err(|e| Error::io(path, "cannot write", e))?;
    file.commit()
}

/// The command that runs the job in `dir`: this very binary, `serve run-attempt DIR`.
pub fn command_line(dir: &Path) -> Result<(PathBuf, Vec<String>)> {
    let me = std::env::current_exe()
        .map_err(|e| Error::Environment(format!("cannot find whitted's own binary: {e}")))?;
    Ok((
        me,
        vec![
            "serve".into(),
            "run-attempt".into(),
            dir.display().to_string(),
        ],
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_outcome_and_its_cpu_time_come_back_as_written() {
        let dir = tempfile::tempdir().expect("dir");
        let outcome = Outcome {
            passed: true,
            verdict: "5 of 5 cases pass (graded)".into(),
            mistake: Some("no-shadows".into()),
            finding: "f".into(),
            progress: "p".into(),
            report: "[\"<html>\"]".into(),
        };
        assert_eq!(finished(dir.path()), None);
        write_atomic(
            &dir.path().join(OUTCOME),
            outcome_json(&outcome, Some(6.5)).as_bytes(),
        )
        .expect("written");
        assert_eq!(
            finished(dir.path()),
            Some(Finished {
                outcome: outcome.clone(),
                cpu: Some(6.5)
            })
        );
        let job = Job {
            course: Course::Y2016,
            seconds: 60,
            student: Student {
                number: 0,
                id: "1201".into(),
                name: "Ada".into(),
                email: String::new(),
                secret: None,
                csrf: String::new(),
            },
        };
        prepare(dir.path(), &job).expect("prepared");
        assert_eq!(finished(dir.path()), None, "an earlier outcome is gone");
        let read = read_job(dir.path()).expect("read");
        assert_eq!((read.course, read.seconds), (Course::Y2016, 60));
        assert_eq!(read.student.id, "1201");
        let step = step_json(&Step::Running {
            case: "tick2.xml -b 2".into(),
            index: 3,
            of: 5,
        });
        assert_eq!(step["case"], "tick2.xml -b 2");
        assert_eq!(
            (step["index"].as_u64(), step["of"].as_u64()),
            (Some(3), Some(5))
        );
    }
}
