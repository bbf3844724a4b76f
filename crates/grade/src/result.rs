//! A student's `result.json`: Gradescope's `results.json` shape (`score`, `output`, `tests[]`
//! with `name`, `score`, `max_score`, `status`, `output`, `tags`), so that it can be uploaded
//! as it is, with whitted's own findings under `extra_data` (Gradescope's place for them).
//! The class files are made from these alone, so a rerun, a Slurm aggregation or a second
//! look reads the same facts.

use serde::{Deserialize, Serialize};
use serde_json::{json, Value};

use super::beyond::CaseBeyond;
use super::intake::Submission;
use super::policy::Policy;
use super::status::StudentStatus;
use super::student::Outcome;
use whitted_check::check::print::json::suite_json;
use whitted_check::check::program::{CaseOutcome, RunStatus, SuiteRun};
use whitted_check::check::suite::Role;
use whitted_check::check::words;
use whitted_check::mistakes::{Bug, Mistakes};

/// A student's `result.json`: Gradescope's `results.json`. Fields are in the order of their
/// names, the order the file has always had.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StudentResult {
    /// whitted's own findings, where Gradescope keeps a tool's data.
    #[serde(rename = "extra_data")]
    pub extra: Extra,
    pub output: String,
    pub score: f64,
    pub tests: Vec<Test>,
}

/// One case, as a Gradescope test.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Test {
    pub max_score: f64,
    pub name: String,
    pub output: String,
    pub score: f64,
    pub status: TestStatus,
    pub tags: Vec<String>,
}

/// Gradescope's verdict on a test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TestStatus {
    Passed,
    Failed,
}

/// `extra_data`: what the class files read, and what a second look needs.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Extra {
    /// `--max-beyond`: the pixels a case may have beyond the tolerance (`10`, `0.1%`); results
    /// written before there was one allowed none.
    #[serde(default = "no_allowance")]
    pub allowance: String,
    /// Per case (in the order of `tests`), the counts that replay the pass rule at another
    /// tolerance and allowance (`beyond.rs`), when the program ran; results written before
    /// there were any have none, and `--calibrate` skips them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beyond: Option<Vec<CaseBeyond>>,
    /// Counted cases, 0 when none ran.
    pub cases: usize,
    /// `check --json`'s report of the suite (hidden cases cut unless shown), when it ran.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<Value>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compile_errors: Option<String>,
    /// The top diagnosis' entries, when it explains the images well.
    pub diagnosis: Vec<String>,
    /// Whether `--rerun failed` runs it again (an error or a timeout).
    pub failed: bool,
    /// The one line sent back to Moodle.
    pub feedback: String,
    /// Their two files' fingerprint, comments and whitespace aside (`similar.rs`), when there
    /// were files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fingerprint: Option<String>,
    /// The folder the submission came in (Moodle's), where its feedback goes back to.
    pub folder: String,
    pub grade: f64,
    pub id: String,
    /// The hash of what decided this result (`key` in lib.rs).
    pub key: String,
    pub name: String,
    pub notes: Vec<String>,
    /// Counted cases passed.
    pub passed: usize,
    pub policy: String,
    /// The stages of the handout the program has reached, when it ran.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub progress: Option<Value>,
    pub sandbox: bool,
    pub skeleton: String,
    pub status: StudentStatus,
    pub tolerance: u8,
    pub warnings: Vec<String>,
    /// The version of whitted that graded it.
    pub whitted: String,
}

/// The allowance of a result written before there was one.
fn no_allowance() -> String {
    "0".into()
}

impl StudentResult {
    /// The row of a student who has no result (yet): `not-graded`, with no grade of theirs
    /// written anywhere (`grade_cell`); any run without `--only` grades them.
    pub fn not_graded(submission: &Submission) -> StudentResult {
        StudentResult {
            extra: Extra {
                allowance: no_allowance(),
                beyond: None,
                cases: 0,
                check: None,
                compile_errors: None,
                diagnosis: Vec::new(),
                failed: true,
                feedback: String::new(),
                fingerprint: None,
                folder: submission.folder.clone(),
                grade: 0.0,
                id: submission.id.clone(),
                key: String::new(),
                name: submission.name.clone(),
                notes: Vec::new(),
                passed: 0,
                policy: String::new(),
                progress: None,
                sandbox: false,
                skeleton: String::new(),
                status: StudentStatus::NotGraded,
                tolerance: 0,
                warnings: Vec::new(),
                whitted: String::new(),
            },
            output: String::new(),
            score: 0.0,
            tests: Vec::new(),
        }
    }

    /// Whether a grade was given: false for a student this run and those before it did not
    /// grade, whose grade cells are left blank (as Moodle's own worksheet has them) so that
    /// an upload leaves their grade as it is, never 0.
    pub fn is_graded(&self) -> bool {
        self.extra.status != StudentStatus::NotGraded
    }

