//! `whitted check --program 'CMD ARGS'`: runs a student's Tick 2 program over the suite and
//! checks every image it writes. The program is untrusted input like any file: it runs in a
//! process group of its own that is killed when its case ends (so nothing it starts outlives
//! it), with a timeout, its standard output discarded and only a bounded tail of its standard
//! error kept; the PNG it writes is checked before it is decoded. Two cases run at a time;
//! Ctrl-C kills every program and removes every temporary directory within a few polls.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::Arc;
use std::time::Duration;

use crate::check::case::Case;
use crate::check::image_cache::ImageCache;
use crate::check::missing_class::MissingClass;
use crate::check::noise::{self, Noise, Seen};
use crate::check::pass_rule::PassRule;
use crate::check::renderer::SharedScene;
use crate::check::star_run::{self, StarImage};
use crate::check::student_png::{self, Rgb8};
use crate::check::suite::{cases_of, SuiteCase};
use crate::check::tick1_star::{self, StarSeen, Tick1Star};
use crate::check::{find, prepare, CaseReport, Findings};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::interrupt;
use whitted_core::scene::{self, Scene};
use whitted_process::orphans;
use whitted_process::{Capture, Process};

/// Cases running at once.
const AT_ONCE: usize = 2;

/// How often running programs are looked at (and Ctrl-C noticed).
const POLL: Duration = Duration::from_millis(20);

/// Bytes of a program's standard error kept: its end, where the exception is.
const STDERR_TAIL: usize = 4096;

/// How one case ended.
#[derive(Debug, Clone)]
pub enum RunStatus {
    /// It wrote a PNG of its year's size (640x480; 800x600 from 2021-22), which was checked.
    Ok(Box<CaseReport>),
    /// It exited with a failure status or was killed by a signal.
    Crashed(String),
    /// It was still running after the timeout (in seconds).
    Timeout(u64),
    /// It exited successfully but wrote no readable PNG.
    NoOutput(String),
    /// It wrote a PNG of another size.
    WrongSize {
        width: u32,
        height: u32,
        /// The year's size (docs/courses.md).
        expected: (u32, u32),
    },
    /// It ran out of the memory it may use (Java's OutOfMemoryError).
    OutOfMemory(String),
    /// It wrote more than a file may hold (the sandbox's file size limit).
    OutputTooLarge(String),
    /// It was not run: a Tick 1* program ran out of time on an earlier case (why, in words).
    NotRun(String),
    /// A Tick 1* option's image, judged by its option (`star_run.rs`), not by the suite.
    Star(Box<StarImage>),
}

impl RunStatus {
    pub fn name(&self) -> &'static str {
        match self {
            RunStatus::Ok(_) => "ok",
            RunStatus::Crashed(_) => "crashed",
            RunStatus::Timeout(_) => "timeout",
            RunStatus::NoOutput(_) => "no-output",
            RunStatus::WrongSize { .. } => "wrong-size",
            RunStatus::OutOfMemory(_) => "out-of-memory",
            RunStatus::OutputTooLarge(_) => "output-too-large",
            RunStatus::NotRun(_) => "not-run",
            RunStatus::Star(_) => "tick1-star",
        }
    }

    /// How a case that wrote no image to check against the suite ended, in a line (None for
    /// `Ok`); a Tick 1* image's line is its judge's.
    pub fn failure_line(&self) -> Option<String> {
        Some(match self {
            RunStatus::Ok(_) => return None,
            RunStatus::Star(s) => format!("{}: {}", s.option.what(), s.verdict.line()),
            RunStatus::WrongSize {
                width,
                height,
                expected: (w, h),
            } => format!("wrong-size: wrote {width}x{height}, expected {w}x{h}"),
            RunStatus::Crashed(message)
            | RunStatus::NoOutput(message)
            | RunStatus::OutOfMemory(message)
            | RunStatus::OutputTooLarge(message)
            | RunStatus::NotRun(message) => format!("{}: {message}", self.name()),
            RunStatus::Timeout(seconds) => format!("timeout: still running after {seconds} s"),
        })
    }
}

/// One case's result.
#[derive(Debug, Clone)]
pub struct CaseOutcome {
    pub name: String,
    /// The suite case it ran.
    pub case: SuiteCase,
    pub status: RunStatus,
    /// The last lines of what the program wrote to standard error.
    pub stderr_tail: String,
    /// Whether the suite's opening lines already say why it failed (a class that did not
    /// compile, a Tick 1* program): its line is short and its tail is not repeated.
    pub said_above: bool,
}

