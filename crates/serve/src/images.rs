//! An attempt of images, checked in this process exactly as `whitted check IMAGE.png --course
//! YEAR --report x.html` checks each: against the year's scene, the verdict, the progress, the
//! diagnosis with where and how to fix it, and the report page that command writes.

use std::path::Path;

use serde_json::Value;

use super::scene_choice::{self, Choice};
use super::store::Outcome;
use whitted_check::check::pass_rule::{Allowance, PassRule};
use whitted_check::check::print::html;
use whitted_check::check::print::json::json;
use whitted_check::check::print::text::{text, Detail};
use whitted_check::check::result::CheckResult;
use whitted_check::check::star_option::StarOption;
use whitted_check::check::star_run::{judge, StarVerdict};
use whitted_check::check::suite::{Role, SuiteCase};
use whitted_check::check::which_course;
use whitted_check::check::{check_image, student_png};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::scene;

/// The pass rule `check` uses by default, which the course's tester used.
const RULE: PassRule = PassRule {
    tolerance: 2,
    allowance: Allowance::NONE,
};

/// One image's check: its result, a Tick 1* screenshot's verdict, or why it could not be
/// checked (a PNG bomb, not a PNG, plainly another scene).
enum Checked {
    Result(Box<CheckResult>),
    Star(StarOption, StarVerdict),
    Refused(String),
}

/// Checks every image of `names` (as uploaded, in order) stored as `image-<n>.png` in `dir`,
/// each against the scene its student chose for it (`scene_choice.rs`), or the one it is.
pub fn check(dir: &Path, names: &[String], course: Course) -> Outcome {
    let checked: Vec<(String, Checked)> = names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let path = dir.join(stored_name(i));
            let choice = scene_choice::read(dir, i, course);
            let checked = match one(&path, name, &choice, course) {
                Ok(checked) => checked,
                Err(e) => {
                    Checked::Refused(e.to_string().replace(&path.display().to_string(), name))
                }
            };
            (name.clone(), checked)
        })
        .collect();
    outcome(&checked)
}

/// Where the `i`-th image of an attempt is kept: a name whitted chose.
pub fn stored_name(i: usize) -> String {
    format!("image-{}.png", i + 1)
}

/// One image checked against each candidate case of `choice`: the first it passes, else the
/// one it is closest to; refused when it is plainly none of them (never a finding then).
fn one(path: &Path, name: &str, choice: &Choice, course: Course) -> Result<Checked> {
    let student = student_png::read(path)?;
    let candidates = scene_choice::candidates(choice, course);
    if let [SuiteCase {
        role: Role::Star(option),
        bounces,
        ..
    }] = candidates.as_slice()
    {
        // As `check --star`: a Tick 1* image is judged by its option's own check.
        return Ok(Checked::Star(
            *option,
            judge(*option, &student, *bounces, course)?,
        ));
    }
    let chosen = which_course::for_image(Some(course), (student.width, student.height), None)?;
    let mut best: Option<CheckResult> = None;
    for case in candidates {
        let input = scene::input::input_of(
            Some(Path::new(&*case.file)),
            Some(case.xml.as_bytes().to_vec()),
            course,
        )?;
        let (report, findings) = check_image(
            &input.scene,
            &input.name,
            case.bounces,
            RULE,
            student.clone(),
            course,
        )?;
        let result = CheckResult::of_image(name, None, report, findings, &chosen);
        if result.passed() {
            return Ok(Checked::Result(Box::new(result)));
        }
        if best.as_ref().is_none_or(|b| beyond(&result) < beyond(b)) {
            best = Some(result);
        }
    }
    let Some(best) = best else {
        return Err(Error::Usage(
            "no scene of the year to check it against".into(),
        ));
    };
    let total = (student.width as usize) * (student.height as usize);
    match scene_choice::plainly_another(beyond(&best), total) {
        false => Ok(Checked::Result(Box::new(best))),
        true => Err(Error::Usage(match choice {
            Choice::Case { file, bounces } => format!(
                "this image is not {}: choose its scene",
                scene_choice::label(file, *bounces)
            ),
            Choice::Recognise => "this image is none of the year's scenes at any bounces \
                                  the tester knows: choose its scene"
                .into(),
        })),
    }
}

/// The pixels of a result's image off by more than the tolerance.
fn beyond(result: &CheckResult) -> usize {
    result
        .image()
        .map_or(usize::MAX, |r| r.difference.beyond_tolerance)
}

