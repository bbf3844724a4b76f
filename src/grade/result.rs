//! A student's `result.json`: Gradescope's `results.json` shape (`score`, `output`, `tests[]`
//! with `name`, `score`, `max_score`, `status`, `output`, `tags`), so that it can be uploaded
//! as it is, with whitted's own findings under `extra_data` (Gradescope's place for them).
//! The class files are made from these alone, so a rerun, a Slurm aggregation or a second
//! look reads the same facts.

use serde_json::{json, Value};

use super::intake::Submission;
use super::student::Outcome;
use crate::check::json::suite_json;
use crate::check::program::{CaseOutcome, Status, SuiteRun};
use crate::check::summary;
use crate::mistakes::{Bug, Mistakes};

/// How the grade is given (`--grade`), out of 100.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Grading {
    /// 100 when every case passes, else 0.
    PassFail,
    /// The share of cases passed.
    Fraction,
}

impl Grading {
    pub fn grade(self, passed: usize, cases: usize) -> f64 {
        match self {
            Grading::PassFail if cases > 0 && passed == cases => 100.0,
            Grading::PassFail => 0.0,
            Grading::Fraction if cases > 0 => {
                (10000.0 * passed as f64 / cases as f64).round() / 100.0
            }
            Grading::Fraction => 0.0,
        }
    }
}

/// What the class files need of one student, read back from `extra_data`.
#[derive(Debug, Clone)]
pub struct Row {
    pub id: String,
    pub name: String,
    /// `graded`, `compile-error`, `no-files` or `error`.
    pub status: String,
    pub passed: usize,
    pub cases: usize,
    /// Per case: its name and whether it passed.
    pub case_passes: Vec<(String, bool)>,
    /// The top diagnosis' entries, when it explains the images well.
    pub diagnosis: Vec<String>,
    pub grade: f64,
    pub feedback: String,
    /// Whether `--rerun failed` runs it again (an error or a timeout).
    pub failed: bool,
    pub key: String,
}

/// The result of `submission` graded to `outcome`, under `key`.
pub fn build(
    submission: &Submission,
    outcome: &Outcome,
    key: &str,
    grading: Grading,
    sandboxed: bool,
    skeleton: &str,
) -> Value {
    let mut extra = json!({
        "whitted": env!("CARGO_PKG_VERSION"),
        "skeleton": skeleton,
        "key": key,
        "id": submission.id,
        "name": submission.name,
        "sandbox": sandboxed,
        "notes": submission.notes,
    });
    let (status, tests, passed, cases, feedback, failed) = match outcome {
        Outcome::Refused { status, message } => (
            *status,
            Vec::new(),
            0,
            0,
            message.clone(),
            *status == "error",
        ),
        Outcome::CompileError(messages) => {
            extra["compile_errors"] = json!(messages);
            let first = messages.lines().next().unwrap_or("javac failed");
            (
                "compile-error",
                Vec::new(),
                0,
                0,
                format!("does not compile: {first}"),
                false,
            )
        }
        Outcome::CompileTimeout => (
            "error",
            Vec::new(),
            0,
            0,
            "javac did not finish within the time limit".to_string(),
            true,
        ),
        Outcome::Ran(run) => {
            let tests: Vec<Value> = run.cases.iter().map(test).collect();
            let passed = run.cases.iter().filter(|c| c.passed()).count();
            let timed_out = run
                .cases
                .iter()
                .any(|c| matches!(c.status, Status::Timeout(_)));
            let check = suite_json(run, None);
            extra["diagnosis"] = json!(diagnosis_ids(run));
            extra["progress"] = check["progress"].clone();
            extra["check"] = check;
            let feedback = feedback(run, passed);
            (
                "graded",
                tests,
                passed,
                run.cases.len(),
                feedback,
                timed_out,
            )
        }
    };
    let grade = grading.grade(passed, cases);
    extra["status"] = json!(status);
    extra["passed"] = json!(passed);
    extra["cases"] = json!(cases);
    extra["grade"] = json!(grade);
    extra["feedback"] = json!(feedback);
    extra["failed"] = json!(failed);
    if !extra.get("diagnosis").is_some_and(Value::is_array) {
        extra["diagnosis"] = json!([]);
    }
    let mut output = feedback.clone();
    if !sandboxed {
        output += "\n(graded with --no-sandbox: the program ran unconfined)";
    }
    json!({
        "score": grade,
        "output": output,
        "tests": tests,
        "extra_data": extra,
    })
}

