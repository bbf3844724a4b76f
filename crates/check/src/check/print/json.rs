//! A check's result as JSON: what `whitted check --json` prints (docs/check.md), what the
//! viewer's check panel shows and what `grade` keeps of a student's run.

use serde_json::{json, Value};

use std::path::Path;

use crate::check::bump_judge::{self, BumpVerdict};
use crate::check::diagnose::Diagnosis;
use crate::check::numbers::NumberFit;
use crate::check::program::{RunStatus, SuiteRun};
use crate::check::progress::Stages;
use crate::check::result::{CaseResult, CheckResult, Subject};
use crate::check::star_fix::place_and_fix;
use crate::check::star_option::StarOption;
use crate::check::terms::TermFit;
use crate::check::{summary, words, CaseReport, Findings};

/// A number (a share of the differing pixels, a factor) rounded to three decimals for the JSON.
fn three_decimals(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

pub fn diagnosis_json(list: &[Diagnosis]) -> Value {
    json!(list
        .iter()
        .map(|d| json!({
            "bugs": d.mistakes.ids(),
            "explained": three_decimals(d.explained),
            "unexplained_pixels": d.unexplained_pixels,
            "wrongly_changed_pixels": d.wrongly_changed_pixels,
            "indistinguishable_from": d.indistinguishable_from.iter().map(|&m| m.name()).collect::<Vec<_>>(),
            "exact": d.exact,
            "number": d.number.map(|n| json!({"name": n.parameter.name(), "fitted": n.value})),
            "explained_by_rounding": three_decimals(d.by_rounding),
            "image_identical_with": d.image_identical_with.iter().map(|b| b.id()).collect::<Vec<_>>(),
            "where": d.mistakes.bugs().iter().map(|b| b.place()).collect::<Vec<_>>(),
            "looks_like": d.mistakes.bugs().iter().map(|b| b.looks_like(d.course)).collect::<Vec<_>>(),
            "fix": d.mistakes.bugs().iter().map(|b| b.fix(d.course)).collect::<Vec<_>>(),
            "text": summary::diagnosis_lines(d),
        }))
        .collect::<Vec<_>>())
}

pub fn terms_json(terms: &[TermFit]) -> Value {
    json!(terms
        .iter()
        .map(|t| json!({
            "layer": t.layer,
            "replaces": t.replaces,
            "factor": three_decimals(t.factor),
            "explained": three_decimals(t.explained),
        }))
        .collect::<Vec<_>>())
}

pub fn parameters_json(parameters: &[NumberFit]) -> Value {
    json!(parameters
        .iter()
        .map(|p| json!({
            "name": p.parameter.name(),
            "course": p.parameter.course(),
            "fitted": p.fitted,
            "with": p.with.ids(),
            "explained": three_decimals(p.explained),
            "wrongly_changed_pixels": p.wrongly_changed_pixels,
            "where": p.parameter.place(),
        }))
        .collect::<Vec<_>>())
}

pub fn progress_json(progress: &Stages) -> Value {
    let object: serde_json::Map<String, Value> = progress
        .stages
        .iter()
        .map(|(stage, state)| (stage.key(progress.course).to_string(), json!(state.name())))
        .collect();
    Value::Object(object)
}

/// What the diagnosis found, as the fields of the check's object.
pub fn add_findings(object: &mut Value, findings: &Findings) {
    object["diagnosis"] = diagnosis_json(&findings.diagnosis);
    object["progress"] = progress_json(&findings.progress);
    object["next"] = json!(findings.progress.next());
    if !findings.terms.is_empty() {
        object["terms"] = terms_json(&findings.terms);
    }
    if !findings.parameters.is_empty() {
        object["parameters"] = parameters_json(&findings.parameters);
    }
    object["summary"] = json!(summary::opening(findings));
    object["not_reproducible"] = match findings.not_reproducible {
        Some(noise) => json!({
            "seen": match noise.seen {
                crate::check::noise::Seen::TwoRuns => "two-runs-differ",
            },
            "blurred_max_difference": noise.blurred_max,
            "noise_tolerance": crate::check::noise::NOISE_TOLERANCE,
            "within_noise_tolerance": noise.within_tolerance(),
        }),
        None => Value::Null,
    };
    object["diagnosis_heading"] = json!(summary::candidates_heading(findings));
    if let Some(m) = &findings.missing_class {
        object["missing_class"] = json!({
            "class": m.class,
            "qualified": m.qualified,
            "cases": m.cases,
            "known_cause": m.known_cause,
        });
    }
    match &findings.bump {
        Some(BumpVerdict::Rendered(bump)) => {
            object["bump"] = json!({
                "verdict": bump_judge::rendered_name(bump),
                "parametrisation": bump.parametrisation,
                "mistake": bump.mistake.map(|m| m.name()),
                "matched": bump.matched,
                "matched_correct": bump.matched_correct,
                "candidates": bump.tried,
                "passes": bump.passes(),
                "where": bump.mistake.map(|m| place_and_fix(m).0),
                "fix": bump.mistake.map(|m| place_and_fix(m).1),
            });
        }
        Some(BumpVerdict::Drawn(draw)) => {
            object["bump_draw"] = json!({
                "verdict": bump_judge::drawn_name(draw),
                "parametrisation": draw.parametrisation,
                "mistake": draw.mistake.map(|m| m.name()),
                "statistic": draw.statistic,
                "statistic_correct": draw.correct,
                "candidates": draw.tried,
                "passes": draw.passes(),
                "where": draw.mistake.map(|m| place_and_fix(m).0),
                "fix": draw.mistake.map(|m| place_and_fix(m).1),
                "line": draw.sentence(),
            });
        }
        Some(BumpVerdict::NotDone) => {
            let option = StarOption::Bump;
            object["star_not_done"] = json!({
                "option": option.name(),
                "line": crate::check::star_not_done::sentence(option, false),
            });
        }
        None => {}
    }
    if let Some(note) = &findings.another_scene {
        object["another_scene"] = json!(note);
    }
    if let Some(star) = &findings.tick1_star {
        object["tick1_star"] = json!({
            "seen": star.seen.name(),
            "timeout": star.timeout,
            "stopped": star.stopped,
            "plan": star.plan,
        });
    }
}

/// One case; with `findings` when it is a check of one image (not a suite's case).
pub fn case_json(case: &CaseReport, findings: Option<&Findings>) -> Value {
    let d = &case.difference;
    let mut object = json!({
        "verdict": d.verdict.name(),
        "verdict_text": words::verdict_name(case),
        "width": d.width,
        "height": d.height,
        "bounces": case.bounces,
        "scene": case.scene_name,
        "tolerance": d.rule.tolerance,
        "max_beyond": d.rule.allowance.to_string(),
        "pixels_allowed_beyond": d.rule.allowance.pixels_of(d.pixels()),
        "differing_pixels": d.differing_pixels,
        "pixels_beyond_tolerance": d.beyond_tolerance,
        "max_difference": d.max_difference,
        "worst_pixel": d.worst_pixel.map(|(x, y)| json!([x, y])),
        "bounds": d.bounds.map(|(x0, y0, x1, y1)| json!([x0, y0, x1, y1])),
        "diagnosis": diagnosis_json(&case.diagnosis),
        "hidden_mistakes": case.hidden_mistakes.ids(),
        "difference_text": summary::difference_sentence(d),
    });
    if let Some(findings) = findings {
        add_findings(&mut object, findings);
    }
    object
}

/// A suite case: its status, its check when it wrote an image, and how to reproduce it.
fn outcome_json(case: &CaseResult) -> Value {
    let mut object = case
        .report()
        .map_or_else(|| json!({}), |report| case_json(report, None));
    object["reproduce"] = case.reproduce.json();
    object["case"] = json!(case.name);
    object["status"] = json!(case.status.name());
    object["stderr_tail"] = json!(case.stderr_tail);
    if let RunStatus::Star(star) = &case.status {
        object["tick1_star"] = star.json();
    }
    if let RunStatus::WrongSize {
        width,
        height,
        expected,
    } = case.status
    {
        object["width"] = json!(width);
        object["height"] = json!(height);
        object["expected_width"] = json!(expected.0);
        object["expected_height"] = json!(expected.1);
    }
    if let RunStatus::Crashed(message)
    | RunStatus::NoOutput(message)
    | RunStatus::OutOfMemory(message)
    | RunStatus::OutputTooLarge(message)
    | RunStatus::NotRun(message) = &case.status
    {
        object["message"] = json!(message);
    }
    object
}

/// The whole result: one image's check, or a program's run with every case, and the year
/// checked against (`"course"`, and `"course_chosen_because"` where it was not asked for).
pub fn json(result: &CheckResult) -> Value {
    let mut object = match (&result.subject, result.image()) {
        (Subject::Image { .. }, Some(case)) => {
            let mut object = case_json(case, Some(&result.findings));
            // The exit status: for a Tick 1* draw, its verdict, not `"verdict"`'s bytes.
            object["passed"] = json!(result.passed());
            object
        }
        (subject, _) => {
            let program = match subject {
                Subject::Program { program, .. } => program,
                Subject::Image { image } => image,
            };
            let mut object = json!({
                "program": program,
                "passed": result.passed(),
                "cases": result.cases.iter().map(outcome_json).collect::<Vec<_>>(),
            });
            add_findings(&mut object, &result.findings);
            object
        }
    };
    object["course"] = Value::from(result.course.name());
    if let Some(why) = &result.course_why {
        object["course_chosen_because"] = Value::from(why.as_str());
    }
    if let Some(project) = &result.project {
        object["project"] = project.clone();
    }
    object
}

/// A `--program` run as [`json`] prints it, for a caller that holds the run itself
/// (`grade`); `suite_dir` is where its scenes were written, if they were.
pub fn suite_json(run: &SuiteRun, suite_dir: Option<&Path>) -> Value {
    let course = run.findings.progress.course;
    json(&CheckResult::of_suite(run.clone(), course, None, suite_dir))
}
