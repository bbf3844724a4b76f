//! The catalogue in each year's own words (docs/courses.md: "The `where` and `fix` texts use
//! that year's names"). The catalogue is written once, in 2016-17's `gfx.tick2` names; from
//! 2017-18 colours are `ColorRGB`s, the exponent is `getPhong_alpha`, and the shipped
//! `illuminate` names the light's distance `distanceToLight`. One table of phrases rewrites
//! every text for the later years, so that no entry is written twice; a second rewrites the
//! shadow ray's offset for the years that move it along N (2020-21 on).

use std::borrow::Cow;

use whitted_core::course::{Course, ShadowBias, View};

/// 2016-17's phrase, and the later years'. Replaced in one pass from left to right, the first
/// phrase of the table that starts at a place winning, so a replacement is never read again.
const LATER: [(&str, &str); 14] = [
    ("Vector3 colour", "ColorRGB colour"),
    ("Vector3 I ", "ColorRGB I "),
    ("Vector3 diffuse", "ColorRGB diffuse"),
    ("Vector3 specular", "ColorRGB specular"),
    ("new Vector3(0)", "new ColorRGB(0)"),
    ("getPhong_n()", "getPhong_alpha()"),
    ("d = |X - P|", "distanceToLight = |light.getPosition() - P|"),
    ("X - P", "light.getPosition() - P"),
    ("getIlluminationAt(d)", "getIlluminationAt(distanceToLight)"),
    ("getDistance() < d", "getDistance() < distanceToLight"),
    ("nearer than d", "nearer than distanceToLight"),
    (
        "the shadow test (inShadow is never set)",
        "the shadow test (no shadow ray is cast)",
    ),
    (
        "inShadow stays false: the shadow stage not written yet",
        "no shadow ray is cast: the shadow stage not written yet",
    ),
    (
        "the specular term is white: I kS max(0, R.V)^n, without C",
        "the specular term has the light's colour, not the object's: C_spec I kS max(0, R.V)^n, without C",
    ),
];

/// The shadow ray's offset as the years whose rule moves it along N (2020-21 on) write it.
const ALONG_N: [(&str, &str); 2] = [
    ("cast Ray(P + EPSILON L, L)", "cast Ray(P + EPSILON N, L)"),
    (
        "start it EPSILON along L: Ray shadowRay = new Ray(P.add(L.scale(EPSILON)), L);",
        "start it EPSILON along N: Ray shadowRay = new Ray(P.add(N.scale(EPSILON)), L);",
    ),
];

/// The view direction as the years whose V points to the origin of the ray that found the
/// point (2017-18 on) write it: there `normalise(-P)` is itself a mistake (`view-to-camera`),
/// so no fix may send a student to it.
const FROM_RAY_ORIGIN: [(&str, &str); 2] = [
    (
        "V = normalise(P) instead of normalise(-P)",
        "V = normalise(P) instead of normalise(O - P), towards the origin O of the ray that found P",
    ),
    (
        "V = normalise(-P): Vector3 V = P.scale(-1).normalised();",
        "V = normalise(O - P): Vector3 V = O.subtract(P).normalised();",
    ),
];

/// `text` (a catalogue text in 2016-17's names) in `course`'s names.
pub fn in_year(text: &'static str, course: Course) -> Cow<'static, str> {
    if course.is_default() {
        return Cow::Borrowed(text);
    }
    let rules = course.rules();
    let named = replaced(Cow::Borrowed(text), &LATER);
    let named = match rules.view {
        View::FromRayOrigin => replaced(named, &FROM_RAY_ORIGIN),
        View::ToCamera => named,
    };
    match rules.shadow_bias {
        ShadowBias::AlongN => replaced(named, &ALONG_N),
        _ => named,
    }
}

/// `text` with every phrase of `table` replaced in one pass.
fn replaced(text: Cow<'static, str>, table: &[(&str, &str)]) -> Cow<'static, str> {
    if !table.iter().any(|(from, _)| text.contains(from)) {
        return text;
    }
    let text = text.as_ref();
    let mut out = String::with_capacity(text.len() + 32);
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        match table.iter().find(|(from, _)| rest.starts_with(from)) {
            Some((from, to)) => {
                out.push_str(to);
                rest = &rest[from.len()..];
            }
            None => {
                out.push(c);
                rest = &rest[c.len_utf8()..];
            }
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mistakes::Bug;

    #[test]
    fn the_later_years_read_their_own_names_and_2016_17_its_own() {
        let no_shadows = Bug::NoShadows;
        assert!(no_shadows
            .description(Course::Y2016)
            .contains("inShadow stays false"));
        let later = no_shadows.description(Course::Y2019);
        assert!(!later.contains("inShadow"), "{later}");
        assert!(!no_shadows.looks_like(Course::Y2019).contains("inShadow"));
        // The shadow ray's offset is the year's: along L until 2019-20, along N after.
        assert!(no_shadows.fix(Course::Y2019).contains("P + EPSILON L, L"));
        assert!(no_shadows.fix(Course::Y2020).contains("P + EPSILON N, L"));
        assert!(Bug::NoShadowBias
            .fix(Course::Y2021)
            .contains("new Ray(P.add(N.scale(EPSILON)), L)"));
        assert!(Bug::NoShadowBias
            .fix(Course::Y2016)
            .contains("new Ray(P.add(L.scale(EPSILON)), L)"));
        // From 2017-18 V points to the ray's origin: the fix of a flipped V says so, never
        // normalise(-P), which is that year's view-to-camera mistake.
        assert!(Bug::ViewFlipped
            .fix(Course::Y2016)
            .contains("P.scale(-1).normalised()"));
        for course in Course::ALL.into_iter().filter(|c| !c.is_default()) {
            let fix = Bug::ViewFlipped.fix(course);
            assert!(
                fix.contains("Vector3 V = O.subtract(P).normalised();")
                    && !fix.contains("scale(-1)"),
                "{course}: {fix}"
            );
            assert!(Bug::ViewFlipped
                .description(course)
                .contains("instead of normalise(O - P)"));
        }
        let fix = no_shadows.fix(Course::Y2023);
        assert!(
            fix.contains("nearer than distanceToLight = |light.getPosition() - P|"),
            "{fix}"
        );
        assert!(Bug::NoAmbient
            .looks_like(Course::Y2017)
            .contains("ColorRGB colour = new ColorRGB(0)"));
        assert!(Bug::NoAmbient
            .looks_like(Course::Y2016)
            .contains("Vector3 colour = new Vector3(0)"));
        // No later year's text keeps a colour as a Vector3 or 2016-17's exponent getter.
        for course in Course::ALL.into_iter().filter(|c| !c.is_default()) {
            for bug in Bug::ALL.into_iter().filter(|b| b.offered_in(course)) {
                for text in [
                    bug.description(course),
                    bug.looks_like(course),
                    bug.fix(course),
                ] {
                    for old in [
                        "Vector3 colour",
                        "Vector3 I ",
                        "Vector3 diffuse",
                        "Vector3 specular",
                        "getPhong_n",
                        "|X - P|",
                    ] {
                        assert!(!text.contains(old), "{course} {}: {text}", bug.id());
                    }
                }
            }
        }
    }
}
