//! whitted-grade: a class at once. Reads Moodle's zip of a class's submissions, compiles and runs
//! every student's untrusted program in a sandbox (bubblewrap, seccomp, a memory cgroup), checks
//! each image with whitted-check, and writes the reports, the class page and Moodle's worksheet
//! and feedback files (`docs/grade.md`).
//!
//! # What it may depend on
//! whitted-core, whitted-io, whitted-check, and zip for Moodle's archives. Never clap: the
//! command line builds this crate's `Options` and passes them down.
//!
//! `whitted grade SUBMISSIONS -o OUTDIR`: a whole class at once (docs/grade.md). Every
//! student's `Plane.java` and `Renderer.java` are compiled against the skeleton and run over
//! the suite in a sandbox, checked as `check --program` checks one student, and written up:
//! a `result.json` (Gradescope's shape), a report to send, and the class's own pages.
//!
//! Runs survive faults: each student's files are written atomically, `result.json` last,
//! keyed by a hash of what decides the result (their two files, the skeleton, the scenes,
//! whitted's version and the settings), so a rerun skips whoever is finished and Ctrl-C keeps
//! them; the class files are made from the `result.json`s alone.

mod archive;
mod beyond;
mod calibrate;
mod clash;
mod class;
mod compile;
mod feedback_zip;
mod finished;
mod html;
mod intake;
mod jvm;
mod memory_cgroup;
mod moodle;
mod package;
mod policy;
pub mod project;
mod reason;
mod redact;
mod report;
mod result;
mod sandbox;
mod scenes;
mod seccomp;
mod similar;
mod skeleton;
mod source_tree;
mod status;
mod student;
mod warm_javac;
mod watch;
mod work_area;
mod wrong_year;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

pub use policy::{Grading, Policy};
pub use sandbox::Limits;
pub use watch::{Step, Watch};

use html::SharedImages;
use intake::Submission;
use result::StudentResult;
use sandbox::Sandbox;
use skeleton::Skeleton;
use status::StudentStatus;
use student::{Outcome, Setup};
use warm_javac::WarmJavac;
use whitted_check::check::image_cache::ImageCache;
use whitted_check::check::pass_rule::{Allowance, PassRule};
use whitted_check::check::suite::{cases_of, SuiteCase};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::fingerprint::fingerprint;
use whitted_io::output::atomic::AtomicFile;
use work_area::WorkArea;

/// Which finished students a run grades again.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rerun {
    /// Only those whose result ended in an error or a timeout.
    Failed,
    /// Everyone.
    All,
}

/// What `whitted grade` was asked.
#[derive(Debug, Clone)]
pub struct Options {
    pub submissions: PathBuf,
    pub outdir: PathBuf,
    pub skeleton: Option<PathBuf>,
    /// The year of the course the class is of (docs/courses.md): its submitted files, its
    /// skeleton's package and main class, its suite and its catalogue.
    pub course: Course,
    /// The course's hidden scenes, added to the suite.
    pub scenes: Option<PathBuf>,
    pub jobs: usize,
    pub limits: Limits,
    pub rerun: Option<Rerun>,
    pub no_sandbox: bool,
    pub grading: Grading,
    /// When a case passes (`--tolerance`, `--max-beyond`).
    pub rule: PassRule,
    /// Whether whitted's diagnostic scenes count towards the grade.
    pub count_diagnostic: bool,
    /// A rubric file weighing the cases (docs/grade.md, "What counts").
    pub rubric: Option<PathBuf>,
    /// Only these students (ids as the class lists them), graded again whatever OUTDIR holds.
    pub only: Vec<String>,
    /// Whether hidden scenes are shown to students in full (their XML, their reference).
    pub show_hidden: bool,
    /// Only the `k`-th of `n` shares of the class (a Slurm array task); the class files are
    /// then left to the run that aggregates.
    pub part: Option<(usize, usize)>,
    pub quiet: bool,
    /// Told of each student's steps as they happen (`whitted serve`'s live page).
    pub watch: Option<Watch>,
}

