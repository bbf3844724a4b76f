//! A Tick 1* program that did both options renders `bump.xml` with its soft shadows and depth
//! of field on: the bump image is then random too, and no deterministic render of the bump
//! method (`bump.rs`) reproduces it. It is judged as `star_draw.rs` judges option 2's image:
//! as one draw of the bumped scene's distribution (`whitted_core::star` combines bump mapping
//! with soft shadows and depth of field). The parametrisation is the student's choice, so it
//! is found first, on the expectations: the handout's method under each parametrisation is
//! scored and the best kept; if that is no draw, each catalogued mistake under that
//! parametrisation is scored, and the best that is a draw is named.

use crate::check::bump::candidates;
use crate::check::star_draw::{score_star, THRESHOLD};
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene::Scene;
use whitted_core::star::bump::PARAMETRISATIONS;
use whitted_core::star::{BumpMethod, BumpMistake, DepthOfField, SoftShadows, Star};

/// A bump image found to be a draw of the bumped scene with both options on.
#[derive(Debug, Clone, PartialEq)]
pub struct BumpDraw {
    /// The parametrisation (`--bump-param` names) whose expectation fits best.
    pub parametrisation: &'static str,
    /// The catalogued mistake it is a draw of, if the handout's method is not.
    pub mistake: Option<BumpMistake>,
    /// Its mean z^2.
    pub statistic: f64,
    /// The handout's method's mean z^2 under that parametrisation.
    pub correct: f64,
    /// Expectations scored.
    pub tried: usize,
}

impl BumpDraw {
    pub fn passes(&self) -> bool {
        self.mistake.is_none()
    }

    /// The report's line.
    pub fn sentence(&self) -> String {
        let p = self.parametrisation;
        match self.mistake {
            None => format!(
                "bump mapping with soft shadows and depth of field on (both options): one draw \
                 of the handout's bump mapping under parametrisation {p} with the course's soft \
                 shadows and depth of field (mean z^2 {:.2}, at most {THRESHOLD} passes)",
                self.statistic
            ),
            Some(m) => format!(
                "bump mapping with soft shadows and depth of field on (both options): a draw of \
                 {} under parametrisation {p} (mean z^2 {:.2}; the handout's method {:.2}): {}",
                m.name(),
                self.statistic,
                self.correct,
                m.explanation()
            ),
        }
    }
}

/// The star of both options with `star`'s bumped spheres under `method`.
fn both(star: &Star, method: BumpMethod) -> Star {
    Star {
        soft: Some(SoftShadows::default()),
        dof: Some(DepthOfField::default()),
        bumps: star.bumps.clone(),
        bump: method,
    }
}

/// What a random bump image is a draw of.
#[derive(Debug, Clone, PartialEq)]
pub enum Drawn {
    /// Of the scene with a smooth sphere: soft shadows and depth of field, no bump mapping
    /// (option 1 not done); its mean z^2.
    Smooth(f64),
    /// Of the bumped scene.
    Bumped(BumpDraw),
}

/// Judges `image` of the bumped `scene` (its maps in `star`) as a draw with soft shadows and
/// depth of field on: of the smooth sphere, else of the handout's method or a catalogued
/// mistake under the parametrisation that fits best; None when it is no draw of any.
pub fn check(
    scene: &Scene,
    star: &Star,
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Option<Drawn>> {
    let smooth = Star {
        soft: Some(SoftShadows::default()),
        dof: Some(DepthOfField::default()),
        ..Star::default()
    };
    let s = score_star(scene, &smooth, 1.0, image, bounces, course)?.mean();
    if s <= THRESHOLD {
        return Ok(Some(Drawn::Smooth(s)));
    }
    Ok(bumped(scene, star, image, bounces, course)?.map(Drawn::Bumped))
}

/// The bumped scene's draws: the parametrisation first, then the mistake.
fn bumped(
    scene: &Scene,
    star: &Star,
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Option<BumpDraw>> {
    let score = |method: BumpMethod| -> Result<f64> {
        Ok(score_star(scene, &both(star, method), 1.0, image, bounces, course)?.mean())
    };
    let mut best: Option<(f64, BumpMethod)> = None;
    for method in candidates(&[None]) {
        let s = score(method)?;
        if best.is_none_or(|(b, _)| s < b) {
            best = Some((s, method));
        }
    }
    let Some((correct, method)) = best else {
        return Ok(None);
    };
    let mut tried = PARAMETRISATIONS.len();
    let found = |mistake, statistic, tried| BumpDraw {
        parametrisation: method.parametrisation.name,
        mistake,
        statistic,
        correct,
        tried,
    };
    if correct <= THRESHOLD {
        return Ok(Some(found(None, correct, tried)));
    }
    let mut draw: Option<(f64, BumpMistake)> = None;
    for mistake in BumpMistake::ALL {
        let s = score(BumpMethod {
            mistake: Some(mistake),
            ..method
        })?;
        tried += 1;
        if s <= THRESHOLD && draw.is_none_or(|(b, _)| s < b) {
            draw = Some((s, mistake));
        }
    }
    Ok(draw.map(|(s, m)| found(Some(m), s, tried)))
}
