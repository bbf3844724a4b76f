//! Tick 1* option 1 (docs/tick1star.md, docs/check.md "Bump mapping"): a student's image of a
//! scene with a `<bumpy-sphere>` is deterministic once the parametrisation is known, so the
//! check renders the handout's method under each named parametrisation, and each catalogued
//! mistake of the method under each, and names the render the image follows: the
//! parametrisation, then what is wrong against it (or nothing).
//!
//! The mistakes are parameters of the one implementation (`BumpMistake`), so a mistake's
//! image is the correct image with exactly that rule changed. Candidates are tried in the
//! catalogue's order (the inverted relief, the handout's "most common mistake", first) and a
//! later one replaces an earlier only by matching strictly more pixels; the correct method
//! wins every tie.

use rayon::prelude::*;

use super::student_png::Rgb8;
use whitted_core::camera::Camera;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::scene::Scene;
use whitted_core::star::bump::PARAMETRISATIONS;
use whitted_core::star::{course_draw, BumpMethod, BumpMistake, Star, StarFrame};
use whitted_core::trace::TraceOptions;
use whitted_io::output::png::bytes_with;

/// Largest channel difference, in 8-bit steps, at which a pixel still matches a candidate:
/// the course's float heights and Java's arithmetic may move a value by a step.
pub const PIXEL_TOLERANCE: u8 = 2;

/// Share of pixels a candidate must match for the image to be said to follow it.
pub const FOLLOWS: f64 = 0.98;

/// What the bump check found.
#[derive(Debug, Clone, PartialEq)]
pub struct BumpFinding {
    /// The parametrisation the image follows best (`--bump-param` names).
    pub parametrisation: &'static str,
    /// The mistake it follows, if the best candidate is one.
    pub mistake: Option<BumpMistake>,
    /// Share of the telling pixels (where candidates differ) within `PIXEL_TOLERANCE` of the
    /// best candidate.
    pub matched: f64,
    /// Share of pixels within `PIXEL_TOLERANCE` of the correct method in that parametrisation.
    pub matched_correct: f64,
    /// Candidates rendered.
    pub tried: usize,
}

impl BumpFinding {
    /// Whether the image is the handout's method in some parametrisation.
    pub fn passes(&self) -> bool {
        self.mistake.is_none() && self.matched >= FOLLOWS
    }

    /// The report's line.
    pub fn sentence(&self) -> String {
        format!("bump mapping: {}", self.finding())
    }

    /// What was found, without the option's name: the line after a case that names it.
    pub fn finding(&self) -> String {
        let share = |s: f64| format!("{:.1}%", 100.0 * s);
        match (self.mistake, self.matched >= FOLLOWS) {
            (None, true) => format!(
                "the handout's method under parametrisation {} ({} of pixels match)",
                self.parametrisation,
                share(self.matched)
            ),
            (Some(m), true) => format!(
                "{} under parametrisation {}: {} ({} of pixels match it, {} the correct method)",
                m.name(),
                self.parametrisation,
                m.explanation(),
                share(self.matched),
                share(self.matched_correct)
            ),
            (best, false) => format!(
                "no parametrisation or catalogued mistake reproduces the image; \
                 nearest: {}{} ({} of pixels match)",
                self.parametrisation,
                best.map_or(String::new(), |m| format!(" with {}", m.name())),
                share(self.matched)
            ),
        }
    }
}

/// The star with its bumped spheres under `method`.
fn with_method(star: &Star, method: BumpMethod) -> Star {
    Star {
        bump: method,
        soft: None,
        dof: None,
        bumps: star.bumps.clone(),
    }
}

/// The 8-bit image of the bump method `method` at `student`'s size, under `course`.
pub fn render_bump(
    scene: &Scene,
    star: &Star,
    method: BumpMethod,
    (width, height): (u32, u32),
    bounces: u32,
    course: Course,
) -> Result<Rgb8> {
    let star = with_method(star, method);
    let frame = StarFrame {
        scene,
        camera: Camera::with_rows(width, height, course.row_step()),
        course,
        trace: TraceOptions {
            bounces,
            shadows: true,
        },
        star: &star,
    };
    let image = course_draw(&frame, 0)?;
    Ok(Rgb8 {
        width,
        height,
        bytes: bytes_with(course.tonemap(), &image.beauty),
    })
}

/// Whether pixel `i` of `a` and `b` is within `PIXEL_TOLERANCE` on every channel.
fn close(a: &Rgb8, b: &Rgb8, i: usize) -> bool {
    let (p, q) = (&a.bytes[3 * i..3 * i + 3], &b.bytes[3 * i..3 * i + 3]);
    p.iter()
        .zip(q)
        .all(|(x, y)| x.abs_diff(*y) <= PIXEL_TOLERANCE)
}

/// Share of the `telling` pixels of `a` within `PIXEL_TOLERANCE` of `b`.
fn matched(a: &Rgb8, b: &Rgb8, telling: &[usize]) -> f64 {
    let close = telling.iter().filter(|&&i| close(a, b, i)).count();
    close as f64 / telling.len().max(1) as f64
}