impl CaseOutcome {
    pub fn passed(&self) -> bool {
        match &self.status {
            RunStatus::Ok(c) => c.difference.verdict.passes(),
            RunStatus::Star(s) => s.verdict.passes(),
            _ => false,
        }
    }
}

/// The whole suite's result.
#[derive(Debug, Clone)]
pub struct SuiteRun {
    pub program: String,
    pub cases: Vec<CaseOutcome>,
    /// One diagnosis over every case that produced an image, all at once.
    pub findings: Findings,
}

impl SuiteRun {
    pub fn passed(&self) -> bool {
        self.cases.iter().all(CaseOutcome::passed)
    }
}

/// The program's words: split as a POSIX shell would, without running one.
pub fn words(program: &str) -> Result<Vec<String>> {
    match shlex::split(program) {
        Some(words) if !words.is_empty() => Ok(words),
        Some(_) => Err(Error::Usage("--program is empty".into())),
        None => Err(Error::Usage(format!(
            "--program `{program}` has an unmatched quote or a trailing backslash"
        ))),
    }
}

/// How a case's program is started: as the user gave it (`check --program`), or inside a
/// sandbox (`whitted grade`). The case's arguments (`--input S --output O --bounces B`, with
/// paths inside `dir`) are appended to the command it returns.
pub trait Launch: Sync {
    /// The command that runs the program, able to read and write `dir`.
    fn command(&self, dir: &Path) -> Result<Command>;
    /// Whether everything the program starts dies with the command (a sandbox's own process
    /// namespace): then no orphan needs adopting, and none is looked for.
    fn contains_descendants(&self) -> bool;
    /// Called once the run in `dir` is over and its processes are gone: the limit of the
    /// launcher's it hit, if any (a sandbox's cgroup, its capped writable area).
    fn ended(&self, _dir: &Path) -> Option<LimitHit> {
        None
    }
    /// Where each case's folder is made: the system's temporary folder, unless the launcher
    /// needs its own (a sandbox whose users must be able to reach it).
    fn scratch(&self) -> PathBuf {
        std::env::temp_dir()
    }
    /// Told of each step of the suite's run as it begins, for a launcher whose caller shows
    /// progress (`whitted serve`'s live attempt page); nothing by default.
    fn stage(&self, _stage: Stage<'_>) {}
}

/// A step of a suite's run, as its launcher is told of it.
#[derive(Debug, Clone, Copy)]
pub enum Stage<'a> {
    /// Case `index` (from 0) of `of` starts running (a rerun counts its own cases).
    Running {
        case: &'a SuiteCase,
        index: usize,
        of: usize,
    },
    /// The image of case `case`, the `index`th (from 0) of the `of` images written, is checked.
    Checking {
        case: &'a SuiteCase,
        index: usize,
        of: usize,
    },
}

/// A limit of a launcher's that a run hit, which only the launcher can see.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LimitHit {
    /// The kernel killed it at its memory limit.
    Memory,
    /// It filled its writable area (bytes or files): what the limit is.
    WritableArea(String),
}

/// The program as given: its words, run directly.
pub struct Plain(pub Vec<String>);

impl Launch for Plain {
    fn command(&self, _dir: &Path) -> Result<Command> {
        let mut command = Command::new(&self.0[0]);
        command.args(&self.0[1..]);
        Ok(command)
    }

    fn contains_descendants(&self) -> bool {
        false
    }
}

/// Runs `program` over the suite and passes each image by `rule`; a Tick 1* program (its
/// package `tick1star`) over its options' handout scenes instead (`star_run.rs`).
pub fn run_suite(program: &str, rule: PassRule, timeout: u64, course: Course) -> Result<SuiteRun> {
    let plain = Plain(words(program)?);
    let cache = ImageCache::new();
    run_suite_with(&plain, program, &cases_of(course), rule, timeout, &cache)
}

/// As [`run_suite_with`], for a program whose sources were seen (`check DIR`, `grade`): one
/// recognised as Tick 1* by them (`tick1_star::in_sources`), or by its package, runs its
/// options' handout scenes instead of the suite (`star_run.rs`).
pub fn run_suite_as(
    launch: &dyn Launch,
    program: &str,
    suite: &[SuiteCase],
    (rule, timeout): (PassRule, u64),
    cache: &Arc<ImageCache>,
    seen: Option<StarSeen>,
) -> Result<SuiteRun> {
    let course = suite.first().map_or(Course::Y2016, |c| c.course);
    match star_seen(program, seen) {
        Some(seen) => star_run::run(launch, program, course, timeout, seen),
        None => run_suite_with(launch, program, suite, rule, timeout, cache),
    }
}

