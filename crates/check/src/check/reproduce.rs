//! What a student runs to see a suite case for themselves: where its scene is, the command of
//! theirs that `--program` ran, the check of that one image, and the `explain` commands of
//! its worst pixel as the reference and as the diagnosis trace it. Every path is relative to
//! the student's own directory, and a command is made only where what it names is on disk:
//! without `--suite-dir` the suite's scenes are not, and the report says once how to get them
//! rather than printing commands that fail.

use std::path::Path;

use serde_json::{json, Value};

use crate::check::suite::{Role, SuiteCase};
use crate::check::CaseReport;
use crate::mistakes::Mistakes;
use whitted_core::course::Course;

/// Where a case's scene is, for the commands that name it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SceneSource {
    /// The scene file the user gave (`-i`), named as they gave it: it is found from where
    /// they ran the check.
    Given(String),
    /// The scene built into whitted that a check reads when no `-i` is given: commands name
    /// no scene.
    Embedded,
    /// A suite scene `--suite-dir` wrote, at this path (as the directory was given).
    Written(String),
    /// A suite scene that was not written out (no `--suite-dir`): its file name. No command
    /// can name it, so none is printed.
    NotWritten(String),
}

/// The commands that reproduce one case. Every one runs as printed from the directory the
/// check ran in: a command that would need a scene that is not on disk is not made.
#[derive(Debug, Clone)]
pub struct Reproduce {
    pub scene: SceneSource,
    /// The student's command as `--program` ran it, writing the image into the current
    /// directory.
    pub run: Option<String>,
    /// The check of that one image.
    pub check: Option<String>,
    /// The `whitted explain` commands of the worst pixel: as the reference and as the case's
    /// mistakes trace it.
    pub explain: Vec<String>,
}

/// What the text says once, in place of every command, when the suite's scenes were not
/// written.
pub const SUITE_DIR_HINT: &str =
    "add --suite-dir DIR to write the suite's scenes into DIR and get the commands that rerun each case";

/// The same, for a Tick 1* program, which runs the handout's scenes, not the suite.
pub const STAR_SUITE_DIR_HINT: &str = "add --suite-dir DIR to write the handout's scenes (bump.xml, its map, distributed.xml) into DIR and get the commands that rerun each option";

/// The hint for a run of the suite, or (`star`) of a Tick 1* program's options.
pub fn suite_dir_hint(star: bool) -> &'static str {
    match star {
        true => STAR_SUITE_DIR_HINT,
        false => SUITE_DIR_HINT,
    }
}

/// `s` quoted for a POSIX shell where it needs to be (a path with a NUL byte cannot be
/// quoted, and is shown as it is).
pub fn shell_word(s: &str) -> String {
    shlex::try_quote(s).map_or_else(|_| s.to_string(), |q| q.into_owned())
}

/// The `whitted explain` commands of pixel `(x, y)`: as the reference traces it, and as
/// `mistakes` do (when there are any).
pub fn explain_commands(
    scene: Option<&str>,
    bounces: u32,
    size: (u32, u32),
    (x, y): (u32, u32),
    mistakes: Mistakes,
    course: Course,
) -> Vec<String> {
    let scene = scene.map_or(String::new(), |s| format!(" -i {}", shell_word(s)));
    let size = match size {
        size if size == course.size() => String::new(),
        (w, h) => format!(" --width {w} --height {h}"),
    };
    let year = match course {
        Course::Y2016 => String::new(),
        other => format!(" --course {other}"),
    };
    let base = format!("whitted explain{scene} -b {bounces}{size}{year} --pixel {x},{y}");
    let mut commands = vec![base.clone()];
    if !mistakes.is_empty() {
        let bugs: String = mistakes
            .ids()
            .iter()
            .map(|id| format!(" --bug {id}"))
            .collect();
        commands.push(format!("{base}{bugs} --compare"));
    }
    commands
}