/// What a run did, for the closing lines.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    pub students: usize,
    pub graded_now: usize,
    pub skipped: usize,
    /// Students per status, over the whole class.
    pub statuses: Vec<(String, usize)>,
    /// Students of the class with no result in OUTDIR (`--only` graded others): the class
    /// files give them no grade.
    pub not_graded: usize,
    /// The class page, when this run wrote it.
    pub index: Option<PathBuf>,
}

impl Summary {
    /// What the closing lines say of the students left ungraded, and how to grade them;
    /// None when there are none.
    pub fn not_graded_line(&self, options: &Options) -> Option<String> {
        (self.not_graded > 0).then(|| {
            format!(
                "{} not graded by this run or an earlier one into {}: their grades in \
                 moodle.csv and class.csv are left blank (an upload leaves them as they are); \
                 grade them with `whitted grade {} -o {}` (without --only)",
                self.not_graded,
                options.outdir.display(),
                options.submissions.display(),
                options.outdir.display()
            )
        })
    }
}

/// Grades the class of `options`.
pub fn run(options: &Options) -> Result<Summary> {
    refuse_outdir_inside(&options.submissions, &options.outdir)?;
    let (skeleton, suite, policy) = course(options)?;
    let submissions = intake::read(&options.submissions, options.course)?;
    wrong_year::refuse_tick1_as_2016(&submissions, options.course)?;
    let only = only(options, &submissions)?;
    let java = jdk_tool("java")?;
    let javac = jdk_tool("javac")?;
    // Run as root, the sandboxes run as users of their own, who must reach the work folder.
    let others = !options.no_sandbox && rustix::process::geteuid().is_root();
    let work = WorkArea::create(others)?;
    let sandbox = match options.no_sandbox {
        true => Sandbox::None,
        false => Sandbox::bubblewrap(&java, work.path())?,
    };
    let students_dir = options.outdir.join("students");
    std::fs::create_dir_all(&students_dir)
        .map_err(|e| Error::io(&students_dir, "cannot create", e))?;
    let setup = Setup {
        sandbox,
        java,
        javac,
        skeleton,
        course: options.course,
        suite,
        limits: options.limits,
        tolerance: policy.rule,
        work: work.path().to_path_buf(),
        skeleton_given: options.skeleton.is_some(),
        images: ImageCache::new(),
        report_images: SharedImages::default(),
        policy,
        show_hidden: options.show_hidden,
        students_dir,
        quiet: options.quiet,
        watch: options.watch.clone(),
    };
    let (policy, students_dir) = (&setup.policy, &setup.students_dir);
    let mine: Vec<&Submission> = submissions
        .iter()
        .enumerate()
        .filter(|(i, _)| options.part.is_none_or(|(k, n)| i % n == k - 1))
        .map(|(_, s)| s)
        .filter(|s| only.is_empty() || only.contains(&s.id))
        .collect();
    let todo: Vec<(&Submission, String)> = mine
        .iter()
        .map(|s| (*s, key(&setup.skeleton, &setup.suite, policy, options, s)))
        .filter(|(s, key)| !only.is_empty() || needs_grading(students_dir, s, key, options.rerun))
        .collect();
    let skipped = mine.len() - todo.len();
    // Without a sandbox, orphans of a program are found as this process's children, which
    // would be the other students' programs too: one student at a time then.
    let jobs = if setup.sandbox.is_none() {
        1
    } else {
        options.jobs.max(1)
    };
    grade_all(&setup, &todo, jobs)?;
    let rows = read_rows(students_dir, &submissions);
    let mut summary = Summary {
        students: submissions.len(),
        graded_now: todo.len(),
        skipped,
        statuses: count_statuses(&rows),
        not_graded: rows.iter().filter(|r| !r.is_graded()).count(),
        index: None,
    };
    if options.part.is_none() {
        let settings = [
            format!("Course: {}.", options.course),
            format!("Skeleton: {}.", setup.skeleton.source),
            format!("Grading: {}.", policy.describe()),
            match setup.sandbox.is_none() {
                true => "Run with --no-sandbox: the programs ran unconfined.".to_string(),
                false => "Every program ran in the sandbox (docs/grade.md).".to_string(),
            },
        ];
        let title = format!("{}: the class", tick(options.course));
        summary.index = Some(write_class(
            &options.outdir,
            &rows,
            &title,
            &settings,
            options.course,
        )?);
    }
    Ok(summary)
}

