//! The workers: threads that take queued attempts from the database, oldest first, and record
//! each one's outcome with its "done" in one transaction. Images and projects have workers of
//! their own (`-j N` each), so that a quick image check never waits behind a program's run.
//! An image check runs in this process; a project runs in a process of its own
//! (`job.rs`: `whitted serve run-attempt DIR`), which counts its CPU time and shows its steps,
//! or, with `--slurm`, as a Slurm job (`slurm.rs`) instead of on these workers.
//! An attempt a killed service left running is queued again at the next start
//! (`Store::requeue_running`) and runs again from its files; its result is written once.

use std::process::{Command, Stdio};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use super::job::{self, Finished, Job};
use super::store::{Attempt, Kind};
use super::{db, images, App};
use whitted_core::error::{Error, Result};

/// Wakes the workers when an attempt is queued (they also look every `IDLE`).
#[derive(Default)]
pub struct Bell {
    rung: Mutex<u64>,
    cond: Condvar,
}

pub const IDLE: Duration = Duration::from_secs(1);

/// The log of a project's run (its standard error), in the attempt's folder.
pub const RUN_LOG: &str = "run.log";

impl Bell {
    pub fn ring(&self) {
        let mut n = self.rung.lock().unwrap_or_else(|e| e.into_inner());
        *n += 1;
        self.cond.notify_all();
    }

    pub fn wait(&self) {
        self.wait_for(IDLE);
    }

    /// Waits until rung, or `most` has passed.
    pub fn wait_for(&self, most: Duration) {
        let n = self.rung.lock().unwrap_or_else(|e| e.into_inner());
        let _ = self.cond.wait_timeout(n, most);
    }
}

/// Starts `jobs` workers of each kind (of images only when the projects go to Slurm).
pub fn start(app: Arc<App>, jobs: usize) -> Result<()> {
    let kinds: &[Kind] = match app.slurm {
        true => &[Kind::Images],
        false => &[Kind::Images, Kind::Project],
    };
    for &kind in kinds {
        for i in 0..jobs.max(1) {
            let app = app.clone();
            std::thread::Builder::new()
                .name(format!("{}-{i}", kind.name()))
                .spawn(move || work(&app, kind))
                .map_err(|e| Error::Environment(format!("cannot start a worker: {e}")))?;
        }
    }
    Ok(())
}

fn work(app: &App, kind: Kind) {
    let path = app.data.database();
    loop {
        match db::with(&path, |s| s.claim(kind)) {
            Ok(Some(attempt)) => {
                let Some(done) = run(app, &attempt) else {
                    // The service is stopping: the attempt is queued again at the next start.
                    return;
                };
                let recorded = db::with(&path, |s| s.finish(attempt.id, &done.outcome, done.cpu));
                if let Err(e) = recorded {
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

/// An attempt's outcome; the service's own failure (no JDK) is an outcome that says so. None
/// when the service is stopping and the run was cut short.
fn run(app: &App, attempt: &Attempt) -> Option<Finished> {
    let dir = app.data.upload(&attempt.folder);
    let names: Vec<String> = attempt.files.lines().map(str::to_string).collect();
    match attempt.kind {
        Kind::Images => Some(Finished {
            outcome: images::check(&dir, &names, app.course),
            cpu: None,
        }),
        Kind::Project => match project(app, attempt) {
            Ok(done) => Some(done),
            Err(_) if whitted_core::interrupt::requested() => None,
            Err(e) => Some(Finished {
                outcome: job::not_run(&e),
                cpu: None,
            }),
        },
    }
}

/// The job of a project's attempt: the year, the time limit and the student.
pub fn job_of(app: &App, attempt: &Attempt) -> Result<Job> {
    let student = db::with(&app.data.database(), |s| s.student(attempt.student))?
        .ok_or_else(|| Error::Environment("the attempt's student is gone".into()))?;
    Ok(Job {
        course: app.course,
        seconds: app.seconds,
        student,
    })
}

/// Runs a project's attempt in a process of its own on this machine, and reads its outcome.
fn project(app: &App, attempt: &Attempt) -> Result<Finished> {
    let dir = app.data.upload(&attempt.folder);
    job::prepare(&dir, &job_of(app, attempt)?)?;
    let (program, args) = job::command_line(&dir)?;
    let log_path = dir.join(RUN_LOG);
    let log =
        std::fs::File::create(&log_path).map_err(|e| Error::io(&log_path, "cannot create", e))?;
    let status = Command::new(&program)
        .args(&args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(log)
        .status()
        .map_err(|e| Error::Environment(format!("cannot start {}: {e}", program.display())))?;
    job::finished(&dir).ok_or_else(|| {
        Error::Environment(format!(
            "its run ended ({status}) without a result (the service's {RUN_LOG} has why)"
        ))
    })
}
