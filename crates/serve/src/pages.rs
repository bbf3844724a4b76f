//! The service's pages, in maud: every value is escaped by construction, and no page holds a
//! script (the one script is `app.js`, which the Content-Security-Policy allows alone).

use maud::{html, Markup, DOCTYPE};
use whitted_check::check::suite::SuiteCase;

use super::scene_choice;
use super::staff_view::ClassView;
use super::store::{Attempt, Status, Student};

/// The upload form's rows: a file input and the select of its scene each.
const ROWS: usize = 4;

pub const SCRIPT: &str = include_str!("assets/app.js");
pub const STYLE: &str = include_str!("assets/style.css");

fn layout(title: &str, status_url: Option<&str>, body: Markup) -> String {
    html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                meta name="viewport" content="width=device-width, initial-scale=1";
                title { (title) }
                link rel="stylesheet" href="/style.css";
                script src="/app.js" defer {}
            }
            body data-status=[status_url] { (body) }
        }
    }
    .into_string()
}

/// `/`: nothing about anyone.
pub fn home() -> String {
    layout(
        "whitted serve",
        None,
        html! {
            h1 { "The course's tester" }
            p { "Open the personal link the course staff sent you." }
        },
    )
}

/// A refusal, as a page a person reads.
pub fn refusal(message: &str) -> String {
    layout(
        "Refused",
        None,
        html! { h1 { "Refused" } p.refusal { (message) } },
    )
}

fn when(seconds: i64) -> String {
    let days = seconds.div_euclid(86_400);
    let s = seconds.rem_euclid(86_400);
    let (y, m, d) = whitted_core::calendar::civil_from_days(days);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02} UTC",
        s / 3600,
        s % 3600 / 60
    )
}

fn result_cell(attempt: &Attempt) -> Markup {
    match (&attempt.outcome, attempt.status) {
        (Some(o), _) => html! {
            span class=(if o.passed { "pass" } else { "fail" }) { (o.verdict) }
            @if let Some(m) = &o.mistake { " — " code { (m) } }
        },
        (None, Status::Running) => html! { span.pending { "running" } },
        (None, _) => html! { span.pending { "queued" } },
    }
}

/// A student's attempts, newest first, each linking to its page under `base` and numbered
/// among that student's own (their 2nd is "2", however many the class made before it).
fn attempts_table(base: &str, attempts: &[Attempt]) -> Markup {
    html! {
        @if attempts.is_empty() { p.muted { "No attempt yet." } } @else {
            table {
                tr { th { "#" } th { "When" } th { "What" } th { "Files" } th { "Result" } th { "CPU" } }
                @for (i, a) in attempts.iter().enumerate() {
                    tr {
                        td { a href=(format!("{base}/attempt/{}", a.id)) { (attempts.len() - i) } }
                        td { (when(a.received)) }
                        td { (a.kind.name()) }
                        td { (a.files.replace('\n', ", ")) }
                        td { (result_cell(a)) }
                        td { @if let Some(cpu) = a.cpu { (format!("{cpu:.1} s")) } }
                    }
                }
            }
        }
    }
}

/// A student's page: the upload form, and every attempt.
pub fn student(
    base: &str,
    student: &Student,
    tick: &str,
    scenes: &[SuiteCase],
    attempts: &[Attempt],
    message: Option<&str>,
) -> String {
    let greeting = match student.name.is_empty() {
        true => student.id.clone(),
        false => student.name.clone(),
    };
    layout(
        &format!("{tick}: {greeting}"),
        None,
        html! {
            h1 { (tick) ": " (greeting) }
            @if let Some(m) = message { p.refusal { (m) } }
            form method="post" action=(format!("{base}/upload")) enctype="multipart/form-data" {
                input type="hidden" name="csrf" value=(student.csrf);
                p { "Upload the PNGs your program wrote for the course's scenes, saying which \
                     scene and bounces each is (checked at once), or your project: its "
                     code { ".java" } " files or a zip of it (compiled and run on the course's \
                     scenes in a sandbox, in turn)." }
                @for row in 0..ROWS {
                    p.file {
                        input type="file" name="files" multiple[row == 0] accept=".png,.java,.zip";
                        " is "
                        select name="scene" aria-label="which scene this image is" {
                            option value=(scene_choice::RECOGNISE) { "recognise it" }
                            @for case in scenes {
                                option value=(scene_choice::value(case)) {
                                    (scene_choice::case_label(case))
                                }
                            }
                        }
                    }
                }
                button type="submit" { "Check" }
            }
            h2 { "Your attempts" }
            (attempts_table(base, attempts))
        },
    )
}

/// An attempt's page: its state, live while it waits or runs, then its finding and report.
/// `ordinal` is the attempt's number among its student's own.
pub fn attempt(
    base: &str,
    back: &str,
    attempt: &Attempt,
    ordinal: usize,
    reports: usize,
) -> String {
    let status_url = format!("{base}/attempt/{}/status", attempt.id);
    let live = attempt.status != Status::Done;
    layout(
        &format!("Attempt {ordinal}"),
        live.then_some(status_url.as_str()),
        html! {
            p { a href=(back) { "← back" } }
            h1 { "Attempt " (ordinal) ": " (attempt.kind.name()) }
            p.muted { "Received " (when(attempt.received)) "."
                @if let Some(f) = attempt.finished { " Finished " (when(f)) "." }
                @if attempt.runs > 1 { " Run " (attempt.runs) " times (the service restarted during a run)." }
                @if let Some(cpu) = attempt.cpu { (format!(" Its run took {cpu:.1} s of CPU.")) }
                " Files: " (attempt.files.replace('\n', ", ")) }
            @match &attempt.outcome {
                None => p #state .pending { (attempt.status.name()) "…" },
                Some(o) => {
                    p class=(if o.passed { "pass" } else { "fail" }) { strong { (o.verdict) } }
                    @if !o.progress.is_empty() { p { (o.progress) } }
                    pre { (o.finding) }
                    @for i in 0..reports {
                        iframe src=(format!("{base}/attempt/{}/report?n={i}", attempt.id))
                            title="report" {}
                    }
                }
            }
        },
    )
}

