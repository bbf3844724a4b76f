//! `--slurm`: projects run as Slurm jobs instead of on the service's own workers. One thread
//! sends each queued project to Slurm (`sbatch`: a job that runs `whitted serve run-attempt
//! DIR`, `job.rs`), at most `-j N` in Slurm at once, records the job's id with the attempt,
//! and every `POLL` collects the outcomes the jobs wrote into their attempts' folders. The
//! binary and the data folder must be on a filesystem the nodes see, at the same paths.
//!
//! - A job that leaves Slurm's queue without an outcome (its node died, it was cancelled) is
//!   queued again, up to `RUNS` runs; then its attempt says the service could not run it.
//! - A restart of the service leaves the jobs in flight alone: their ids are in the database,
//!   and their outcomes are collected as they arrive.
//! - On shutdown the jobs still pending are cancelled and their attempts queued again (the next
//!   start sends them again); the running ones finish, and the next start collects them.
//! - Site settings (partition, account, time limit) come from sbatch's own environment
//!   variables (`SBATCH_PARTITION`, `SBATCH_ACCOUNT`, `SBATCH_TIMELIMIT`) in the service's.

use std::collections::HashMap;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::Arc;
use std::time::Duration;

use super::job::{self, Finished};
use super::store::Kind;
use super::{db, worker, App};
use whitted_core::error::{Error, Result};

/// How often Slurm's queue and the attempts' folders are looked at.
const POLL: Duration = Duration::from_secs(2);
/// A job gone from the queue without an outcome is believed gone after this many polls (a
/// shared filesystem may show a file written on a node a moment late).
const GRACE: u32 = 3;
/// Runs of one attempt at most before it is given up.
const RUNS: i64 = 3;
/// The jobs' name, by which the service finds its own in the queue.
pub const JOB_NAME: &str = "whitted-serve";
/// CPUs a job asks for: grade runs two cases of a program at once.
const CPUS: u32 = 2;

/// Refuses `--slurm` where sbatch cannot be run.
pub fn check() -> Result<()> {
    let ran = Command::new("sbatch")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    match ran {
        Ok(status) if status.success() => Ok(()),
        _ => Err(Error::Environment(
            "--slurm sends the programs to Slurm, but `sbatch --version` does not run here".into(),
        )),
    }
}

/// Starts the thread that sends projects to Slurm and collects their outcomes.
pub fn start(app: Arc<App>, in_flight: usize) -> Result<()> {
    std::thread::Builder::new()
        .name("slurm".into())
        .spawn(move || dispatch(&app, in_flight.max(1)))
        .map(drop)
        .map_err(|e| Error::Environment(format!("cannot start the Slurm dispatcher: {e}")))
}

fn dispatch(app: &App, in_flight: usize) {
    let mut missing: HashMap<i64, u32> = HashMap::new();
    loop {
        if whitted_core::interrupt::requested() {
            return;
        }
        if let Err(e) = round(app, in_flight, &mut missing) {
            eprintln!("whitted serve: Slurm: {e}");
        }
        app.bell.wait_for(POLL);
    }
}

/// One round: collect what finished, then send what is queued, up to `in_flight` in Slurm.
fn round(app: &App, in_flight: usize, missing: &mut HashMap<i64, u32>) -> Result<()> {
    let path = app.data.database();
    let states = queue();
    if let Some(states) = &states {
        *app.job_states.lock().unwrap_or_else(|e| e.into_inner()) = states.clone();
    }
    let flying = db::with(&path, |s| s.jobs_in_flight())?;
    let mut left = flying.len();
    for (attempt, job) in flying {
        let Some(a) = db::with(&path, |s| s.attempt(attempt))? else {
            continue;
        };
        let dir = app.data.upload(&a.folder);
        if let Some(done) = job::finished(&dir) {
            db::with(&path, |s| s.finish(attempt, &done.outcome, done.cpu))?;
            missing.remove(&attempt);
            left -= 1;
            continue;
        }
        // Gone from the queue (and the queue was read), with no outcome.
        if states.as_ref().is_some_and(|s| !s.contains_key(&job)) {
            let polls = missing.entry(attempt).or_insert(0);
            *polls += 1;
            if *polls >= GRACE {
                missing.remove(&attempt);
                left -= 1;
                lost(app, attempt, &job, a.runs)?;
            }
        }
    }
    while left < in_flight {
        let Some(attempt) = db::with(&path, |s| s.claim(Kind::Project))? else {
            break;
        };
        let dir = app.data.upload(&attempt.folder);
        let sent = worker::job_of(app, &attempt)
            .and_then(|j| job::prepare(&dir, &j))
            .and_then(|()| submit(&dir));
        match sent {
            Ok(id) => {
                db::with(&path, |s| s.set_job(attempt.id, &id))?;
                left += 1;
            }
            Err(e) => {
                // Slurm refused or is down: the attempt waits in the queue for the next round.
                db::with(&path, |s| s.requeue(attempt.id))?;
                return Err(e);
            }
        }
    }
    Ok(())
}

