//! A check's result as one self-contained HTML page (`check --report x.html`), and the pieces
//! `grade`'s student pages are made of too: the findings, and a failing case's block (the
//! student's image, the reference and the difference side by side, then the same three cut
//! to the worst region and enlarged). Every string is escaped: scene names, program lines and
//! error output are a student's and must never become markup.

use super::zoom::worst_region;
use crate::check::program::RunStatus;
use crate::check::report::heat_map;
use crate::check::result::{CheckResult, Subject};
use crate::check::summary::{self, candidates_heading};
use crate::check::{words, CaseReport, Findings};
use whitted_io::html::{escape, image};
use whitted_io::output::png::PngPixels;

/// The style of every page: readable, printable, no fonts or scripts from anywhere.
pub const STYLE: &str = "body{font:15px/1.45 system-ui,sans-serif;margin:2em auto;max-width:70em;\
padding:0 1em;color:#1b1b1b}h1{font-size:1.5em}h2{font-size:1.15em;margin-top:1.6em}\
table{border-collapse:collapse}td,th{padding:.25em .6em;border-bottom:1px solid #ddd;\
text-align:left;vertical-align:top}.pass{color:#17663a}.fail{color:#a4161a}\
pre{background:#f4f4f4;padding:.6em;overflow:auto;white-space:pre-wrap}\
figure{display:inline-block;margin:.3em}figcaption{font-size:.85em;color:#555}\
img{image-rendering:pixelated;max-width:100%;height:auto}.bar{fill:#3a6ea5}\
.stage{fill:#c77d2e}svg text{font:12px system-ui,sans-serif}\
.trio{display:grid;grid-template-columns:repeat(3,1fr);gap:.6em;align-items:start}\
.trio figure{margin:0}.zoom img{width:100%}";

/// How an image becomes an `<img>`: inline each time, or (`grade`) a reference shared by a
/// whole class encoded once.
pub trait Embed {
    fn embed(&self, width: u32, height: u32, rgb: &[u8], alt: &str) -> String;
}

/// Every image encoded where it is shown.
pub struct Inline;

impl Embed for Inline {
    fn embed(&self, width: u32, height: u32, rgb: &[u8], alt: &str) -> String {
        image(width, height, rgb.to_vec(), alt)
    }
}

/// Lines as paragraphs.
fn paragraphs(lines: &[String]) -> String {
    lines
        .iter()
        .map(|l| format!("<p>{}</p>\n", escape(l)))
        .collect()
}

/// The ranked candidates with where and how to fix each, then what explains the images
/// beyond the catalogue: every opening line but the progress, which the caller places.
pub fn findings_block(findings: &Findings) -> String {
    let mut out = String::new();
    if !findings.diagnosis.is_empty() && !findings.settled_by_fit() {
        out += &format!("<h2>{}</h2>\n<ol>\n", escape(&candidates_heading(findings)));
        for d in &findings.diagnosis {
            let lines: Vec<String> = summary::diagnosis_lines(d)
                .iter()
                .map(|l| escape(l))
                .collect();
            out += &format!("<li>{}</li>\n", lines.join("<br>"));
        }
        out += "</ol>\n";
    }
    out += &paragraphs(&summary::opening(findings)[1..]);
    out
}

/// Images side by side, each `<img>` with its caption (already escaped).
pub(super) fn trio(images: &[(String, &str)]) -> String {
    let mut row = String::from("<div class=\"trio\">");
    for (html, caption) in images {
        row += &format!("<figure>{html}<figcaption>{caption}</figcaption></figure>");
    }
    row + "</div>\n"
}

