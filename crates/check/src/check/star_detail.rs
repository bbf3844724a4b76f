//! What a Tick 1* option's case shows beyond its verdict's line: the reference an option 1
//! image was compared with (for the report page to show beside it), and the numbers the
//! verdict rests on (for `--verbose`): how many pixels matched which render, or how far the
//! image is from each random process tried, and where it differs most. A verdict that rests
//! on no number (the option not done, not judged) adds nothing.

use std::sync::Arc;

use crate::check::bump::{render_bump, FOLLOWS};
use crate::check::star_option::StarOption;
use crate::check::star_run::{handout_map, StarImage, StarVerdict};
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene;
use whitted_core::star::bump::Parametrisation;
use whitted_core::star::{BumpMethod, BumpedSphere, Star};

/// The render an option 1 image was compared with: the handout's method under the
/// parametrisation its judge found, at the image's size (what `bump::check_bump` scores
/// "the correct method" against). None for any other verdict: a random image has no one
/// reference, and an option not done is the Tick 1 render itself.
pub fn reference(
    option: StarOption,
    verdict: &StarVerdict,
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Option<Rgb8>> {
    let StarVerdict::Bump(finding) = verdict else {
        return Ok(None);
    };
    let Some(parametrisation) = Parametrisation::named(finding.parametrisation) else {
        return Ok(None);
    };
    let (scene, _, bumps) =
        scene::input::parse_with_bumps(option.file(), option.xml().as_bytes(), course)?;
    let map = Arc::new(handout_map(option)?);
    let star = Star {
        bumps: bumps
            .iter()
            .map(|b| BumpedSphere {
                object: b.object,
                map: Arc::clone(&map),
            })
            .collect(),
        ..Star::default()
    };
    let method = BumpMethod {
        parametrisation,
        mistake: None,
    };
    let size = (image.width, image.height);
    render_bump(&scene, &star, method, size, bounces, course).map(Some)
}

/// The lines `--verbose` adds under an option's case: the image's size, then what its
/// verdict rests on.
pub fn lines(star: &StarImage) -> Vec<String> {
    let share = |s: f64| format!("{:.1}%", 100.0 * s);
    let mut lines = vec![format!("image: {}x{}", star.image.width, star.image.height)];
    match &star.verdict {
        StarVerdict::Bump(b) => {
            lines.push(format!(
                "renders tried: {} (the handout's method and each catalogued mistake, under \
                 each parametrisation); an image follows one when {} of the pixels where they \
                 differ match it",
                b.tried,
                share(FOLLOWS)
            ));
            lines.push(format!(
                "closest: {}{}, {} of those pixels match; the handout's method under {}: {}",
                b.parametrisation,
                b.mistake
                    .map_or(String::new(), |m| format!(" with {}", m.name())),
                share(b.matched),
                b.parametrisation,
                share(b.matched_correct)
            ));
        }
        StarVerdict::Draw(d) => {
            lines.push(
                "mean z^2 of the image against each process tried (a draw is near 1):".into(),
            );
            lines.extend(d.fits.iter().map(|f| {
                format!(
                    "  {:<22} {:.2}{}",
                    f.process.name(),
                    f.statistic,
                    if f.is_draw() { "  (a draw)" } else { "" }
                )
            }));
            let (x, y, w, h) = d.region;
            lines.push(format!(
                "the course's process fits worst at x {x}..={}, y {y}..={}",
                x + w - 1,
                y + h - 1
            ));
        }
        StarVerdict::BumpDraw(b) => {
            lines.push(format!(
                "draws tried: {} (the handout's method under each parametrisation{})",
                b.tried,
                match b.tried > whitted_core::star::bump::PARAMETRISATIONS.len() {
                    true => ", then each catalogued mistake under the closest",
                    false => "",
                }
            ));
            lines.push(format!(
                "mean z^2 (a draw is near 1): the handout's method under {} {:.2}{}",
                b.parametrisation,
                b.correct,
                b.mistake.map_or(String::new(), |m| format!(
                    ", {} {:.2}",
                    m.name(),
                    b.statistic
                ))
            ));
        }
        StarVerdict::NotDone { .. } | StarVerdict::NotJudged(_) => {}
    }
    lines
}
