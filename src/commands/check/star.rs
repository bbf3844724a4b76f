//! `whitted check --course YEAR --star distributed IMAGE.png`: a Tick 1* option 2 image judged
//! as a draw of the course's random process or of a variant (docs/check.md, "Tick 1*"): the
//! same judge `--program` gives a Tick 1* program's distributed.xml image.

use std::path::Path;

use crate::cli::CheckArgs;
use whitted_check::check::star_option::StarOption;
use whitted_check::check::star_run::{judge, StarImage};
use whitted_check::check::student_png;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_io::output::stdout;

/// Returns whether the image passes (is a draw of the course's process).
pub fn run(args: &CheckArgs, image: &Path) -> Result<bool> {
    let option = StarOption::Distributed;
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
