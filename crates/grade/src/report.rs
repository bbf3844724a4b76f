//! What a student is sent: `report.html` (one file, images inline) and `report.png` (the
//! contact sheet `check --report` draws): their image, the reference and where they differ
//! for each failing case, the mistake in words with where and how to fix it, and how far
//! through the handout they are.

use super::compile::SHOWN_LINES;
use super::html::{escape, SharedImages, STYLE};
use super::intake::Submission;
use super::policy::Policy;
use super::student::Outcome;
use whitted_check::check::print::html::{case_block, findings_block};
use whitted_check::check::print::html_star::star_block;
use whitted_check::check::program::CaseOutcome;
use whitted_check::check::program::{RunStatus, SuiteRun};
use whitted_check::check::report::{contact_sheet, failing_rows, ReportRow};
use whitted_check::check::suite::Role;
use whitted_check::check::words;
use whitted_io::canvas::Canvas;
use whitted_io::output::png::PngImage;

/// What a report shows beyond the student's own findings: the policy it was graded under, and
/// whether hidden cases are shown in full.
pub struct Shown<'a> {
    pub hidden: bool,
    pub policy: &'a Policy,
    /// The run's encoded references.
    pub images: &'a SharedImages,
    /// The exercise's name (`Tick 2`, `Tick 1 (2021-22)`).
    pub tick: &'a str,
}

impl Shown<'_> {
    /// Whether `case` is shown by name and verdict only (a hidden scene, not `--show-hidden`).
    fn withheld(&self, case: &CaseOutcome) -> bool {
        case.case.role == Role::Hidden && !self.hidden
    }
}

/// The report page of `submission`, whose result says `feedback`.
pub fn page(
    submission: &Submission,
    outcome: &Outcome,
    feedback: &str,
    sandboxed: bool,
    shown: &Shown,
) -> String {
    let mut body = format!(
        "<h1>{}: {}</h1>\n<p class=\"feedback\">{}</p>\n",
        escape(shown.tick),
        escape(&submission.name),
        escape(feedback)
    );
    if !submission.warnings.is_empty() {
        body += "<h2>Warnings</h2>\n<ul class=\"warnings\">\n";
        for warning in &submission.warnings {
            body += &format!("<li>{}</li>\n", escape(warning));
        }
        body += "</ul>\n";
    }
    if !sandboxed {
        body += "<p><strong>Graded with --no-sandbox:</strong> the program ran unconfined.</p>\n";
    }
    match outcome {
        Outcome::Refused { message, .. } => {
            body += &format!("<p>{}</p>\n", escape(message));
        }
        Outcome::CompileError(messages) => {
            body += &format!(
                "<h2>javac's first messages (up to {SHOWN_LINES} lines)</h2>\n<pre>{}</pre>\n",
                escape(messages)
            );
        }
        Outcome::CompileTimeout => body += "<p>javac did not finish within the time limit.</p>\n",
        Outcome::Ran(run) => {
            body += &ran(run, shown, feedback, super::result::completed(submission))
        }
    }
    body += &format!(
        "<p class=\"policy\">Graded {}.</p>\n",
        escape(&policy_line(outcome, shown.policy))
    );
    if !submission.notes.is_empty() {
        body += "<h2>Notes on the submission</h2>\n<ul>\n";
        for note in &submission.notes {
            body += &format!("<li>{}</li>\n", escape(note));
        }
        body += "</ul>\n";
    }
    format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\">\
         <title>{} report: {}</title><style>{STYLE}</style></head><body>\n{body}</body></html>\n",
        escape(shown.tick),
        escape(&submission.name)
    )
}