/// The staff's page of the class.
pub fn class(base: &str, view: &ClassView, tick: &str) -> String {
    layout(
        &format!("{tick}: the class"),
        None,
        html! {
            h1 { (tick) ": the class, live" }
            p { (view.rows.len()) " students; " (view.started()) " started; "
                (view.passing()) " passing now. Export the latest attempts: "
                a href=(format!("{base}/export/moodle.csv")) { "Moodle worksheet" } ", "
                a href=(format!("{base}/export/feedback.zip")) { "feedback zip" } ", "
                a href=(format!("{base}/export/class.csv")) { "class.csv" } "." }
            p.muted { "Moodle's worksheet import matches its own participant numbers, which \
                only the grading worksheet Moodle downloads carries: serve with it as the \
                roster to export a worksheet (a participants export has none, and the \
                worksheet is then refused)." }
            h2 { "Programs" }
            p { (view.programs.queued) " queued, " (view.programs.running) " running, "
                (view.programs.done) " done"
                @if view.programs.done > 0 {
                    ", " (view.programs.wall) " s of wall time in all"
                    @if view.programs.measured > 0 {
                        "; the programs' own CPU time (compiler, JVMs, checks) "
                        (format!("{:.0}", view.programs.cpu)) " s over " (view.programs.measured)
                        " runs, " (format!("{:.1}", view.programs.cpu / view.programs.measured as f64))
                        " s each"
                    }
                }
                "." }
            h2 { "Mistakes, ranked" }
            @if view.mistakes.is_empty() { p.muted { "None diagnosed yet." } } @else {
                table {
                    tr { th { "Mistake" } th { "Students who had it" } th { "Still have it" } th { "Held for (hours, all students)" } }
                    @for m in &view.mistakes {
                        tr { td { code { (m.id) } } td { (m.students) } td { (m.now) }
                             td { (format!("{:.1}", m.seconds as f64 / 3600.0)) } }
                    }
                }
            }
            h2 { "Attempts over time" }
            table {
                tr { th { "Hour" } th { "Attempts" } }
                @for (hour, n) in &view.per_hour { tr { td { (when(*hour)) } td { (n) } } }
            }
            h2 { "Students" }
            table {
                tr { th { "Id" } th { "Name" } th { "Attempts" } th { "Latest" } th { "Finding" } }
                @for row in &view.rows {
                    tr {
                        td { a href=(format!("{base}/student/{}", row.student.number)) { (row.student.id) } }
                        td { (row.student.name) }
                        td { (row.attempts) }
                        td { @if let Some(a) = &row.latest { (result_cell(a)) } @else { span.muted { "not started" } } }
                        td { @if let Some(o) = row.latest.as_ref().and_then(|a| a.outcome.as_ref()) { (headline(&o.finding)) } }
                    }
                }
            }
            h2 { "Not started" }
            @if view.not_started().next().is_none() { p.muted { "Everyone has started." } } @else {
                p { @for (i, row) in view.not_started().enumerate() { @if i > 0 { ", " } (row.student.id) } }
            }
        },
    )
}

/// The finding in a line, for the staff's table: the best diagnosis (`bounces-minus-one: one
/// bounce fewer than --bounces`), else how the image differs, else the first line (a refusal,
/// a project's feedback); never the check's heading of scene, size and rule.
pub fn headline(text: &str) -> &str {
    let lines: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    if let Some(i) = lines.iter().position(|l| l.starts_with("diagnosis")) {
        if let Some(best) = lines.get(i + 1) {
            return best.strip_prefix("1. ").unwrap_or(best);
        }
    }
    lines
        .iter()
        .find(|l| l.contains("pixels differ"))
        .or(lines.first())
        .copied()
        .unwrap_or("")
}

/// One student's history, for the staff.
pub fn history(base: &str, student: &Student, attempts: &[Attempt]) -> String {
    layout(
        &format!("{}: history", student.id),
        None,
        html! {
            p { a href=(base) { "← the class" } }
            h1 { (student.id) " " (student.name) }
            @if !student.email.is_empty() { p { (student.email) } }
            @if student.secret.is_none() { p.refusal { "Their link is revoked." } }
            (attempts_table(base, attempts))
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_staff_read_the_finding_not_the_heading() {
        let finding = "tick2.xml (embedded), 640x480, 2 bounces: differs (tolerance: 2)\n\
            progress: planes done\n90160 of 307200 pixels differ\ndiagnosis, best first:\n  \
            1. bounces-minus-one: one bounce fewer than --bounces\n     where: Renderer.trace";
        assert_eq!(
            headline(finding),
            "bounces-minus-one: one bounce fewer than --bounces"
        );
        assert_eq!(
            headline("a 640x480: differs\n5 of 9 pixels differ (5 by more)"),
            "5 of 9 pixels differ (5 by more)"
        );
        assert_eq!(
            headline("x.png: this image is not tick2.xml"),
            "x.png: this image is not tick2.xml"
        );
    }

    #[test]
    fn dates_and_escaping() {
        assert_eq!(when(0), "1970-01-01 00:00 UTC");
        assert_eq!(when(1_796_371_200), "2026-12-04 08:00 UTC");
        let page = refusal("<script>alert(1)</script>");
        assert!(page.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
        assert!(!page.contains("<script>alert"));
    }
}