/// One case as a Gradescope test.
fn test(case: &CaseOutcome) -> Value {
    let passed = case.passed();
    let (output, tags) = match &case.status {
        Status::Ok(report) => {
            let d = &report.difference;
            let mut line = d.verdict.name().to_string();
            if !passed {
                line = format!("{line}: {}", summary::difference_sentence(d));
            }
            let shown = report
                .diagnosis
                .first()
                .map(|t| t.mistakes)
                .unwrap_or(report.hidden_mistakes);
            if !shown.is_empty() {
                line += &format!("; looks like {}", shown.name());
            }
            (line, shown.ids())
        }
        other => (status_line(other, &case.stderr_tail), Vec::new()),
    };
    json!({
        "name": case.name,
        "score": if passed { 1 } else { 0 },
        "max_score": 1,
        "status": if passed { "passed" } else { "failed" },
        "output": output,
        "tags": tags,
    })
}

/// A case that wrote no image to check: how it ended, and the end of its standard error.
fn status_line(status: &Status, tail: &str) -> String {
    let what = status.failure_line().unwrap_or_else(|| "ok".into());
    match tail.lines().last() {
        Some(last) if !last.trim().is_empty() => format!("{what}\n{tail}"),
        _ => what,
    }
}

/// The entries the class page counts for this student: the top diagnosis, when it explains
/// the images well (a weak one is not a finding to count).
fn diagnosis_ids(run: &SuiteRun) -> Vec<&'static str> {
    let findings = &run.findings;
    if findings.weak() {
        return Vec::new();
    }
    findings
        .diagnosis
        .first()
        .map_or_else(Vec::new, |d| d.mistakes.ids())
}

/// The one line sent back to Moodle: how many cases pass, and the mistake with its fix.
fn feedback(run: &SuiteRun, passed: usize) -> String {
    let cases = run.cases.len();
    if passed == cases {
        let hidden: Mistakes = run
            .cases
            .iter()
            .filter_map(|c| match &c.status {
                Status::Ok(r) => Some(r.hidden_mistakes),
                _ => None,
            })
            .fold(Mistakes::NONE, |all, m| {
                m.bugs().into_iter().fold(all, Mistakes::with)
            });
        return match hidden.is_empty() {
            true => format!("passes all {cases} cases"),
            false => format!(
                "passes all {cases} cases, but renders exactly what {} renders: fix it all the same",
                hidden.name()
            ),
        };
    }
    let mut line = format!("passes {passed} of {cases} cases");
    let findings = &run.findings;
    match findings.diagnosis.first() {
        Some(top) if !findings.weak() => {
            let bugs: Vec<Bug> = top.mistakes.bugs();
            let said: Vec<String> = bugs
                .iter()
                .map(|b| format!("{} ({}; {})", b.id(), b.description(), b.advice()[1]))
                .collect();
            line += &format!("; looks like {}", said.join(" and "));
        }
        _ => line += &format!("; {}", findings.progress.sentence()),
    }
    line
}

/// The row of a `result.json`, or None for one that is not whitted's.
pub fn row(result: &Value) -> Option<Row> {
    let extra = result.get("extra_data")?;
    let text = |k: &str| extra.get(k).and_then(Value::as_str).map(str::to_string);
    let count = |k: &str| extra.get(k).and_then(Value::as_u64).unwrap_or(0) as usize;
    let case_passes = result
        .get("tests")
        .and_then(Value::as_array)
        .map(|tests| {
            tests
                .iter()
                .map(|t| {
                    let name = t.get("name").and_then(Value::as_str).unwrap_or("");
                    (
                        name.to_string(),
                        t.get("status").and_then(Value::as_str) == Some("passed"),
                    )
                })
                .collect()
        })
        .unwrap_or_default();
    Some(Row {
        id: text("id")?,
        name: text("name").unwrap_or_default(),
        status: text("status")?,
        passed: count("passed"),
        cases: count("cases"),
        case_passes,
        diagnosis: extra
            .get("diagnosis")
            .and_then(Value::as_array)
            .map(|a| {
                a.iter()
                    .filter_map(Value::as_str)
                    .map(str::to_string)
                    .collect()
            })
            .unwrap_or_default(),
        grade: extra.get("grade").and_then(Value::as_f64).unwrap_or(0.0),
        feedback: text("feedback").unwrap_or_default(),
        failed: extra.get("failed").and_then(Value::as_bool).unwrap_or(true),
        key: text("key").unwrap_or_default(),
    })
}
