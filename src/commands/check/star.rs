//! `whitted check --course YEAR --star distributed IMAGE.png` (or `--star bump` without -i):
//! a Tick 1* image of the handout's scene judged by its option's judge (docs/check.md,
//! "Tick 1*"), the same `--program` gives a Tick 1* program's image: first whether it is the
//! Tick 1 render (the option not done), then the bump map's parametrisation and mistake, or
//! whether it is a draw of the course's random process or of a variant.

use std::path::Path;

use crate::cli::{CheckArgs, StarCheck};
use whitted_check::check::star_option::StarOption;
use whitted_check::check::star_run::{judge, StarImage};
use whitted_check::check::student_png;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_io::output::stdout;

/// The handout's option `args` asks to judge an image of: `--star distributed`, or
/// `--star bump` with no scene given (a scene given is checked as any bump-mapped scene).
pub fn handout_option(args: &CheckArgs) -> Option<StarOption> {
    match (args.star, &args.input) {
        (Some(StarCheck::Distributed), _) => Some(StarOption::Distributed),
        (Some(StarCheck::Bump), None) => Some(StarOption::Bump),
        _ => None,
    }
}

/// `args` with `--star distributed` when `-i` names a copy of the handout's distributed.xml
/// and no `--star` was given: its images are random, so the Tick 1 check would call a sharp
/// render identical and a correct draw wrong. Says so on stderr. None when the scene is any
/// other (or unreadable: the ordinary path reports that).
pub fn routed(args: &CheckArgs) -> Option<CheckArgs> {
    if args.star.is_some() || args.program.is_some() {
        return None;
    }
    let path = args.input.as_deref()?;
    let xml = std::fs::read(path).ok()?;
    if StarOption::of_content(&xml)? != StarOption::Distributed {
        return None;
    }
    eprintln!(
        "note: {} is the handout's distributed.xml (Tick 1* option 2, random images): \
         checked as --star distributed",
        path.display()
    );
    Some(CheckArgs {
        star: Some(StarCheck::Distributed),
        input: None,
        ..args.clone()
    })
}

/// Returns whether the image passes (its option's judge finds nothing wrong).
pub fn run(args: &CheckArgs, image: &Path) -> Result<bool> {
    let Some(option) = handout_option(args) else {
        return Err(Error::Usage("--star: not a handout scene's check".into()));
    };
    // A Tick 1* image's size says nothing of its year: 2023-24's programs render any size.
    let Some(course) = args.course.map(Course::from) else {
        return Err(Error::Usage(
            "--star needs --course YEAR (the year whose shading and tone map the image has)".into(),
        ));
    };
    let student = student_png::read(image)?;
    let verdict = judge(option, &student, args.bounces, course)?;
    let star = StarImage {
        option,
        image: student,
        verdict,
        // The text and JSON of one image show no images.
        reference: None,
    };
    let passes = star.verdict.passes();
    let name = image.display().to_string();
    let out = match args.json {
        true => {
            let value = serde_json::json!({
                "image": name,
                "course": course.name(),
                "bounces": args.bounces,
                "passed": passes,
                "tick1_star": star.json(),
            });
            // serde_json cannot fail to print a Value it built itself.
            serde_json::to_string_pretty(&value).unwrap_or_default()
        }
        false => format!(
            "{name} ({}x{}, course {}, {}): {}",
            star.image.width,
            star.image.height,
            course.name(),
            option.what(),
            star.verdict.line()
        ),
    };
    stdout::print_line(&out)?;
    Ok(passes)
}
