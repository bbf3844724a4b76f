//! An image of another scene checked against the default one (no `-i`): nearly every pixel
//! differs and no catalogued mistake explains it, so the diagnosis would be nonsense (spheres
//! "not written yet", a reflectivity factor). Said first, with the scenes a Tick 1* image is of,
//! and in place of that diagnosis: the report keeps the note and the verdict.

use super::difference::Difference;
use super::{CaseReport, Findings};
use crate::mistakes::Mistakes;
use whitted_core::course::Course;

/// Share of pixels differing at which an unexplained image is likely of another scene.
pub const NEARLY_EVERY: f64 = 0.9;

/// The note for an image checked with no scene given whose differences nearly cover it and
/// that no catalogued mistake explains; None otherwise.
pub fn note(difference: &Difference, findings: &Findings, scene_given: bool) -> Option<String> {
    let share = difference.differing_pixels as f64 / difference.pixels().max(1) as f64;
    if scene_given || share < NEARLY_EVERY || !findings.weak() {
        return None;
    }
    Some(format!(
        "{:.0}% of pixels differ from the default scene and no catalogued mistake explains it: \
         is this another scene? give -i SCENE (a Tick 1* image: -i bump.xml, or -i \
         distributed.xml)",
        100.0 * share
    ))
}

/// The findings as the report gives them: when the note is said, only it, for what the
/// diagnosis says (the stages not written, a reflectivity factor) assumes the default scene
/// and would contradict it, and `case` keeps no diagnosis either; else `findings` as they are.
pub fn findings(
    case: &mut CaseReport,
    findings: Findings,
    scene_given: bool,
    course: Course,
) -> Findings {
    match note(&case.difference, &findings, scene_given) {
        Some(note) => {
            case.diagnosis.clear();
            case.hidden_mistakes = Mistakes::NONE;
            Findings::of_another_scene(note, course)
        }
        None => findings,
    }
}
