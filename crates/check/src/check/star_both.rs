//! A Tick 1* program that did both options renders `bump.xml` with its soft shadows and depth
//! of field on: the bump image is then random too, and no deterministic render of the bump
//! method (`bump.rs`) reproduces it. It is judged as `star_draw.rs` judges option 2's image:
//! as one draw of the bumped scene's distribution (`whitted_core::star` combines bump mapping
//! with soft shadows and depth of field). The parametrisation is the student's choice, so it
//! is found first, on the expectations: the handout's method under each parametrisation is
//! scored and the best kept; if that is no draw, each catalogued mistake under that
//! parametrisation is scored, and the best, if a draw, is named. Each set is scored on the
//! pre-pass's sparse grid and only its best on every pixel (`star_prepass.rs`).

use crate::check::bump::candidates;
use crate::check::star_draw::THRESHOLD;
use crate::check::star_prepass;
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene::Scene;
use whitted_core::star::bump::PARAMETRISATIONS;
use whitted_core::star::{BumpMethod, BumpMistake, DepthOfField, Grid, SoftShadows, Star};

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
    let s = lowest(scene, &[smooth], image, bounces, course)?.map_or(f64::INFINITY, |(_, s)| s);
    if s <= THRESHOLD {
        return Ok(Some(Drawn::Smooth(s)));
    }
    Ok(bumped(scene, star, image, bounces, course)?.map(Drawn::Bumped))
}

/// The lowest statistic of `image` against the stars (each with soft shadows and depth of
/// field), and its index: on the pre-pass's grid, the lowest in full (`star_prepass.rs`).
fn lowest(
    scene: &Scene,
    stars: &[Star],
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Option<(usize, f64)>> {
    let stars: Vec<(Star, f64)> = stars.iter().map(|s| (s.clone(), 1.0)).collect();
    let scores = star_prepass::scores(scene, &stars, image, bounces, course)?;
    // The one scored on every pixel, if any was: a grid's score runs low (its floor is
    // coarser) and would win against it unfairly.
    let whole = scores.iter().any(|s| s.grid == Grid::EVERY);
    Ok(scores
        .iter()
        .enumerate()
        .filter(|(_, s)| !whole || s.grid == Grid::EVERY)
        .map(|(i, s)| (i, s.mean()))
        .min_by(|a, b| a.1.total_cmp(&b.1)))
}

/// The bumped scene's draws: the parametrisation first, then the mistake.
fn bumped(
    scene: &Scene,
    star: &Star,
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Option<BumpDraw>> {
    let methods = candidates(&[None]);
    let stars: Vec<Star> = methods.iter().map(|m| both(star, *m)).collect();
    let Some((best, correct)) = lowest(scene, &stars, image, bounces, course)? else {
        return Ok(None);
    };
    let method = methods[best];
    let found = |mistake, statistic, tried| BumpDraw {
        parametrisation: method.parametrisation.name,
        mistake,
        statistic,
        correct,
        tried,
    };
    if correct <= THRESHOLD {
        return Ok(Some(found(None, correct, PARAMETRISATIONS.len())));
    }
    let stars: Vec<Star> = BumpMistake::ALL
        .iter()
        .map(|m| {
            let mistaken = BumpMethod {
                mistake: Some(*m),
                ..method
            };
            both(star, mistaken)
        })
        .collect();
    let tried = PARAMETRISATIONS.len() + stars.len();
    Ok(lowest(scene, &stars, image, bounces, course)?
        .filter(|&(_, s)| s <= THRESHOLD)
        .map(|(i, s)| found(Some(BumpMistake::ALL[i]), s, tried)))
}
