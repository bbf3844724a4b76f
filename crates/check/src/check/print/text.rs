//! A check's result as text. By default one screen (`screen.rs`): the verdict, the course
//! line, the progress, a line per case, the finding with where and fix, and a line saying
//! what `--verbose` adds. `--verbose` prints everything: every candidate with what its images
//! cannot tell, a program's whole standard error tail, and the commands that rerun and
//! explain each case.

use super::screen::{Keep, Screen, SCREEN_LINES};
use crate::check::program::RunStatus;
use crate::check::reproduce::suite_dir_hint;
use crate::check::result::{CaseResult, CheckResult, Subject};
use crate::check::star_detail;
use crate::check::summary::{self, candidates_heading, opening};
use crate::check::{words, CaseReport, Findings};
use whitted_core::numbers::plain;

/// How much of the result is printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Detail {
    /// What fits one screen (`SCREEN_LINES`).
    Screen,
    /// Everything (`--verbose`).
    Full,
}

impl Detail {
    fn full(self) -> bool {
        self == Detail::Full
    }
}

/// The text report of `result`.
pub fn text(result: &CheckResult, detail: Detail) -> String {
    let mut screen = Screen::default();
    let mut hidden = Hidden {
        // A Tick 1* option's image is shown whatever its verdict: it is a random one.
        images: (result.any_image() && !result.passed()) || any_star_image(result),
        report: result.report.clone(),
        ..Hidden::default()
    };
    match (&result.subject, result.image()) {
        (Subject::Image { .. }, Some(case)) => {
            image(result, case, detail, &mut screen, &mut hidden)
        }
        _ => program(result, detail, &mut screen, &mut hidden),
    }
    if let Some(line) = hidden.line() {
        screen.line(Keep::Always, line);
    }
    let max = (!detail.full()).then_some(SCREEN_LINES);
    screen.render(max).trim_end().to_string()
}

/// What the one-screen text left out, for its last line.
#[derive(Default)]
struct Hidden {
    candidates: usize,
    details: bool,
    /// The commands left out, in words.
    commands: Option<&'static str>,
    stderr: bool,
    /// The numbers a Tick 1* option's verdict rests on (`star_detail.rs`).
    star_numbers: bool,
    /// The suite's scenes were not written, so there are no commands to rerun a case.
    suite_dir: bool,
    /// Some case wrote an image, which a report page would show.
    images: bool,
    /// The report that shows them, when one was written.
    report: Option<String>,
}

impl Hidden {
    fn line(&self) -> Option<String> {
        let mut parts = Vec::new();
        match self.candidates {
            0 => {}
            1 => parts.push("1 more candidate".to_string()),
            n => parts.push(format!("{n} more candidates")),
        }
        if self.details {
            parts.push("what the images cannot tell apart".into());
        }
        if self.star_numbers {
            parts.push("the numbers behind each option's verdict".into());
        }
        if self.stderr {
            parts.push("the program's standard error".into());
        }
        parts.extend(self.commands.map(String::from));
        let mut line = match parts.is_empty() {
            true => String::new(),
            false => format!("--verbose adds {}; ", parts.join(", ")),
        };
        if self.suite_dir {
            line += "--suite-dir DIR writes the scenes to rerun each case; ";
        }
        match (self.images, &self.report) {
            (true, Some(report)) => line += &format!("{report} shows the images; "),
            (true, None) => line += "--report FILE.html shows the images; ",
            (false, _) => {}
        }
        let line = line.trim_end_matches("; ");
        (!line.is_empty()).then(|| line.to_string())
    }
}

/// The first line of an image's report: the scene, the size, the bounces, the verdict and
/// the rule it was given by.
/// The verdict that decides a checked image, where one does (a Tick 1* bump image's draw or
/// option not done), not its bytes.
fn decided_verdict(result: &CheckResult) -> Option<&crate::check::bump_judge::BumpVerdict> {
    result
        .cases
        .first()
        .and_then(|c| c.decided)
        .and(result.findings.bump.as_ref())
}

/// A checked image's heading, in the text and the report page: the verdict's name where the
/// verdict decides it, else the byte comparison's (`image_heading`).
pub fn checked_heading(result: &CheckResult, case: &CaseReport) -> String {
    let d = &case.difference;
    match decided_verdict(result) {
        Some(verdict) => format!(
            "{}, {}x{}, {} bounces: {}",
            case.scene_name,
            d.width,
            d.height,
            case.bounces,
            verdict.name()
        ),
        None => image_heading(case),
    }
}