/// Runs the program `launch` starts (shown to the user as `program`) over `suite`, and checks
/// each image, passing it by `rule`; a Tick 1* program (its package `tick1star`) over its
/// options' handout scenes instead (`star_run.rs`). The suite's whole images are kept in
/// `cache`, which a caller checking many programs over one suite (a class) shares between
/// them.
pub fn run_suite_with(
    launch: &dyn Launch,
    program: &str,
    suite: &[SuiteCase],
    rule: PassRule,
    timeout: u64,
    cache: &Arc<ImageCache>,
) -> Result<SuiteRun> {
    let course = suite.first().map_or(Course::Y2016, |c| c.course);
    if is_tick1_star(program) {
        return star_run::run(launch, program, course, timeout, StarSeen::Package);
    }
    let (finished, stopped) = run_programs(launch, suite, Duration::from_secs(timeout), false)?;
    let missing = {
        let tails: Vec<Option<&str>> = finished
            .iter()
            .map(|(ran, tail)| match ran {
                Ran::Failed(RunStatus::Crashed(_)) => Some(tail.as_str()),
                _ => None,
            })
            .collect();
        MissingClass::of_suite(&tails, course)
    };
    // Not recognised before running, but its first case ran out of time.
    let mut star = stopped.then_some(Tick1Star {
        seen: StarSeen::FirstCaseTimedOut,
        timeout,
        stopped,
        plan: None,
    });
    let mut statuses: Vec<Option<RunStatus>> = Vec::new();
    let mut tails = Vec::new();
    let mut scenes: Vec<(usize, Scene)> = Vec::new();
    let mut images: Vec<Rgb8> = Vec::new();
    for (i, (case, (result, stderr_tail))) in suite.iter().zip(finished).enumerate() {
        tails.push(stderr_tail);
        match result {
            Ran::Image(image) => {
                let (parsed, _) =
                    scene::input::parse_for_course(&case.file, case.xml.as_bytes(), case.course)?;
                scenes.push((i, parsed));
                images.push(image);
                statuses.push(None);
            }
            Ran::Failed(status) => statuses.push(Some(said_once(status, &missing, star.clone()))),
        }
    }
    let count = scenes.len();
    let mut prepared = Vec::new();
    let mut reports = Vec::new();
    let keys: Vec<String> = scenes
        .iter()
        .map(|(i, _)| whitted_core::fingerprint::fingerprint(&[suite[*i].xml.as_bytes()]))
        .collect();
    let sizes: Vec<(u32, u32)> = images.iter().map(|m| (m.width, m.height)).collect();
    for (k, ((i, scene), image)) in scenes.iter().zip(images).enumerate() {
        let case = &suite[*i];
        launch.stage(Stage::Checking {
            case,
            index: k,
            of: count,
        });
        // The cases of this scene at this image's size: rendered whole together.
        let bounce_family = (0..count)
            .filter(|&j| keys[j] == keys[k] && sizes[j] == sizes[k])
            .map(|j| suite[scenes[j].0].bounces)
            .collect();
        let shared = SharedScene {
            key: keys[k].clone(),
            bounce_family,
            cache: Arc::clone(cache),
            samples: true,
        };
        let (c, report) = prepare(
            scene,
            &case.file,
            case.bounces,
            rule,
            image,
            count,
            Some(shared),
            case.course,
        )?;
        interrupt::check()?;
        prepared.push(c);
        reports.push(report);
    }
    let all_pass = statuses.iter().all(Option::is_none)
        && reports.iter().all(|r| r.difference.verdict.passes());
    let findings = find(&prepared, all_pass, course)?;
    // Noise is never reproduced exactly: a program the diagnosis renders exactly needs no
    // second run.
    let exact = findings
        .diagnosis
        .first()
        .is_some_and(|d| d.exact && d.unexplained_pixels == 0);
    let mut findings = match exact {
        true => findings,
        false => match rerun_differs(launch, suite, &scenes, &prepared, &reports, timeout)? {
            Some(noise) => {
                star = star.or(Some(Tick1Star {
                    seen: StarSeen::TwoRunsDiffer,
                    timeout,
                    stopped: false,
                    plan: None,
                }));
                Findings::not_reproducible(prepared.len(), course, noise)
            }
            None => findings,
        },
    };
    findings.tick1_star = star;
    findings.missing_class = missing;
    let mut reports = reports.into_iter().zip(&findings.per_case);
    let outcomes = suite
        .iter()
        .zip(statuses)
        .zip(tails)
        .map(|((case, status), stderr_tail)| {
            let status = status.unwrap_or_else(|| match reports.next() {
                Some((mut report, finding)) => {
                    report.diagnosis = finding.label.iter().cloned().collect();
                    report.hidden_mistakes = finding.hidden(report.difference.verdict.passes());
                    RunStatus::Ok(Box::new(report))
                }
                None => RunStatus::Crashed("not checked".into()),
            });
            let said_above = said_above(&status, &findings);
            CaseOutcome {
                name: case.name(),
                case: case.clone(),
                status,
                stderr_tail,
                said_above,
            }
        })
        .collect();
    Ok(SuiteRun {
        program: program.to_string(),
        cases: outcomes,
        findings,
    })
}

