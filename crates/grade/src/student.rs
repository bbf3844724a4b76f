//! One student graded: their files beside the skeleton's in a work folder (from 2017-18 in
//! the student's own package, the skeleton moved into it), compiled and run over the year's
//! suite in the sandbox, checked as `check --program` checks.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};

use super::compile::{compile, Compiled};
use super::html::SharedImages;
use super::intake::{Files, Submission};
use super::jvm;
use super::policy::Policy;
use super::sandbox::{
    Area, Limits, Priority, RunGuard, Sandbox, AREA_BYTES, AREA_FILES, AREA_FULL,
};
use super::skeleton::Skeleton;
use super::source_tree::write_sources;
use super::status::StudentStatus;
use super::warm_javac::{Warm, WarmJavac};
use super::watch::Step;
use whitted_check::check::image_cache::ImageCache;
use whitted_check::check::program::{run_suite_as, Launch, LimitHit, Stage, SuiteRun};
use whitted_check::check::star_option;
use whitted_check::check::suite::SuiteCase;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

/// What a class is graded with: the same for every student.
pub struct Setup {
    pub sandbox: Sandbox,
    pub java: PathBuf,
    pub javac: PathBuf,
    pub skeleton: Skeleton,
    /// Whether the skeleton is the course's own (`--skeleton`), which a student's result names
    /// by its fingerprint, not its path.
    pub skeleton_given: bool,
    /// The year of the course the class is of (docs/courses.md).
    pub course: Course,
    pub suite: Vec<SuiteCase>,
    pub limits: Limits,
    pub tolerance: whitted_check::check::pass_rule::PassRule,
    /// Where the students' work folders are made (removed at the end).
    pub work: PathBuf,
    /// The suite's whole images, rendered once for the class.
    pub images: Arc<ImageCache>,
    /// The references every report shows, encoded once for the class.
    pub report_images: SharedImages,
    /// How cases become a grade.
    pub policy: Policy,
    /// Whether hidden scenes are shown to students in full.
    pub show_hidden: bool,
    /// OUTDIR/students: a folder per student.
    pub students_dir: PathBuf,
    /// No progress bar.
    pub quiet: bool,
    /// Told of each student's steps.
    pub watch: Option<super::watch::Watch>,
}

/// How far a student got.
pub enum Outcome {
    /// The files could not be had: `no-files` or `error`, and why.
    Refused {
        status: StudentStatus,
        message: String,
    },
    /// javac refused them: its first messages.
    CompileError(String),
    /// javac did not finish in time.
    CompileTimeout,
    /// Run over the suite and checked.
    Ran(Box<SuiteRun>),
}

/// Grades `submission` in slot `slot` of the class's workers, compiled by the warm `javac` the
/// slot shares.
pub fn grade(
    setup: &Setup,
    submission: &Submission,
    slot: usize,
    javac: &Mutex<WarmJavac>,
) -> Result<Outcome> {
    let files = match &submission.files {
        Ok(files) => files,
        Err(refusal) => {
            return Ok(Outcome::Refused {
                status: refusal.status,
                message: refusal.message.clone(),
            })
        }
    };
    let tell = |step| {
        if let Some(watch) = &setup.watch {
            watch.tell(&submission.id, step);
        }
    };
    tell(super::watch::Step::Compiling);
    let work = setup
        .work
        .join(super::work_area::STUDENTS)
        .join(&submission.id);
    let _cleanup = WorkFolder(work.clone());
    let package = package_of(setup, files);
    let owned = sources(setup, files, package);
    let sources: Vec<(&str, &[u8])> = owned
        .iter()
        .map(|(path, bytes)| (path.as_str(), bytes.as_slice()))
        .collect();
    let classes = work.join("classes");
    // The lock is held for the warm compilation only, not a fallback's; a compiler another
    // student holds for longer than `PATIENCE` (a source that makes javac slow) is left to
    // them, and this student is compiled by a javac of their own.
    let warm = match lock_within(javac, PATIENCE) {
        Some(mut warm) => warm.compile(&sources, &classes)?,
        None => Warm::Unavailable,
    };
    let priority = match warm {
        Warm::Done(_) | Warm::Unavailable => Priority::Normal,
        // A source the warm compiler could not finish may keep javac busy for a minute: it
        // must not take the CPU of the students graded beside it.
        Warm::Suspect => Priority::Background,
    };
    let compiled = match warm {
        Warm::Done(compiled) => compiled,
        Warm::Unavailable | Warm::Suspect => {
            let paths = lay_out(&sources, &work)?;
            compile(
                &setup.sandbox,
                &setup.javac,
                &work,
                &paths,
                slot,
                setup.limits,
                priority,
            )?
        }
    };
    match compiled {
        Compiled::Ok => {}
        Compiled::Errors(messages) => {
            return Ok(Outcome::CompileError(blamed(setup, files, messages)))
        }
        Compiled::Timeout => return Ok(Outcome::CompileTimeout),
    }
    // The classes, however they were made, for the sandbox's users to read.
    super::work_area::open_up(&work)?;
    let main = super::package::qualified(package, setup.skeleton.main);
    // A Tick 1* submission runs its options' handout scenes, not the suite (`star_run.rs`).
    let star = files.star;
    let launch = SandboxedJava {
        setup,
        limits: run_limits(setup, star.is_some()),
        classes,
        main: main.clone(),
        slot,
        runs: Mutex::default(),
        student: &submission.id,
    };
    let run = run_suite_as(
        &launch,
        &format!("java {main}"),
        &setup.suite,
        (setup.tolerance, setup.limits.seconds),
        &setup.images,
        star,
    )?;
    let mut run = run;
    offer_only_their_files(&mut run, setup.course);
    Ok(Outcome::Ran(Box::new(run)))
}

