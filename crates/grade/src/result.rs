//! A student's `result.json`: Gradescope's `results.json` shape (`score`, `output`, `tests[]`
//! with `name`, `score`, `max_score`, `status`, `output`, `tags`), so that it can be uploaded
//! as it is, with whitted's own findings under `extra_data` (Gradescope's place for them).
//! The class files are made from these alone, so a rerun, a Slurm aggregation or a second
//! look reads the same facts.

use serde_json::{json, Value};

use super::intake::Submission;
use super::policy::Policy;
use super::student::Outcome;
use whitted_check::check::json::suite_json;
use whitted_check::check::program::{CaseOutcome, Status, SuiteRun};
use whitted_check::check::suite::Role;
use whitted_check::check::summary;
use whitted_check::mistakes::{Bug, Mistakes};

/// What the class files need of one student, read back from `extra_data`.
#[derive(Debug, Clone)]
pub struct Row {
    pub id: String,
    pub name: String,
    /// The folder the submission came in (Moodle's), where its feedback goes back to.
    pub folder: String,
    /// Its two files' fingerprint, comments and whitespace aside (`similar.rs`); empty when
    /// there were no files.
    pub fingerprint: String,
    /// `graded`, `compile-error`, `no-files` or `error`.
    pub status: String,
    /// Counted cases passed, of how many counted.
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
    policy: &Policy,
    sandboxed: bool,
    skeleton: &str,
    show_hidden: bool,
) -> Value {
    let mut extra = json!({
        "whitted": env!("CARGO_PKG_VERSION"),
        "skeleton": skeleton,
        "policy": policy.describe(),
        "tolerance": policy.tolerance,
        "key": key,
        "id": submission.id,
        "name": submission.name,
        "folder": submission.folder,
        "sandbox": sandboxed,
        "notes": submission.notes,
        "warnings": submission.warnings,
    });
    if let Ok(files) = &submission.files {
        extra["fingerprint"] = json!(super::similar::fingerprint(files));
    }
    let counted = (0..policy.weights.len())
        .filter(|&i| policy.counts(i))
        .count();
    let (status, tests, passes, feedback, failed) = match outcome {
        Outcome::Refused { status, message } => (
            *status,
            Vec::new(),
            Vec::new(),
            message.clone(),
            *status == "error",
        ),
        Outcome::CompileError(messages) => {
            extra["compile_errors"] = json!(messages);
            let first = messages.lines().next().unwrap_or("javac failed");
            (
                "compile-error",
                Vec::new(),
                Vec::new(),
                format!("does not compile: {first}"),
                false,
            )
        }
        Outcome::CompileTimeout => (
            "error",
            Vec::new(),
            Vec::new(),
            "javac did not finish within the time limit".to_string(),
            true,
        ),
        Outcome::Ran(run) => {
            let tests: Vec<Value> = run
                .cases
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    test(
                        c,
                        policy.weights.get(i).copied().unwrap_or(0.0),
                        show_hidden,
                    )
                })
                .collect();
            let passes: Vec<bool> = run.cases.iter().map(|c| c.passed()).collect();
            let timed_out = run
                .cases
                .iter()
                .any(|c| matches!(c.status, Status::Timeout(_)));
            let mut check = suite_json(run, None);
            if !show_hidden {
                withhold_hidden(&mut check, run);
            }
            extra["diagnosis"] = json!(diagnosis_ids(run));
            extra["progress"] = check["progress"].clone();
            extra["check"] = check;
            let feedback = feedback(run, policy);
            ("graded", tests, passes, feedback, timed_out)
        }
    };
    let grade = policy.grade(&passes);
    let passed = (0..passes.len())
        .filter(|&i| passes[i] && policy.counts(i))
        .count();
    let cases = if passes.is_empty() { 0 } else { counted };
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

/// One case as a Gradescope test, worth `weight` (0: it informs, scores nothing). A hidden
/// case says its verdict only, unless `show_hidden`.
fn test(case: &CaseOutcome, weight: f64, show_hidden: bool) -> Value {
    let passed = case.passed();
    let hidden = case.case.role == Role::Hidden && !show_hidden;
    let (output, tags) = match &case.status {
        _ if hidden => (verdict(case), Vec::new()),
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
    let output = match weight > 0.0 {
        true => output,
        false => format!("{output}\n(whitted's diagnostic scene: it informs, it is not graded)"),
    };
    json!({
        "name": case.name,
        "score": if passed { weight } else { 0.0 },
        "max_score": weight,
        "status": if passed { "passed" } else { "failed" },
        "output": output,
        "tags": tags,
    })
}

/// The check's JSON with each hidden case cut to its name, status and verdict: no scene, no
/// reference, no commands that would reveal it.
fn withhold_hidden(check: &mut Value, run: &SuiteRun) {
    let Some(cases) = check.get_mut("cases").and_then(Value::as_array_mut) else {
        return;
    };
    for (json, case) in cases.iter_mut().zip(&run.cases) {
        if case.case.role == Role::Hidden {
            *json = json!({
                "case": case.name,
                "status": case.status.name(),
                "verdict": verdict(case),
                "hidden": true,
            });
        }
    }
}

/// A case's verdict alone: `identical`, `differs`, `timeout`, ...
pub fn verdict(case: &CaseOutcome) -> String {
    match &case.status {
        Status::Ok(report) => report.difference.verdict.name().to_string(),
        other => other.name().to_string(),
    }
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

/// The one line sent back to Moodle: how many counted cases pass, and the mistake with its fix
/// (found over every case, the diagnostic ones too).
fn feedback(run: &SuiteRun, policy: &Policy) -> String {
    let counted: Vec<usize> = (0..run.cases.len()).filter(|&i| policy.counts(i)).collect();
    let cases = counted.len();
    let passed = counted.iter().filter(|&&i| run.cases[i].passed()).count();
    let all = run.cases.iter().all(|c| c.passed());
    if passed == cases && all {
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
            true => format!("passes all {cases} graded cases"),
            false => format!(
                "passes all {cases} graded cases, but renders exactly what {} renders: fix it \
                 all the same",
                hidden.name()
            ),
        };
    }
    let mut line = match passed == cases {
        true => format!(
            "passes all {cases} graded cases, but not every one of whitted's diagnostic scenes"
        ),
        false => format!("passes {passed} of {cases} graded cases"),
    };
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
        folder: text("folder").unwrap_or_default(),
        fingerprint: text("fingerprint").unwrap_or_default(),
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
