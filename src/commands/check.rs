//! `whitted check IMAGE.png [-i SCENE] [-b N]` and `whitted check --program 'CMD ARGS'`: the
//! verdict, where the image differs, and which mistake made it (docs/check.md). Exit 0 when
//! every image passes, 1 when one differs, 2 when they cannot be compared.

mod project;
mod star;

use serde_json::Value;

use crate::cli::{CheckArgs, StarCheck};
use whitted_check::check::print::json::json;
use whitted_check::check::print::text::{text, Detail};
use whitted_check::check::print::write_report;
use whitted_check::check::program::{run_suite, star_seen, SuiteRun};
use whitted_check::check::report::heat_map;
use whitted_check::check::result::CheckResult;
use whitted_check::check::which_course::{self, Chosen};
use whitted_check::check::{check_bump_image, check_image, student_png};
use whitted_check::check::{star_option, suite};
use whitted_check::mistakes::Bug;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene;
use whitted_core::star::Star;
use whitted_io::output::destination::{refuse_clashes, Destination};
use whitted_io::output::stdout;

/// Returns whether every image passed.
pub fn run(args: &CheckArgs) -> Result<bool> {
    if args.list_bugs {
        stdout::print_line(&catalogue(args.course.map(Course::from)))?;
        return Ok(true);
    }
    let serve = &args.serve;
    if !args.view && (serve.watch || serve.no_browser || serve.port != 0) {
        return Err(whitted_core::Error::Usage(
            "--watch, --no-browser and --port are options of --view".into(),
        ));
    }
    // A Tick 1* image's reference, the first time, takes up to a minute: show how far it is.
    whitted_check::check::star_reference::show_progress();
    if let Some(routed) = star::routed(args) {
        return run(&routed);
    }
    let project = match (&args.program, &args.image) {
        (None, Some(dir)) => project::is_project_arg(dir),
        (None, None) => true,
        (Some(_), _) => false,
    };
    if args.suite_dir.is_some() && args.program.is_none() && !project {
        return Err(whitted_core::Error::Usage(
            "--suite-dir writes the scenes a program runs: give it with --program, a project \
             folder, or no image in a project folder"
                .into(),
        ));
    }
    match (&args.program, &args.image) {
        (Some(program), _) => run_program(args, program),
        // The handout's scenes, embedded: `--star distributed`, and `--star bump` without -i.
        (None, Some(image)) if star::handout_option(args).is_some() => star::run(args, image),
        (None, Some(dir)) if project::is_project_arg(dir) => project::run(args, dir),
        (None, Some(image)) if args.view => view(args, image),
        (None, Some(image)) => run_image(args, image),
        (None, None) => match project::here() {
            Some(dir) => project::run(args, &dir),
            None => Err(whitted_core::Error::Usage(
                "give the PNG to check, a project folder, or --program 'CMD ARGS' (the current \
                 folder holds no Tick1.java or Tick2.java)"
                    .into(),
            )),
        },
    }
}

/// The catalogue: each entry's id and statement on a line (with the years that offer it,
/// where not every year does), then where and how to fix it; for one year, its entries only,
/// in its words.
fn catalogue(course: Option<Course>) -> String {
    let words = course.unwrap_or_default();
    Bug::ALL
        .iter()
        .filter(|b| course.is_none_or(|c| b.offered_in(c)))
        .map(|b| {
            let [place, fix] = b.advice(words);
            let years: Vec<&str> = Course::ALL
                .into_iter()
                .filter(|&c| b.offered_in(c))
                .map(Course::name)
                .collect();
            let years = if years.len() == Course::ALL.len() || course.is_some() {
                String::new()
            } else {
                format!(" [--course {}]", years.join(", "))
            };
            format!(
                "{:<24} {}{years}\n{:25}{place}\n{:25}{fix}",
                b.id(),
                b.description(words),
                "",
                ""
            )
        })
        .collect::<Vec<_>>()
        .into_iter()
        // Tick 1* (bump mapping) is set from 2017-18 on.
        .chain(
            course
                .is_none_or(|c| c >= Course::Y2017)
                .then(whitted_check::check::star_fix::list)
                .into_iter()
                .flatten(),
        )
        .collect::<Vec<_>>()
        .join("\n")
}