/// A failed case's status, its message short where the suite's opening says why: a class that
/// did not compile (named here), a Tick 1* program (whose cases not run say only that).
fn said_once(
    status: RunStatus,
    missing: &Option<MissingClass>,
    star: Option<Tick1Star>,
) -> RunStatus {
    match (status, missing, star) {
        (RunStatus::Crashed(message), Some(m), _) if message != NOT_RUN => {
            RunStatus::Crashed(m.case_message(&message))
        }
        (RunStatus::NotRun(_), _, Some(star)) => RunStatus::NotRun(star.not_run()),
        (status, _, _) => status,
    }
}

/// Whether the suite's opening lines say why this case failed.
fn said_above(status: &RunStatus, findings: &Findings) -> bool {
    match status {
        RunStatus::Crashed(_) => findings.missing_class.is_some(),
        RunStatus::NotRun(_) | RunStatus::Timeout(_) => findings.tick1_star.is_some(),
        _ => false,
    }
}

/// What running one case gave.
pub(crate) enum Ran {
    Image(Rgb8),
    Failed(RunStatus),
}

/// A case whose program is running.
struct Running {
    index: usize,
    /// The program, the leader of its own process group, keeping the tail of its standard
    /// error.
    process: Process,
    /// Holds the scene and the output; removed when dropped (after `process`).
    dir: tempfile::TempDir,
    /// The size the case's year renders.
    expected: (u32, u32),
}

/// Runs every case's program, `AT_ONCE` at a time, and returns each one's result and standard
/// error tail in suite order.
/// The first failing case run once more: a program that writes another image the second time
/// samples at random (Tick 1*), and its images are compared as noise, not diagnosed. One
/// extra run, and only when a case fails and no candidate renders every case exactly.
fn rerun_differs(
    launch: &dyn Launch,
    suite: &[SuiteCase],
    scenes: &[(usize, Scene)],
    prepared: &[Case],
    reports: &[CaseReport],
    timeout: u64,
) -> Result<Option<Noise>> {
    let Some(k) = reports.iter().position(|r| !r.difference.verdict.passes()) else {
        return Ok(None);
    };
    let case = &suite[scenes[k].0];
    let again = run_programs(
        launch,
        std::slice::from_ref(case),
        Duration::from_secs(timeout),
        false,
    )?
    .0;
    let first = &prepared[k];
    Ok(match again.into_iter().next() {
        Some((Ran::Image(image), _)) if image != first.student => Some(noise::compared(
            Seen::TwoRuns,
            &first.student,
            &first.reference,
        )),
        _ => None,
    })
}

/// Whether `program` (its command line) runs a class of the course's `tick1star` package: the
/// optional Tick 1* (soft shadows, depth of field: hundreds of rays a pixel, a random image).
pub fn is_tick1_star(program: &str) -> bool {
    tick1_star::in_package(program)
}

/// How a program is known as Tick 1* before it runs, if it is: by its sources where they were
/// seen (`seen`), else by its package. Such a program runs its options' handout scenes, not
/// the suite, and `--suite-dir` writes those.
pub fn star_seen(program: &str, seen: Option<StarSeen>) -> Option<StarSeen> {
    seen.or(is_tick1_star(program).then_some(StarSeen::Package))
}

