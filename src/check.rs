//! `whitted check`: the tester a student runs at home (docs/check.md). It renders the
//! reference at the student's image size, compares every byte, and, where they differ, names
//! the catalogued mistake (or pair of mistakes) that reproduces the student's image best
//! (`check::diagnose`), or else the terms of the model the difference lives in
//! (`check::terms`). `--program` runs the student's own program over a suite of scenes.

pub mod diagnose;
pub mod difference;
pub mod json;
pub mod program;
pub mod report;
pub mod student_png;
pub mod suite;
pub mod terms;

use crate::accel::Accelerator;
use crate::check::diagnose::{analyse, rank, spread, CaseAnalysis, Diagnosis, Renderer, SAMPLE};
use crate::check::difference::{difference, pixel_difference, Difference};
use crate::check::student_png::Rgb8;
use crate::check::terms::TermFit;
use crate::error::Result;
use crate::frame::{Frame, FrameSpec};
use crate::model::Tick;
use crate::render::trace_pixels;
use crate::sample::Sample;
use crate::scene::Scene;

/// Below this share of differing pixels explained, the best catalogued candidate is not a
/// good explanation and the term fit is reported too.
const GOOD_EXPLANATION: f64 = 0.9;

/// Everything known about one student image of one scene.
#[derive(Debug, Clone)]
pub struct CaseReport {
    pub scene_name: String,
    pub bounces: u32,
    pub tolerance: u8,
    pub difference: Difference,
    pub analysis: CaseAnalysis,
    /// Best first; empty when the image is identical or nothing explains it better than the
    /// reference does.
    pub diagnosis: Vec<Diagnosis>,
    /// Where no candidate explains the image well: the model's terms it differs in.
    pub terms: Vec<TermFit>,
    pub student: Rgb8,
    pub reference: Rgb8,
}

/// Checks `student` against `scene` rendered at its size with `bounces` bounces.
pub fn check_image(
    scene: &Scene,
    scene_name: &str,
    bounces: u32,
    tolerance: u8,
    student: Rgb8,
) -> Result<CaseReport> {
    let renderer = Renderer::new(scene, student.width, student.height, bounces)?;
    let reference = renderer.reference()?;
    let difference = difference(&student, &reference, tolerance);
    let analysis = analyse(&renderer, &student, &reference)?;
    let diagnosis = match difference.differing_pixels {
        0 => Vec::new(),
        _ => rank(&[&analysis]),
    };
    let poorly_explained = diagnosis
        .first()
        .is_none_or(|d| d.explained < GOOD_EXPLANATION);
    let terms = if difference.differing_pixels > 0 && poorly_explained {
        fit_terms(scene, bounces, &student, &reference)?
    } else {
        Vec::new()
    };
    Ok(CaseReport {
        scene_name: scene_name.to_string(),
        bounces,
        tolerance,
        difference,
        analysis,
        diagnosis,
        terms,
        student,
        reference,
    })
}