/// The students `--only` names, as the class lists them; an id the class does not have is
/// refused before anyone is graded.
fn only(options: &Options, submissions: &[Submission]) -> Result<Vec<String>> {
    let mut ids = Vec::new();
    for id in &options.only {
        let safe = intake::safe_id(id);
        if !submissions.iter().any(|s| s.id == safe) {
            return Err(Error::Usage(format!(
                "--only {id}: no student of that id in {}",
                options.submissions.display()
            )));
        }
        ids.push(safe);
    }
    Ok(ids)
}

/// Every student in class order, and whether OUTDIR holds their finished result: what a farm
/// needs to share the class out and to resume it. Needs neither a JDK nor a sandbox.
pub fn list(options: &Options) -> Result<Vec<(String, bool)>> {
    let (skeleton, suite, policy) = course(options)?;
    let submissions = intake::read(&options.submissions, options.course)?;
    let students_dir = options.outdir.join("students");
    Ok(submissions
        .iter()
        .map(|s| {
            let key = key(&skeleton, &suite, &policy, options, s);
            let done = !needs_grading(&students_dir, s, &key, options.rerun);
            (s.id.clone(), done)
        })
        .collect())
}

/// whitted's clean-room skeleton of `course`, its sources moved into `package` (None: the
/// skeleton's own, `gfx.tick2` or the course's placeholder `...gfxintro.crsid.tick1`), each at
/// its path under the source root: what a student's files compile beside.
pub fn clean_room_skeleton(
    course: Course,
    package: Option<&str>,
) -> Result<Vec<(String, Vec<u8>)>> {
    let skeleton = Skeleton::clean_room(course)?;
    let to = package.or(skeleton.package.as_deref());
    Ok(skeleton.sources_in(to))
}

/// `text`, a Java source in the skeleton template's markers (`skeleton/tick1/README.md`), as
/// `course`'s API has it: how the tests write one student's files for every year.
pub fn for_year(text: &str, course: Course) -> std::result::Result<String, String> {
    skeleton::select(text, course)
}

/// `text`, whitted's finished Tick 1 (`skeleton/tick1/finished/`) or an edit of it, as
/// `course`'s student has it: how the tests write a student's files from the finished ones.
pub fn finished_for_year(text: &str, course: Course) -> std::result::Result<String, String> {
    finished::for_year(text, course)
}

/// `--calibrate`: over the class graded into `outdir`, how many students each pair (channel
/// tolerance, pixel allowance) passes and what it lets through, from the results alone (no
/// program runs); `extra` adds an allowance to those shown.
pub fn calibrate(outdir: &Path, extra: Option<Allowance>) -> Result<String> {
    calibrate::run(outdir, extra)
}

/// The class files (`class.csv`, `mistakes.csv`, `moodle.csv`, `feedback.zip`, `index.html`)
/// of the students graded into `outdir/students`, from their `result.json`s alone, nothing
/// run: what `whitted serve` exports from the students' latest attempts, each graded by a run
/// of its own. Returns the class page.
pub fn write_class_files(outdir: &Path, course: Course) -> Result<PathBuf> {
    let rows = read_rows(&outdir.join("students"), &[]);
    let settings = [
        format!("Course: {course}."),
        "Each student's latest attempt at the course's tester (`whitted serve`).".to_string(),
    ];
    let title = format!("{}: the class", tick(course));
    write_class(outdir, &rows, &title, &settings, course)
}

