//! `whitted grade SUBMISSIONS -o OUTDIR`: a whole class (docs/grade.md). Exit 0 when the class
//! is graded (whatever the students' verdicts), 2 when it cannot be, 130 on Ctrl-C (the
//! students finished by then are kept). `whitted grade -o OUTDIR --calibrate` grades no one
//! and prints what other tolerances would pass, from the results alone; `--write-skeleton`
//! writes the year's clean-room classes.

use crate::cli::GradeArgs;
use whitted_core::error::{Error, Result};
use whitted_grade::{Limits, Options};
use whitted_io::output::stdout;

pub fn run(args: &GradeArgs) -> Result<()> {
    if args.calibrate {
        return stdout::print_line(
            whitted_grade::calibrate(&args.output, args.max_beyond)?.trim_end(),
        );
    }
    if args.write_skeleton {
        return write_skeleton(args);
    }
    let Some(submissions) = &args.submissions else {
        return Err(Error::Usage("grade needs SUBMISSIONS".into()));
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let options = Options {
        submissions: submissions.clone(),
        outdir: args.output.clone(),
        skeleton: args.skeleton.clone(),
        course: args.course.course(),
        scenes: args.scenes.clone(),
        jobs: args.jobs.unwrap_or(cores),
        limits: Limits {
            memory_mib: args.memory,
            seconds: args.timeout,
        },
        rerun: args.rerun.map(Into::into),
        no_sandbox: args.no_sandbox,
        grading: args.grade.into(),
        rule: args.rule(),
        count_diagnostic: args.count_diagnostic,
        rubric: args.rubric.clone(),
        only: args.only.clone(),
        show_hidden: args.show_hidden,
        part: args.part,
        quiet: args.quiet,
        watch: None,
    };
    if args.list {
        let lines: Vec<String> = whitted_grade::list(&options)?
            .into_iter()
            .map(|(id, done)| format!("{id}\t{}", if done { "done" } else { "todo" }))
            .collect();
        return stdout::print_line(&lines.join("\n"));
    }
    let summary = whitted_grade::run(&options)?;
    let statuses: Vec<String> = summary
        .statuses
        .iter()
        .map(|(status, n)| format!("{n} {status}"))
        .collect();
    let mut text = format!(
        "{} students: {}; graded now {}, already graded {}",
        summary.students,
        statuses.join(", "),
        summary.graded_now,
        summary.skipped
    );
    if let Some(line) = summary.not_graded_line(&options) {
        text += &format!("\n{line}");
    }
    if let Some(index) = &summary.index {
        text += &format!("\n{}", index.display());
    }
    stdout::print_line(&text)
}

/// `--write-skeleton`: the year's clean-room skeleton under `OUTDIR/src/`, written into a
/// temporary folder beside OUTDIR and renamed into place, so that OUTDIR is whole or absent; an
/// existing OUTDIR is never written into.
fn write_skeleton(args: &GradeArgs) -> Result<()> {
    let out = &args.output;
    if out.exists() {
        return Err(Error::Usage(format!(
            "{}: already exists; --write-skeleton writes a new folder",
            out.display()
        )));
    }
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    let course = args.course.course();
    let sources = whitted_grade::clean_room_skeleton(course, None)?;
    let temp = tempfile::Builder::new()
        .prefix(".whitted-skeleton-")
        .tempdir_in(parent)
        .map_err(|e| Error::io(parent, "cannot create a folder in", e))?;
    for (path, bytes) in &sources {
        let path = temp.path().join("src").join(path);
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|e| Error::io(folder, "cannot create", e))?;
        }
        std::fs::write(&path, bytes).map_err(|e| Error::io(&path, "cannot write", e))?;
    }
    let temp = temp.keep();
    std::fs::rename(&temp, out).map_err(|e| {
        let _ = std::fs::remove_dir_all(&temp);
        Error::io(out, "cannot create", e)
    })?;
    stdout::print_line(&format!(
        "wrote {} files of whitted's clean-room {course} skeleton under {}",
        sources.len(),
        out.join("src").display()
    ))
}
