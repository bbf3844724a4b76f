//! The diagnosis under the later years' rules (docs/courses.md): each year's own expected
//! images check as identical, and each entry the year's catalogue offers, rendered over the
//! year's suite, is named first wherever the year's scenes show it.

use super::*;
use crate::check::suite::{cases_of, SuiteCase};
use crate::mistakes::{Bug, Mistakes, Number, Parameter, Variant};
use whitted_core::scene::input::parse_for_course;

/// The default rule: 2 of 255 in a channel, no pixel beyond.
const STRICT: PassRule = PassRule::strict(2);

/// The size the tests render at: the year's aspect, a quarter of its width, so that the
/// whole catalogue runs in seconds.
fn size(course: Course) -> (u32, u32) {
    let (w, h) = course.size();
    (w / 4, h / 4)
}

fn scene_of(case: &SuiteCase) -> Scene {
    parse_for_course(&case.file, case.xml.as_bytes(), case.course)
        .expect("the course's scene")
        .0
}

/// The findings over `course`'s suite for a program with `mistakes`, and whether any case
/// fails.
fn suite_findings(course: Course, mistakes: Mistakes) -> (Findings, bool) {
    let (w, h) = size(course);
    let suite = cases_of(course);
    let scenes: Vec<Scene> = suite.iter().map(scene_of).collect();
    let mut prepared = Vec::new();
    let mut all_pass = true;
    for (case, scene) in suite.iter().zip(&scenes) {
        let r = Renderer::new(scene, w, h, case.bounces)
            .expect("renderer")
            .in_course(course);
        let image = r.variant_image(&Variant::from(mistakes)).expect("image");
        let (c, report) = prepare(
            scene,
            &case.file,
            case.bounces,
            STRICT,
            image,
            suite.len(),
            None,
            course,
        )
        .expect("case");
        all_pass &= report.difference.verdict.passes();
        prepared.push(c);
    }
    (
        find(&prepared, all_pass, course).expect("findings"),
        !all_pass,
    )
}

#[test]
fn each_year_s_expected_images_check_identical() {
    let years = [
        (Course::Y2019, "2019-20", "test1"),
        (Course::Y2019, "2019-20", "test2"),
        (Course::Y2020, "2020-21", "test1"),
        (Course::Y2021, "2021-24", "test1"),
        (Course::Y2023, "2021-24", "test2"),
    ];
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../reference/courses");
    for (course, dir, test) in years {
        let png = std::path::PathBuf::from(format!("{root}/{dir}/{test}_reference.png"));
        let student = student_png::read(&png).expect("the course's image");
        let case = cases_of(course)
            .into_iter()
            .find(|c| c.file.starts_with(test) && c.bounces == 2)
            .expect("in the suite");
        let scene = scene_of(&case);
        let (report, findings) =
            check_image(&scene, &case.file, 2, STRICT, student, course).expect("check");
        assert_eq!(report.difference.differing_pixels, 0, "{course} {test}");
        assert!(findings.diagnosis.is_empty());
        let keys: Vec<&str> = findings
            .progress
            .stages
            .iter()
            .map(|(s, _)| s.key(course))
            .collect();
        assert_eq!(
            keys,
            ["spheres", "shading", "planes", "shadows", "reflection"]
        );
    }
}

#[test]
fn every_offered_entry_that_shows_is_named_first_in_each_year() {
    for course in [Course::Y2019, Course::Y2020, Course::Y2021] {
        let mut named = 0;
        let mut hidden = Vec::new();
        for bug in Bug::offered(course) {
            let wanted = Mistakes::of(&[bug]);
            let (findings, fails) = suite_findings(course, wanted);
            if !fails {
                hidden.push(bug.id());
                continue;
            }
            let top = findings.diagnosis.first().expect("a diagnosis");
            assert!(
                top.mistakes == wanted || top.indistinguishable_from.contains(&wanted),
                "{course}: {} named as {}",
                bug.id(),
                top.mistakes.name()
            );
            named += 1;
        }
        assert!(
            named >= 15,
            "{course}: only {named} entries show on the year's scenes"
        );
    }
}

#[test]
fn the_common_variant_of_2021_24_is_named_as_both_mistakes() {
    // Reflection moved along N and no N.L gate: most finished projects (docs/courses.md).
    let wanted = Mistakes::of(&[Bug::ReflectionBiasAlongN, Bug::NoGate]);
    let (findings, fails) = suite_findings(Course::Y2021, wanted);
    assert!(fails);
    let top = findings.diagnosis.first().expect("a diagnosis");
    assert!(
        top.mistakes == wanted || top.indistinguishable_from.contains(&wanted),
        "{}",
        top.mistakes.name()
    );
}

#[test]
fn the_years_rules_are_not_offered_as_mistakes() {
    let later = Bug::offered(Course::Y2021);
    for rule in [
        Bug::ViewFromRayOrigin,
        Bug::SpecularGated,
        Bug::SphereFarRoot,
        Bug::ShadowBiasAlongN,
    ] {
        assert!(!later.contains(&rule), "{}", rule.id());
    }
    assert!(later.contains(&Bug::ShadowBiasAlongL));
    assert!(Bug::offered(Course::Y2019).contains(&Bug::ShadowBiasAlongN));
    assert_eq!(Bug::offered(Course::Y2016).len(), 26);
    assert!(!Bug::offered(Course::Y2016).contains(&Bug::ViewToCamera));
}

#[test]
fn candidates_replaying_the_course_s_searches_render_what_searching_renders() {
    // Every year, every scene of its suite, every entry and pair of its catalogue, and the
    // fitted offset: the bytes with the course's recorded searches answering the rays they
    // hold are the bytes with every ray searched. An entry that changes a hit but is let
    // through as intersecting as the course does fails here.
    let mut replayed = 0;
    for course in Course::ALL {
        let (w, h) = (size(course).0 / 2, size(course).1 / 2);
        let catalogue = Bug::offered(course);
        let mut variants: Vec<Variant> = Vec::new();
        for (i, &a) in catalogue.iter().enumerate() {
            variants.push(Variant::from(Mistakes::of(&[a])));
            for &b in &catalogue[i + 1..] {
                if !a.excludes(b) {
                    variants.push(Variant::from(Mistakes::of(&[a, b])));
                }
            }
        }
        variants.push(Variant {
            number: Some(Number {
                parameter: Parameter::Epsilon,
                value: 1e-3,
            }),
            ..Variant::default()
        });
        for case in cases_of(course) {
            let scene = scene_of(&case);
            let r = Renderer::new(&scene, w, h, case.bounces)
                .expect("renderer")
                .in_course(course);
            // Every seventh pixel: spread over the whole image, a few seconds for all.
            let pixels: Vec<(u32, u32)> = (0..w * h).step_by(7).map(|i| (i % w, i / w)).collect();
            let tapes = r.searches_at(&pixels).expect("searches");
            for v in &variants {
                let frame = r.frame(v.mistakes).expect("frame");
                let searched = r.bytes_at(v, &frame, &pixels).expect("bytes");
                let shared = r.bytes_replaying(v, &frame, &pixels, Some(&tapes));
                assert!(
                    shared.expect("bytes") == searched,
                    "{course:?} {} b{}: {v:?}",
                    case.file,
                    case.bounces
                );
                replayed += usize::from(v.intersects_as_course());
            }
        }
    }
    assert!(replayed > 1000, "{replayed} candidates replayed");
}