/// A job that ended without an outcome: queued again, or given up after `RUNS` runs.
fn lost(app: &App, attempt: i64, job: &str, runs: i64) -> Result<()> {
    let path = app.data.database();
    eprintln!("whitted serve: Slurm job {job} (attempt {attempt}) ended without a result");
    match runs < RUNS {
        true => db::with(&path, |s| s.requeue(attempt)),
        false => {
            let e = Error::Environment(format!(
                "its Slurm job ended without a result {runs} times (the attempt's {} has why)",
                worker::RUN_LOG
            ));
            let done = Finished {
                outcome: job::not_run(&e),
                cpu: None,
            };
            db::with(&path, |s| s.finish(attempt, &done.outcome, done.cpu))
        }
    }
}

/// Sends the job in `dir` to Slurm; its id.
fn submit(dir: &Path) -> Result<String> {
    let (program, args) = job::command_line(dir)?;
    let mut script = String::from("#!/bin/sh\nexec");
    for word in std::iter::once(program.display().to_string()).chain(args) {
        script.push(' ');
        script.push_str(&quoted(&word));
    }
    script.push('\n');
    let mut child = Command::new("sbatch")
        .arg("--parsable")
        .arg(format!("--job-name={JOB_NAME}"))
        .arg(format!("--cpus-per-task={CPUS}"))
        .arg(format!("--chdir={}", dir.display()))
        .arg(format!("--output={}", dir.join(worker::RUN_LOG).display()))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| Error::Environment(format!("cannot run sbatch: {e}")))?;
    if let Some(mut stdin) = child.stdin.take() {
        stdin
            .write_all(script.as_bytes())
            .map_err(|e| Error::Environment(format!("cannot give sbatch its script: {e}")))?;
    }
    let out = child
        .wait_with_output()
        .map_err(|e| Error::Environment(format!("sbatch: {e}")))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let id = text.trim().split(';').next().unwrap_or("").to_string();
    match out.status.success() && !id.is_empty() {
        true => Ok(id),
        false => Err(Error::Environment(format!(
            "sbatch refused the job: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ))),
    }
}

/// `word` quoted for sh.
fn quoted(word: &str) -> String {
    format!("'{}'", word.replace('\'', "'\\''"))
}

/// This user's jobs of the service in Slurm's queue, with their states (`PENDING`,
/// `RUNNING`…); None when the queue cannot be read (slurmctld down): nothing is concluded then.
fn queue() -> Option<HashMap<String, String>> {
    let uid = rustix::process::getuid().as_raw().to_string();
    let out = Command::new("squeue")
        .args([
            "-h",
            "-o",
            "%i %T",
            "-u",
            &uid,
            &format!("--name={JOB_NAME}"),
        ])
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    Some(
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter_map(|l| l.split_once(' '))
            .map(|(id, state)| (id.trim().to_string(), state.trim().to_string()))
            .collect(),
    )
}

/// Cancels `jobs` (best effort): the jobs of attempts a start without `--slurm` runs here.
pub fn cancel(jobs: &[String]) {
    if jobs.is_empty() {
        return;
    }
    let _ = Command::new("scancel")
        .args(jobs)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
}

/// On shutdown: the jobs not yet started are cancelled and their attempts queued again; the
/// running ones go on, and the next start collects their outcomes.
pub fn shutdown(app: &App) -> Result<usize> {
    let path = app.data.database();
    let flying = db::with(&path, |s| s.jobs_in_flight())?;
    let Some(states) = queue() else {
        return Ok(0);
    };
    let pending: Vec<String> = flying
        .iter()
        .filter(|(_, j)| states.get(j).is_some_and(|s| s == "PENDING"))
        .map(|(_, j)| j.clone())
        .collect();
    if pending.is_empty() {
        return Ok(0);
    }
    let _ = Command::new("scancel")
        .arg("--state=PENDING")
        .args(&pending)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    // One that started meanwhile was not cancelled: it stays in flight.
    let after = queue().unwrap_or_default();
    let mut requeued = 0;
    for (attempt, job) in flying.iter().filter(|(_, j)| pending.contains(j)) {
        let running = after
            .get(job)
            .is_some_and(|s| s == "RUNNING" || s == "COMPLETING" || s == "CONFIGURING");
        if !running {
            db::with(&path, |s| s.requeue(*attempt))?;
            requeued += 1;
        }
    }
    Ok(requeued)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_word_is_quoted_for_the_shell_whatever_it_holds() {
        assert_eq!(quoted("/data/uploads/ab"), "'/data/uploads/ab'");
        assert_eq!(quoted("it's"), "'it'\\''s'");
    }
}
