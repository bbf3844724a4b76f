//! The workers: threads that take queued attempts from the database, oldest first, and record
//! each one's outcome with its "done" in one transaction. Images and projects have workers of
//! their own (`-j N` each), so that a quick image check never waits behind a program's run.
//! An attempt a killed service left running is queued again at the next start
//! (`Store::requeue_running`) and runs again from its files; its result is written once.

use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use super::project::{self, Run};
use super::store::{Attempt, Kind, Outcome};
use super::{db, images, App};
use whitted_core::error::Result;

/// Wakes the workers when an attempt is queued (they also look every `IDLE`).
#[derive(Default)]
pub struct Bell {
    rung: Mutex<u64>,
    cond: Condvar,
}

const IDLE: Duration = Duration::from_secs(1);

impl Bell {
    pub fn ring(&self) {
        let mut n = self.rung.lock().unwrap_or_else(|e| e.into_inner());
        *n += 1;
        self.cond.notify_all();
    }

    fn wait(&self) {
        let n = self.rung.lock().unwrap_or_else(|e| e.into_inner());
        let _ = self.cond.wait_timeout(n, IDLE);
    }
}

/// Starts `jobs` workers of each kind.
pub fn start(app: Arc<App>, jobs: usize) -> Result<()> {
    for kind in [Kind::Images, Kind::Project] {
        for i in 0..jobs.max(1) {
            let app = app.clone();
            std::thread::Builder::new()
                .name(format!("{}-{i}", kind.name()))
                .spawn(move || work(&app, kind))
                .map_err(|e| {
                    whitted_core::Error::Environment(format!("cannot start a worker: {e}"))
                })?;
        }
    }
    Ok(())
}

fn work(app: &App, kind: Kind) {
    let path = app.data.database();
    loop {
        match db::with(&path, |s| s.claim(kind)) {
            Ok(Some(attempt)) => {
                let outcome = run(app, &attempt);
                if let Err(e) = db::with(&path, |s| s.finish(attempt.id, &outcome)) {
                    eprintln!("whitted serve: attempt {}: {e}", attempt.id);
                }
            }
            Ok(None) => app.bell.wait(),
            Err(e) => {
                eprintln!("whitted serve: {e}");
                std::thread::sleep(IDLE);
            }
        }
    }
}

/// An attempt's outcome; the service's own failure (no JDK) is an outcome that says so.
fn run(app: &App, attempt: &Attempt) -> Outcome {
    let dir = app.data.upload(&attempt.folder);
    let names: Vec<String> = attempt.files.lines().map(str::to_string).collect();
    let outcome = match attempt.kind {
        Kind::Images => Ok(images::check(&dir, &names, app.course)),
        Kind::Project => {
            db::with(&app.data.database(), |s| s.student(attempt.student)).and_then(|student| {
                let student = student.ok_or_else(|| {
                    whitted_core::Error::Environment("the attempt's student is gone".into())
                })?;
                project::run(&dir, &student, Run::new(app.course, app.seconds))
            })
        }
    };
    outcome.unwrap_or_else(|e| Outcome {
        passed: false,
        verdict: "not tested: the service could not run it".into(),
        mistake: None,
        finding: format!("The tester could not run this attempt: {e}. Tell the course staff."),
        progress: String::new(),
        report: "[]".into(),
    })
}
