//! The staff's export of the latest attempts as `whitted grade` writes a class: Moodle's
//! grading worksheet, the feedback zip, class.csv. Nothing runs again: each student's latest
//! project attempt was graded into its folder (`graded/students/<id>/`) by grade itself, and
//! grade's own writers make the class files from those results.

use super::project::{graded_student, GRADED};
use super::reply::Reply;
use super::route::Export;
use super::store::{Kind, Status, Store};
use super::App;
use whitted_core::error::{Error, Result};

pub fn reply(app: &App, store: &Store, which: Export) -> Result<Reply> {
    let out = tempfile::Builder::new()
        .prefix("export-")
        .tempdir_in(&app.data.dir)
        .map_err(|e| Error::io(&app.data.dir, "cannot create a folder in", e))?;
    let students = out.path().join("students");
    std::fs::create_dir_all(&students).map_err(|e| Error::io(&students, "cannot create", e))?;
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
        copy_dir(&graded, &students.join(name))?;
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
