//! `whitted check`: the tester a student runs at home (docs/check.md). It renders the
//! reference at the student's image size, compares every byte, and, where they differ, names
//! the catalogued mistake (or pair of mistakes) that reproduces the student's image best
//! (`check::diagnose`), or else the terms of the model the difference lives in
//! (`check::terms`). `--program` runs the student's own program over a suite of scenes.

pub mod diagnose;
pub mod difference;
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
use crate::render::sample_pixels;
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
fn fit_terms(scene: &Scene, bounces: u32, student: &Rgb8, reference: &Rgb8) -> Result<Vec<TermFit>> {
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
    let samples = sample_pixels(scene, &accel, &frame, &pixels);
    Ok(terms::fit(scene, bounces, &samples, &pixels, student))
}
