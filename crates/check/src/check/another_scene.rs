//! An image of another scene checked against the default one (no `-i`): nearly every pixel
//! differs and no catalogued mistake explains it, so the diagnosis would be nonsense (spheres
//! "not written yet", a reflectivity factor). Said first, with the scenes a Tick 1* image is of.

use super::difference::Difference;
use super::Findings;

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
