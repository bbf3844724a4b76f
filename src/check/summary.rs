//! The opening lines of every report of a check (text, `--report`, `--view`): where the
//! student is, and, when no catalogued candidate explains the images well, that fact and what
//! does explain most, before any weak candidate.

use super::{Findings, GOOD_EXPLANATION};
use crate::numbers::plain;

/// The explanations beyond the catalogue (numbers and terms), best first, each as "what:
/// reproduces N% of the differing pixels".
pub fn fits(findings: &Findings) -> Vec<String> {
    let mut fits: Vec<(f64, String)> = findings
        .parameters
        .iter()
        .map(|p| (p.explained, p.sentence()))
        .chain(findings.terms.iter().map(|t| (t.explained, t.sentence())))
        .collect();
    fits.sort_by(|a, b| b.0.total_cmp(&a.0));
    fits.into_iter()
        .map(|(explained, sentence)| {
            format!(
                "{sentence}: reproduces {}% of the differing pixels",
                plain(100.0 * explained)
            )
        })
        .collect()
}

/// The progress line, then, when the catalogue explains little, what explains most.
pub fn opening(findings: &Findings) -> Vec<String> {
    let mut lines = vec![findings.progress.sentence()];
    if !findings.weak() {
        return lines;
    }
    let good = plain(100.0 * GOOD_EXPLANATION);
    let fits = fits(findings);
    match fits.first() {
        Some(_) => {
            lines.push(format!(
                "no catalogued mistake explains {good}% of the differing pixels; what explains most:"
            ));
            lines.extend(fits.iter().take(3).map(|fit| format!("  {fit}")));
        }
        None if !findings.diagnosis.is_empty() => lines.push(format!(
            "no catalogued mistake explains {good}% of the differing pixels, and no term or number of the model does"
        )),
        None => {}
    }
    lines
}

/// The heading of the candidate list: plain when the best is good, marked weak otherwise.
pub fn candidates_heading(findings: &Findings) -> String {
    if findings.weak() {
        format!(
            "weak candidates (each explains less than {}%), best first:",
            plain(100.0 * GOOD_EXPLANATION)
        )
    } else {
        "diagnosis, best first:".to_string()
    }
}