/// The pixels where the candidates do not all agree: the bumped surface as the camera sees
/// it, directly or in a mirror. The background and everything else say nothing.
fn telling_pixels(images: &[Rgb8]) -> Vec<usize> {
    let Some(first) = images.first() else {
        return Vec::new();
    };
    (0..first.bytes.len() / 3)
        .filter(|&i| {
            let p = &first.bytes[3 * i..3 * i + 3];
            images.iter().any(|im| &im.bytes[3 * i..3 * i + 3] != p)
        })
        .collect()
}

/// The methods to try: each of `mistakes` (None: the handout's method) under every named
/// parametrisation, parametrisation by parametrisation in catalogue order. The one list of
/// candidates for the deterministic check here and the random one (`star_both.rs`).
pub fn candidates(mistakes: &[Option<BumpMistake>]) -> Vec<BumpMethod> {
    PARAMETRISATIONS
        .iter()
        .flat_map(|&parametrisation| {
            mistakes.iter().map(move |&mistake| BumpMethod {
                parametrisation,
                mistake,
            })
        })
        .collect()
}

/// Checks `student` against every parametrisation and mistake; also returns the correct
/// render of the parametrisation found (the case's reference).
pub fn check_bump(
    scene: &Scene,
    star: &Star,
    student: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<(BumpFinding, Rgb8)> {
    if star.bumps.is_empty() {
        return Err(Error::Usage(
            "--star bump: the scene has no <bumpy-sphere> (give the handout's bump.xml with -i)"
                .into(),
        ));
    }
    let size = (student.width, student.height);
    let mistakes: Vec<Option<BumpMistake>> = std::iter::once(None)
        .chain(BumpMistake::ALL.into_iter().map(Some))
        .collect();
    let candidates = candidates(&mistakes);
    if student.bytes.len() != 3 * (student.width as usize) * (student.height as usize) {
        return Err(Error::Usage(
            "the image is not 8-bit RGB of its size".into(),
        ));
    }
    let images: Vec<Rgb8> = candidates
        .par_iter()
        .map(|&method| render_bump(scene, star, method, size, bounces, course))
        .collect::<Result<_>>()?;
    let telling = telling_pixels(&images);
    let scored: Vec<(f64, Rgb8)> = images
        .into_iter()
        .map(|image| (matched(student, &image, &telling), image))
        .collect();
    // The first best in catalogue order: correct before any mistake, inverted first.
    let mut best = 0;
    for (i, (score, _)) in scored.iter().enumerate() {
        if *score > scored[best].0 {
            best = i;
        }
    }
    let method = candidates[best];
    let correct = candidates
        .iter()
        .position(|c| c.parametrisation == method.parametrisation && c.mistake.is_none())
        .unwrap_or(best);
    Ok((
        BumpFinding {
            parametrisation: method.parametrisation.name,
            mistake: method.mistake,
            matched: scored[best].0,
            matched_correct: scored[correct].0,
            tried: candidates.len(),
        },
        scored[correct].1.clone(),
    ))
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::sync::Arc;

    use super::*;
    use whitted_core::scene::input::parse_with_bumps;
    use whitted_core::star::BumpedSphere;

    /// The handout's bump.xml and map (the test map's halves repeat, so it cannot tell every
    /// parametrisation apart).
    fn bump_scene() -> (Scene, Star) {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/courses/tick1star");
        let xml = std::fs::read(root.join("bump.xml")).expect("bump.xml");
        let (scene, _, bumps) =
            parse_with_bumps("bump.xml", &xml, Course::Y2020).expect("the scene reads");
        let map = whitted_io::bump_map::read(&root.join("bumpmap.png"), "bump.xml")
            .expect("the map reads");
        let star = Star {
            bumps: vec![BumpedSphere {
                object: bumps[0].object,
                map: Arc::new(map),
            }],
            ..Star::default()
        };
        (scene, star)
    }

    const SIZE: (u32, u32) = (128, 96);

    #[test]
    fn each_mistake_is_named_and_the_correct_image_passes_under_every_parametrisation() {
        let (scene, star) = bump_scene();
        for parametrisation in PARAMETRISATIONS {
            for mistake in std::iter::once(None).chain(BumpMistake::ALL.into_iter().map(Some)) {
                let method = BumpMethod {
                    parametrisation,
                    mistake,
                };
                let student =
                    render_bump(&scene, &star, method, SIZE, 2, Course::Y2020).expect("renders");
                let (finding, _) =
                    check_bump(&scene, &star, &student, 2, Course::Y2020).expect("checks");
                assert_eq!(
                    (finding.parametrisation, finding.mistake),
                    (parametrisation.name, mistake),
                    "{}",
                    finding.sentence()
                );
                assert_eq!(finding.passes(), mistake.is_none());
                assert_eq!(finding.matched, 1.0);
                if mistake.is_some() {
                    // The mistake's image is told from the correct one on some pixels.
                    assert!(finding.matched_correct < 0.99, "{}", finding.sentence());
                }
            }
        }
    }

    #[test]
    fn a_smooth_sphere_follows_nothing() {
        let (scene, star) = bump_scene();
        let smooth = Star::default();
        let method = BumpMethod::default();
        let student =
            render_bump(&scene, &smooth, method, SIZE, 2, Course::Y2020).expect("renders");
        let (finding, _) = check_bump(&scene, &star, &student, 2, Course::Y2020).expect("checks");
        assert!(!finding.passes());
        assert!(finding.matched < FOLLOWS, "{}", finding.sentence());
        assert!(finding.sentence().contains("no parametrisation"));
    }
}
