//! The diagnosis on whitted's own renders of the catalogue: every entry named first where it
//! shows, combinations of two and three found over the suite, the model's numbers fitted, and
//! the progress read per stage.

use super::*;
use crate::check::difference::Verdict;
use crate::check::image_cache::ImageCache;
use crate::check::progress::StageState;
use crate::check::suite::{cases, SuiteCase};
use crate::mistakes::{Bug, Mistakes, Number, Parameter, Stage, Variant};

/// The default rule: 2 of 255 in a channel, no pixel beyond.
const STRICT: PassRule = PassRule::strict(2);

/// The first suite case on which `mistakes` fails, each of its entries showing, with its
/// image.
fn failing_case(mistakes: Mistakes) -> (SuiteCase, Scene, Rgb8) {
    for case in cases() {
        let scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
        let r = Renderer::new(&scene, 640, 480, case.bounces).expect("renderer");
        let image = r.image(mistakes).expect("image");
        let fails =
            difference(&image, &r.reference().expect("reference"), STRICT).beyond_tolerance > 0;
        let members = mistakes.bugs();
        let each_shows = members.len() == 1
            || members
                .iter()
                .all(|&b| r.image(Mistakes::of(&[b])).expect("image") != image);
        if fails && each_shows {
            return (case, scene, image);
        }
    }
    panic!("{mistakes:?} fails no case");
}

/// Whether `wanted` is the top diagnosis or indistinguishable from it.
fn named_first(diagnosis: &[Diagnosis], wanted: Mistakes) -> bool {
    diagnosis
        .first()
        .is_some_and(|d| d.mistakes == wanted || d.indistinguishable_from.contains(&wanted))
}

/// Fails unless `wanted` (or a twin of it) is among the first three.
fn assert_in_top_three(diagnosis: &[Diagnosis], wanted: Mistakes) {
    let top3: Vec<&Diagnosis> = diagnosis.iter().take(3).collect();
    assert!(
        top3.iter()
            .any(|d| d.mistakes == wanted || d.indistinguishable_from.contains(&wanted)),
        "{}: {:?}",
        wanted.name(),
        top3.iter().map(|d| d.mistakes.name()).collect::<Vec<_>>()
    );
}

/// Every suite case's scene and whitted's render of `variant` there, as a student's program
/// with those mistakes writes it.
fn suite_images(variant: Variant) -> Vec<(SuiteCase, Scene, Rgb8)> {
    cases()
        .into_iter()
        .map(|case| {
            let scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
            let r = Renderer::new(&scene, 640, 480, case.bounces).expect("renderer");
            let image = r.variant_image(&variant).expect("image");
            (case, scene, image)
        })
        .collect()
}

/// The findings of `check --program` over the suite's images.
fn suite_findings(images: &[(SuiteCase, Scene, Rgb8)]) -> Findings {
    let (prepared, reports): (Vec<Case>, Vec<CaseReport>) = images
        .iter()
        .map(|(case, scene, image)| {
            prepare(
                scene,
                &case.file,
                case.bounces,
                STRICT,
                image.clone(),
                images.len(),
                None,
                Course::Y2016,
            )
            .expect("case")
        })
        .unzip();
    let all_pass = reports.iter().all(|r| r.difference.verdict.passes());
    find(&prepared, all_pass, Course::Y2016).expect("findings")
}

#[test]
fn every_entry_is_named_first_on_its_own_render() {
    for bug in Bug::offered(Course::Y2016) {
        let wanted = Mistakes::of(&[bug]);
        let (case, scene, image) = failing_case(wanted);
        let (_, findings) = check_image(
            &scene,
            &case.file,
            case.bounces,
            STRICT,
            image,
            Course::Y2016,
        )
        .expect("check");
        assert!(
            named_first(&findings.diagnosis, wanted),
            "{}: {:?}",
            bug.id(),
            findings.diagnosis.first()
        );
        let top = &findings.diagnosis[0];
        assert_eq!(
            (top.explained, top.wrongly_changed_pixels, top.exact),
            (1.0, 0, true),
            "{}",
            bug.id()
        );
        // After an exact explanation of everything, nothing but its twins.
        assert_eq!(findings.diagnosis.len(), 1, "{}", bug.id());
    }
}

#[test]
fn pairs_with_stages_are_found_in_the_top_three() {
    let pairs = [
        [Bug::NoAmbient, Bug::ReflectUnclamped],
        [Bug::NoShadowBias, Bug::ViewFlipped],
        [Bug::FirstLightOnly, Bug::BouncesPlusOne],
        [Bug::SpecularObjectColour, Bug::NoReflectionBias],
        [Bug::ReflectionMissing, Bug::ReflectUnclamped],
        [Bug::PlanesMissing, Bug::SpecularGated],
        [Bug::NoShadows, Bug::DiffuseNoColour],
    ];
    for pair in pairs {
        let wanted = Mistakes::of(&pair);
        let (case, scene, image) = failing_case(wanted);
        let (_, findings) = check_image(
            &scene,
            &case.file,
            case.bounces,
            STRICT,
            image,
            Course::Y2016,
        )
        .expect("check");
        assert_in_top_three(&findings.diagnosis, wanted);
    }
}

