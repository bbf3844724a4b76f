//! `whitted check IMAGE.png [-i SCENE] [-b N]` and `whitted check --program 'CMD ARGS'`: the
//! verdict, where the image differs, and which mistake made it (docs/check.md). Exit 0 when
//! every image passes, 1 when one differs, 2 when they cannot be compared.

use std::path::Path;

use serde_json::Value;

use crate::cli::CheckArgs;
use whitted_check::check::diagnose::Diagnosis;
use whitted_check::check::json::{case_json, suite_json};
use whitted_check::check::program::{run_suite, RunStatus, SuiteRun};
use whitted_check::check::report::{contact_sheet, failing_rows, heat_map, ReportRow};
use whitted_check::check::reproduce::{explain_commands, Reproduce};
use whitted_check::check::suite;
use whitted_check::check::summary::{self, candidates_heading, opening};
use whitted_check::check::which_course::{self, Chosen};
use whitted_check::check::words;
use whitted_check::check::{check_image, student_png, CaseReport, Findings};
use whitted_check::mistakes::Bug;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene;
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
    match (&args.program, &args.image) {
        (Some(program), _) => run_program(args, program),
        (None, Some(image)) if args.view => view(args, image),
        (None, Some(image)) => run_image(args, image),
        (None, None) => Err(whitted_core::Error::Usage(
            "give the PNG to check, or --program 'CMD ARGS'".into(),
        )),
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
    let (case, findings) = check_image(
        &input.scene,
        &input.name,
        args.bounces,
        args.rule(),
        student,
        chosen.course,
    )?;
    if let Some(out) = heatmap.as_mut() {
        out.write_png(&heat_map(&case.student, &case.reference, args.tolerance))?;
    }
    if let Some(out) = report.as_mut() {
        let rows = [ReportRow::of(
            &image.display().to_string(),
            &case,
            &findings,
        )];
        out.write_png(&contact_sheet(&rows))?;
    }
    for out in [heatmap, report].into_iter().flatten() {
        out.commit()?;
    }
    let text = if args.json {
        let mut json = case_json(&case, Some(&findings));
        add_course(&mut json, &chosen);
        pretty(&json)
    } else {
        with_course_line(
            case_text(&case, &findings, args.input.as_deref(), chosen.course),
            &chosen,
        )
    };
    stdout::print_line(&text)?;
    Ok(case.difference.verdict.passes())
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
    if let Some(dir) = &args.suite_dir {
        suite::write_scenes(dir, chosen.course)?;
    }
    let mut report = args.report.as_deref().map(Destination::open).transpose()?;
    let run = run_suite(program, args.rule(), args.timeout, chosen.course)?;
    if let Some(out) = report.as_mut() {
        let rows = failing_rows(&run, |_| true);
        out.write_png(&contact_sheet(&rows))?;
    }
    if let Some(out) = report {
        out.commit()?;
    }
    let suite_dir = args.suite_dir.as_deref();
    let text = if args.json {
        let mut json = suite_json(&run, suite_dir);
        add_course(&mut json, &chosen);
        pretty(&json)
    } else {
        with_course_line(suite_text(&run, suite_dir), &chosen)
    };
    stdout::print_line(&text)?;
    Ok(run.passed())
}

/// The year checked against, in JSON: `"course"`, and `"course_chosen_because"` where it was
/// not asked for.
fn add_course(json: &mut Value, chosen: &Chosen) {
    json["course"] = Value::from(chosen.course.name());
    if let Some(why) = &chosen.why {
        json["course_chosen_because"] = Value::from(why.as_str());
    }
}

/// The report with the line saying which year was picked and why, after its first line.
fn with_course_line(text: String, chosen: &Chosen) -> String {
    let Some(why) = &chosen.why else {
        return text;
    };
    match text.split_once('\n') {
        Some((first, rest)) => format!("{first}\n{why}\n{rest}"),
        None => format!("{text}\n{why}"),
    }
}

fn pretty(value: &Value) -> String {
    // serde_json cannot fail to print a Value it built itself.
    serde_json::to_string_pretty(value).unwrap_or_default()
}