pub fn image_heading(case: &CaseReport) -> String {
    let d = &case.difference;
    format!(
        "{}, {}x{}, {} bounces: {} (tolerance: {})",
        case.scene_name,
        d.width,
        d.height,
        case.bounces,
        words::verdict_name(case),
        d.rule.words()
    )
}

/// The course line after the first, then the opening lines.
fn opening_lines(result: &CheckResult, first: String, screen: &mut Screen) {
    screen.line(Keep::Always, first);
    if let Some(why) = &result.course_why {
        screen.line(Keep::Always, why.clone());
    }
    screen.push(Keep::Always, result.notes.clone());
    screen.push(Keep::Always, opening(&result.findings));
}

fn image(
    result: &CheckResult,
    case: &CaseReport,
    detail: Detail,
    screen: &mut Screen,
    hidden: &mut Hidden,
) {
    let d = &case.difference;
    // A Tick 1* bump image whose verdict, not its bytes, decides it: its heading names the
    // verdict, and its bytes are only compared with what they are measured against.
    let decided = decided_verdict(result).map(|v| (v, crate::check::star_fix::compared_with(v)));
    opening_lines(result, checked_heading(result, case), screen);
    if d.differing_pixels == 0 {
        screen.line(
            Keep::Always,
            "every byte of every pixel equals the reference",
        );
        return;
    }
    screen.push(Keep::Always, words::passes_but_hidden(case));
    match decided {
        Some((_, against)) => screen.line(
            Keep::Always,
            format!("against {against}: {}", summary::difference_sentence(d)),
        ),
        None => screen.line(Keep::Always, summary::difference_sentence(d)),
    }
    if let (Some((x0, y0, x1, y1)), Some((x, y))) = (d.bounds, d.worst_pixel) {
        screen.line(
            Keep::IfRoom,
            format!("they lie in x {x0}..={x1}, y {y0}..={y1}; the worst pixel is ({x}, {y})"),
        );
    }
    findings_lines(&result.findings, detail, screen, hidden);
    if decided.is_some() {
        // Its worst pixel against one render says nothing of a draw or of an option not done.
        return;
    }
    let commands = &result.cases[0].reproduce.explain;
    if detail.full() {
        if let Some(reference) = commands.first() {
            screen.push(
                Keep::Always,
                [
                    "the worst pixel, as the reference traces it:".to_string(),
                    format!("  {reference}"),
                ],
            );
        }
        if let Some(compare) = commands.get(1) {
            screen.push(
                Keep::Always,
                [
                    "and beside it as the top diagnosis traces it, the steps that differ:"
                        .to_string(),
                    format!("  {compare}"),
                ],
            );
        }
    } else if !commands.is_empty() {
        hidden.commands = Some("the commands that trace the worst pixel");
    }
}

fn program(result: &CheckResult, detail: Detail, screen: &mut Screen, hidden: &mut Hidden) {
    let name = match &result.subject {
        Subject::Program { program, .. } => program.as_str(),
        Subject::Image { image } => image.as_str(),
    };
    opening_lines(
        result,
        format!("{name} over {} cases:", result.cases.len()),
        screen,
    );
    if detail.full() && result.needs_suite_dir() {
        screen.line(Keep::Always, suite_dir_hint(result.star_run()));
    }
    let mut tails_shown: Vec<&str> = Vec::new();
    for c in &result.cases {
        screen.line(Keep::Always, format!("  {:<28} {}", c.name, case_line(c)));
        if let RunStatus::Star(star) = &c.status {
            match detail.full() {
                true => screen.push(
                    Keep::Always,
                    star_detail::lines(star)
                        .iter()
                        .map(|l| format!("      {l}")),
                ),
                false => hidden.star_numbers = true,
            }
        }
        if c.report().is_none() && !c.stderr_tail.is_empty() && !c.said_above {
            let lines = c.stderr_tail.lines();
            if detail.full() {
                screen.push(Keep::Always, lines.map(|l| format!("      | {l}")));
            } else {
                // The line that names the error; the same one is said once, and at most two
                // are said at all.
                let last = telling_line(lines);
                hidden.stderr |= c.stderr_tail.lines().count() > 1;
                if tails_shown.len() < 2 && !last.is_empty() && !tails_shown.contains(&last) {
                    tails_shown.push(last);
                    screen.line(Keep::IfRoom, format!("      | {last}"));
                } else {
                    hidden.stderr = true;
                }
            }
        }
        if c.worth_rerunning() {
            let lines = c.reproduce.lines();
            match detail.full() {
                true => screen.push(Keep::Always, lines.iter().map(|l| format!("      {l}"))),
                false if !lines.is_empty() => {
                    hidden.commands = Some("the commands that rerun and explain each failing case")
                }
                false => hidden.suite_dir = result.needs_suite_dir(),
            }
        }
    }
    let (passed, hiding) = result.pass_counts();
    screen.line(
        Keep::Always,
        words::pass_count(passed, result.cases.len(), hiding),
    );
    if result.star_run() {
        // Each option's image was judged on its line; there is no suite to diagnose.
    } else if !result.any_image() {
        screen.line(
            Keep::Always,
            "diagnosis: no case wrote an image to diagnose",
        );
    } else if !result.passed() {
        findings_lines(&result.findings, detail, screen, hidden);
    }
}