/// The exercise's name in reports and on the class page: 2016-17's Tick 2, the later years'
/// Tick 1 with its year.
pub fn tick(course: Course) -> String {
    match course.is_default() {
        true => "Tick 2".into(),
        false => format!("Tick 1 ({course})"),
    }
}

/// What every student is graded against: the year's skeleton, its suite (with `--scenes`)
/// and the grading policy.
fn course(options: &Options) -> Result<(Skeleton, Vec<SuiteCase>, Policy)> {
    let skeleton = Skeleton::of(options.course, options.skeleton.as_deref())?;
    let mut suite = cases_of(options.course);
    if let Some(dir) = &options.scenes {
        for case in scenes::read(dir, options.course)? {
            if suite.iter().any(|c| c.name() == case.name()) {
                return Err(Error::Usage(format!(
                    "--scenes {}: {} has the name of a case of the suite; rename it",
                    dir.display(),
                    case.file
                )));
            }
            suite.push(case);
        }
    }
    let policy = Policy::new(
        &suite,
        options.grading,
        options.rule,
        options.count_diagnostic,
        options.rubric.as_deref(),
    )?;
    Ok((skeleton, suite, policy))
}

/// OUTDIR inside the submissions folder would be read as a student next time.
fn refuse_outdir_inside(submissions: &Path, outdir: &Path) -> Result<()> {
    let (Ok(inputs), Some(parent)) = (submissions.canonicalize(), absolute_parent(outdir)) else {
        return Ok(());
    };
    if inputs.is_dir() && parent.starts_with(&inputs) {
        return Err(Error::Usage(format!(
            "-o {} is inside the submissions {}: give a folder outside them",
            outdir.display(),
            submissions.display()
        )));
    }
    Ok(())
}

/// `path` made absolute through its nearest existing ancestor.
fn absolute_parent(path: &Path) -> Option<PathBuf> {
    let absolute = std::path::absolute(path).ok()?;
    let mut existing = absolute.as_path();
    let mut rest = Vec::new();
    while !existing.exists() {
        rest.push(existing.file_name()?.to_os_string());
        existing = existing.parent()?;
    }
    let mut resolved = existing.canonicalize().ok()?;
    for part in rest.iter().rev() {
        resolved.push(part);
    }
    Some(resolved)
}

/// `java` or `javac`, from PATH.
fn jdk_tool(name: &str) -> Result<PathBuf> {
    sandbox::find_in_path(name).ok_or_else(|| {
        Error::Environment(format!(
            "whitted grade compiles and runs the students' Java: `{name}` is not on PATH \
             (`apt install default-jdk-headless`)"
        ))
    })
}

/// What decides a student's result, hashed: their files, the skeleton, the year, the suite,
/// whitted's version and the settings that change a verdict or a grade. The limits are not in
/// it: they change only the results that hit one, which `--rerun failed` grades again.
fn key(
    skeleton: &Skeleton,
    suite: &[SuiteCase],
    policy: &Policy,
    options: &Options,
    submission: &Submission,
) -> String {
    let mut parts: Vec<Vec<u8>> = vec![env!("CARGO_PKG_VERSION").as_bytes().to_vec()];
    parts.push(options.course.name().as_bytes().to_vec());
    match &submission.files {
        Ok(files) => {
            for (name, bytes) in &files.sources {
                parts.push(name.as_bytes().to_vec());
                parts.push(bytes.clone());
            }
            // What completes a one-file Tick 1* hand-in is graded too.
            for name in &files.completed {
                parts.push(format!("finished {name}").into_bytes());
                parts.extend(finished::source(name, options.course));
            }
        }
        Err(refusal) => parts.push(refusal.message.as_bytes().to_vec()),
    }
    for (name, bytes) in &skeleton.files {
        parts.push(name.as_bytes().to_vec());
        parts.push(bytes.clone());
    }
    for case in suite {
        parts.push(case.xml.as_bytes().to_vec());
        parts.push(case.bounces.to_le_bytes().to_vec());
    }
    parts.push(policy.key_bytes());
    parts.push(vec![
        u8::from(options.no_sandbox),
        u8::from(options.show_hidden),
    ]);
    // Each part's length first, so that moving bytes from one part to the next changes it.
    let framed: Vec<Vec<u8>> = parts
        .iter()
        .flat_map(|p| [(p.len() as u64).to_le_bytes().to_vec(), p.clone()])
        .collect();
    let slices: Vec<&[u8]> = framed.iter().map(Vec::as_slice).collect();
    fingerprint(&slices)
}