    /// Per case: its name and whether it passed.
    pub fn case_passes(&self) -> impl Iterator<Item = (&str, bool)> {
        self.tests
            .iter()
            .map(|t| (t.name.as_str(), t.status == TestStatus::Passed))
    }

    /// Reads a `result.json`; None for one that is not whitted's (or not this shape).
    pub fn parse(bytes: &[u8]) -> Option<StudentResult> {
        serde_json::from_slice(bytes).ok()
    }

    /// The file's text.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
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
) -> StudentResult {
    let counted = (0..policy.weights.len())
        .filter(|&i| policy.counts(i))
        .count();
    let mut check = None;
    let mut progress = None;
    let mut compile_errors = None;
    let mut diagnosis = Vec::new();
    let mut beyond = None;
    let (status, tests, passes, feedback, failed) = match outcome {
        Outcome::Refused { status, message } => (
            *status,
            Vec::new(),
            Vec::new(),
            message.clone(),
            *status == StudentStatus::Error,
        ),
        Outcome::CompileError(messages) => {
            compile_errors = Some(messages.clone());
            let first = messages.lines().next().unwrap_or("javac failed");
            (
                StudentStatus::CompileError,
                Vec::new(),
                Vec::new(),
                format!("does not compile: {first}"),
                false,
            )
        }
        Outcome::CompileTimeout => (
            StudentStatus::Error,
            Vec::new(),
            Vec::new(),
            "javac did not finish within the time limit".to_string(),
            true,
        ),
        Outcome::Ran(run) => {
            // A Tick 1* run's two options are judged, each worth the same; the suite's
            // weights are not theirs.
            let weight = |i: usize| match is_star(run) {
                true => 1.0,
                false => policy.weights.get(i).copied().unwrap_or(0.0),
            };
            let tests: Vec<Test> = run
                .cases
                .iter()
                .enumerate()
                .map(|(i, c)| test(c, weight(i), show_hidden))
                .collect();
            let passes: Vec<bool> = run.cases.iter().map(|c| c.passed()).collect();
            let timed_out = run
                .cases
                .iter()
                .any(|c| matches!(c.status, RunStatus::Timeout(_)));
            let mut report = suite_json(run, None);
            if !show_hidden {
                withhold_hidden(&mut report, run);
            }
            diagnosis = diagnosis_ids(run).into_iter().map(String::from).collect();
            progress = Some(report["progress"].clone());
            check = Some(report);
            beyond = Some(run.cases.iter().map(CaseBeyond::of).collect());
            let mut feedback = feedback(run, policy);
            if let Some(completed) = completed(submission) {
                feedback = format!("{feedback} {}", super::finished::feedback(completed));
            }
            (StudentStatus::Graded, tests, passes, feedback, timed_out)
        }
    };
    let star = matches!(outcome, Outcome::Ran(run) if is_star(run));
    // Tick 1* passes or not as a whole, as a ticker judges it: one option done well is enough.
    let (grade, passed, cases) = match star {
        true => (
            if passes.iter().all(|p| *p) {
                100.0
            } else {
                0.0
            },
            passes.iter().filter(|p| **p).count(),
            passes.len(),
        ),
        false => (
            policy.grade(&passes),
            (0..passes.len())
                .filter(|&i| passes[i] && policy.counts(i))
                .count(),
            if passes.is_empty() { 0 } else { counted },
        ),
    };
    let mut output = feedback.clone();
    if !sandboxed {
        output += "\n(graded with --no-sandbox: the program ran unconfined)";
    }
    StudentResult {
        extra: Extra {
            allowance: policy.rule.allowance.to_string(),
            beyond,
            cases,
            check,
            compile_errors,
            diagnosis,
            failed,
            feedback,
            fingerprint: submission
                .files
                .as_ref()
                .ok()
                .map(super::similar::fingerprint),
            folder: submission.folder.clone(),
            grade,
            id: submission.id.clone(),
            key: key.to_string(),
            name: submission.name.clone(),
            notes: submission.notes.clone(),
            passed,
            policy: policy.describe(),
            progress,
            sandbox: sandboxed,
            skeleton: skeleton.to_string(),
            status,
            tolerance: policy.rule.tolerance,
            warnings: submission.warnings.clone(),
            whitted: env!("CARGO_PKG_VERSION").to_string(),
        },
        output,
        score: grade,
        tests,
    }
}

/// One case as a Gradescope test, worth `weight` (0: it informs, scores nothing). A hidden
/// case says its verdict only, unless `show_hidden`.
fn test(case: &CaseOutcome, weight: f64, show_hidden: bool) -> Test {
    let passed = case.passed();
    let hidden = case.case.role == Role::Hidden && !show_hidden;
    let (output, tags) = match &case.status {
        _ if hidden => (verdict(case), Vec::new()),
        RunStatus::Ok(report) => {
            let tags = report.shown_mistakes().ids();
            (
                words::test_line(report),
                tags.into_iter().map(String::from).collect(),
            )
        }
        other => (status_line(other, &case.stderr_tail), Vec::new()),
    };
    let output = match weight > 0.0 {
        true => output,
        false => format!("{output}\n(whitted's diagnostic scene: it informs, it is not graded)"),
    };
    Test {
        max_score: weight,
        name: case.name.to_string(),
        output,
        score: if passed { weight } else { 0.0 },
        status: if passed {
            TestStatus::Passed
        } else {
            TestStatus::Failed
        },
        tags,
    }
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
        RunStatus::Ok(report) => report.difference.verdict.name().to_string(),
        other => other.name().to_string(),
    }
}