#[test]
fn three_at_once_are_found_over_the_suite() {
    let triples = [
        [
            Bug::NoShadows,
            Bug::ReflectionMissing,
            Bug::ReflectUnclamped,
        ],
        [Bug::NoShadows, Bug::ReflectionMissing, Bug::NoAmbient],
        [Bug::NoAmbient, Bug::ViewFlipped, Bug::BouncesPlusOne],
    ];
    for triple in triples {
        let wanted = Mistakes::of(&triple);
        let findings = suite_findings(&suite_images(Variant::from(wanted)));
        assert_in_top_three(&findings.diagnosis, wanted);
    }
}

#[test]
fn the_progress_names_each_stage() {
    let expect = [
        (Bug::PlanesMissing, Stage::Planes, StageState::Missing),
        (Bug::LightsMissing, Stage::Lights, StageState::Missing),
        (Bug::NoShadows, Stage::Shadows, StageState::Missing),
        (
            Bug::ReflectionMissing,
            Stage::Reflection,
            StageState::Missing,
        ),
        (
            Bug::ShadowAnyHit,
            Stage::Shadows,
            StageState::Mistaken(vec!["shadow-any-hit".into()]),
        ),
    ];
    for (bug, stage, state) in expect {
        let findings = suite_findings(&suite_images(Variant::from(Mistakes::of(&[bug]))));
        for (s, got) in &findings.progress.stages {
            // Without the lights' terms there is no light for a shadow to take away.
            let hidden = bug == Bug::LightsMissing && *s == Stage::Shadows;
            let wanted = if *s == stage {
                &state
            } else if hidden {
                &StageState::NotReached(Stage::Lights)
            } else {
                &StageState::Done
            };
            assert_eq!(got, wanted, "{} in {s:?}", bug.id());
        }
    }
    let correct = suite_findings(&suite_images(Variant::default()));
    assert!(correct
        .progress
        .stages
        .iter()
        .all(|(_, s)| *s == StageState::Done));
}

#[test]
fn rounding_noise_is_not_a_mistake() {
    let scene = whitted_core::scene::parse_str("tick2.xml", whitted_core::scene::EMBEDDED_TICK2)
        .expect("scene");
    let r = Renderer::new(&scene, 640, 480, 2).expect("renderer");
    let mut image = r.reference().expect("reference");
    // A student's pow rounding the other way in a few pixels.
    for i in (0..image.bytes.len()).step_by(9973) {
        image.bytes[i] = image.bytes[i].saturating_add(1);
    }
    let (report, findings) =
        check_image(&scene, "tick2.xml", 2, STRICT, image, Course::Y2016).expect("check");
    assert_eq!(report.difference.verdict, Verdict::WithinTolerance);
    assert!(
        findings.diagnosis.is_empty(),
        "{:?}",
        findings.diagnosis.first()
    );
}

#[test]
fn the_model_s_numbers_are_fitted() {
    let scene = whitted_core::scene::parse_str("tick2.xml", whitted_core::scene::EMBEDDED_TICK2)
        .expect("scene");
    let wrong = [
        (Parameter::SpecularExponent, 20.0, 2),
        (Parameter::FalloffPower, 1.0, 0),
        (Parameter::Reflectivity, 0.5, 2),
        (Parameter::Ambient, 0.5, 0),
        (Parameter::Epsilon, 0.05, 1),
    ];
    for (parameter, value, bounces) in wrong {
        let r = Renderer::new(&scene, 640, 480, bounces).expect("renderer");
        let variant = Variant {
            mistakes: Mistakes::NONE,
            number: Some(Number { parameter, value }),
            ..Variant::default()
        };
        let image = r.variant_image(&variant).expect("image");
        let (_, findings) =
            check_image(&scene, "tick2.xml", bounces, STRICT, image, Course::Y2016).expect("check");
        let fit = findings
            .parameters
            .iter()
            .find(|p| p.parameter == parameter)
            .unwrap_or_else(|| {
                panic!(
                    "{parameter:?}: {:?} {:?}",
                    findings.parameters,
                    findings.diagnosis.first()
                )
            });
        assert!(
            (fit.fitted - value).abs() <= 0.1 * value,
            "{parameter:?}: {fit:?}"
        );
        assert!(fit.explained > 0.9, "{parameter:?}: {fit:?}");
    }
}

