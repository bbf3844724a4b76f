//! `whitted check DIR` (or `whitted check` in a project folder): the student's project found,
//! its year read from its classes, compiled by javac into a private temporary folder, and run
//! over the suite exactly as `--program` runs a program (docs/check.md, "From your project
//! folder"). The logic is `whitted_grade::project`'s; this is the command's side of it.

use std::path::{Path, PathBuf};

use super::{report_suite, Preamble};
use crate::cli::CheckArgs;
use whitted_check::check::image_cache::ImageCache;
use whitted_check::check::program::{run_suite_as, star_seen, Plain};
use whitted_check::check::suite::cases_of;
use whitted_check::check::which_course::Chosen;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_grade::project::{self, Project};
use whitted_io::output::destination::refuse_clashes;

/// Whether the command line's positional argument is a project folder rather than an image:
/// a folder (a name ending in `.png` stays an image).
pub fn is_project_arg(path: &Path) -> bool {
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    !png && path.is_dir()
}

/// The current folder, when it is a project (`whitted check` with no argument).
pub fn here() -> Option<PathBuf> {
    let dir = std::env::current_dir().ok()?;
    project::is_project(&dir).then(|| PathBuf::from("."))
}

/// Checks the project in `dir`; returns whether every case passed.
pub fn run(args: &CheckArgs, dir: &Path) -> Result<bool> {
    let image_only = [
        (args.view, "--view"),
        (args.heatmap.is_some(), "--heatmap"),
        (args.input.is_some(), "--input"),
    ];
    if let Some((_, option)) = image_only.iter().find(|(given, _)| *given) {
        return Err(Error::Usage(format!(
            "{option} is an option of an image check; {} is a project folder, checked over the \
             suite as --program is",
            dir.display()
        )));
    }
    if let Some(report) = &args.report {
        refuse_clashes(&[], &[report])?;
    }
    let asked = args.course.map(Course::from);
    let project = Project::open(dir, asked, |warning| eprintln!("warning: {warning}"))?;
    let chosen = Chosen {
        course: project.course(),
        why: project.why().map(str::to_string),
    };
    let seen = project.tick1_star();
    let star = star_seen(&project.shown_program(None), seen).is_some();
    report_suite(args, &chosen, star, |course| {
        let launch = Plain(project.command());
        // With the scenes written, the classes go beside them, so that every rerun command
        // printed runs what was checked.
        let kept = match &args.suite_dir {
            Some(dir) => Some(project.keep_classes(dir)?),
            None => None,
        };
        let run = run_suite_as(
            &launch,
            &project.shown_program(kept.as_deref()),
            &cases_of(course),
            (args.rule(), args.timeout),
            &ImageCache::new(),
            seen,
        )?;
        let mut lines = project.lines(kept.as_deref());
        // The second build runs only when a case fails: a project that passes costs its
        // compile and nothing more.
        if !run.passed() {
            lines.extend(project.explain_failure(&run, args.timeout, &|line| eprintln!("{line}"))?);
        }
        let notes: Vec<String> = lines
            .iter()
            .filter(|l| l.starts_with("note: "))
            .cloned()
            .collect();
        Ok((
            run,
            Preamble {
                lines,
                json: Some(project.json(&notes)),
            },
        ))
    })
}
