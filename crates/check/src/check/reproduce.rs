//! What a student runs to see a suite case for themselves: where its scene is, the command of
//! theirs that `--program` ran, the check of that one image, and the `explain` commands of
//! its worst pixel as the reference and as the diagnosis trace it. Every path is relative to
//! the student's own directory.

use std::path::Path;

use serde_json::{json, Value};

use crate::check::suite::SuiteCase;
use crate::check::CaseReport;
use crate::mistakes::Mistakes;
use whitted_core::course::Course;

/// The commands that reproduce one case.
pub struct Reproduce {
    /// The scene's path, or the placeholder `DIR/file` when no `--suite-dir` was given.
    pub scene: String,
    /// Whether `scene` exists (was written by `--suite-dir`).
    pub written: bool,
    pub run: String,
    pub check: String,
    pub explain: Vec<String>,
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
    pub fn of(
        program: &str,
        suite_dir: Option<&Path>,
        case: &SuiteCase,
        report: Option<&CaseReport>,
    ) -> Self {
        let scene = match suite_dir {
            Some(dir) => dir.join(&*case.file).display().to_string(),
            None => format!("DIR/{}", case.file),
        };
        let output = case.output_name();
        let quoted = shell_word(&scene);
        let explain = report
            .and_then(|r| {
                let d = &r.difference;
                let top = r.shown_mistakes();
                d.worst_pixel.map(|pixel| {
                    explain_commands(
                        Some(&scene),
                        case.bounces,
                        (d.width, d.height),
                        pixel,
                        top,
                        case.course,
                    )
                })
            })
            .unwrap_or_default();
        Reproduce {
            written: suite_dir.is_some(),
            run: format!(
                "{program} --input {quoted} --output {output} --bounces {}{}",
                case.bounces,
                case.size_option()
                    .map_or(String::new(), |[option, size]| format!(" {option} {size}"))
            ),
            check: format!(
                "whitted check {output} -i {quoted} -b {}{}",
                case.bounces,
                match case.course {
                    Course::Y2016 => String::new(),
                    other => format!(" --course {other}"),
                }
            ),
            explain,
            scene,
        }
    }

    /// The lines under a case in the text report.
    pub fn lines(&self) -> Vec<String> {
        let mut lines = vec![if self.written {
            format!("scene: {}", self.scene)
        } else {
            format!(
                "scene: built in ({}; --suite-dir DIR writes it)",
                self.scene
            )
        }];
        lines.push(format!("rerun it: {}", self.run));
        lines.push(format!("check it: {}", self.check));
        lines.extend(self.explain.iter().map(|c| format!("its worst pixel: {c}")));
        lines
    }

    pub fn json(&self) -> Value {
        json!({
            "scene": self.scene,
            "scene_written": self.written,
            "run": self.run,
            "check": self.check,
            "explain": self.explain,
        })
    }
}