fn outcome(checked: &[(String, Checked)]) -> Outcome {
    let passes = |c: &Checked| match c {
        Checked::Result(r) => r.passed(),
        Checked::Star(_, v) => v.passes(),
        Checked::Refused(_) => false,
    };
    let passed = checked.iter().all(|(_, c)| passes(c));
    // The mistake and progress the attempt is known by: the first image that fails, else the
    // first.
    let shown = checked.iter().find(|(_, c)| !passes(c)).or(checked.first());
    let (mistake, progress) = match shown {
        Some((_, Checked::Result(result))) => {
            let value = json(result);
            (top_mistake(&value), progress_of(&value))
        }
        _ => (None, String::new()),
    };
    // Every image's text, each under its name and verdict.
    let finding = match checked {
        [] => "no image".to_string(),
        [(name, c)] => one_text(name, c),
        _ => checked
            .iter()
            .map(|(name, c)| format!("{name}: {}\n{}", image_verdict(c), one_text(name, c)))
            .collect::<Vec<_>>()
            .join("\n\n"),
    };
    let verdict = match checked {
        [(name, c)] => format!("{name}: {}", image_verdict(c)),
        _ => {
            let names = |pass: bool| {
                checked
                    .iter()
                    .filter(|(_, c)| passes(c) == pass)
                    .map(|(n, _)| n.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let count = checked.iter().filter(|(_, c)| passes(c)).count();
            match (count, checked.len() - count) {
                (_, 0) => format!("all {count} images pass"),
                (0, _) => format!(
                    "none of the {} images pass: {}",
                    checked.len(),
                    names(false)
                ),
                _ => format!(
                    "{count} of {} images pass ({}); not {}",
                    checked.len(),
                    names(true),
                    names(false)
                ),
            }
        }
    };
    let reports: Vec<String> = checked
        .iter()
        .map(|(name, c)| match c {
            Checked::Result(r) => html::page(r),
            Checked::Star(option, v) => plain_page(name, &star_line(*option, v)),
            Checked::Refused(why) => {
                plain_page(name, &format!("This image cannot be checked: {why}"))
            }
        })
        .collect();
    Outcome {
        passed,
        verdict,
        mistake,
        finding,
        progress,
        report: serde_json::to_string(&reports).unwrap_or_default(),
    }
}

/// One image's verdict in words.
fn image_verdict(checked: &Checked) -> String {
    match checked {
        Checked::Result(r) => verdict_of(&json(r)),
        Checked::Star(_, v) => v.name().into(),
        Checked::Refused(_) => "cannot be checked".into(),
    }
}

/// One image's text, as the page shows it.
fn one_text(name: &str, checked: &Checked) -> String {
    match checked {
        Checked::Result(r) => for_the_web(&text(r, Detail::Screen)),
        Checked::Star(option, v) => star_line(*option, v),
        Checked::Refused(why) => format!("{name}: {why}"),
    }
}

/// The check's text without its hints to the command line (`--verbose adds ...; --report
/// FILE.html shows the images`): on the web the report is shown below, and there is no
/// command to add options to.
pub fn for_the_web(text: &str) -> String {
    text.lines()
        .filter(|l| !l.trim_start().trim_start_matches('(').starts_with("--"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The report of an image that has only a sentence (it could not be checked; a Tick 1*
/// verdict), escaped.
fn plain_page(name: &str, sentence: &str) -> String {
    maud::html! {
        (maud::DOCTYPE)
        html lang="en" { head { meta charset="utf-8"; title { (name) } }
            body { h1 { (name) } p { (sentence) } } }
    }
    .into_string()
}

/// A Tick 1* verdict in words, as `check --star` prints it.
fn star_line(option: StarOption, verdict: &StarVerdict) -> String {
    format!("{}: {}", option.what(), verdict.line())
}

/// The top candidate's first catalogue entry, when the check names one.
pub fn top_mistake(value: &Value) -> Option<String> {
    value["diagnosis"].as_array()?.first()?["bugs"]
        .as_array()?
        .first()?
        .as_str()
        .map(str::to_string)
}

fn verdict_of(value: &Value) -> String {
    value["verdict_text"]
        .as_str()
        .unwrap_or("checked")
        .to_string()
}

/// The progress line of the check's summary (`progress: planes done; ...`).
fn progress_of(value: &Value) -> String {
    value["summary"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(Value::as_str)
        .find(|l| l.starts_with("progress"))
        .unwrap_or("")
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_web_text_has_no_command_line_hints() {
        let text = "diagnosis\n  fix: x\n--verbose adds the commands; --report FILE.html shows \
                    the images\n(--suite-dir DIR writes the scenes)";
        assert_eq!(for_the_web(text), "diagnosis\n  fix: x");
    }
}