/// The term fit over a sample of the differing pixels.
fn fit_terms(
    scene: &Scene,
    bounces: u32,
    student: &Rgb8,
    reference: &Rgb8,
) -> Result<Vec<TermFit>> {
    let width = student.width as usize;
    let wrong: Vec<(u32, u32)> = (0..student.bytes.len() / 3)
        .filter(|&i| pixel_difference(&student.bytes, &reference.bytes, i) > 0)
        .map(|i| ((i % width) as u32, (i / width) as u32))
        .collect();
    let pixels = spread(&wrong, SAMPLE);
    let spec = FrameSpec {
        width: student.width,
        height: student.height,
        bounces,
        ..FrameSpec::default()
    };
    let frame = Frame::new(scene, &spec)?;
    let accel = Accelerator::build(&scene.objects);
    let samples = trace_pixels::<true, _>(&Tick, scene, &accel, &frame, &pixels, Sample::clone);
    crate::interrupt::check()?;
    Ok(terms::fit(scene, bounces, &samples, &pixels, student))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::diagnose::Renderer;
    use crate::check::suite::{cases, SuiteCase};
    use crate::mistakes::{Bug, Mistakes};

    /// The first suite case on which `mistakes` fails, each of its mistakes showing, with its
    /// image.
    fn failing_case(mistakes: Mistakes) -> (SuiteCase, Scene, Rgb8) {
        for case in cases() {
            let scene = crate::scene::parse_str(case.file, case.xml).expect("scene");
            let r = Renderer::new(&scene, 640, 480, case.bounces).expect("renderer");
            let image = r.image(mistakes).expect("image");
            let fails =
                difference(&image, &r.reference().expect("reference"), 2).beyond_tolerance > 0;
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
    fn named_first(report: &CaseReport, wanted: Mistakes) -> bool {
        report
            .diagnosis
            .first()
            .is_some_and(|d| d.mistakes == wanted || d.indistinguishable_from.contains(&wanted))
    }

    #[test]
    fn every_mistake_is_named_first_on_its_own_render() {
        for bug in Bug::ALL {
            let wanted = Mistakes::of(&[bug]);
            let (case, scene, image) = failing_case(wanted);
            let report = check_image(&scene, case.file, case.bounces, 2, image).expect("check");
            assert!(
                named_first(&report, wanted),
                "{}: {:?}",
                bug.id(),
                report.diagnosis.first()
            );
            let top = &report.diagnosis[0];
            assert_eq!(
                (top.explained, top.wrongly_changed_pixels),
                (1.0, 0),
                "{}",
                bug.id()
            );
        }
    }

    #[test]
    fn pairs_are_found_in_the_top_three() {
        let pairs = [
            [Bug::NoAmbient, Bug::ReflectUnclamped],
            [Bug::NoShadowBias, Bug::ViewFlipped],
            [Bug::FirstLightOnly, Bug::BouncesPlusOne],
            [Bug::SpecularObjectColour, Bug::NoReflectionBias],
        ];
        for pair in pairs {
            let wanted = Mistakes::of(&pair);
            let (case, scene, image) = failing_case(wanted);
            let report = check_image(&scene, case.file, case.bounces, 2, image).expect("check");
            let top3: Vec<Mistakes> = report
                .diagnosis
                .iter()
                .take(3)
                .map(|d| d.mistakes)
                .collect();
            assert!(top3.contains(&wanted), "{pair:?}: {top3:?}");
        }
    }

    #[test]
    fn rounding_noise_is_not_a_mistake() {
        let scene =
            crate::scene::parse_str("tick2.xml", crate::scene::EMBEDDED_TICK2).expect("scene");
        let r = Renderer::new(&scene, 640, 480, 2).expect("renderer");
        let mut image = r.reference().expect("reference");
        // A student's pow rounding the other way in a few pixels.
        for i in (0..image.bytes.len()).step_by(9973) {
            image.bytes[i] = image.bytes[i].saturating_add(1);
        }
        let report = check_image(&scene, "tick2.xml", 2, 2, image).expect("check");
        assert_eq!(
            report.difference.verdict,
            difference::Verdict::WithinTolerance
        );
        assert!(
            report.diagnosis.is_empty(),
            "{:?}",
            report.diagnosis.first()
        );
    }

    #[test]
    fn mistakes_beyond_the_catalogue_are_located_in_the_terms() {
        let scene =
            crate::scene::parse_str("tick2.xml", crate::scene::EMBEDDED_TICK2).expect("scene");
        let spec = FrameSpec {
            bounces: 0,
            ..FrameSpec::default()
        };
        let frame = Frame::new(&scene, &spec).expect("frame");
        let accel = Accelerator::build(&scene.objects);
        let every: Vec<(u32, u32)> = (0..480)
            .flat_map(|y| (0..640).map(move |x| (x, y)))
            .collect();
        let samples = trace_pixels::<true, _>(&Tick, &scene, &accel, &frame, &every, Sample::clone);
        let render = |f: &dyn Fn(&crate::sample::Sample) -> glam::DVec3| Rgb8 {
            width: 640,
            height: 480,
            bytes: crate::output::png::tick_bytes(&samples.iter().map(f).collect::<Vec<_>>()),
        };
        let half_ambient = render(&|s| s.beauty - s.ambient * 0.5);
        let report = check_image(&scene, "tick2.xml", 0, 2, half_ambient).expect("check");
        let top = report.terms.first().expect("a term");
        assert_eq!(top.layer, "ambient");
        assert!((top.factor - 0.5).abs() < 0.05, "{top:?}");
        let unshadowed = render(&|s| s.beauty - s.lights[1].shadowed + s.lights[1].unshadowed);
        let report = check_image(&scene, "tick2.xml", 0, 2, unshadowed).expect("check");
        let top = report.terms.first().expect("a term");
        assert_eq!(
            (top.layer.as_str(), top.replaces.as_deref()),
            ("unshadowed_1", Some("light_1"))
        );
        assert!(top.explained > 0.9, "{top:?}");
    }
}
