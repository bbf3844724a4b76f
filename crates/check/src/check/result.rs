//! The one result of a check: what `whitted check` found, as plain data, built once here and
//! printed by every printer (`print`: the text on one screen or in full, the JSON, the HTML
//! page) so that no printer finds a fact again. The command builds it and picks a printer;
//! `grade` prints its students' runs through the same HTML pieces.

use std::path::Path;

use super::program::{RunStatus, SuiteRun};
use super::reproduce::Reproduce;
use super::suite::Role;
use super::which_course::Chosen;
use super::{CaseReport, Findings};
use whitted_core::course::Course;

/// A whole check: of one image, or of a program over the suite.
#[derive(Debug, Clone)]
pub struct CheckResult {
    /// The year checked against.
    pub course: Course,
    /// Why that year, where it was not asked for (`--course`): a line of the report.
    pub course_why: Option<String>,
    pub subject: Subject,
    /// One for an image; one per suite case, in suite order, for a program.
    pub cases: Vec<CaseResult>,
    /// The diagnosis over every case with an image, the progress, the fits.
    pub findings: Findings,
    /// Lines said before the cases by whoever ran the check (a project folder's: its main
    /// class, its build, a course class that differs from the year's), after the course line.
    pub notes: Vec<String>,
    /// The JSON's `"project"` object, for a check of a project folder.
    pub project: Option<serde_json::Value>,
    /// The report file written beside the text (`--report`), as it was named.
    pub report: Option<String>,
}

/// What was checked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Subject {
    /// A student's image, by the name it was given.
    Image { image: String },
    /// A student's program (`--program`), and whether the suite's scenes were written
    /// (`--suite-dir`), which decides whether its cases can be rerun.
    Program {
        program: String,
        scenes_written: bool,
    },
}

/// One case of a check.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The case's name: the image's, or the suite case's (`test1.xml -b 2`).
    pub name: String,
    /// How the run ended, with its check when it wrote an image (an image's check is `Ok`).
    pub status: RunStatus,
    /// The end of the program's standard error (empty for an image).
    pub stderr_tail: String,
    /// Whether what its standard error says is said once above every case (a class missing
    /// because compilation failed), so the case does not repeat it.
    pub said_above: bool,
    /// A suite case's role; None for an image.
    pub role: Option<Role>,
    /// What reproduces it from the directory the check ran in.
    pub reproduce: Reproduce,
    /// Whether it passes, where a verdict other than its bytes' decides it: a Tick 1* bump
    /// image judged as a draw (no random image equals any one render) or as option 1 not
    /// done (`BumpVerdict::decides`).
    pub decided: Option<bool>,
}

impl CaseResult {
    /// The check of its image, if it wrote one.
    pub fn report(&self) -> Option<&CaseReport> {
        match &self.status {
            RunStatus::Ok(case) => Some(case),
            _ => None,
        }
    }

    pub fn passed(&self) -> bool {
        match (&self.status, self.decided) {
            (_, Some(passes)) => passes,
            (RunStatus::Star(s), None) => s.verdict.passes(),
            (_, None) => self.report().is_some_and(|r| r.difference.verdict.passes()),
        }
    }

    /// Whether its commands are worth a student's time: it fails, or passes while rendering
    /// exactly what catalogued mistakes render; a Tick 1* option's image always (a random
    /// image is seen again only by running it again).
    pub fn worth_rerunning(&self) -> bool {
        // An image judged by its verdict (a bump draw, an option not done): its bytes'
        // comparison, and the commands that trace it, say nothing.
        matches!(self.status, RunStatus::Star(_))
            || (self.decided.is_none()
                && self.report().is_some_and(|r| {
                    !r.difference.verdict.passes() || !r.hidden_mistakes.is_empty()
                }))
    }
}

impl CheckResult {
    /// The check of one image (`name` as given) of a scene (`scene`: the `-i` path as given,
    /// None for the embedded one).
    pub fn of_image(
        name: &str,
        scene: Option<&Path>,
        report: CaseReport,
        findings: Findings,
        chosen: &Chosen,
    ) -> Self {
        let scene = scene.map(|p| p.display().to_string());
        let reproduce = Reproduce::of_image(&report, scene.as_deref(), chosen.course);
        CheckResult {
            course: chosen.course,
            course_why: chosen.why.clone(),
            subject: Subject::Image {
                image: name.to_string(),
            },
            cases: vec![CaseResult {
                name: name.to_string(),
                status: RunStatus::Ok(Box::new(report)),
                stderr_tail: String::new(),
                said_above: false,
                role: None,
                reproduce,
                decided: findings.bump.as_ref().and_then(|b| b.decides()),
            }],
            findings,
            notes: Vec::new(),
            project: None,
            report: None,
        }
    }

    /// A program's run over the suite; `suite_dir` is where its scenes were written, if they
    /// were.
    pub fn of_suite(
        run: SuiteRun,
        course: Course,
        course_why: Option<String>,
        suite_dir: Option<&Path>,
    ) -> Self {
        let cases = run
            .cases
            .into_iter()
            .map(|c| {
                let report = match &c.status {
                    RunStatus::Ok(case) => Some(case.as_ref()),
                    _ => None,
                };
                let reproduce = Reproduce::of(&run.program, suite_dir, &c.case, report);
                CaseResult {
                    name: c.name,
                    status: c.status,
                    stderr_tail: c.stderr_tail,
                    said_above: c.said_above,
                    role: Some(c.case.role),
                    reproduce,
                    decided: None,
                }
            })
            .collect();
        CheckResult {
            course,
            course_why,
            subject: Subject::Program {
                program: run.program,
                scenes_written: suite_dir.is_some(),
            },
            cases,
            findings: run.findings,
            notes: Vec::new(),
            project: None,
            report: None,
        }
    }

    /// Whether every case passes: the exit status. A Tick 1* bump image's case is decided by
    /// its verdict where its bytes cannot say (`CaseResult::decided`): option 1 not done is
    /// no mistake (one option is enough), and a random image is judged as a draw, as a
    /// program's run of it is.
    pub fn passed(&self) -> bool {
        self.cases.iter().all(CaseResult::passed)
    }

    /// The one image checked, when this is the check of an image.
    pub fn image(&self) -> Option<&CaseReport> {
        match self.subject {
            Subject::Image { .. } => self.cases.first().and_then(CaseResult::report),
            Subject::Program { .. } => None,
        }
    }

    /// How many cases pass, and how many of those render exactly what the diagnosis does.
    pub fn pass_counts(&self) -> (usize, usize) {
        let passed = self.cases.iter().filter(|c| c.passed()).count();
        let hiding = self
            .cases
            .iter()
            .filter(|c| c.passed() && c.report().is_some_and(|r| !r.hidden_mistakes.is_empty()))
            .count();
        (passed, hiding)
    }

    /// Whether this is a Tick 1* program's run of its options' scenes (`star_run.rs`).
    pub fn star_run(&self) -> bool {
        self.cases
            .iter()
            .any(|c| matches!(c.role, Some(Role::Star(_))))
    }

    /// Whether any case wrote an image to diagnose.
    pub fn any_image(&self) -> bool {
        self.cases.iter().any(|c| c.report().is_some())
    }

    /// The commands that would rerun a case need the suite's scenes, which were not
    /// written: the report says so once instead.
    pub fn needs_suite_dir(&self) -> bool {
        matches!(
            self.subject,
            Subject::Program {
                scenes_written: false,
                ..
            }
        ) && self.cases.iter().any(CaseResult::worth_rerunning)
    }
}
