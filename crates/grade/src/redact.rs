//! What a student's files (`report.html`, `report.png`, `result.json`) show of the grading
//! machine: nothing. A program sees its own folders at their paths on the host (bubblewrap
//! binds them where they are) and may print them, its command line, `/proc/self/mountinfo` or
//! its sandbox's (`/proc/1/cmdline`) to its standard error, which the report shows; javac and
//! grade's own errors name the work folder too. Every text of a student's outcome has the work
//! folder (`work_area.rs`: every path a sandbox sees of whitted's is in it) replaced by
//! `<work>`, and the skeleton is named by what it is, not by where it is on the grader's disk.
//! The sandbox's own options never reach a program: bubblewrap reads them from a descriptor
//! (`--args`, `sandbox.rs`), so its command line inside holds only the program's.

use std::path::{Path, PathBuf};

use super::skeleton::Skeleton;
use super::student::Outcome;
use whitted_check::check::program::RunStatus;

/// What the work folder is shown as.
pub const WORK: &str = "<work>";

/// Takes the work folder out of texts.
pub struct Redactor {
    /// The work folder's path as given and as resolved (a `TMPDIR` behind a link), longest
    /// first, and its own name (what `/proc/self/mountinfo` shows under a mount's root).
    hidden: Vec<String>,
}

impl Redactor {
    pub fn new(work: &Path) -> Redactor {
        let mut hidden: Vec<String> = [Some(work.to_path_buf()), work.canonicalize().ok()]
            .into_iter()
            .flatten()
            .map(|p: PathBuf| p.display().to_string())
            .collect();
        if let Some(name) = work.file_name() {
            hidden.push(name.to_string_lossy().into_owned());
        }
        hidden.retain(|h| h.len() > 1);
        hidden.sort_by_key(|h| std::cmp::Reverse(h.len()));
        hidden.dedup();
        Redactor { hidden }
    }

    /// `text` with every mention of the work folder replaced by `<work>`.
    pub fn text(&self, text: &str) -> String {
        self.hidden
            .iter()
            .fold(text.to_string(), |text, hidden| text.replace(hidden, WORK))
    }

    /// `outcome` with every text it holds redacted.
    pub fn outcome(&self, outcome: Outcome) -> Outcome {
        match outcome {
            Outcome::Refused { status, message } => Outcome::Refused {
                status,
                message: self.text(&message),
            },
            Outcome::CompileError(messages) => Outcome::CompileError(self.text(&messages)),
            Outcome::CompileTimeout => Outcome::CompileTimeout,
            Outcome::Ran(mut run) => {
                for case in &mut run.cases {
                    case.stderr_tail = self.text(&case.stderr_tail);
                    match &mut case.status {
                        RunStatus::Crashed(message)
                        | RunStatus::NoOutput(message)
                        | RunStatus::OutOfMemory(message)
                        | RunStatus::OutputTooLarge(message) => *message = self.text(message),
                        RunStatus::Ok(_)
                        | RunStatus::Timeout(_)
                        | RunStatus::WrongSize { .. }
                        | RunStatus::NotRun(_)
                        | RunStatus::Star(_) => {}
                    }
                }
                Outcome::Ran(run)
            }
        }
    }
}

/// The skeleton as a student's `result.json` names it: whitted's own, or the course's given
/// with `--skeleton` and told apart by a fingerprint of its files, never its path.
pub fn skeleton_label(skeleton: &Skeleton, given: bool) -> String {
    if !given {
        return skeleton.source.clone();
    }
    let parts: Vec<&[u8]> = skeleton
        .files
        .iter()
        .flat_map(|(name, bytes)| [name.as_bytes(), bytes.as_slice()])
        .collect();
    format!(
        "the course's skeleton given with --skeleton ({} files, fingerprint {})",
        skeleton.files.len(),
        whitted_core::fingerprint::fingerprint(&parts)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_work_folder_is_named_nowhere_as_given_resolved_or_by_its_name() {
        let dir = tempfile::tempdir().expect("tempdir");
        let real = dir.path().join("whitted-grade-AbC123");
        std::fs::create_dir(&real).expect("mkdir");
        let link = dir.path().join("tmp-link");
        std::os::unix::fs::symlink(dir.path(), &link).expect("link");
        let work = link.join("whitted-grade-AbC123");
        let redactor = Redactor::new(&work);
        let said = format!(
            "cwd={0}/cases/x\nreal={1}/students/7/classes\n\
             mountinfo: 412 398 0:41 /whitted-grade-AbC123/cases/x {0}/cases/x rw",
            work.display(),
            real.canonicalize().expect("real").display()
        );
        let shown = redactor.text(&said);
        assert_eq!(
            shown,
            "cwd=<work>/cases/x\nreal=<work>/students/7/classes\n\
             mountinfo: 412 398 0:41 /<work>/cases/x <work>/cases/x rw"
        );
    }

    #[test]
    fn a_given_skeleton_is_named_by_its_files_not_its_path() {
        let mut skeleton =
            Skeleton::clean_room(whitted_core::course::Course::Y2016).expect("skeleton");
        let ours = skeleton_label(&skeleton, false);
        assert!(!ours.contains('/'), "{ours}");
        skeleton.source = "/home/grader/secret/course/gfx/tick2".into();
        let label = skeleton_label(&skeleton, true);
        assert!(!label.contains("/home"), "{label}");
        let files = skeleton.files.len();
        assert!(
            label.starts_with(&format!(
                "the course's skeleton given with --skeleton ({files} files, fingerprint "
            )),
            "{label}"
        );
        // Another skeleton's files, another label.
        skeleton.files[0].1.push(b' ');
        assert_ne!(skeleton_label(&skeleton, true), label);
    }
}