/// A failing case: its name and verdict, the student's image, the reference and where they
/// differ side by side, and below them the same three cut to the worst region, enlarged.
/// `references` embeds the reference.
pub fn case_block(name: &str, case: &CaseReport, references: &dyn Embed) -> String {
    let (w, h) = (case.student.width, case.student.height);
    let heat = match heat_map(
        &case.student,
        &case.reference,
        case.difference.rule.tolerance,
    )
    .pixels
    {
        PngPixels::Eight(bytes) => bytes,
        PngPixels::Sixteen(_) => Vec::new(),
    };
    let mut out = format!(
        "<section class=\"case\">\n<h2>{}</h2>\n<p class=\"fail\">{}</p>\n",
        escape(name),
        escape(&words::verdict(case))
    );
    out += &trio(&[
        (
            image(w, h, case.student.bytes.clone(), "your image"),
            "your image",
        ),
        (
            references.embed(w, h, &case.reference.bytes, "the reference"),
            "the reference",
        ),
        (
            image(w, h, heat.clone(), "where they differ"),
            "where they differ",
        ),
    ]);
    if let Some(region) = worst_region(&case.student, &case.reference) {
        let side = region.shown_side();
        let zoom = |rgb: &[u8], alt: &str| image(side, side, region.enlarged(rgb, w), alt);
        out += &format!("<p>Where they differ most: {}:</p>\n", region.described());
        out += &trio(&[
            (
                zoom(&case.student.bytes, "your image, enlarged"),
                "your image",
            ),
            (
                zoom(&case.reference.bytes, "the reference, enlarged"),
                "the reference",
            ),
            (
                zoom(&heat, "where they differ, enlarged"),
                "where they differ",
            ),
        ])
        .replace("class=\"trio\"", "class=\"trio zoom\"");
    }
    out + "</section>\n"
}

/// The whole page of `result`: what the text report says in full (the verdict, the course,
/// the progress, the findings with where and fix, every case), each failing case's images,
/// and the commands that reproduce it.
pub fn page(result: &CheckResult) -> String {
    let title = match &result.subject {
        Subject::Image { image } => format!("whitted check: {image}"),
        Subject::Program { program, .. } => format!("whitted check --program {program}"),
    };
    let mut body = format!("<h1>{}</h1>\n", escape(&title));
    let passed = result.passed();
    let (class, verdict) = match passed {
        true => ("pass", "passes"),
        false => ("fail", "fails"),
    };
    let (n, _) = result.pass_counts();
    let heading = match result.image() {
        Some(case) => super::text::checked_heading(result, case),
        None => format!("{n} of {} cases pass", result.cases.len()),
    };
    body += &format!(
        "<p class=\"{class}\"><strong>{verdict}</strong>: {} (course {})</p>\n",
        escape(&heading),
        escape(result.course.name())
    );
    if let Some(why) = &result.course_why {
        body += &paragraphs(std::slice::from_ref(why));
    }
    body += &paragraphs(&result.notes);
    let star_image = crate::check::star_fix::is_star_image(&result.findings);
    body += &paragraphs(&summary::opening(&result.findings)[..1]);
    if result.any_image() && !passed && !star_image {
        body += &findings_block(&result.findings);
        if result.findings.diagnosis.is_empty() && result.findings.another_scene.is_none() {
            body += "<p>No catalogued mistake reproduces the images better than the reference does.</p>\n";
        }
    } else {
        body += &paragraphs(&summary::opening(&result.findings)[1..]);
    }
    body += "<h2>The cases</h2>\n<table><tr><th>case</th><th>result</th></tr>\n";
    for c in &result.cases {
        let class = if c.passed() { "pass" } else { "fail" };
        let what = match c.report() {
            Some(r) => words::case_line(r),
            None => c.status.failure_line().unwrap_or_default(),
        };
        body += &format!(
            "<tr><td>{}</td><td class=\"{class}\">{}</td></tr>\n",
            escape(&c.name),
            escape(&what)
        );
    }
    body += "</table>\n";
    for c in &result.cases {
        if let RunStatus::Star(star) = &c.status {
            body += &super::html_star::star_block(&c.name, star);
        }
        match c.report() {
            Some(r) if !c.passed() => body += &case_block(&c.name, r, &Inline),
            Some(_) => {}
            None if !c.stderr_tail.is_empty() && !c.said_above => {
                body += &format!(
                    "<h2>{}: {}</h2>\n<pre>{}</pre>\n",
                    escape(&c.name),
                    c.status.name(),
                    escape(&c.stderr_tail)
                );
            }
            None => {}
        }
        let commands = c.reproduce.lines();
        if c.worth_rerunning() && !commands.is_empty() {
            body += &format!("<pre>{}</pre>\n", escape(&commands.join("\n")));
        }
    }
    if result.needs_suite_dir() {
        body +=
            &paragraphs(&[crate::check::reproduce::suite_dir_hint(result.star_run()).to_string()]);
    }
    format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\">\
         <title>{}</title><style>{STYLE}</style></head><body>\n{body}</body></html>\n",
        escape(&title)
    )
}