/// The limits a student's program runs under: `--timeout`'s, but for a Tick 1* program at a
/// year's own size, whose cases are given minutes (`star_option::timeout`): its sandbox's CPU
/// time limit must follow that time, or a correct 800x600 render of hundreds of rays a pixel
/// is killed after twice `--timeout` of CPU, long before its case's time is up.
fn run_limits(setup: &Setup, star: bool) -> Limits {
    match star {
        true => Limits {
            seconds: star_option::timeout(setup.course, setup.limits.seconds),
            ..setup.limits
        },
        false => setup.limits,
    }
}

/// The candidates after the first keep only mistakes in the files a student hands in: one in
/// the skeleton's classes (`Sphere.intersectionWith`) cannot be theirs, since grade compiles
/// the skeleton's own. The first stays whatever it is: the per-case labels are its.
fn offer_only_their_files(run: &mut SuiteRun, course: Course) {
    let theirs = |bug: whitted_check::mistakes::Bug| {
        let class = bug.place().split('.').next().unwrap_or("");
        super::archive::submitted(course)
            .iter()
            .any(|file| file.strip_suffix(".java") == Some(class))
    };
    let mut first = true;
    run.findings.diagnosis.retain(|d| {
        let keep = first || d.mistakes.bugs().into_iter().all(theirs);
        first = false;
        keep
    });
}

/// javac's messages, after a line saying whose the fault is when it is not plainly the
/// student's: their file declares one of the skeleton's classes (`clash.rs`), or the first
/// error is in the skeleton's own files.
fn blamed(setup: &Setup, files: &Files, messages: String) -> String {
    let theirs = files.sources.iter().map(|(n, b)| (*n, b.as_slice()));
    let skeleton: Vec<&str> = setup
        .skeleton
        .files
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    match super::clash::message(&super::clash::clashes(theirs, &skeleton)) {
        Some(clash) => format!("{clash}\n{messages}"),
        None => skeleton_named(&setup.skeleton, messages),
    }
}

/// javac's messages, with a first line saying so when the first error is in one of the
/// skeleton's files rather than the student's: the skeleton given to grade may not compile
/// (2023-24's `BumpySphere` as shipped lacks a return), which is the grader's to mend.
fn skeleton_named(skeleton: &Skeleton, messages: String) -> String {
    let first_error = messages.lines().find(|l| l.contains(": error:"));
    let file = first_error
        .and_then(|l| l.split(':').next())
        .and_then(|path| path.rsplit('/').next());
    match file {
        Some(file) if skeleton.files.iter().any(|(name, _)| name == file) => format!(
            "The first error is in the skeleton's {file}, not in a file the student hands in: \
             the skeleton given to grade may not compile (2023-24's BumpySphere.java as \
             shipped does not; give --skeleton one that does).\n{messages}"
        ),
        _ => messages,
    }
}

/// How long a student waits for the warm compiler its slot shares before compiling with a
/// javac of its own: a warm compilation takes a tenth of a second, so a wait this long means
/// the compiler is busy with a slow source, and one slow compile must not hold the others.
const PATIENCE: std::time::Duration = std::time::Duration::from_secs(2);

/// `mutex` locked, if it can be within `patience` (a poisoned lock still guards a usable
/// compiler: the one who panicked held it between students).
fn lock_within<T>(mutex: &Mutex<T>, patience: std::time::Duration) -> Option<MutexGuard<'_, T>> {
    let started = std::time::Instant::now();
    loop {
        match mutex.try_lock() {
            Ok(guard) => return Some(guard),
            Err(TryLockError::Poisoned(e)) => return Some(e.into_inner()),
            Err(TryLockError::WouldBlock) if started.elapsed() < patience => {
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
            Err(TryLockError::WouldBlock) => return None,
        }
    }
}

