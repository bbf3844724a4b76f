//! Which of the year's scenes, at how many bounces, an uploaded image is: the student says so
//! with the select beside each file, or leaves it to be recognised. An image is only ever
//! checked against the scene it is: a correct test2.png checked as test1.xml reads as a
//! wholesale failure, and a correct `-b 0` render checked at 2 bounces as "reflection not
//! written yet", which the staff page would then count as the class's mistake.

use std::path::Path;

use whitted_check::check::star_option;
use whitted_check::check::suite::{cases_of, Role, SuiteCase};
use whitted_core::course::Course;

/// What the student chose for one image.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Choice {
    /// Try each of the year's scenes and take the one the image is.
    Recognise,
    /// This scene file at these bounces.
    Case { file: String, bounces: u32 },
}

/// The form's value for "recognise it".
pub const RECOGNISE: &str = "recognise";

/// The course's own image cases of `course` (test1.xml at 0, 1 and 2 bounces, test2.xml...),
/// in the order the suite runs them, then the later years' Tick 1* handout scenes (bump.xml,
/// distributed.xml), judged as `check --star` judges them: the choices the form offers.
pub fn cases(course: Course) -> Vec<SuiteCase> {
    let mut cases: Vec<SuiteCase> = cases_of(course)
        .into_iter()
        .filter(|c| c.role == Role::Course)
        .collect();
    if !course.is_default() {
        cases.extend(star_option::cases(course));
    }
    cases
}

/// The words for a case in the form: `test1.xml at 2 bounces`, `bump.xml (Tick 1*)`.
pub fn case_label(case: &SuiteCase) -> String {
    match case.role {
        Role::Star(_) => format!("{} (Tick 1*)", case.file),
        _ => label(&case.file, case.bounces),
    }
}

/// The form value of a case: `test1.xml:2`.
pub fn value(case: &SuiteCase) -> String {
    format!("{}:{}", case.file, case.bounces)
}

/// The words for a case: `test1.xml at 2 bounces`.
pub fn label(file: &str, bounces: u32) -> String {
    match bounces {
        1 => format!("{file} at 1 bounce"),
        b => format!("{file} at {b} bounces"),
    }
}

/// The choice a form value names, for `course`; None for a value no choice of the year has.
pub fn parse(value: &str, course: Course) -> Option<Choice> {
    if value == RECOGNISE {
        return Some(Choice::Recognise);
    }
    cases(course)
        .iter()
        .find(|c| self::value(c) == value)
        .map(|c| Choice::Case {
            file: c.file.to_string(),
            bounces: c.bounces,
        })
}

/// Where the choice of the `i`-th image is kept beside it (none kept: recognise).
pub fn stored_name(i: usize) -> String {
    format!("image-{}.scene", i + 1)
}

/// The choice kept for the `i`-th image in `dir`.
pub fn read(dir: &Path, i: usize, course: Course) -> Choice {
    std::fs::read_to_string(dir.join(stored_name(i)))
        .ok()
        .and_then(|v| parse(v.trim(), course))
        .unwrap_or(Choice::Recognise)
}

/// The cases an image is checked against for `choice`: the one chosen, or every one.
pub fn candidates(choice: &Choice, course: Course) -> Vec<SuiteCase> {
    cases(course)
        .into_iter()
        .filter(|c| match choice {
            // A Tick 1* screenshot is only judged as one when the student says it is one.
            Choice::Recognise => c.role == Role::Course,
            Choice::Case { file, bounces } => c.file == file.as_str() && c.bounces == *bounces,
        })
        .collect()
}

/// Whether an image with `beyond` of `total` pixels off by more than the tolerance is plainly
/// not the scene it was checked against: no mistake of the catalogue changes nine pixels in
/// ten (a missing plane or shadow leaves the spheres and the sky), while another scene does.
pub fn plainly_another(beyond: usize, total: usize) -> bool {
    total > 0 && beyond * 10 >= total * 9
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_choices_are_the_years_own_scenes_and_round_trip() {
        let offered: Vec<String> = cases(Course::Y2023).iter().map(value).collect();
        assert_eq!(
            offered[..4],
            ["test1.xml:0", "test1.xml:1", "test1.xml:2", "test2.xml:2"]
        );
        assert!(offered[4..].iter().any(|v| v.starts_with("bump.xml:")));
        assert_eq!(candidates(&Choice::Recognise, Course::Y2023).len(), 4);
        assert_eq!(
            parse("test2.xml:2", Course::Y2023),
            Some(Choice::Case {
                file: "test2.xml".into(),
                bounces: 2
            })
        );
        assert_eq!(parse("test2.xml:2", Course::Y2017), None);
        assert_eq!(parse("../x:9", Course::Y2023), None);
        assert_eq!(parse(RECOGNISE, Course::Y2016), Some(Choice::Recognise));
        assert_eq!(candidates(&Choice::Recognise, Course::Y2016).len(), 5);
        assert_eq!(label("test1.xml", 1), "test1.xml at 1 bounce");
        assert!(plainly_another(480_000, 480_000));
        assert!(!plainly_another(200_000, 480_000));
    }
}