fn run_image(args: &CheckArgs, image: &std::path::Path) -> Result<bool> {
    let outputs: Vec<&std::path::Path> = args
        .heatmap
        .iter()
        .chain(&args.report)
        .map(|p| p.as_path())
        .collect();
    let mut inputs = vec![image];
    inputs.extend(args.input.as_deref());
    refuse_clashes(&inputs, &outputs)?;
    let mut heatmap = args.heatmap.as_deref().map(Destination::open).transpose()?;
    let mut report = args.report.as_deref().map(Destination::open).transpose()?;
    let student = student_png::read(image)?;
    let scene_bytes = args.input.as_deref().map(scene::read_file).transpose()?;
    let chosen = which_course::for_image(
        args.course.map(Course::from),
        (student.width, student.height),
        scene_bytes.as_deref(),
    )?;
    let input = scene::input::input_of(args.input.as_deref(), scene_bytes, chosen.course)?;
    for warning in &input.warnings {
        eprintln!("warning: {warning}");
    }
    let bump = args.star == Some(StarCheck::Bump) || !input.bumps.is_empty();
    let (mut case, findings) = if bump {
        let star = Star {
            bumps: super::render_star::bumped_spheres(&input, args.input.as_deref())?,
            ..Star::default()
        };
        check_bump_image(
            &input.scene,
            &input.name,
            &star,
            (args.bounces, args.rule()),
            student,
            chosen.course,
        )?
    } else {
        check_image(
            &input.scene,
            &input.name,
            args.bounces,
            args.rule(),
            student,
            chosen.course,
        )?
    };
    if let Some(out) = heatmap.as_mut() {
        out.write_png(&heat_map(&case.student, &case.reference, args.tolerance))?;
    }
    let name = image.display().to_string();
    // An image of another scene: the note, and no diagnosis that assumes the default scene.
    let findings = whitted_check::check::another_scene::findings(
        &mut case,
        findings,
        args.input.is_some(),
        chosen.course,
    );
    let mut result = CheckResult::of_image(&name, args.input.as_deref(), case, findings, &chosen);
    result.report = args.report.as_ref().map(|p| p.display().to_string());
    if let Some(out) = report.as_mut() {
        write_report(out, &result)?;
    }
    for out in [heatmap, report].into_iter().flatten() {
        out.commit()?;
    }
    print(args, &result)
}

/// The result on standard output, as `--json`, `--verbose` or the one screen ask; whether
/// every case passed.
fn print(args: &CheckArgs, result: &CheckResult) -> Result<bool> {
    let out = match (args.json, args.verbose) {
        (true, _) => pretty(&json(result)),
        (false, true) => text(result, Detail::Full),
        (false, false) => text(result, Detail::Screen),
    };
    stdout::print_line(&out)?;
    Ok(result.passed())
}

/// `--view`: the check in the viewer, until a signal stops it (the status is then 130).
fn view(args: &CheckArgs, image: &std::path::Path) -> Result<bool> {
    let source = whitted_view::Source::Check {
        image: image.to_path_buf(),
        scene: args.input.clone(),
        bounces: args.bounces,
        rule: args.rule(),
        course: args.course.map(Course::from),
    };
    let serve = &args.serve;
    whitted_view::serve(source, serve.port, serve.no_browser, serve.watch)?;
    Ok(true)
}

fn run_program(args: &CheckArgs, program: &str) -> Result<bool> {
    if let Some(report) = &args.report {
        refuse_clashes(&[], &[report])?;
    }
    let chosen = which_course::for_program(args.course.map(Course::from), program)?;
    let star = star_seen(program, None).is_some();
    report_suite(args, &chosen, star, |course| {
        let run = run_suite(program, args.rule(), args.timeout, course)?;
        Ok((run, Preamble::default()))
    })
}

/// What a project folder adds to its suite's report (`check DIR`): lines after the year's, and
/// the JSON's `"project"`.
#[derive(Default)]
struct Preamble {
    lines: Vec<String>,
    json: Option<Value>,
}

/// The suite `run` runs under `chosen`'s year, reported as `--program` reports it; `star`: the
/// program is known as Tick 1* before it runs, and runs its options' handout scenes, which are
/// what `--suite-dir` writes.
fn report_suite(
    args: &CheckArgs,
    chosen: &Chosen,
    star: bool,
    run: impl FnOnce(Course) -> Result<(SuiteRun, Preamble)>,
) -> Result<bool> {
    match (&args.suite_dir, star) {
        (Some(dir), true) => star_option::write_scenes(dir)?,
        (Some(dir), false) => suite::write_scenes(dir, chosen.course)?,
        (None, _) => {}
    }
    let report = args.report.as_deref().map(Destination::open).transpose()?;
    let (run, preamble) = run(chosen.course)?;
    let mut result = CheckResult::of_suite(
        run,
        chosen.course,
        chosen.why.clone(),
        args.suite_dir.as_deref(),
    );
    result.notes = preamble.lines;
    result.project = preamble.json;
    result.report = args.report.as_ref().map(|p| p.display().to_string());
    if let Some(mut out) = report {
        write_report(&mut out, &result)?;
        out.commit()?;
    }
    print(args, &result)
}

fn pretty(value: &Value) -> String {
    // serde_json cannot fail to print a Value it built itself.
    serde_json::to_string_pretty(value).unwrap_or_default()
}
