//! What a Tick 1* option's case shows beyond its verdict's line: the reference an option 1
//! image was compared with (for the report page to show beside it), and the numbers the
//! verdict rests on (for `--verbose`): how many pixels matched which render, or how far the
//! image is from each random process tried, and where it differs most. A verdict that rests
//! on no number (the option not done, not judged) adds nothing.

use crate::check::bump::{render_bump, FOLLOWS};
use crate::check::star_option::StarOption;
use crate::check::star_run::{handout_scene, StarImage, StarVerdict};
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::star::bump::Parametrisation;
use whitted_core::star::BumpMethod;

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
    let (scene, star) = handout_scene(option, course)?;
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
            let closest = match b.mistake {
                None => format!(
                    "closest: the handout's method under {}, {} of those pixels match",
                    b.parametrisation,
                    share(b.matched)
                ),
                Some(m) => format!(
                    "closest: {} under {}, {} of those pixels match; the handout's method \
                     under {}: {}",
                    m.name(),
                    b.parametrisation,
                    share(b.matched),
                    b.parametrisation,
                    share(b.matched_correct)
                ),
            };
            lines.push(closest);
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
                    match (f.is_draw(), f.stride) {
                        (true, _) => "  (a draw)".to_string(),
                        (false, 1) => String::new(),
                        (false, n) =>
                            format!("  (scored on every {n}th pixel of every {n}th row only)"),
                    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::bump::BumpFinding;
    use crate::check::star_both::BumpDraw;
    use crate::check::star_draw::{DrawCheck, Fit, Process};
    use whitted_core::star::BumpMistake;

    fn star(option: StarOption, verdict: StarVerdict) -> StarImage {
        StarImage {
            option,
            image: Rgb8 {
                width: 4,
                height: 3,
                bytes: vec![0; 36],
            },
            verdict,
            reference: None,
        }
    }

    #[test]
    fn a_bump_mistake_s_numbers_name_it_beside_the_correct_method() {
        let finding = BumpFinding {
            parametrisation: "z-yx",
            mistake: Some(BumpMistake::Inverted),
            matched: 0.995,
            matched_correct: 0.41,
            tried: 48,
        };
        let lines = lines(&star(StarOption::Bump, StarVerdict::Bump(finding)));
        assert_eq!(lines[0], "image: 4x3");
        assert!(lines[1].starts_with("renders tried: 48 "), "{lines:?}");
        assert_eq!(
            lines[2],
            "closest: bump-inverted under z-yx, 99.5% of those pixels match; the handout's \
             method under z-yx: 41.0%"
        );
    }

    #[test]
    fn a_draw_lists_every_process_tried_and_its_worst_tile() {
        let fits = vec![
            Fit {
                process: Process::Course,
                statistic: 1.9876,
                stride: 1,
            },
            Fit {
                process: Process::LightSize,
                statistic: 1.13,
                stride: 1,
            },
        ];
        let draw = DrawCheck {
            fits,
            region: (144, 96, 16, 16),
        };
        let lines = lines(&star(StarOption::Distributed, StarVerdict::Draw(draw)));
        assert_eq!(lines.len(), 5, "{lines:?}");
        assert_eq!(lines[2].trim_end(), "  course                 1.99");
        assert!(lines[3].ends_with("1.13  (a draw)"), "{lines:?}");
        assert_eq!(
            lines[4],
            "the course's process fits worst at x 144..=159, y 96..=111"
        );
    }

    #[test]
    fn a_bump_draw_says_how_many_draws_and_the_mistake_s_score() {
        let draw = BumpDraw {
            parametrisation: "y-zx",
            mistake: Some(BumpMistake::Inverted),
            statistic: 1.44,
            correct: 3.5,
            tried: 13,
        };
        let lines = lines(&star(StarOption::Bump, StarVerdict::BumpDraw(draw)));
        assert!(
            lines[1].contains("then each catalogued mistake under the closest"),
            "{lines:?}"
        );
        assert_eq!(
            lines[2],
            "mean z^2 (a draw is near 1): the handout's method under y-zx 3.50, bump-inverted 1.44"
        );
    }

    #[test]
    fn an_option_not_done_has_only_its_size_and_no_reference() {
        let verdict = StarVerdict::NotDone {
            option: StarOption::Distributed,
            neither: false,
        };
        let shown = star(StarOption::Distributed, verdict.clone());
        assert_eq!(lines(&shown), ["image: 4x3"]);
        let reference = reference(
            StarOption::Distributed,
            &verdict,
            &shown.image,
            2,
            Course::Y2023,
        );
        assert_eq!(reference.ok().flatten(), None);
    }

    #[test]
    fn an_option_1_image_s_reference_is_the_handout_s_method_at_its_size() {
        let finding = BumpFinding {
            parametrisation: "y-zx",
            mistake: None,
            matched: 1.0,
            matched_correct: 1.0,
            tried: 48,
        };
        let image = Rgb8 {
            width: 32,
            height: 24,
            bytes: vec![0; 32 * 24 * 3],
        };
        let verdict = StarVerdict::Bump(finding);
        let shown = reference(StarOption::Bump, &verdict, &image, 2, Course::Y2023)
            .expect("renders")
            .expect("a reference");
        assert_eq!((shown.width, shown.height), (32, 24));
        // The sphere is lit: not the black the image given is.
        assert!(shown.bytes.iter().any(|&b| b > 40));
    }
}
