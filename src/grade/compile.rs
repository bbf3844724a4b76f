//! `javac` over a student's two files and the skeleton, in the sandbox: the first errors it
//! prints are what the student's report shows for `compile-error`.

use std::io::Read;
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

use super::sandbox::{Limits, Sandbox};
use crate::error::{Error, Result};

/// Bytes of javac's messages kept (the first ones: the first error is the one to fix).
const MESSAGES: u64 = 64 << 10;
/// javac's own time limit, at least: `--timeout` is a case's, and a busy machine can take
/// seconds to start a JVM; a source that keeps javac busy for a minute is a timeout all the same.
const COMPILE_SECONDS: u64 = 60;
/// Lines of them shown in a report.
pub const SHOWN_LINES: usize = 30;

/// How a compilation ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Compiled {
    Ok,
    /// javac's first messages, with the work folder's path taken out of them.
    Errors(String),
    /// Still compiling after the time limit.
    Timeout,
}

/// Compiles `sources` (paths inside `work/src`, which javac sees read-only) into
/// `work/classes` (the only folder it may write).
pub fn compile(
    sandbox: &Sandbox,
    javac: &Path,
    work: &Path,
    sources: &[String],
    slot: usize,
    limits: Limits,
) -> Result<Compiled> {
    let mut program = vec![
        javac.display().to_string(),
        format!("-J-Xmx{}m", (limits.memory_mib / 2).max(32)),
        // javac runs for about a second: the C2 compiler would cost more CPU than it saves.
        "-J-XX:TieredStopAtLevel=1".into(),
        "-J-XX:+UseSerialGC".into(),
        "-J-XX:-UsePerfData".into(),
        "-proc:none".into(),
        "-encoding".into(),
        "UTF-8".into(),
        "-Xmaxerrs".into(),
        "20".into(),
        "-d".into(),
        work.join("classes").display().to_string(),
    ];
    program.extend(sources.iter().cloned());
    let (src, classes) = (work.join("src"), work.join("classes"));
    let mut command = sandbox.command(&program, &[&src], &classes, slot, limits)?;
    command
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    std::os::unix::process::CommandExt::process_group(&mut command, 0);
    let mut child = command
        .spawn()
        .map_err(|e| Error::Environment(format!("cannot run javac: {e}")))?;
    let stderr = child.stderr.take();
    let reader = std::thread::spawn(move || {
        let mut kept = Vec::new();
        if let Some(pipe) = stderr {
            let mut pipe = pipe.take(MESSAGES);
            let _ = pipe.read_to_end(&mut kept);
            // Drained to the end, so that javac never blocks on a full pipe.
            let _ = std::io::copy(&mut pipe.into_inner(), &mut std::io::sink());
        }
        kept
    });
    let started = Instant::now();
    let timeout = Duration::from_secs(limits.seconds.max(COMPILE_SECONDS));
    let status = loop {
        if crate::interrupt::requested() || started.elapsed() > timeout {
            kill(&child);
            let _ = child.wait();
            crate::interrupt::check()?;
            break None;
        }
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => {
                kill(&child);
                return Err(Error::Environment(format!("cannot wait for javac: {e}")));
            }
        }
    };
    let messages = reader.join().unwrap_or_default();
    Ok(match status {
        None => Compiled::Timeout,
        Some(s) if s.success() => Compiled::Ok,
        Some(_) => Compiled::Errors(first_lines(&messages, work)),
    })
}

fn kill(child: &std::process::Child) {
    if let Some(pid) = rustix::process::Pid::from_child(child).into() {
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
}

/// javac's first `SHOWN_LINES` lines, paths relative to the sources' folder.
fn first_lines(messages: &[u8], work: &Path) -> String {
    let text = String::from_utf8_lossy(messages);
    let prefix = format!("{}/src/", work.display());
    text.lines()
        .take(SHOWN_LINES)
        .map(|l| l.replace(&prefix, ""))
        .collect::<Vec<_>>()
        .join("\n")
}
