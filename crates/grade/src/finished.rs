//! whitted's finished Tick 1 (`skeleton/tick1/finished/`: a correct `Sphere`, `Plane` and
//! `Renderer` of each year, written from the handout's method, never from the course's code).
//!
//! The Tick 1* handout asks a student to submit the one file their option changes
//! (`BumpySphere.java` for option 1, `Renderer.java` for option 2) and a screenshot, not their
//! whole Tick 1 (docs/tick1star.md). Such a hand-in cannot compile alone: grade completes it with
//! these classes, so that the option's file is judged as the ticker judges it, on a Tick 1 that
//! works. A student's own copy of any of the three always wins over ours.

use whitted_core::course::Course;

use super::skeleton;

/// The files a later year's submission gives that grade can supply, and their finished text.
const FINISHED: [(&str, &str); 3] = [
    (
        "Plane.java",
        include_str!("../skeleton/tick1/finished/Plane.java"),
    ),
    (
        "Renderer.java",
        include_str!("../skeleton/tick1/finished/Renderer.java"),
    ),
    (
        "Sphere.java",
        include_str!("../skeleton/tick1/finished/Sphere.java"),
    ),
];

/// whitted's finished `name` (`Plane.java`, `Renderer.java` or `Sphere.java`) of `course`, in
/// the skeleton's placeholder package (`skeleton::TICK1_PACKAGE`), or None for another name or
/// 2016-17 (whose Tick 2 hand-in is always whole).
pub fn source(name: &str, course: Course) -> Option<Vec<u8>> {
    if course.is_default() {
        return None;
    }
    let (_, text) = FINISHED.iter().find(|(n, _)| *n == name)?;
    // The templates are tested for every year below: a failure here is a build's mistake.
    Some(for_year(text, course).ok()?.into_bytes())
}

/// `text`, a finished Tick 1 template (ours, or the tests' student edits of it), as `course`'s
/// student has it: the year's API selected and `${YEAR}` (the year whose rules `Renderer`
/// follows) filled in. The one rule for both, so a test's student is ours edited, never a copy.
pub fn for_year(text: &str, course: Course) -> Result<String, String> {
    Ok(skeleton::select(text, course)?.replace("${YEAR}", course.name()))
}

/// The report's note on a hand-in of `handed` alone, completed with ours of `missing`.
pub fn note(handed: &[&str], missing: &[&str], course: Course) -> String {
    format!(
        "A Tick 1* hand-in of {} alone, as the handout asks: {} {} whitted's finished Tick 1 \
         of {course} (correct, in the student's package), so the option is judged on a Tick 1 \
         that works, as a ticker judges the screenshot",
        handed.join(" and "),
        missing.join(", "),
        if missing.len() == 1 { "is" } else { "are" },
    )
}

/// The feedback's words for a hand-in completed with ours of `missing`.
pub fn feedback(missing: &[&str]) -> String {
    format!(
        "(judged on whitted's finished Tick 1 in place of {}, not handed in)",
        missing.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_later_year_has_each_finished_file_in_its_own_api() {
        for course in Course::ALL.into_iter().filter(|c| !c.is_default()) {
            for (name, _) in FINISHED {
                let text = source(name, course).expect("finished file");
                let text = String::from_utf8(text).expect("utf-8");
                assert!(!text.contains("//@"), "{course} {name}: a marker left");
                assert!(!text.contains("${"), "{course} {name}: a placeholder left");
                assert!(
                    text.starts_with(&format!("package {};", skeleton::TICK1_PACKAGE)),
                    "{course} {name}"
                );
            }
            let renderer = String::from_utf8(source("Renderer.java", course).expect("renderer"))
                .expect("utf-8");
            assert!(renderer.contains(&format!("\"{}\"", course.name())));
            // The tone map is the course's from 2018-19 (T2) on only.
            assert_eq!(
                renderer.contains("tonemap(linearRGB)"),
                course >= Course::Y2018,
                "{course}"
            );
            let sphere =
                String::from_utf8(source("Sphere.java", course).expect("sphere")).expect("utf-8");
            assert_eq!(
                sphere.contains("ColorRGB transmittance)"),
                course == Course::Y2023
            );
        }
        assert!(source("Renderer.java", Course::Y2016).is_none());
        assert!(source("BumpySphere.java", Course::Y2021).is_none());
    }
}