#[test]
fn mistakes_beyond_the_catalogue_are_located_in_the_terms() {
    let scene = whitted_core::scene::parse_str("tick2.xml", whitted_core::scene::EMBEDDED_TICK2)
        .expect("scene");
    let r = Renderer::new(&scene, 640, 480, 0).expect("renderer");
    let every: Vec<(u32, u32)> = (0..480)
        .flat_map(|y| (0..640).map(move |x| (x, y)))
        .collect();
    let samples = r.layers_at(&every).expect("layers");
    let render = |f: &dyn Fn(&whitted_core::sample::Sample) -> glam::DVec3| Rgb8 {
        width: 640,
        height: 480,
        bytes: whitted_io::output::png::tick_bytes(&samples.iter().map(f).collect::<Vec<_>>()),
    };
    let half_ambient = render(&|s| s.beauty - s.ambient * 0.5);
    let (_, findings) =
        check_image(&scene, "tick2.xml", 0, STRICT, half_ambient, Course::Y2016).expect("check");
    let top = findings.terms.first().expect("a term");
    assert_eq!(top.layer, "ambient");
    assert!((top.factor - 0.5).abs() < 0.05, "{top:?}");
    let unshadowed = render(&|s| s.beauty - s.lights[1].shadowed + s.lights[1].unshadowed);
    let (_, findings) =
        check_image(&scene, "tick2.xml", 0, STRICT, unshadowed, Course::Y2016).expect("check");
    let top = findings.terms.first().expect("a term");
    assert_eq!(
        (top.layer.as_str(), top.replaces.as_deref()),
        ("unshadowed_1", Some("light_1"))
    );
    assert!(top.explained > 0.9, "{top:?}");
}

#[test]
fn a_passing_image_that_is_exactly_a_mistake_says_so() {
    let scene = whitted_core::scene::parse_str("tick2.xml", whitted_core::scene::EMBEDDED_TICK2)
        .expect("scene");
    let r = Renderer::new(&scene, 640, 480, 2).expect("renderer");
    let gated = Mistakes::of(&[Bug::SpecularGated]);
    let image = r.image(gated).expect("image");
    let (report, findings) =
        check_image(&scene, "tick2.xml", 2, STRICT, image, Course::Y2016).expect("check");
    assert_eq!(report.difference.verdict, Verdict::WithinTolerance);
    assert_eq!(report.hidden_mistakes, gated, "{:?}", findings.diagnosis);
    // A reference is hiding nothing.
    let (report, _) = check_image(
        &scene,
        "tick2.xml",
        2,
        STRICT,
        r.reference().expect("reference"),
        Course::Y2016,
    )
    .expect("check");
    assert!(report.hidden_mistakes.is_empty());
}

#[test]
fn no_implausible_term_factor_is_a_finding() {
    let scene = whitted_core::scene::parse_str("tick2.xml", whitted_core::scene::EMBEDDED_TICK2)
        .expect("scene");
    for (bounces, bugs) in [
        (
            2,
            vec![Bug::ReflectionWrongSign, Bug::NoAmbient, Bug::ViewFlipped],
        ),
        (1, vec![Bug::LightUnnormalised]),
    ] {
        let r = Renderer::new(&scene, 640, 480, bounces).expect("renderer");
        let image = r.image(Mistakes::of(&bugs)).expect("image");
        let (_, findings) =
            check_image(&scene, "tick2.xml", bounces, STRICT, image, Course::Y2016).expect("check");
        for t in &findings.terms {
            assert!((-0.05..=4.0).contains(&t.factor), "{t:?}");
            assert!(!t.sentence().contains("x as strong") || t.factor >= 0.0);
        }
    }
}

#[test]
fn a_scene_s_bounce_counts_rendered_together_are_each_one_s_own_render() {
    // Mirrors and the course's scene: chains that use every bounce, planes and spheres.
    for case in cases().iter().filter(|c| c.bounces == 3) {
        let scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
        let mut variants: Vec<Variant> = [Mistakes::NONE]
            .into_iter()
            .chain(
                Bug::offered(Course::Y2016)
                    .iter()
                    .map(|&b| Mistakes::of(&[b])),
            )
            .chain([Mistakes::of(&[Bug::BouncesMinusOne, Bug::NoShadows])])
            .map(Variant::from)
            .collect();
        variants.push(Variant {
            mistakes: Mistakes::NONE,
            number: Some(Number {
                parameter: Parameter::Reflectivity,
                value: 0.5,
            }),
            ..Variant::default()
        });
        let cache = ImageCache::new();
        for (n, variant) in variants.iter().enumerate() {
            let family = vec![0, 1, 2, 3];
            for &bounces in &family {
                let alone = Renderer::new(&scene, 96, 72, bounces).expect("renderer");
                let together = Renderer::new(&scene, 96, 72, bounces)
                    .expect("renderer")
                    .remembered_as(Some(SharedScene {
                        key: format!("bounce family test {} {n}", case.file),
                        bounce_family: family.clone(),
                        cache: cache.clone(),
                        samples: true,
                    }));
                assert!(
                    alone.variant_image(variant).expect("image")
                        == together.variant_image(variant).expect("image"),
                    "{} {variant:?} at {bounces} bounces",
                    case.file
                );
                if variant.mistakes == Mistakes::NONE && variant.number.is_none() {
                    assert!(
                        alone.reference().expect("reference")
                            == together.reference().expect("reference")
                    );
                }
            }
        }
    }
}