/// One case's program run alone, as the suite runs it (its own folder, scene and limits): its
/// image when it wrote one of the course's size, else `None`. For a caller that runs one case
/// again on another build of the same program (project mode's second build).
pub fn image_of_one_case(
    launch: &dyn Launch,
    case: &SuiteCase,
    timeout: u64,
) -> Result<Option<Rgb8>> {
    let (mut results, _) = run_programs(
        launch,
        std::slice::from_ref(case),
        Duration::from_secs(timeout),
        false,
    )?;
    Ok(match results.pop() {
        Some((Ran::Image(image), _)) => Some(image),
        _ => None,
    })
}

/// A crashed case's message when it was never started.
const NOT_RUN: &str = "not run";

/// Runs every case, `AT_ONCE` at a time, and says whether the suite was stopped early. With
/// `star` (a Tick 1* program) the first case out of time stops the others, and any program's
/// first case (the suite's quickest) out of time does too: a row of timeouts would tell nothing
/// more, and the report says once what it is (`tick1_star.rs`).
pub(crate) fn run_programs(
    launch: &dyn Launch,
    suite: &[SuiteCase],
    timeout: Duration,
    star: bool,
) -> Result<(Vec<(Ran, String)>, bool)> {
    let mut results: Vec<Option<(Ran, String)>> = suite.iter().map(|_| None).collect();
    let mut running: Vec<Running> = Vec::new();
    let mut next = 0;
    let mut stopped_star = false;
    let orphans = !launch.contains_descendants();
    let kill_orphans = || {
        if orphans {
            orphans::kill_adopted();
        }
    };
    if orphans {
        orphans::adopt();
    }
    loop {
        if interrupt::requested() {
            for mut r in running.drain(..) {
                stop(&mut r);
            }
            kill_orphans();
            interrupt::check()?;
        }
        while running.len() < AT_ONCE && next < suite.len() {
            launch.stage(Stage::Running {
                case: &suite[next],
                index: next,
                of: suite.len(),
            });
            match start(launch, &suite[next], next) {
                Ok(r) => running.push(r),
                Err(e) => {
                    for mut r in running.drain(..) {
                        stop(&mut r);
                    }
                    kill_orphans();
                    return Err(e);
                }
            }
            next += 1;
        }
        if running.is_empty() {
            kill_orphans();
            break;
        }
        let mut still = Vec::new();
        for mut r in running.drain(..) {
            match r.process.try_wait() {
                Ok(Some(status)) => {
                    let index = r.index;
                    results[index] = Some(finish(launch, r, Some(status), timeout));
                }
                Ok(None) if r.process.elapsed() > timeout => {
                    let index = r.index;
                    results[index] = Some(finish(launch, r, None, timeout));
                    if star || index == 0 {
                        next = suite.len();
                        stopped_star = true;
                    }
                }
                Ok(None) => still.push(r),
                Err(e) => {
                    let index = r.index;
                    let tail = stop(&mut r);
                    let status = RunStatus::Crashed(format!("cannot wait for the program: {e}"));
                    results[index] = Some((Ran::Failed(status), tail));
                }
            }
        }
        running = still;
        if stopped_star {
            for mut r in running.drain(..) {
                stop(&mut r);
            }
        }
        if !running.is_empty() {
            std::thread::sleep(POLL);
        }
    }
    let not_run = match stopped_star {
        true => RunStatus::NotRun("ran out of time on an earlier case".into()),
        false => RunStatus::Crashed(NOT_RUN.into()),
    };
    let results = results
        .into_iter()
        .map(|r| r.unwrap_or((Ran::Failed(not_run.clone()), String::new())))
        .collect();
    Ok((results, stopped_star))
}

/// Starts case `index`'s program in a fresh temporary directory and process group.
fn start(launch: &dyn Launch, case: &SuiteCase, index: usize) -> Result<Running> {
    let scratch = launch.scratch();
    let dir = tempfile::Builder::new()
        .prefix("whitted-check-")
        .tempdir_in(&scratch)
        .map_err(|e| Error::io(&scratch, "cannot create a temporary directory", e))?;
    let scene = dir.path().join(&*case.file);
    std::fs::write(&scene, case.xml_in(dir.path()).as_bytes())
        .map_err(|e| Error::io(&scene, "cannot write", e))?;
    for (name, bytes) in case.assets() {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).map_err(|e| Error::io(&path, "cannot write", e))?;
    }
    let output = output_path(dir.path());
    let mut command = launch.command(dir.path())?;
    command
        .arg("--input")
        .arg(&scene)
        .arg("--output")
        .arg(&output)
        .arg("--bounces")
        .arg(case.bounces.to_string())
        .args(case.size_option().into_iter().flatten())
        .stdin(Stdio::null())
        .stdout(Stdio::null());
    let program = command.get_program().to_string_lossy().into_owned();
    let process = Process::spawn(command, Capture::Tail(STDERR_TAIL))
        .map_err(|e| Error::Usage(format!("cannot start the program `{program}`: {e}")))?;
    Ok(Running {
        index,
        process,
        dir,
        expected: case.expected_size(),
    })
}

