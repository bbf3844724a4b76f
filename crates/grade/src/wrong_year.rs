//! A later year's class graded as 2016-17's, the default: refused before anyone is graded.
//! Tick 1 hand-ins (2017-18 on) do not compile against 2016-17's `gfx.tick2` classes, so every
//! student would be a compile error with grade 0, in a worksheet ready to upload; the class's
//! own files say which exercise it is, and `check` refuses a Tick 1 program without a year too.

use crate::intake::Submission;
use crate::package;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

/// Refuses grading `submissions` as `course` when that is 2016-17 and most of those with files
/// hand in Tick 1 code: a `Renderer.java` in a package other than `gfx.tick2` that names a
/// later year's class (`ColorRGB`) or a `tick1` package.
pub fn refuse_tick1_as_2016(submissions: &[Submission], course: Course) -> Result<()> {
    if !course.is_default() {
        return Ok(());
    }
    let with_files: Vec<&Submission> = submissions.iter().filter(|s| s.files.is_ok()).collect();
    let tick1: Vec<&str> = with_files
        .iter()
        .filter(|s| s.files.as_ref().is_ok_and(|f| is_tick1(&f.sources)))
        .map(|s| s.id.as_str())
        .collect();
    if tick1.is_empty() || tick1.len() * 2 < with_files.len() {
        return Ok(());
    }
    let later: Vec<&str> = Course::ALL
        .into_iter()
        .filter(|c| !c.is_default())
        .map(|c| c.name())
        .collect();
    let some: Vec<&str> = tick1.iter().take(3).copied().collect();
    Err(Error::Usage(format!(
        "{} of {} submissions are Tick 1 hand-ins (students {}{}: a Renderer.java in a tick1 \
         package, or with ColorRGB), which the default --course 2016-17 (the Tick 2) would grade \
         as compile errors: give --course YEAR, one of {}",
        tick1.len(),
        with_files.len(),
        some.join(", "),
        if tick1.len() > some.len() {
            ", ..."
        } else {
            ""
        },
        later.join(", "),
    )))
}

/// Whether a hand-in's sources are a later year's Tick 1.
fn is_tick1(sources: &[(&'static str, Vec<u8>)]) -> bool {
    sources.iter().any(|(name, bytes)| {
        let declared = package::declared(bytes).ok().flatten();
        let in_tick1 = declared
            .as_deref()
            .is_some_and(|p| p.ends_with(".tick1") || p.ends_with(".tick1star") || p == "tick1");
        let colour = *name == "Renderer.java"
            && declared.as_deref() != Some("gfx.tick2")
            && String::from_utf8_lossy(bytes).contains("ColorRGB");
        in_tick1 || colour
    })
}