/// The cases, the diagnosis with its fixes, and the progress.
/// The progress is said once: the feedback above holds it when no mistake explains the images.
/// `completed`: the files whitted's finished Tick 1 supplied to a one-file Tick 1* hand-in.
fn ran(
    run: &SuiteRun,
    shown: &Shown,
    feedback: &str,
    completed: Option<&[&'static str]>,
) -> String {
    let findings = &run.findings;
    let mut out = String::new();
    // A Tick 1* run's options' scenes say nothing of the Tick 1 stages: what was run instead.
    let progress = match findings.tick1_star.as_ref().filter(|t| t.plan.is_some()) {
        // A one-file hand-in says which files whitted's finished Tick 1 supplied.
        Some(star) => match completed {
            Some(completed) => star.sentence().replacen(
                &format!("({})", star.seen.why()),
                &format!("({}: {})", star.seen.why(), completed.join(", ")),
                1,
            ),
            None => star.sentence(),
        },
        None => findings.progress.sentence(),
    };
    if !feedback.contains(&progress) {
        out += &format!("<p>{}</p>\n", escape(&progress));
    }
    out += &findings_block(findings);
    out += "<h2>The cases</h2>\n<table><tr><th>case</th><th>result</th><th>counts</th></tr>\n";
    for (i, case) in run.cases.iter().enumerate() {
        let class = if case.passed() { "pass" } else { "fail" };
        let counts = match (&case.status, shown.policy.counts(i)) {
            (RunStatus::Star(_), _) => "judged by its option",
            (_, true) => "graded",
            (_, false) => "informs only",
        };
        let what = match &case.status {
            _ if shown.withheld(case) => super::result::verdict(case),
            RunStatus::Ok(r) => words::verdict(r),
            RunStatus::Star(s) => format!("{}: {}", s.option.what(), s.verdict.line()),
            other => other.name().to_string(),
        };
        out += &format!(
            "<tr><td>{}</td><td class=\"{class}\">{}</td><td>{counts}</td></tr>\n",
            escape(&case.name),
            escape(&what)
        );
    }
    out += "</table>\n";
    for case in run.cases.iter().filter(|c| !shown.withheld(c)) {
        match &case.status {
            RunStatus::Ok(r) if !case.passed() => out += &case_block(&case.name, r, shown.images),
            // A Tick 1* option's image, whatever its verdict, as `check --report` shows it.
            RunStatus::Star(star) => out += &star_block(&case.name, star),
            RunStatus::Ok(_) => {}
            _ if !case.stderr_tail.is_empty() => {
                out += &format!(
                    "<h2>{}: {}</h2>\n<pre>{}</pre>\n",
                    escape(&case.name),
                    case.status.name(),
                    escape(&case.stderr_tail)
                );
            }
            _ => {}
        }
    }
    out
}

/// The contact sheet of the failing cases and of every Tick 1* option's image (a random
/// draw, shown whatever its verdict); of the first case when every one passes; of the
/// feedback alone when nothing ran.
pub fn sheet(outcome: &Outcome, feedback: &str, shown: &Shown) -> PngImage {
    let Outcome::Ran(run) = outcome else {
        let mut caption = vec![feedback.to_string()];
        if let Outcome::CompileError(messages) = outcome {
            caption.extend(messages.lines().take(8).map(str::to_string));
        }
        return caption_only(caption);
    };
    // The hidden cases withheld: the rows of the others alone.
    let mut rows = failing_rows(run, |c| !shown.withheld(c));
    rows.extend(
        run.cases
            .iter()
            .filter(|c| !shown.withheld(c))
            .filter_map(|c| match &c.status {
                RunStatus::Star(star) => Some(ReportRow::of_star(&c.name, star)),
                _ => None,
            }),
    );
    if rows.is_empty() {
        rows.extend(run.cases.iter().filter(|c| !shown.withheld(c)).find_map(
            |c| match &c.status {
                RunStatus::Ok(case) => Some(ReportRow::of(&c.name, case, &run.findings)),
                _ => None,
            },
        ));
    }
    match rows.is_empty() {
        true => caption_only(vec![feedback.to_string()]),
        false => contact_sheet(&rows),
    }
}

/// A sheet of one row of blank tiles above `caption`: for a student with no image.
fn caption_only(caption: Vec<String>) -> PngImage {
    let blank = || Canvas::new(160, 120, [0; 3]);
    contact_sheet(&[ReportRow {
        caption,
        tiles: [blank(), blank(), blank()],
    }])
}

/// How the student was graded, in words: the suite's policy, or for a Tick 1* run (whose two
/// options' images are judged, not compared with the suite's references) Tick 1*'s own rule.
fn policy_line(outcome: &Outcome, policy: &Policy) -> String {
    match outcome {
        Outcome::Ran(run) if super::result::is_star(run) => STAR_POLICY.to_string(),
        _ => policy.describe(),
    }
}

/// Tick 1*'s rule (docs/grade.md, "Tick 1*"), as `result.rs` applies it.
const STAR_POLICY: &str = "as Tick 1*: each option's handout scene run once and its image \
     judged by its option, accepted (100) when every option's verdict passes (one option done \
     well and the other not done is enough), else 0; the Tick 1 suite's cases and tolerance do \
     not apply";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tick1_star_run_is_said_to_be_graded_by_its_options_not_the_suite() {
        let policy = Policy {
            grading: super::super::policy::Grading::PassFail,
            rule: whitted_check::check::pass_rule::PassRule::strict(2),
            weights: vec![1.0],
            source: "every case, 1 each".into(),
        };
        let star = Outcome::Ran(Box::new(SuiteRun {
            program: "java a.tick1star.Tick1".into(),
            cases: Vec::new(),
            findings: {
                let mut findings =
                    whitted_check::check::Findings::of_star(whitted_core::course::Course::Y2021);
                findings.tick1_star = Some(whitted_check::check::tick1_star::Tick1Star {
                    seen: whitted_check::check::tick1_star::StarSeen::Package,
                    timeout: 900,
                    stopped: false,
                    plan: Some("ran the options' scenes".into()),
                });
                findings
            },
        }));
        let said = policy_line(&star, &policy);
        assert!(said.starts_with("as Tick 1*"), "{said}");
        assert!(said.ends_with("cases and tolerance do not apply"), "{said}");
        let refused = Outcome::CompileTimeout;
        assert_eq!(policy_line(&refused, &policy), policy.describe());
    }
}