/// A case that wrote no image to check: how it ended, and the end of its standard error.
fn status_line(status: &RunStatus, tail: &str) -> String {
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

/// The files a one-file Tick 1* hand-in lacked, which whitted's finished Tick 1 supplied.
pub fn completed(submission: &Submission) -> Option<&[&'static str]> {
    let files = submission.files.as_ref().ok()?;
    (!files.completed.is_empty()).then_some(files.completed.as_slice())
}

/// Whether `run` is a Tick 1* program's run of its options' handout scenes (`star_run.rs`),
/// not of the suite.
pub fn is_star(run: &SuiteRun) -> bool {
    run.findings
        .tick1_star
        .as_ref()
        .is_some_and(|t| t.plan.is_some())
}

/// A Tick 1* run's line: which options were done and how each was judged.
fn star_feedback(run: &SuiteRun) -> String {
    let verdict = match run.passed() {
        true => "Tick 1* accepted",
        false => "Tick 1* not accepted",
    };
    let options: Vec<String> = run
        .cases
        .iter()
        .map(|c| match &c.status {
            RunStatus::Star(s) => format!("{}: {}", s.option.what(), s.verdict.line()),
            other => format!(
                "{}: {}",
                c.name,
                other.failure_line().unwrap_or_else(|| other.name().into())
            ),
        })
        .collect();
    format!(
        "{verdict} (judged by option, not by the Tick 1 suite). {}",
        options.join("; ")
    )
}

/// The one line sent back to Moodle: how many counted cases pass, and the mistake with its fix
/// (found over every case, the diagnostic ones too); a Tick 1* run's options.
fn feedback(run: &SuiteRun, policy: &Policy) -> String {
    if is_star(run) {
        return star_feedback(run);
    }
    // A Tick 1* program stopped at its first case out of time: what it is, and what to do.
    let not_run = run.cases.iter().find_map(|c| match &c.status {
        RunStatus::NotRun(why) => Some(why),
        _ => None,
    });
    if let Some(why) = not_run {
        return format!("not auto-gradable: {why}");
    }
    let counted: Vec<usize> = (0..run.cases.len()).filter(|&i| policy.counts(i)).collect();
    let cases = counted.len();
    let passed = counted.iter().filter(|&&i| run.cases[i].passed()).count();
    let all = run.cases.iter().all(|c| c.passed());
    let allowed = by_allowance(run, &counted, policy);
    if passed == cases && all {
        let hidden: Mistakes = run
            .cases
            .iter()
            .filter_map(|c| match &c.status {
                RunStatus::Ok(r) => Some(r.hidden_mistakes),
                _ => None,
            })
            .fold(Mistakes::NONE, |all, m| {
                m.bugs().into_iter().fold(all, Mistakes::with)
            });
        return words::all_pass(cases, &allowed, hidden);
    }
    let mut line = match passed == cases {
        true => format!(
            "passes all {cases} graded cases{allowed}, but not every one of whitted's \
             diagnostic scenes"
        ),
        false => format!("passes {passed} of {cases} graded cases{allowed}"),
    };
    let findings = &run.findings;
    match findings.diagnosis.first() {
        Some(top) if !findings.weak() => {
            let bugs: Vec<Bug> = top.mistakes.bugs();
            let said: Vec<String> = bugs
                .iter()
                .map(|b| {
                    let course = top.course;
                    format!(
                        "{} ({}; {})",
                        b.id(),
                        b.description(course),
                        b.advice(course)[1]
                    )
                })
                .collect();
            line += &format!("; looks like {}", said.join(" and "));
        }
        _ => line += &format!("; {}", findings.progress.sentence()),
    }
    line
}

/// How many of the `counted` cases that pass do so only by the allowance, as words to follow
/// "passes N graded cases": " (2 of them only by the allowance: at most 10 pixels beyond ±2)";
/// empty when none does, so that a feedback never calls such a case simply right.
fn by_allowance(run: &SuiteRun, counted: &[usize], policy: &Policy) -> String {
    let n = counted
        .iter()
        .filter(|&&i| match &run.cases[i].status {
            RunStatus::Ok(report) => report.difference.allowed_words().is_some(),
            _ => false,
        })
        .count();
    match n {
        0 => String::new(),
        n => format!(
            " ({n} of them only by the allowance: {})",
            policy.rule.allowance_words()
        ),
    }
}
