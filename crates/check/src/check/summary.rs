//! The opening lines of every report of a check (text, `--report`, `--view`): where the
//! student is, and, when no catalogued candidate explains the images well, that fact and what
//! does explain most, before any weak candidate.

use super::diagnose::Diagnosis;
use super::difference::Difference;
use super::{Findings, GOOD_EXPLANATION};
use crate::mistakes::{Bug, Mistakes};
use whitted_core::numbers::plain;

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

/// The progress line, what the program is or why its cases died (a Tick 1* program, a class
/// that did not compile), then, when the catalogue explains little, what explains most.
pub fn opening(findings: &Findings) -> Vec<String> {
    // A Tick 1* program's options' scenes say nothing of the Tick 1 stages: what was run.
    if let Some(star) = findings.tick1_star.as_ref().filter(|s| s.plan.is_some()) {
        return vec![star.sentence()];
    }
    // A Tick 1* image: the options' progress and option 1's verdict, with where and fix for
    // a mistake; Tick 1's stages and diagnosis say nothing of it.
    // An image of another scene: the note alone; Tick 1's stages would read the default
    // scene's.
    if let Some(note) = &findings.another_scene {
        return vec![note.clone()];
    }
    if let (Some(progress), Some(verdict)) = (super::star_fix::progress(findings), &findings.bump) {
        let mut lines = vec![progress];
        lines.extend(super::star_fix::verdict_lines(verdict));
        return lines;
    }
    let mut lines = vec![findings.progress.sentence()];
    lines.extend(findings.progress.next());
    // What the program is, or why its cases died, before anything about its images.
    lines.extend(findings.tick1_star.as_ref().map(|star| star.sentence()));
    lines.extend(findings.missing_class.as_ref().map(|m| m.sentence()));
    if let Some(noise) = findings.not_reproducible {
        lines.push(noise.sentence());
        return lines;
    }
    if let Some(line) = common_variant(findings) {
        lines.push(line);
    }
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
    lines.extend(findings.outside.as_ref().map(|o| o.sentence()));
    lines
}

/// The image most finished projects of 2021-24 render (docs/courses.md, "A variant the
/// course's tester may accept"): the reflected ray moved along N and no N.L gate. Said when
/// the top explanation is exactly that pair in a year whose rules make both mistakes.
fn common_variant(findings: &Findings) -> Option<String> {
    let pair = Mistakes::of(&[Bug::NoGate, Bug::ReflectionBiasAlongN]);
    let course = findings.progress.course;
    let offered = pair.bugs().iter().all(|b| b.offered_in(course));
    let top = findings.diagnosis.first()?;
    let is_pair = top.mistakes == pair || top.indistinguishable_from.contains(&pair);
    (offered && is_pair && top.explained >= GOOD_EXPLANATION).then(|| {
        "this is the common variant: the image most finished projects of 2021-24 render \
         (the reflected ray moved along N, as the handout's words suggest, and no N.L gate); \
         the course's own tester may accept it, but both differ from the course's rules"
            .to_string()
    })
}

/// The heading of the candidate list: plain when the best is good, marked weak otherwise.
pub fn candidates_heading(findings: &Findings) -> String {
    if findings.settled_by_fit() {
        String::new()
    } else if findings.weak() {
        format!(
            "weak candidates (each explains less than {}%), best first:",
            plain(100.0 * GOOD_EXPLANATION)
        )
    } else {
        "diagnosis, best first:".to_string()
    }
}

/// How far a channel is off, in the student's terms.
pub fn largest(d: &Difference) -> String {
    format!("by up to {} of 255 in a channel", d.max_difference)
}

/// How the image differs, in one sentence.
pub fn difference_sentence(d: &Difference) -> String {
    let total = u64::from(d.width) * u64::from(d.height);
    format!(
        "{} of {total} pixels differ ({} by more than the tolerance), {}",
        d.differing_pixels,
        d.beyond_tolerance,
        largest(d)
    )
}

/// One diagnosis in words: each entry, where and how to fix it (only for a good explanation:
/// a weak candidate is no finding, and a fix under it would read as one), and what it
/// explains, then what the images cannot tell (`diagnosis_details`).
pub fn diagnosis_lines(d: &Diagnosis) -> Vec<String> {
    let mut lines = finding_lines(d);
    lines.extend(diagnosis_details(d));
    lines
}

/// The finding a student acts on, as the one-screen report gives it: each entry, where and
/// how to fix it, what it explains, and what the pixels rounding decides look like.
pub fn finding_lines(d: &Diagnosis) -> Vec<String> {
    let mut lines = Vec::new();
    let finding = d.explained >= GOOD_EXPLANATION;
    for (i, bug) in d.mistakes.bugs().into_iter().enumerate() {
        let and = if i == 0 { "" } else { "and " };
        lines.push(format!("{and}{}: {}", bug.id(), bug.description(d.course)));
        if finding {
            lines.extend(bug.advice(d.course).map(|line| format!("  {line}")));
        }
    }
    lines.push(format!(
        "explains {}% of the differing pixels ({} not explained; changes {} pixels you had right){}",
        plain(100.0 * d.explained),
        d.unexplained_pixels,
        d.wrongly_changed_pixels,
        if d.exact {
            ""
        } else {
            "; figures estimated from a sample of the pixels, not counted over the whole image"
        }
    ));
    if d.by_rounding > 0.0 {
        lines.push(format!(
            "{}% of the differing pixels can go either way with the last bits of P and the ray: {}",
            plain(100.0 * d.by_rounding),
            rounding_words(d.mistakes)
        ));
    }
    lines
}

/// What a diagnosis leaves open, for the full report: the entries its images cannot rule
/// out, and the candidates that render the same.
pub fn diagnosis_details(d: &Diagnosis) -> Vec<String> {
    let mut lines = Vec::new();
    for (i, bug) in d.image_identical_with.iter().enumerate() {
        if i == 0 {
            lines.push(format!(
                "the images cannot tell whether the program also has: {}",
                d.image_identical_with
                    .iter()
                    .map(|b| b.id())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        lines.push(format!(
            "  with {} in place, {} ({}) renders the same: if fixing it leaves a difference, look at {}: {}",
            d.mistakes.name(),
            bug.id(),
            bug.description(d.course),
            bug.place(),
            bug.fix(d.course)
        ));
    }
    if !d.indistinguishable_from.is_empty() {
        let twins: Vec<String> = d.indistinguishable_from.iter().map(|m| m.name()).collect();
        lines.push(format!(
            "renders these images exactly as: {}",
            twins.join(", ")
        ));
    }
    lines
}

/// What pixels that hinge on rounding look like, in plain words, for the entries that make them.
fn rounding_words(mistakes: Mistakes) -> &'static str {
    if mistakes.has(Bug::NoShadowBias) {
        "scattered dark pixels on lit surfaces: shadow acne (each surface point shadows itself, or not, by rounding)"
    } else if mistakes.has(Bug::NoReflectionBias) {
        "speckles in reflections: a reflected ray that starts on its surface sees that surface again, or not, by rounding"
    } else {
        "an offset too small to clear rounding: surfaces shadow or reflect themselves at scattered pixels"
    }
}