/// Whether a Tick 1* program's case wrote an image (which the report page shows).
fn any_star_image(result: &CheckResult) -> bool {
    result
        .cases
        .iter()
        .any(|c| matches!(c.status, RunStatus::Star(_)))
}

/// The line of a standard error tail that says what went wrong: its last line that is not a
/// stack frame (Java's `\tat ...` and `\t... 3 more`), so the exception or its cause.
fn telling_line<'a>(lines: impl DoubleEndedIterator<Item = &'a str>) -> &'a str {
    lines
        .rev()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with("at ") && !l.starts_with("... "))
        .unwrap_or("")
}

/// A case's line after its name: its verdict and what of the diagnosis shows in it, or how
/// it ended without an image.
fn case_line(c: &CaseResult) -> String {
    match c.report() {
        Some(case) => words::case_line(case),
        None => c.status.failure_line().unwrap_or_default(),
    }
}

/// The candidates, after the opening lines (which hold the fits beyond the catalogue). On one
/// screen only the best, and only when it explains the images well; else every one.
fn findings_lines(findings: &Findings, detail: Detail, screen: &mut Screen, hidden: &mut Hidden) {
    let list = &findings.diagnosis;
    if crate::check::star_fix::is_star_image(findings) || findings.another_scene.is_some() {
        // The opening lines hold the bump finding, or the note that the image is of another
        // scene; no Tick 1 mistake is looked for.
        return;
    }
    if list.is_empty() {
        screen.line(
            Keep::Always,
            "diagnosis: no catalogued mistake reproduces the images better than the reference does",
        );
        return;
    }
    if findings.settled_by_fit() {
        // The fit in the opening lines is the story; weak candidates would tell another.
        return;
    }
    if !detail.full() {
        hidden.candidates = list.len() - 1;
        if findings.weak() {
            // A weak candidate is no finding: named, its where and fix left to --verbose.
            hidden.candidates = list.len();
            screen.line(
                Keep::Always,
                format!(
                    "the best catalogued candidate, {}, explains only {}% of the differing pixels",
                    list[0].name(),
                    plain(100.0 * list[0].explained)
                ),
            );
            return;
        }
        hidden.details |= !summary::diagnosis_details(&list[0]).is_empty();
        screen.line(Keep::Always, candidates_heading(findings));
        screen.push(Keep::Always, numbered(1, summary::finding_lines(&list[0])));
        return;
    }
    screen.line(Keep::Always, candidates_heading(findings));
    for (rank, d) in list.iter().enumerate() {
        screen.push(
            Keep::Always,
            numbered(rank + 1, summary::diagnosis_lines(d)),
        );
    }
}

/// A candidate's lines under its rank: "  1. first", then indented.
fn numbered(rank: usize, lines: Vec<String>) -> Vec<String> {
    lines
        .into_iter()
        .enumerate()
        .map(|(i, line)| match i {
            0 => format!("  {rank}. {line}"),
            _ => format!("     {line}"),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stack_trace_is_told_by_its_exception_not_its_last_frame() {
        let tail = "Exception in thread \"main\" java.lang.IllegalStateException: x\n\
                    \tat Renderer.trace(Renderer.java:40)\n\
                    Caused by: java.lang.NullPointerException\n\
                    \tat Scene.get(Scene.java:9)\n\
                    \t... 3 more\n";
        assert_eq!(
            telling_line(tail.lines()),
            "Caused by: java.lang.NullPointerException"
        );
        assert_eq!(telling_line("one\ntwo\n\n".lines()), "two");
        assert_eq!(telling_line("".lines()), "");
    }
}