fn output_path(dir: &Path) -> PathBuf {
    dir.join("output.png")
}

/// The last lines of a standard error tail, as text.
fn tail_text(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(12)..].join("\n")
}

/// Kills the case's whole process group, reaps the program and returns its stderr tail. The
/// temporary directory stays until `r` is dropped.
fn stop(r: &mut Running) -> String {
    tail_text(&r.process.finish())
}

/// The result of a case whose program exited with `status` (`None`: timed out). Every
/// process of the case is gone before its output is read.
fn finish(
    launch: &dyn Launch,
    mut r: Running,
    status: Option<ExitStatus>,
    timeout: Duration,
) -> (Ran, String) {
    let tail = stop(&mut r);
    let hit = launch.ended(r.dir.path());
    let memory_limit = hit == Some(LimitHit::Memory);
    let ran = match (status, hit) {
        (None, _) => Ran::Failed(RunStatus::Timeout(timeout.as_secs())),
        (Some(_), Some(LimitHit::WritableArea(limit))) => Ran::Failed(RunStatus::OutputTooLarge(
            format!("filled its writable area ({limit})"),
        )),
        (Some(s), _) if !s.success() && memory_limit => Ran::Failed(RunStatus::OutOfMemory(
            format!("{}: killed at its memory limit", describe(s)),
        )),
        (Some(s), _) if !s.success() => Ran::Failed(failure(s, &tail)),
        (Some(_), _) => match read_output(&output_path(r.dir.path()), r.expected) {
            Ok(Ok(image)) => Ran::Image(image),
            Ok(Err((width, height))) => Ran::Failed(RunStatus::WrongSize {
                width,
                height,
                expected: r.expected,
            }),
            Err(message) => Ran::Failed(RunStatus::NoOutput(message)),
        },
    };
    (ran, tail)
}

/// Why a program failed: a limit it hit, named (Java's OutOfMemoryError; a write past the file
/// size limit, which kills with SIGXFSZ or, where the signal is ignored as the JVM does, fails
/// with EFBIG, "File too large"), or a crash.
fn failure(status: ExitStatus, tail: &str) -> RunStatus {
    const SIGXFSZ: i32 = 25;
    #[cfg(unix)]
    let signal = std::os::unix::process::ExitStatusExt::signal(&status);
    #[cfg(not(unix))]
    let signal: Option<i32> = None;
    if tail.contains("OutOfMemoryError") {
        RunStatus::OutOfMemory(describe(status))
    } else if signal == Some(SIGXFSZ) || tail.contains("File too large") {
        RunStatus::OutputTooLarge(describe(status))
    } else {
        RunStatus::Crashed(describe(status))
    }
}

/// How a program that failed ended.
fn describe(status: ExitStatus) -> String {
    #[cfg(unix)]
    if let Some(signal) = std::os::unix::process::ExitStatusExt::signal(&status) {
        return format!("killed by signal {signal}");
    }
    match status.code() {
        Some(code) => format!("exited with status {code}"),
        None => "ended abnormally".into(),
    }
}

/// The program's PNG, checked as any image is, or its size when it is not the course's (read
/// from its header, nothing decoded); the message says why there is none.
fn read_output(
    path: &Path,
    (width, height): (u32, u32),
) -> Result<std::result::Result<Rgb8, (u32, u32)>, String> {
    match std::fs::symlink_metadata(path) {
        Err(_) => return Err("the program wrote no output file".into()),
        Ok(m) if !m.is_file() => return Err("the output is not a regular file".into()),
        Ok(_) => {}
    }
    student_png::read_expecting(path, width, height).map_err(|e| match e {
        Error::Raster { msg, .. } => format!("the output {msg}"),
        other => other.to_string(),
    })
}
