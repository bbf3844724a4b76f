//! A student's status, in a file of its own: intake decides some, the student's run others,
//! and the result records it.

use serde::{Deserialize, Serialize};

/// Where a student stands: what `result.json`, `class.csv`, `moodle.csv` and the class page say.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StudentStatus {
    /// Their program compiled and ran over the suite.
    Graded,
    /// javac refused their files.
    CompileError,
    /// Their submission holds no Plane.java and Renderer.java to grade.
    NoFiles,
    /// Something stopped them being graded (a compilation that timed out, two submissions of
    /// one id, a program that could not be started): `--rerun failed` tries again.
    Error,
    /// In the class but not graded by this run nor any before it into OUTDIR (`--only`
    /// graded others): no result, and no grade written for them anywhere. Never in a
    /// `result.json`, only in the class files' rows.
    NotGraded,
}

impl StudentStatus {
    /// Its name in every file (the serde name).
    pub fn name(self) -> &'static str {
        match self {
            StudentStatus::Graded => "graded",
            StudentStatus::CompileError => "compile-error",
            StudentStatus::NoFiles => "no-files",
            StudentStatus::Error => "error",
            StudentStatus::NotGraded => "not-graded",
        }
    }
}