fn diagnosis_lines(list: &[Diagnosis]) -> String {
    let mut out = String::new();
    for (rank, d) in list.iter().enumerate() {
        for (i, line) in summary::diagnosis_lines(d).iter().enumerate() {
            match i {
                0 => out += &format!("  {}. {line}\n", rank + 1),
                _ => out += &format!("     {line}\n"),
            }
        }
    }
    out
}

/// The candidates and the fits beyond the catalogue, after the opening lines.
fn findings_text(findings: &Findings) -> String {
    let mut out = String::new();
    if findings.diagnosis.is_empty() {
        out += "diagnosis: no catalogued mistake reproduces the images better than the reference does\n";
    } else if findings.settled_by_fit() {
        // The fit above is the story; weak candidates would tell another.
    } else {
        out += &candidates_heading(findings);
        out += "\n";
        out += &diagnosis_lines(&findings.diagnosis);
    }
    out
}

fn case_text(
    case: &CaseReport,
    findings: &Findings,
    input: Option<&std::path::Path>,
    course: Course,
) -> String {
    let d = &case.difference;
    let mut out = format!(
        "{}, {}x{}, {} bounces: {} (tolerance: {})\n",
        case.scene_name,
        d.width,
        d.height,
        case.bounces,
        words::verdict_name(case),
        d.rule.words()
    );
    for line in opening(findings) {
        out += &line;
        out += "\n";
    }
    if d.differing_pixels == 0 {
        out += "every byte of every pixel equals the reference";
        return out;
    }
    if let Some(line) = words::passes_but_hidden(case) {
        out += &line;
        out += "\n";
    }
    out += &summary::difference_sentence(d);
    out += "\n";
    if let (Some((x0, y0, x1, y1)), Some((x, y))) = (d.bounds, d.worst_pixel) {
        out +=
            &format!("they lie in x {x0}..={x1}, y {y0}..={y1}; the worst pixel is ({x}, {y})\n");
    }
    out += &findings_text(findings);
    if let Some(pixel) = d.worst_pixel {
        let scene = input.map(|p| p.display().to_string());
        let top = case.shown_mistakes();
        let size = (d.width, d.height);
        let commands = explain_commands(scene.as_deref(), case.bounces, size, pixel, top, course);
        out += &format!(
            "the worst pixel, as the reference traces it:\n  {}\n",
            commands[0]
        );
        if let Some(compare) = commands.get(1) {
            out += &format!(
                "and beside it as the top diagnosis traces it, the steps that differ:\n  {compare}\n"
            );
        }
    }
    out.trim_end().to_string()
}

fn suite_text(run: &SuiteRun, suite_dir: Option<&Path>) -> String {
    let mut out = format!("{} over {} cases:\n", run.program, run.cases.len());
    for line in opening(&run.findings) {
        out += &line;
        out += "\n";
    }
    for c in &run.cases {
        let report = match &c.status {
            RunStatus::Ok(case) => Some(case.as_ref()),
            _ => None,
        };
        let detail = match &c.status {
            RunStatus::Ok(case) => words::case_line(case),
            other => other.failure_line().unwrap_or_default(),
        };
        out += &format!("  {:<28} {detail}\n", c.name);
        if !c.stderr_tail.is_empty() && report.is_none() && !c.said_above {
            for line in c.stderr_tail.lines() {
                out += &format!("      | {line}\n");
            }
        }
        let worth_seeing =
            report.is_some_and(|r| !r.difference.verdict.passes() || !r.hidden_mistakes.is_empty());
        if worth_seeing {
            for line in Reproduce::of(&run.program, suite_dir, &c.case, report).lines() {
                out += &format!("      {line}\n");
            }
        }
    }
    let passed = run.cases.iter().filter(|c| c.passed()).count();
    let hiding = run
        .cases
        .iter()
        .filter(|c| match &c.status {
            RunStatus::Ok(case) => c.passed() && !case.hidden_mistakes.is_empty(),
            _ => false,
        })
        .count();
    out += &words::pass_count(passed, run.cases.len(), hiding);
    out += "\n";
    let any_image = run
        .cases
        .iter()
        .any(|c| matches!(c.status, RunStatus::Ok(_)));
    if !any_image {
        out += "diagnosis: no case wrote an image to diagnose\n";
    } else if !run.passed() {
        out += &findings_text(&run.findings);
    }
    out.trim_end().to_string()
}