impl Reproduce {
    /// The commands of a suite case that `program` ran; the scene is on disk only where
    /// `suite_dir` wrote it.
    pub fn of(
        program: &str,
        suite_dir: Option<&Path>,
        case: &SuiteCase,
        report: Option<&CaseReport>,
    ) -> Self {
        let Some(dir) = suite_dir else {
            return Reproduce {
                scene: SceneSource::NotWritten(case.file.to_string()),
                run: None,
                check: None,
                explain: Vec::new(),
            };
        };
        let scene = dir.join(&*case.file).display().to_string();
        let output = case.output_name();
        let quoted = shell_word(&scene);
        let explain = report
            .map(|r| worst_pixel_commands(r, Some(&scene), case.course))
            .unwrap_or_default();
        // The program's words as `--program` split them, quoted for a shell: the line runs
        // as printed even where the words hold what a shell reads otherwise (`<`, `$`).
        let program = match crate::check::program::words(program) {
            Ok(words) => words
                .iter()
                .map(|w| shell_word(w))
                .collect::<Vec<_>>()
                .join(" "),
            Err(_) => program.to_string(),
        };
        Reproduce {
            run: Some(format!(
                "{program} --input {quoted} --output {output} --bounces {}{}",
                case.bounces,
                case.size_option()
                    .map_or(String::new(), |[option, size]| format!(" {option} {size}"))
            )),
            check: Some(check_command(case, &output, &quoted)),
            explain,
            scene: SceneSource::Written(scene),
        }
    }

    /// The commands of a check of one image: the `explain` commands of its worst pixel, on
    /// the scene as it was given (`None`: the embedded one).
    pub fn of_image(report: &CaseReport, scene: Option<&str>, course: Course) -> Self {
        Reproduce {
            scene: scene.map_or(SceneSource::Embedded, |s| SceneSource::Given(s.to_string())),
            run: None,
            check: None,
            explain: worst_pixel_commands(report, scene, course),
        }
    }

    /// Every command, in the order they are run: the program, its check, the explains.
    pub fn commands(&self) -> Vec<&str> {
        let mut all: Vec<&str> = self
            .run
            .iter()
            .chain(&self.check)
            .map(|s| s.as_str())
            .collect();
        all.extend(self.explain.iter().map(|s| s.as_str()));
        all
    }

    /// The lines under a case in the verbose text: the scene and the commands.
    pub fn lines(&self) -> Vec<String> {
        let mut lines = Vec::new();
        if let SceneSource::Written(path) = &self.scene {
            lines.push(format!("scene: {path}"));
        }
        lines.extend(self.run.iter().map(|c| format!("rerun it: {c}")));
        lines.extend(self.check.iter().map(|c| format!("check it: {c}")));
        lines.extend(self.explain.iter().map(|c| format!("its worst pixel: {c}")));
        lines
    }

    /// The scene as the JSON names it: its path where it is on disk, else its file name.
    pub fn scene_name(&self) -> &str {
        match &self.scene {
            SceneSource::Given(s) | SceneSource::Written(s) | SceneSource::NotWritten(s) => s,
            SceneSource::Embedded => "",
        }
    }

    pub fn json(&self) -> Value {
        json!({
            "scene": self.scene_name(),
            "scene_written": matches!(self.scene, SceneSource::Written(_)),
            "run": self.run,
            "check": self.check,
            "explain": self.explain,
        })
    }
}

/// The check of the image a rerun of `case` writes (`output`) of the scene at `scene`: a Tick 1
/// case's against its scene; a Tick 1* option's by that option's judge (`--star`), which
/// knows the handout's scene, at the year it was run under.
fn check_command(case: &SuiteCase, output: &str, scene: &str) -> String {
    match (case.role, case.course) {
        (Role::Star(option), course) => format!(
            "whitted check {output} -b {} --course {course} --star {}",
            case.bounces,
            option.name()
        ),
        (_, Course::Y2016) => format!("whitted check {output} -i {scene} -b {}", case.bounces),
        (_, course) => format!(
            "whitted check {output} -i {scene} -b {} --course {course}",
            case.bounces
        ),
    }
}

/// The `explain` commands of `report`'s worst pixel (none when no pixel differs).
fn worst_pixel_commands(report: &CaseReport, scene: Option<&str>, course: Course) -> Vec<String> {
    let d = &report.difference;
    d.worst_pixel
        .map(|pixel| {
            explain_commands(
                scene,
                report.bounces,
                (d.width, d.height),
                pixel,
                report.shown_mistakes(),
                course,
            )
        })
        .unwrap_or_default()
}
