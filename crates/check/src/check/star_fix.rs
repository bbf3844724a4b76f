//! Where each Tick 1* bump mistake lives in a student's program and what line to change: the
//! one table the text, JSON and HTML reports and `--list-bugs` read, as `mistakes.rs` is for
//! Tick 1. The option's progress line replaces Tick 1's stages for a Tick 1* image, whose
//! stages say nothing of the options.

use super::bump::BumpFinding;
use super::bump_judge::BumpVerdict;
use super::star_option::StarOption;
use super::Findings;
use whitted_core::star::BumpMistake;

/// The method a bump mistake is in, and the change that fixes it.
pub fn place_and_fix(m: BumpMistake) -> (&'static str, &'static str) {
    const METHOD: &str = "BumpySphere.getNormalAt";
    let fix = match m {
        BumpMistake::Inverted => {
            "flip the sign of the perturbation: n' = n + B_u (n x P_v) - B_v (n x P_u) as the \
             handout writes it, with B_u = h[u+1] - h[u] and B_v = h[v+1] - h[v]"
        }
        BumpMistake::SwappedGradients => {
            "pair B_u with n x P_v and B_v with n x P_u in the line that sums the perturbation"
        }
        BumpMistake::UnnormalisedTangents => {
            "normalise P_u and P_v (.normalised()) where they are computed, before the cross products"
        }
        BumpMistake::UnnormalisedResult => "return the perturbed normal normalised: n'.normalised()",
        BumpMistake::WrongTexel => {
            "read the texel to the right / below: B_u = h[u+1][v] - h[u][v], B_v = h[u][v+1] - h[u][v]"
        }
        BumpMistake::ColourAsHeight => {
            "mask the colour to its blue byte where the map is read: (getRGB(x, y) & 0xFF) * 5 / 255"
        }
        BumpMistake::NoCentre => {
            "take n as position.subtract(getPosition()).normalised() (or super.getNormalAt(position))"
        }
    };
    (METHOD, fix)
}

/// The where and fix lines of a bump finding that names a mistake; none when it passes or
/// nothing reproduces the image.
pub fn lines(finding: &BumpFinding) -> Vec<String> {
    match finding.mistake {
        Some(m) if finding.matched >= super::bump::FOLLOWS => where_and_fix(m),
        _ => Vec::new(),
    }
}

/// The where and fix lines of `m`.
fn where_and_fix(m: BumpMistake) -> Vec<String> {
    let (place, fix) = place_and_fix(m);
    vec![format!("where: {place}"), format!("fix: {fix}")]
}

/// Option 1's verdict in the report's lines: what it is, then, for a mistake (of a
/// deterministic image or of a draw), where it is and the line to change.
pub fn verdict_lines(verdict: &BumpVerdict) -> Vec<String> {
    match verdict {
        BumpVerdict::NotDone => vec![super::star_not_done::sentence(StarOption::Bump, false)],
        BumpVerdict::Rendered(f) => std::iter::once(f.sentence()).chain(lines(f)).collect(),
        BumpVerdict::Drawn(d) => std::iter::once(d.sentence())
            .chain(d.mistake.into_iter().flat_map(where_and_fix))
            .collect(),
    }
}

/// What the case's bytes were compared with, where `verdict` decides it rather than they
/// (`BumpVerdict::decides`): the render its reference is.
pub fn compared_with(verdict: &BumpVerdict) -> &'static str {
    match verdict {
        BumpVerdict::NotDone => "the scene's Tick 1 render",
        BumpVerdict::Drawn(_) => {
            "the handout's method rendered with no soft shadows or depth of field, which no \
             random image equals"
        }
        BumpVerdict::Rendered(_) => "the handout's method's render",
    }
}

/// Whether the findings are of a Tick 1* image (bump mapping), whose report has no Tick 1
/// stages or diagnosis.
pub fn is_star_image(findings: &Findings) -> bool {
    findings.bump.is_some()
}

/// The progress of the options shown by a Tick 1* image: option 1's state as the image shows
/// it; option 2 is not shown by a bump image, unless it is a draw with both options on (then
/// it is on, and judged on distributed.xml's image).
pub fn progress(findings: &Findings) -> Option<String> {
    let verdict = findings.bump.as_ref()?;
    let option2 = match verdict {
        BumpVerdict::Drawn(_) => "on in this image too (judged on distributed.xml's image)",
        _ => "not shown by this image",
    };
    Some(format!(
        "progress: option 1 (bump mapping) {}; option 2 (distributed ray tracing) {option2}",
        verdict.progress()
    ))
}

/// The `--list-bugs` section of Tick 1*: each bump mistake's name, where and fix.
pub fn list() -> Vec<String> {
    let mut lines = vec!["Tick 1* option 1 (bump mapping, check -i bump.xml):".to_string()];
    for m in BumpMistake::ALL {
        let (place, fix) = place_and_fix(m);
        lines.push(format!("  {:<28} {}", m.name(), m.explanation()));
        lines.push(format!("  {:<28} where: {place}; fix: {fix}", ""));
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_bump_mistake_has_a_place_and_a_fix_in_the_list() {
        let list = list().join("\n");
        for m in BumpMistake::ALL {
            let (place, fix) = place_and_fix(m);
            assert_eq!(place, "BumpySphere.getNormalAt");
            assert!(
                list.contains(m.name()) && list.contains(fix),
                "{}",
                m.name()
            );
        }
    }

    #[test]
    fn an_inverted_relief_says_where_and_what_to_change() {
        let finding = BumpFinding {
            parametrisation: "y-zx",
            mistake: Some(BumpMistake::Inverted),
            matched: 0.995,
            matched_correct: 0.6,
            tried: 32,
        };
        let lines = lines(&finding);
        assert_eq!(lines[0], "where: BumpySphere.getNormalAt");
        assert!(lines[1].starts_with("fix: flip the sign"), "{}", lines[1]);
        let passing = BumpFinding {
            mistake: None,
            ..finding
        };
        assert!(super::lines(&passing).is_empty());
    }
}
