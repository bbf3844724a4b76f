//! `whitted check DIR`: a student's project folder checked as `check --program` checks the
//! program it builds (docs/check.md, "From your project folder"). The main class is found
//! (`find.rs`), the year read from the project's own classes (`year.rs`), the project compiled
//! by javac into a private temporary folder (`javac.rs`), and its copies of the course's
//! classes held against the year's (`compare.rs`): by their members before the suite runs,
//! and by a render of one failing case after, only when a case fails.

mod compare;
mod find;
mod javac;
mod keep;
mod members;
mod star_verdicts;
mod year;

use std::path::{Path, PathBuf};

use serde_json::{json, Value};
use whitted_check::check::program::{RunStatus, SuiteRun};
use whitted_check::check::tick1_star::{self, StarSeen};
use whitted_core::course::Course;
use whitted_core::error::Result;

pub use find::Main;

/// A project found, its year chosen and its program compiled; the classes are removed when
/// this is dropped.
#[derive(Debug)]
pub struct Project {
    found: find::Found,
    year: year::Year,
    build: javac::Build,
    java: PathBuf,
    /// Per course class whose members differ from the year's: its file and the line.
    members: Vec<(String, String)>,
}

/// Whether `dir` is a project folder: a `Tick1.java` or `Tick2.java` in it or below.
pub fn is_project(dir: &Path) -> bool {
    dir.is_dir() && find::is_project(dir)
}

impl Project {
    /// The project in `dir`, of the year `asked` (`--course`) or the one its classes say;
    /// `warn` hears what the search saw (copies, files left out) at once. A project that does
    /// not compile is an error with javac's first errors.
    pub fn open(dir: &Path, asked: Option<Course>, warn: impl Fn(&str)) -> Result<Project> {
        let want = asked.map(|c| match c.is_default() {
            true => Main::Tick2,
            false => Main::Tick1,
        });
        // With --course, the main class of its kind; without, whichever is there.
        let found = match find::find(dir, want) {
            Ok(found) => found,
            Err(_) if want.is_some() => find::find(dir, None)?,
            Err(e) => return Err(e),
        };
        for warning in &found.warnings {
            warn(warning);
        }
        let year = year::year(&found, asked)?;
        let java = javac::jdk_tool("java")?;
        let members = compare::members_differ(&found, year.course)?;
        let build = javac::project(&found)?;
        Ok(Project {
            found,
            year,
            build,
            java,
            members,
        })
    }

    /// Whether the project is a Tick 1* program, and by what: its package `tick1star`, or
    /// a Renderer with option 2's ray counts. (A `BumpySphere.java` says nothing here: the
    /// 2023-24 skeleton ships a stub of it in every project.)
    pub fn tick1_star(&self) -> Option<StarSeen> {
        let renderer: Vec<(&str, Vec<u8>)> = self
            .found
            .sources
            .iter()
            .filter(|(name, _)| name == "Renderer.java")
            .filter_map(|(name, path)| Some((name.as_str(), std::fs::read(path).ok()?)))
            .collect();
        let sources: Vec<(&str, &[u8])> =
            renderer.iter().map(|(n, b)| (*n, b.as_slice())).collect();
        tick1_star::in_sources(self.found.package.as_deref(), &sources)
    }

    /// The year checked against.
    pub fn course(&self) -> Course {
        self.year.course
    }

    /// The line saying which year and why (None when `--course` chose it).
    pub fn why(&self) -> Option<&str> {
        self.year.why.as_deref()
    }

    /// The words that run the compiled program (`java -cp TEMP MAIN`).
    pub fn command(&self) -> Vec<String> {
        self.build.command(&self.java)
    }

    /// The program as the report shows it, which the student can run: `java -cp CLASSES MAIN`,
    /// CLASSES the copy of this build kept beside the suite's scenes (`kept`, from
    /// [`Project::keep_classes`]), else their IDE's output folder when it holds the main class
    /// (the temporary one is gone when the check ends).
    pub fn shown_program(&self, kept: Option<&Path>) -> String {
        let classes = kept
            .map(Path::to_path_buf)
            .or_else(|| self.ide_output())
            .map_or("CLASSES".to_string(), |p| p.display().to_string());
        format!("java -cp {classes} {}", self.build.main)
    }

    /// This build's classes copied to `suite_dir/classes` (replacing what a previous check put
    /// there), so that the rerun commands printed beside the suite's scenes run what was
    /// checked, not an IDE's older build; returns the folder.
    pub fn keep_classes(&self, suite_dir: &Path) -> Result<PathBuf> {
        keep::classes(&self.build.classes(), &suite_dir.join("classes"))
    }

    /// The IDE's or build's output folder that holds the main class's `.class`, if any:
    /// IntelliJ's `out/production/*`, Maven's `target/classes`, Eclipse's `bin`, `out`.
    fn ide_output(&self) -> Option<PathBuf> {
        let class = format!("{}.class", self.build.main.replace('.', "/"));
        let root = &self.found.root;
        let mut candidates = vec![
            root.join("target/classes"),
            root.join("bin"),
            root.join("out"),
        ];
        if let Ok(entries) = std::fs::read_dir(root.join("out/production")) {
            let mut modules: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
            modules.sort();
            candidates.splice(0..0, modules);
        }
        candidates.into_iter().find(|c| c.join(&class).is_file())
    }