/// The result.json a student has, if it can be read.
fn read_result(students_dir: &Path, id: &str) -> Option<StudentResult> {
    let path = students_dir.join(id).join("result.json");
    StudentResult::parse(&std::fs::read(path).ok()?)
}

/// Whether `submission` is graded on this run: no result under this key, or `--rerun` says so.
fn needs_grading(
    students_dir: &Path,
    submission: &Submission,
    key: &str,
    rerun: Option<Rerun>,
) -> bool {
    let Some(result) = read_result(students_dir, &submission.id) else {
        return true;
    };
    let extra = &result.extra;
    match rerun {
        Some(Rerun::All) => true,
        Some(Rerun::Failed) => extra.failed || extra.key != key,
        None => extra.key != key,
    }
}

/// Workers that share one warm compiler (`warm_javac.rs`): a compilation is a small part of a
/// student's time, and each compiler's JVM costs seconds of CPU to start and warm up (on the
/// bench class with `-j 2`, two compilers took 5.7 s of CPU for 24 students).
const WORKERS_PER_COMPILER: usize = 4;

/// Grades `todo`, `jobs` students at a time, each written as soon as it is done.
fn grade_all(setup: &Setup, todo: &[(&Submission, String)], jobs: usize) -> Result<()> {
    let progress = whitted_core::progress::Bar::counting(
        todo.len() as u64,
        setup.quiet,
        "grading",
        "students",
    );
    let next = AtomicUsize::new(0);
    let failure: Mutex<Option<Error>> = Mutex::new(None);
    let workers = jobs.min(todo.len());
    let root = setup.work.join(work_area::COMPILERS);
    let compilers: Vec<Mutex<WarmJavac>> = (0..workers.div_ceil(WORKERS_PER_COMPILER))
        .map(|c| {
            let javac = WarmJavac::new(&setup.sandbox, &setup.java, &root, c, setup.limits);
            Mutex::new(javac)
        })
        .collect();
    std::thread::scope(|scope| {
        for slot in 0..workers {
            let (next, failure, progress) = (&next, &failure, &progress);
            let javac = &compilers[slot / WORKERS_PER_COMPILER];
            scope.spawn(move || loop {
                let stop = failure.lock().map(|f| f.is_some()).unwrap_or(true);
                let i = next.fetch_add(1, Ordering::SeqCst);
                if stop || i >= todo.len() || whitted_core::interrupt::requested() {
                    return;
                }
                let (submission, key) = &todo[i];
                let graded = grade_one(setup, submission, key, slot, javac);
                match graded {
                    Ok(()) => progress.advance(1),
                    Err(e) => {
                        if let Ok(mut f) = failure.lock() {
                            f.get_or_insert(e);
                        }
                        return;
                    }
                }
            });
        }
    });
    progress.finish();
    whitted_core::interrupt::check()?;
    match failure.into_inner().ok().flatten() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Grades one student and writes their folder: report.png, report.html, then result.json.
fn grade_one(
    setup: &Setup,
    submission: &Submission,
    key: &str,
    slot: usize,
    javac: &Mutex<WarmJavac>,
) -> Result<()> {
    let outcome = match student::grade(setup, submission, slot, javac) {
        Ok(outcome) => outcome,
        Err(e @ Error::Interrupted { .. }) => return Err(e),
        // Anything else that stops this student (the program could not be started, a
        // folder not written) is their status, not the class's end.
        Err(e) => Outcome::Refused {
            status: StudentStatus::Error,
            message: e.to_string(),
        },
    };
    // Nothing of the grading machine in what the student is sent (redact.rs).
    let outcome = redact::Redactor::new(&setup.work).outcome(outcome);
    let sandboxed = !setup.sandbox.is_none();
    let skeleton = &redact::skeleton_label(&setup.skeleton, setup.skeleton_given);
    let result = result::build(
        submission,
        &outcome,
        key,
        &setup.policy,
        sandboxed,
        skeleton,
        setup.show_hidden,
    );
    let feedback = &result.extra.feedback;
    let dir = setup.students_dir.join(&submission.id);
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, "cannot create", e))?;
    let mut png = Vec::new();
    let tick = tick(setup.course);
    let shown = report::Shown {
        hidden: setup.show_hidden,
        policy: &setup.policy,
        images: &setup.report_images,
        tick: &tick,
    };
    whitted_io::output::png::write_png(&mut png, &report::sheet(&outcome, feedback, &shown))
        .map_err(|e| Error::Environment(format!("cannot encode a report: {e}")))?;
    write_atomic(&dir.join("report.png"), &png)?;
    let page = report::page(submission, &outcome, feedback, sandboxed, &shown);
    write_atomic(&dir.join("report.html"), page.as_bytes())?;
    write_atomic(&dir.join("result.json"), result.to_json().as_bytes())
}

