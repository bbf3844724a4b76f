//! One checked image as JSON: what `whitted check --json` prints (docs/check.md) and what the
//! viewer's check panel shows.

use serde_json::{json, Value};

use super::diagnose::Diagnosis;
use super::terms::TermFit;
use super::CaseReport;
use crate::mistakes::Mistakes;

/// `a+b` for a pair.
pub fn name(m: Mistakes) -> String {
    m.ids().join("+")
}

pub fn diagnosis_json(list: &[Diagnosis]) -> Value {
    json!(list
        .iter()
        .map(|d| json!({
            "bugs": d.mistakes.ids(),
            "explained": (d.explained * 1000.0).round() / 1000.0,
            "unexplained_pixels": d.unexplained_pixels,
            "wrongly_changed_pixels": d.wrongly_changed_pixels,
            "indistinguishable_from": d.indistinguishable_from.iter().map(|&m| name(m)).collect::<Vec<_>>(),
            "exact": d.exact,
        }))
        .collect::<Vec<_>>())
}

pub fn terms_json(terms: &[TermFit]) -> Value {
    json!(terms
        .iter()
        .map(|t| json!({
            "layer": t.layer,
            "replaces": t.replaces,
            "factor": (t.factor * 1000.0).round() / 1000.0,
            "explained": (t.explained * 1000.0).round() / 1000.0,
        }))
        .collect::<Vec<_>>())
}

pub fn case_json(case: &CaseReport) -> Value {
    let d = &case.difference;
    let mut object = json!({
        "verdict": d.verdict.name(),
        "width": d.width,
        "height": d.height,
        "bounces": case.bounces,
        "scene": case.scene_name,
        "tolerance": case.tolerance,
        "differing_pixels": d.differing_pixels,
        "pixels_beyond_tolerance": d.beyond_tolerance,
        "max_difference": d.max_difference,
        "worst_pixel": d.worst_pixel.map(|(x, y)| json!([x, y])),
        "bounds": d.bounds.map(|(x0, y0, x1, y1)| json!([x0, y0, x1, y1])),
        "diagnosis": diagnosis_json(&case.diagnosis),
    });
    if !case.terms.is_empty() {
        object["terms"] = terms_json(&case.terms);
    }
    object
}