    /// The lines the report opens with: where the main class was found and compiled from, and
    /// every way the project's course classes differ from the year's by their members;
    /// `kept` is where the build's classes were kept, if they were.
    pub fn lines(&self, kept: Option<&Path>) -> Vec<String> {
        let f = &self.found;
        let mut lines = vec![format!(
            "project: {} in {}, compiled by javac{}",
            f.main_class(),
            f.shown(&f.folder),
            match (kept, self.ide_output()) {
                (Some(kept), _) => format!(" into {}", kept.display()),
                (None, Some(_)) => String::new(),
                (None, None) =>
                    " (CLASSES below: where your IDE or `javac -d` puts the classes)".into(),
            }
        )];
        lines.extend(self.year.notes.iter().map(|n| format!("note: {n}")));
        lines.extend(self.members.iter().map(|(_, line)| format!("note: {line}")));
        lines
    }

    /// When a case failed: its render on the student's own files and the year's classes,
    /// against the project's, naming the class the project changed where they differ. Lines
    /// for the report (none when the project's classes render as the year's). A Tick 1*
    /// case's image is random, so its verdict is compared instead (`star_verdicts.rs`); `say`
    /// hears what is rendered again and why before it starts, since that takes as long as
    /// the project's own render.
    pub fn explain_failure(
        &self,
        run: &SuiteRun,
        timeout: u64,
        say: &dyn Fn(&str),
    ) -> Result<Vec<String>> {
        let star = run.findings.tick1_star.is_some();
        // In a Tick 1* run, only an image judged can be judged again: a case out of time
        // would only run out of time again.
        let failing = run
            .cases
            .iter()
            .find(|c| !c.passed() && (!star || matches!(c.status, RunStatus::Star(_))));
        let Some(failing) = failing else {
            return Ok(Vec::new());
        };
        let suspects: Vec<String> = self.members.iter().map(|(name, _)| name.clone()).collect();
        let (course, case) = (self.year.course, &failing.case);
        let compared = match &failing.status {
            RunStatus::Star(image) => star_verdicts::verdicts_differ(
                &self.found,
                course,
                case,
                &image.verdict,
                &suspects,
                timeout,
                say,
            ),
            status => {
                let theirs = match status {
                    RunStatus::Ok(report) => compare::Rendered::Image(report.student.clone()),
                    _ => compare::Rendered::Nothing,
                };
                compare::renders_differ(&self.found, course, case, &theirs, &suspects, timeout)
            }
        };
        let lines = match compared {
            Ok(lines) => lines,
            Err(e @ whitted_core::Error::Interrupted { .. }) => return Err(e),
            // The suite's report stands without the comparison; say why it is missing.
            Err(e) => vec![format!(
                "the project's classes could not be compared with {course}'s: {e}"
            )],
        };
        Ok(lines.into_iter().map(|l| format!("note: {l}")).collect())
    }

    /// The project in the JSON report: `"project": {"main_class", "folder", "notes"}`.
    pub fn json(&self, notes: &[String]) -> Value {
        let f = &self.found;
        json!({
            "main_class": f.main_class(),
            "folder": f.shown(&f.folder),
            "warnings": f.warnings,
            "notes": notes
                .iter()
                .map(|n| n.strip_prefix("note: ").unwrap_or(n))
                .collect::<Vec<_>>(),
        })
    }
}

/// A project of `course`'s clean-room classes alone, in a student's package, for the tests.
#[cfg(test)]
fn clean_project(course: Course) -> (tempfile::TempDir, find::Found) {
    let dir = tempfile::tempdir().expect("tempdir");
    let package = match course.is_default() {
        true => None,
        false => Some("uk.ac.cam.cl.gfxintro.ab123.tick1"),
    };
    for (path, bytes) in crate::clean_room_skeleton(course, package).expect("skeleton") {
        let path = dir.path().join("src").join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, bytes).expect("write");
    }
    let found = find::find(dir.path(), None).expect("found");
    (dir, found)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_year_s_classes_say_their_year_and_match_their_own_members() {
        for course in Course::ALL {
            let (_dir, found) = clean_project(course);
            let chosen = year::year(&found, None).expect("a year");
            // 2019-20's classes are 2020-21's: the later is taken, and said.
            let expected = match course {
                Course::Y2019 => Course::Y2020,
                other => other,
            };
            assert_eq!(chosen.course, expected, "{course}: {:?}", chosen.why);
            assert!(chosen.notes.is_empty(), "{course}: {:?}", chosen.notes);
            let differ = compare::members_differ(&found, course).expect("compared");
            assert!(differ.is_empty(), "{course}: {differ:?}");
        }
        let (_dir, found) = clean_project(Course::Y2019);
        let why = year::year(&found, None).expect("a year").why.expect("why");
        assert!(why.contains("as in 2019-20 and 2020-21"), "{why}");
    }

    #[test]
    fn another_year_s_classes_are_named_with_what_differs() {
        let (_dir, found) = clean_project(Course::Y2021);
        let differ = compare::members_differ(&found, Course::Y2023).expect("compared");
        let lines: Vec<&str> = differ.iter().map(|(_, l)| l.as_str()).collect();
        let said = lines.join("\n");
        assert!(
            said.contains("ColorRGB.java is not 2023-24's: it lacks isZero(), subtract(double)"),
            "{said}"
        );
        assert!(
            said.contains(
                "SceneObject.java is not 2023-24's: it lacks getRefractiveIndex(), \
                 getTransmittance(), isTransmissive(), field refractive_index, field transmittance"
            ),
            "{said}"
        );
        assert_eq!(lines.len(), 3, "{said}");
        let asked = year::year(&found, Some(Course::Y2023)).expect("asked");
        assert_eq!(asked.course, Course::Y2023);
        assert!(
            asked.notes[0].contains("look like 2021-22's"),
            "{:?}",
            asked.notes
        );
    }
}