#[test]
fn renders_as_says_what_comparing_whole_images_says() {
    // The masked-entry proof stops a render at its first differing strip: it must answer
    // exactly what rendering both whole and comparing them answers, alone and with a cache
    // holding the base's other bounce counts (then every one of them must match), rendered
    // or as kept.
    let family = vec![0, 1, 2, 3];
    let bases = [
        Mistakes::NONE,
        Mistakes::of(&[Bug::SpecularGated]),
        Mistakes::of(&[Bug::PlanesMissing]),
    ];
    let (mut same, mut different) = (0, 0);
    for case in cases().iter().filter(|c| c.bounces == 3) {
        let scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
        let alone: Vec<Renderer> = family
            .iter()
            .map(|&b| Renderer::new(&scene, 96, 72, b).expect("renderer"))
            .collect();
        for base in bases.map(Variant::from) {
            let base_images: Vec<Rgb8> = alone
                .iter()
                .map(|r| r.variant_image(&base).expect("image"))
                .collect();
            for bug in Bug::offered(Course::Y2016) {
                if !base.mistakes.admits(bug) {
                    continue;
                }
                let variant = Variant::from(base.mistakes.with(bug));
                let equal: Vec<bool> = alone
                    .iter()
                    .zip(&base_images)
                    .map(|(r, image)| r.variant_image(&variant).expect("image") == *image)
                    .collect();
                for (i, r) in alone.iter().enumerate() {
                    let says = r.renders_as(&variant, &base, &base_images[i]);
                    assert_eq!(says.expect("renders"), equal[i], "{variant:?} alone");
                }
                // At 0 bounces, where a reflection mistake renders as the base does and only
                // the family's deeper images can tell.
                let shared = Renderer::new(&scene, 96, 72, 0)
                    .expect("renderer")
                    .remembered_as(Some(SharedScene {
                        key: case.file.to_string(),
                        bounce_family: family.clone(),
                        cache: ImageCache::new(),
                        samples: false,
                    }));
                let base_image = shared.variant_image(&base).expect("image");
                let says = shared.renders_as(&variant, &base, &base_image);
                let all_equal = equal.iter().all(|&e| e);
                assert_eq!(
                    says.expect("renders"),
                    all_equal,
                    "{variant:?} with the family"
                );
                // Once the variant's images are kept, the answer comes from them: the same.
                shared.variant_image(&variant).expect("image");
                let says = shared.renders_as(&variant, &base, &base_image);
                assert_eq!(says.expect("renders"), all_equal, "{variant:?} as kept");
                if variant.mistakes != base.mistakes {
                    match equal[2] {
                        true => same += 1,
                        false => different += 1,
                    }
                }
            }
        }
    }
    assert!(same > 0 && different > 0, "{same} alike, {different} not");
}

#[test]
fn the_course_s_searches_are_recorded_within_a_budget() {
    // A tape per sampled pixel for the course's scenes; none for a scene whose tapes could
    // take more than the budget (thousands of lights), where each candidate searches itself.
    let case = &cases()[0];
    let mut scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
    let pixels: Vec<(u32, u32)> = (0..200).map(|i| (i % 64, i / 64)).collect();
    let r = Renderer::new(&scene, 64, 48, 3).expect("renderer");
    assert_eq!(
        r.searches_at(&pixels).expect("searches").len(),
        pixels.len()
    );
    let light = scene.lights[0].clone();
    scene.lights = vec![light; 3000];
    let r = Renderer::new(&scene, 64, 48, 3).expect("renderer");
    assert!(r.searches_at(&pixels).expect("searches").is_empty());
    // And the sample is still scored the same way: by searching.
    let frame = r.frame(Mistakes::NONE).expect("frame");
    let v = Variant::from(Mistakes::of(&[Bug::SpecularObjectColour]));
    let at = &pixels[..4];
    let searched = r.bytes_at(&v, &frame, at).expect("bytes");
    let replayed = r.bytes_replaying(&v, &frame, at, Some(&[])).expect("bytes");
    assert_eq!(searched, replayed);
}