/// Writes `bytes` to `path` whole or not at all (`output::atomic`).
fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let mut file = AtomicFile::create(path)?;
    file.file()
        .write_all(bytes)
        .map_err(|e| Error::io(path, "cannot write output", e))?;
    file.commit()
}

/// Every student's row, from their result.json; one without is an `error` row. Students
/// OUTDIR holds from earlier runs on other inputs (a late submission graded alone, `--only`)
/// keep their rows: grading into an existing output merges, never drops anyone.
fn read_rows(students_dir: &Path, submissions: &[Submission]) -> Vec<StudentResult> {
    let mut rows: Vec<StudentResult> = submissions
        .iter()
        .map(|s| read_result(students_dir, &s.id).unwrap_or_else(|| StudentResult::not_graded(s)))
        .collect();
    if let Ok(entries) = std::fs::read_dir(students_dir) {
        let mut others: Vec<StudentResult> = entries
            .flatten()
            .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
            .filter_map(|e| read_result(students_dir, &e.file_name().to_string_lossy()))
            .filter(|r| !submissions.iter().any(|s| s.id == r.extra.id))
            .collect();
        rows.append(&mut others);
    }
    rows.sort_by(|a, b| a.extra.id.cmp(&b.extra.id));
    rows
}

fn count_statuses(rows: &[StudentResult]) -> Vec<(String, usize)> {
    let mut counts: std::collections::BTreeMap<&str, usize> = Default::default();
    for r in rows {
        *counts.entry(r.extra.status.name()).or_default() += 1;
    }
    counts
        .into_iter()
        .map(|(s, n)| (s.to_string(), n))
        .collect()
}

/// The class files; returns the path of index.html.
fn write_class(
    outdir: &Path,
    rows: &[StudentResult],
    title: &str,
    settings: &[String],
    course: Course,
) -> Result<PathBuf> {
    let now = moodle::modified_now();
    write_atomic(&outdir.join("class.csv"), class::class_csv(rows).as_bytes())?;
    write_atomic(
        &outdir.join("mistakes.csv"),
        class::mistakes_csv(rows, course).as_bytes(),
    )?;
    write_atomic(
        &outdir.join("moodle.csv"),
        class::moodle_csv(rows, &now).as_bytes(),
    )?;
    let (zip, students) = (outdir.join("feedback.zip"), outdir.join("students"));
    if !feedback_zip::is_current(&zip, &students, rows) {
        write_atomic(&zip, &feedback_zip::build(&students, rows)?)?;
    }
    let index = outdir.join("index.html");
    write_atomic(&index, class::index_html(rows, title, settings).as_bytes())?;
    Ok(index)
}
