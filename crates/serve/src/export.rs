//! The staff's export of the latest attempts as `whitted grade` writes a class: Moodle's
//! grading worksheet, the feedback zip, class.csv. Nothing runs again: each student's latest
//! project attempt was graded into its folder (`graded/students/<id>/`) by grade itself, and
//! grade's own writers make the class files from those results.
//!
//! The names are the roster's, whatever the folder grade read them from: a participants
//! export's `cd456` is Carol Davis in class.csv and the feedback zip, not `cd456` twice. Moodle's
//! worksheet import matches rows by its own participant numbers, which only the grading
//! worksheet carries (a participants export has none): with ids that are not such numbers,
//! the worksheet is refused with that sentence rather than written with made-up identifiers.

use super::project::{graded_student, GRADED};
use super::reply::Reply;
use super::route::Export;
use super::store::{Kind, Status, Store};
use super::App;
use whitted_core::error::{Error, Result};

/// Why the worksheet cannot be written for a class whose ids are not Moodle's numbers.
pub const NO_PARTICIPANT_NUMBERS: &str = "the roster's ids are not Moodle participant \
    numbers (a participants export has none), and Moodle's worksheet import needs them: \
    give the grading worksheet Moodle downloads as --roster to export one; class.csv and the \
    feedback zip carry the grades meanwhile";

/// Whether `id` can be Moodle's participant number (the grading worksheet's `Participant N`).
pub fn is_participant_number(id: &str) -> bool {
    !id.is_empty() && id.bytes().all(|b| b.is_ascii_digit())
}

pub fn reply(app: &App, store: &Store, which: Export) -> Result<Reply> {
    let students = store.students()?;
    if matches!(which, Export::Worksheet) && !students.iter().all(|s| is_participant_number(&s.id))
    {
        return Ok(Reply::refusal(409, NO_PARTICIPANT_NUMBERS));
    }
    let out = tempfile::Builder::new()
        .prefix("export-")
        .tempdir_in(&app.data.dir)
        .map_err(|e| Error::io(&app.data.dir, "cannot create a folder in", e))?;
    let dir = out.path().join("students");
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, "cannot create", e))?;
    let mut latest = std::collections::HashMap::new();
    for attempt in store.all_attempts()? {
        if attempt.kind == Kind::Project && attempt.status == Status::Done {
            latest.insert(attempt.student, attempt);
        }
    }
    for attempt in latest.values() {
        let Ok(graded) = graded_student(&app.data.upload(&attempt.folder).join(GRADED)) else {
            continue; // the service could not run it: nothing was graded
        };
        let Some(name) = graded.file_name() else {
            continue;
        };
        let target = out.path().join("students").join(name);
        copy_dir(&graded, &target)?;
        if let Some(member) = students.iter().find(|s| s.number == attempt.student) {
            rename(&target.join("result.json"), &member.name)?;
        }
    }
    whitted_grade::write_class_files(out.path(), app.course)?;
    let path = out.path().join(which.file_name());
    let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, "cannot read", e))?;
    let kind = match which {
        Export::FeedbackZip => "application/zip",
        Export::Worksheet | Export::ClassCsv => "text/csv; charset=utf-8",
    };
    Ok(Reply {
        download: Some(which.file_name()),
        ..Reply::bytes(kind, bytes)
    })
}

/// Puts the roster's `name` into a graded `result.json` (an empty name leaves grade's).
fn rename(path: &std::path::Path, name: &str) -> Result<()> {
    if name.trim().is_empty() {
        return Ok(());
    }
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, "cannot read", e))?;
    let mut value: serde_json::Value = serde_json::from_slice(&bytes)
        .map_err(|e| Error::Environment(format!("{}: {e}", path.display())))?;
    value["extra_data"]["name"] = serde_json::Value::String(name.to_string());
    std::fs::write(path, value.to_string()).map_err(|e| Error::io(path, "cannot write", e))
}

fn copy_dir(from: &std::path::Path, to: &std::path::Path) -> Result<()> {
    std::fs::create_dir_all(to).map_err(|e| Error::io(to, "cannot create", e))?;
    let entries = std::fs::read_dir(from).map_err(|e| Error::io(from, "cannot read", e))?;
    for entry in entries.flatten() {
        let target = to.join(entry.file_name());
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            copy_dir(&entry.path(), &target)?;
        } else {
            std::fs::copy(entry.path(), &target)
                .map_err(|e| Error::io(&target, "cannot write", e))?;
        }
    }
    Ok(())
}
