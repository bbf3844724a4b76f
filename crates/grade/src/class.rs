//! The class at a glance, made from every student's `result.json` alone: `class.csv` (a row
//! per student), `mistakes.csv` (how many students have each catalogue entry: the mistakes
//! and the unfinished stages), `moodle.csv` (Moodle's offline grading worksheet) and
//! `index.html` (a bar chart of the same counts, the pass rate per scene, and every student
//! linked to their report; one file, no script, works offline from the folder).

use std::collections::BTreeMap;

use super::html::{escape, STYLE};
use super::result::StudentResult;
use super::status::StudentStatus;
use whitted_check::mistakes::Bug;

/// A field that a spreadsheet would run as a formula (`=`, `+`, `-`, `@`, a tab or a carriage
/// return first) gets a `'` before it, since names and messages come from submissions (OWASP's
/// CSV injection advice). The csv crate does the quoting.
fn formula_guarded(text: &str) -> String {
    match text.chars().next() {
        Some('=' | '+' | '-' | '@' | '\t' | '\r') => format!("'{text}"),
        _ => text.to_string(),
    }
}

/// One record, CRLF-terminated as spreadsheets write it; a field is quoted when it holds a
/// comma, a quote or a line break.
fn line(fields: &[String]) -> String {
    let mut writer = csv::WriterBuilder::new()
        .terminator(csv::Terminator::CRLF)
        .from_writer(Vec::new());
    // Writing to memory cannot fail.
    let _ = writer.write_record(fields.iter().map(|f| formula_guarded(f)));
    let bytes = writer.into_inner().unwrap_or_default();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// A grade as Moodle reads it: no needless decimals.
fn grade_text(grade: f64) -> String {
    whitted_core::numbers::plain(grade)
}

/// A student's grade in every class file: blank for one not graded (`--only` graded
/// others), as Moodle's own worksheet has an ungraded student's, never a 0 that an upload
/// would give them.
fn grade_cell(r: &StudentResult) -> String {
    match r.is_graded() {
        true => grade_text(r.extra.grade),
        false => String::new(),
    }
}

pub fn class_csv(rows: &[StudentResult]) -> String {
    let mut out = line(
        &[
            "id",
            "name",
            "status",
            "passed",
            "cases",
            "diagnosis",
            "grade",
            "reason",
        ]
        .map(String::from),
    );
    for r in rows {
        out += &line(&[
            r.extra.id.clone(),
            r.extra.name.clone(),
            r.extra.status.name().to_string(),
            r.extra.passed.to_string(),
            r.extra.cases.to_string(),
            r.extra.diagnosis.join("+"),
            grade_cell(r),
            super::reason::reason(r),
        ]);
    }
    out
}

/// How many students have each entry (their top diagnosis holds it), the most common first
/// (what to teach again), ties in catalogue order; the entries no one has left out.
pub fn counts(rows: &[StudentResult]) -> Vec<(Bug, usize)> {
    let has = |b: Bug| {
        rows.iter()
            .filter(|r| r.extra.diagnosis.iter().any(|d| d == b.id()))
            .count()
    };
    let mut counts: Vec<(Bug, usize)> = Bug::ALL
        .iter()
        .map(|&b| (b, has(b)))
        .filter(|&(_, n)| n > 0)
        .collect();
    // A stable sort keeps the catalogue order among equal counts.
    counts.sort_by_key(|&(_, n)| std::cmp::Reverse(n));
    counts
}

pub fn mistakes_csv(rows: &[StudentResult], course: whitted_core::course::Course) -> String {
    let graded = rows
        .iter()
        .filter(|r| r.extra.status == StudentStatus::Graded)
        .count();
    let mut out =
        line(&["id", "kind", "stage", "students", "share", "description"].map(String::from));
    for (bug, n) in counts(rows) {
        out += &line(&[
            bug.id().to_string(),
            if bug.is_unfinished() {
                "unfinished stage"
            } else {
                "mistake"
            }
            .to_string(),
            bug.stage().key(course).to_string(),
            n.to_string(),
            fraction_of(n, graded),
            bug.description(course).to_string(),
        ]);
    }
    out
}

/// `n` students of `of`, as a fraction to three decimals (mistakes.csv).
fn fraction_of(n: usize, of: usize) -> String {
    match of {
        0 => "0".into(),
        _ => whitted_core::numbers::plain((1000.0 * n as f64 / of as f64).round() / 1000.0),
    }
}

/// Moodle's offline grading worksheet, the columns its import reads: `Identifier` is
/// `Participant <id>`; the grade and the feedback always together (importing feedback alone
/// would overwrite grades with nothing). A student not graded has grade, feedback and date
/// blank, as Moodle's own worksheet has an ungraded student's grade and feedback: Moodle's
/// import skips a blank grade, and takes any grade it holds for them as newer than a blank
/// date, so that their feedback there is kept too.
pub fn moodle_csv(rows: &[StudentResult], modified: &str) -> String {
    let mut out = line(
        &[
            "Identifier",
            "Full name",
            "Status",
            "Grade",
            "Maximum Grade",
            "Grade can be changed",
            "Last modified (grade)",
            "Feedback comments",
        ]
        .map(String::from),
    );
    for r in rows {
        out += &line(&[
            format!("Participant {}", r.extra.id),
            r.extra.name.clone(),
            r.extra.status.name().to_string(),
            grade_cell(r),
            "100".into(),
            "Yes".into(),
            match r.is_graded() {
                true => modified.to_string(),
                false => String::new(),
            },
            r.extra.feedback.clone(),
        ]);
    }
    out
}

/// Each case's name and how many students pass it, of those who were run.
fn pass_rates(rows: &[StudentResult]) -> Vec<(String, usize, usize)> {
    let mut rates: BTreeMap<String, (usize, usize, usize)> = BTreeMap::new();
    for r in rows {
        for (order, (name, passed)) in r.case_passes().enumerate() {
            let e = rates.entry(name.to_string()).or_insert((order, 0, 0));
            e.1 += usize::from(passed);
            e.2 += 1;
        }
    }
    let mut list: Vec<(usize, String, usize, usize)> = rates
        .into_iter()
        .map(|(n, (o, p, t))| (o, n, p, t))
        .collect();
    list.sort();
    list.into_iter().map(|(_, n, p, t)| (n, p, t)).collect()
}

/// A horizontal bar chart, as inline SVG: (label, value, of, class).
fn bars(items: &[(String, usize, usize, &str)]) -> String {
    const LABEL: usize = 260;
    const WIDTH: usize = 360;
    const ROW: usize = 22;
    let height = ROW * items.len().max(1) + 4;
    let mut svg = format!(
        "<svg role=\"img\" width=\"{}\" height=\"{height}\" viewBox=\"0 0 {} {height}\">",
        LABEL + WIDTH + 80,
        LABEL + WIDTH + 80
    );
    for (i, (label, n, of, class)) in items.iter().enumerate() {
        let y = i * ROW + 2;
        let w = if *of == 0 { 0 } else { WIDTH * n / of };
        svg += &format!(
            "<g class=\"row\"><text x=\"0\" y=\"{}\">{}</text>\
             <rect class=\"{class}\" x=\"{LABEL}\" y=\"{y}\" width=\"{w}\" height=\"{}\"></rect>\
             <text x=\"{}\" y=\"{}\">{n} of {of}</text></g>",
            y + 14,
            escape(label),
            ROW - 6,
            LABEL + w + 6,
            y + 14
        );
    }
    svg + "</svg>"
}

pub fn index_html(rows: &[StudentResult], title: &str, settings: &[String]) -> String {
    let graded = rows
        .iter()
        .filter(|r| r.extra.status == StudentStatus::Graded)
        .count();
    let passing = rows
        .iter()
        .filter(|r| r.extra.cases > 0 && r.extra.passed == r.extra.cases)
        .count();
    let mut by_status: BTreeMap<&str, usize> = BTreeMap::new();
    for r in rows {
        *by_status.entry(r.extra.status.name()).or_default() += 1;
    }
    let statuses: Vec<String> = by_status.iter().map(|(s, n)| format!("{n} {s}")).collect();
    let mut body = format!(
        "<h1>{}</h1>\n<p id=\"totals\">{} students: {}; {passing} pass every graded case.</p>\n",
        escape(title),
        rows.len(),
        escape(&statuses.join(", "))
    );
    body += "<ul id=\"settings\">\n";
    for line in settings {
        body += &format!("<li>{}</li>\n", escape(line));
    }
    body += "</ul>\n";
    let mistakes: Vec<(String, usize, usize, &str)> = counts(rows)
        .into_iter()
        .map(|(b, n)| {
            let class = if b.is_unfinished() { "stage" } else { "bar" };
            (b.id().to_string(), n, graded, class)
        })
        .collect();
    body += "<h2>Mistakes and unfinished stages</h2>\n";
    body += "<p>Students whose top diagnosis holds each entry, of those whose program ran \
             (orange: a stage not written yet).</p>\n";
    body += &format!("<div id=\"mistakes\">{}</div>\n", bars(&mistakes));
    let rates: Vec<(String, usize, usize, &str)> = pass_rates(rows)
        .into_iter()
        .map(|(n, p, t)| (n, p, t, "bar"))
        .collect();
    body += "<h2>Pass rate per scene</h2>\n";
    body += &format!("<div id=\"scenes\">{}</div>\n", bars(&rates));
    let groups = identical(rows);
    body += "<h2>Identical submissions</h2>\n";
    if groups.is_empty() {
        body += "<p id=\"identical\">No two students handed in the same files (comments and \
                 whitespace aside).</p>\n";
    } else {
        body += "<p>Students whose Plane.java and Renderer.java are the same once comments and \
                 whitespace are gone: worth a look, not a verdict.</p>\n<ul id=\"identical\">\n";
        for group in &groups {
            let links: Vec<String> = group
                .iter()
                .map(|r| {
                    format!(
                        "<a href=\"students/{0}/report.html\">{0}</a> ({1})",
                        escape(&r.extra.id),
                        escape(&r.extra.name)
                    )
                })
                .collect();
            body += &format!("<li>{}</li>\n", links.join(", "));
        }
        body += "</ul>\n";
    }
    body += "<h2>Students</h2>\n<table id=\"students\"><tr><th>id</th><th>name</th>\
             <th>status</th><th>cases passed</th><th>diagnosis</th><th>grade</th></tr>\n";
    for r in rows {
        body += &format!(
            "<tr><td><a href=\"students/{0}/report.html\">{0}</a></td><td>{1}</td><td>{2}</td>\
             <td>{3} of {4}</td><td>{5}</td><td>{6}</td></tr>\n",
            escape(&r.extra.id),
            escape(&r.extra.name),
            escape(r.extra.status.name()),
            r.extra.passed,
            r.extra.cases,
            escape(&r.extra.diagnosis.join(" + ")),
            grade_cell(r)
        );
    }
    body += "</table>\n";
    format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\"><title>{}</title>\
         <style>{STYLE}</style></head><body>\n{body}</body></html>\n",
        escape(title)
    )
}

/// The groups of two or more students who share a fingerprint, in class order.
fn identical(rows: &[StudentResult]) -> Vec<Vec<&StudentResult>> {
    let mut by_print: BTreeMap<&str, Vec<&StudentResult>> = BTreeMap::new();
    for r in rows {
        if let Some(print) = &r.extra.fingerprint {
            by_print.entry(print.as_str()).or_default().push(r);
        }
    }
    let mut groups: Vec<Vec<&StudentResult>> =
        by_print.into_values().filter(|g| g.len() > 1).collect();
    groups.sort_by(|a, b| a[0].extra.id.cmp(&b[0].extra.id));
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_are_quoted_and_never_formulas() {
        let fields = [
            "plain",
            "a,b",
            "say \"hi\"",
            "=HYPERLINK(1)",
            "-1",
            "two\nlines",
            "",
            "\t=1",
        ]
        .map(String::from);
        assert_eq!(
            line(&fields),
            "plain,\"a,b\",\"say \"\"hi\"\"\",'=HYPERLINK(1),'-1,\"two\nlines\",,'\t=1\r\n"
        );
    }
}