/// The work folder, removed when the student is done (or the grading stops).
struct WorkFolder(PathBuf);

impl Drop for WorkFolder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The package the student's program is compiled in: 2016-17's is the skeleton's
/// (`gfx.tick2`); from 2017-18 the one their files declare, their own user id in it.
fn package_of<'a>(setup: &'a Setup, files: &'a Files) -> Option<&'a str> {
    match setup.course.is_default() {
        true => setup.skeleton.package.as_deref(),
        false => files.package.as_deref(),
    }
}

/// What is compiled, each at its path under the source root: the skeleton's files moved
/// into `package`, and the student's.
fn sources(setup: &Setup, files: &Files, package: Option<&str>) -> Vec<(String, Vec<u8>)> {
    let folder = super::package::folder(package);
    let theirs = files
        .sources
        .iter()
        .map(|(name, bytes)| (format!("{folder}{name}"), bytes.clone()));
    // A Tick 1* hand-in of one file: whitted's finished Tick 1 for the rest (`finished.rs`).
    let finished = files.completed.iter().filter_map(|name| {
        let bytes = super::finished::source(name, setup.course)?;
        let from = Some(super::skeleton::TICK1_PACKAGE);
        Some((
            format!("{folder}{name}"),
            super::package::moved(&bytes, from, package),
        ))
    });
    setup
        .skeleton
        .sources_in(package)
        .into_iter()
        .chain(finished)
        .chain(theirs)
        .map(|(path, bytes)| (path, without_bom(&bytes).to_vec()))
        .collect()
}

/// `source` without a leading UTF-8 byte order mark, which Windows editors write and IDEs
/// accept but javac rejects as an illegal character (JDK-4508058).
fn without_bom(source: &[u8]) -> &[u8] {
    source.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(source)
}

/// `work/src/` with `sources` at their paths and an empty `work/classes`; returns the
/// sources' paths.
fn lay_out(sources: &[(&str, &[u8])], work: &Path) -> Result<Vec<String>> {
    let _ = std::fs::remove_dir_all(work);
    let classes = work.join("classes");
    std::fs::create_dir_all(&classes).map_err(|e| Error::io(&classes, "cannot create", e))?;
    let paths = write_sources(&work.join("src"), sources)?;
    super::work_area::open_up(work)?;
    Ok(paths)
}

/// The student's compiled program, run in the sandbox: `java gfx.tick2.Tick2` (from 2017-18
/// `java <their package>.Tick1`) with the case's arguments appended.
struct SandboxedJava<'a> {
    setup: &'a Setup,
    /// The limits its cases run under (`run_limits`).
    limits: Limits,
    classes: PathBuf,
    /// The main class, qualified.
    main: String,
    slot: usize,
    /// Each running case's guard (its cgroup, its filter), by its folder (removed when dropped).
    runs: Mutex<HashMap<PathBuf, RunGuard>>,
    /// The student's id, which the setup's watch is told with each step.
    student: &'a str,
}

impl Launch for SandboxedJava<'_> {
    fn command(&self, dir: &Path) -> Result<Command> {
        let limits = self.limits;
        let mut program = vec![self.setup.java.display().to_string()];
        program.extend(jvm::options(limits));
        program.extend([
            "-Djava.awt.headless=true".into(),
            "-cp".into(),
            self.classes.display().to_string(),
            self.main.clone(),
        ]);
        // The scene in it, for the sandbox's user to read.
        super::work_area::open_up(dir)?;
        let classes = self.classes.as_path();
        let (command, run) = self.setup.sandbox.command(
            &program,
            &[classes],
            dir,
            Area::Capped,
            self.slot,
            limits,
            Priority::Normal,
        )?;
        self.runs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .insert(dir.to_path_buf(), run);
        Ok(command)
    }

    fn contains_descendants(&self) -> bool {
        !self.setup.sandbox.is_none()
    }

    fn scratch(&self) -> PathBuf {
        self.setup.work.join(super::work_area::CASES)
    }

    fn stage(&self, stage: Stage<'_>) {
        if let Some(watch) = &self.setup.watch {
            watch.tell(self.student, Step::of(stage, self.setup.show_hidden));
        }
    }

    fn ended(&self, dir: &Path) -> Option<LimitHit> {
        let run = self
            .runs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .remove(dir);
        if run.is_some_and(|r| r.oom_killed()) {
            return Some(LimitHit::Memory);
        }
        let full = dir.join(AREA_FULL).exists() && !self.setup.sandbox.is_none();
        full.then(|| {
            LimitHit::WritableArea(format!("{} MiB or {} files", AREA_BYTES >> 20, AREA_FILES))
        })
    }
}
