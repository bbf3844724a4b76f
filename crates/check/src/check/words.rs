//! The check's words: every sentence about a case that a student or a teacher reads (the text
//! report, `--report`'s captions, the viewer's lines, a graded student's Gradescope tests,
//! report page and Moodle feedback) is made here, so that the same finding reads the same
//! everywhere. The opening lines and the fits beyond the catalogue are `summary.rs`'s.

use super::summary;
use super::CaseReport;
use crate::mistakes::Mistakes;
use whitted_core::numbers::plain;

impl CaseReport {
    /// The mistakes this case shows: the top of its diagnosis, or what it renders exactly
    /// while passing. Every report names these for the case, and traces them.
    pub fn shown_mistakes(&self) -> Mistakes {
        self.diagnosis
            .first()
            .map_or(self.hidden_mistakes, |t| t.mistakes)
    }
}

/// "exactly what `mistakes` renders".
fn exactly_what(mistakes: Mistakes) -> String {
    format!("exactly what {} renders", mistakes.name())
}

/// The warning of a passing case that renders exactly what catalogued mistakes render, as a
/// line of its own; None when it hides none.
pub fn passes_but_hidden(case: &CaseReport) -> Option<String> {
    let hidden = case.hidden_mistakes;
    (!hidden.is_empty()).then(|| {
        format!(
            "it passes, but is {}: fix it all the same",
            exactly_what(hidden)
        )
    })
}

/// A case's verdict, and when it fails, how far off it is: "differs: N of M pixels differ ...".
/// A case that passes with pixels beyond the tolerance says so: "within-tolerance (5 pixels
/// beyond ±2, allowed up to 10)", never only "within-tolerance".
pub fn verdict(case: &CaseReport) -> String {
    let d = &case.difference;
    match d.verdict.passes() {
        true => verdict_name(case),
        false => format!("{}: {}", d.verdict.name(), summary::difference_sentence(d)),
    }
}

/// A case's verdict's name, and for a case that passes with pixels beyond the tolerance, how
/// many ("within-tolerance (5 pixels beyond ±2, allowed up to 10)").
pub fn verdict_name(case: &CaseReport) -> String {
    let d = &case.difference;
    match d.allowed_words() {
        Some(allowed) => format!("{} ({allowed})", d.verdict.name()),
        None => d.verdict.name().to_string(),
    }
}

/// A suite case's verdict in one line of the text report: how far it is off and what of the
/// diagnosis shows in it, or that it passes while rendering exactly what the diagnosis renders.
pub fn case_line(case: &CaseReport) -> String {
    let d = &case.difference;
    if d.verdict.passes() {
        return match case.hidden_mistakes.is_empty() {
            true => verdict_name(case),
            false => format!(
                "{}, but is {}: the same fix",
                verdict_name(case),
                exactly_what(case.hidden_mistakes)
            ),
        };
    }
    let shows = case.diagnosis.first().map_or(String::new(), |t| {
        format!(
            "; shows {} ({}% of this case explained)",
            t.name(),
            plain(100.0 * t.explained)
        )
    });
    format!(
        "{}: {} pixels ({} by more than the tolerance), {}{shows}",
        d.verdict.name(),
        d.differing_pixels,
        d.beyond_tolerance,
        summary::largest(d)
    )
}

/// A graded case as a Gradescope test's output: its verdict, and the mistakes it shows.
pub fn test_line(case: &CaseReport) -> String {
    let shown = case.shown_mistakes();
    match shown.is_empty() {
        true => verdict(case),
        false => format!("{}; looks like {}", verdict(case), shown.name()),
    }
}

/// A student's feedback when every graded case passes: how many, how (`how`: how many pass
/// only by the allowance, or nothing), and the mistakes the passing images render exactly, if
/// any.
pub fn all_pass(cases: usize, how: &str, hidden: Mistakes) -> String {
    match hidden.is_empty() {
        true => format!("passes all {cases} graded cases{how}"),
        false => format!(
            "passes all {cases} graded cases{how}, but renders {}: fix it all the same",
            exactly_what(hidden)
        ),
    }
}

/// How many of a suite's cases pass, and how many of those passing cases render exactly what
/// the diagnosis renders (they pass, but need the same fix).
pub fn pass_count(passed: usize, cases: usize, hiding: usize) -> String {
    match hiding {
        0 => format!("{passed} of {cases} cases pass"),
        n => format!(
            "{passed} of {cases} cases pass ({n} of them {} exactly what the diagnosis renders: the same fix)",
            if n == 1 { "renders" } else { "render" }
        ),
    }
}
