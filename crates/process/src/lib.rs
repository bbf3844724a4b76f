//! whitted-process: the one way whitted runs a program it does not trust to end: a student's
//! program under `check --program`, javac, and every graded run.
//!
//! A [`Process`] is spawned as the leader of its own process group (inside a sandbox, bubblewrap
//! adds a PID namespace on top), is given a deadline by its caller, and is killed together with
//! every descendant still in its group. What it writes to standard error is read on a thread of
//! its own into a bounded buffer (the first bytes or the last ones, as the caller needs), and
//! that thread is never waited for beyond a short grace: a descendant that left the group may
//! hold the pipe open for ever, and the run must not hang on it. Processes that leave the group
//! altogether (`setsid`, a daemon's double fork) are adopted and killed by [`orphans`] where
//! there is no sandbox's PID namespace to end them.
//!
//! # What it may depend on
//! The standard library and rustix (to signal a process group). Nothing of whitted's: the
//! checker and the grader build on it.

pub mod orphans;

use std::io::Read;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long the standard error reader is waited for once the process is gone: the pipe ends
/// when every process holding it has exited, and one that escaped the group is not waited for.
pub const STDERR_GRACE: Duration = Duration::from_millis(200);

/// What is kept of the program's standard error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Capture {
    /// Nothing: standard error goes to /dev/null.
    Nothing,
    /// The first `n` bytes (the rest is read and dropped, so the program never blocks on a full
    /// pipe): a compiler's first error is the one to fix.
    Head(usize),
    /// The last `n` bytes: a crash's stack trace ends its output.
    Tail(usize),
}

/// How a [`Process::wait`] ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ended {
    /// The program exited by itself.
    Exited(ExitStatus),
    /// The deadline passed; the process group has been killed.
    TimedOut,
    /// The caller's `stop` said so; the process group has been killed.
    Stopped,
}

/// A running program, the leader of its own process group.
pub struct Process {
    child: Child,
    started: Instant,
    reader: Option<JoinHandle<()>>,
    kept: Arc<Mutex<Vec<u8>>>,
    /// Reaped: its process ID (and so its group's) may belong to someone else now.
    reaped: bool,
}

impl Process {
    /// Starts `command` in a new process group, with its standard error captured as `stderr`
    /// says. Standard input and output are the caller's to set on `command` (the default here is
    /// /dev/null for both, unless set).
    pub fn spawn(mut command: Command, stderr: Capture) -> std::io::Result<Process> {
        command.stderr(match stderr {
            Capture::Nothing => Stdio::null(),
            Capture::Head(_) | Capture::Tail(_) => Stdio::piped(),
        });
        #[cfg(unix)]
        std::os::unix::process::CommandExt::process_group(&mut command, 0);
        let mut child = command.spawn()?;
        let kept = Arc::new(Mutex::new(Vec::new()));
        let reader = child.stderr.take().map(|pipe| {
            let kept = Arc::clone(&kept);
            std::thread::spawn(move || read_bounded(pipe, stderr, &kept))
        });
        Ok(Process {
            child,
            started: Instant::now(),
            reader,
            kept,
            reaped: false,
        })
    }

    /// The child, for its standard input and output pipes.
    pub fn child_mut(&mut self) -> &mut Child {
        &mut self.child
    }

    /// Time since the program started.
    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    /// Its exit status if it has exited, without waiting.
    pub fn try_wait(&mut self) -> std::io::Result<Option<ExitStatus>> {
        let status = self.child.try_wait()?;
        self.reaped |= status.is_some();
        Ok(status)
    }

    /// Waits for the program to exit, polling every `poll`, until `timeout` has passed since it
    /// started or `stop()` says to stop (an interruption); then kills the group. An error is a
    /// failure to wait, after which the group has been killed too.
    pub fn wait(
        &mut self,
        timeout: Duration,
        poll: Duration,
        stop: impl Fn() -> bool,
    ) -> std::io::Result<Ended> {
        loop {
            if stop() {
                self.kill();
                return Ok(Ended::Stopped);
            }
            if self.elapsed() > timeout {
                self.kill();
                return Ok(Ended::TimedOut);
            }
            match self.try_wait() {
                Ok(Some(status)) => return Ok(Ended::Exited(status)),
                Ok(None) => std::thread::sleep(poll),
                Err(e) => {
                    self.kill();
                    return Err(e);
                }
            }
        }
    }

    /// Kills the whole process group and reaps the leader. Anything of the group still running
    /// after the leader exited is killed too.
    pub fn kill(&mut self) {
        self.kill_group();
        let _ = self.child.kill();
        let _ = self.child.wait();
        self.reaped = true;
    }

    /// Kills what is left of the group, reaps the leader, and returns what standard error kept
    /// (waiting at most [`STDERR_GRACE`] for its reader).
    pub fn finish(&mut self) -> Vec<u8> {
        self.kill();
        let deadline = Instant::now() + STDERR_GRACE;
        if let Some(reader) = self.reader.take() {
            while !reader.is_finished() && Instant::now() < deadline {
                std::thread::sleep(Duration::from_millis(5));
            }
            if reader.is_finished() {
                let _ = reader.join();
            }
        }
        // A poisoned lock only means the reader panicked: the bytes are still worth keeping.
        let kept = self.kept.lock().unwrap_or_else(|e| e.into_inner());
        kept.clone()
    }

    /// Sends SIGKILL to the process group the leader started, unless the leader was reaped
    /// and the group was killed with it already.
    fn kill_group(&self) {
        #[cfg(unix)]
        if !self.reaped {
            if let Some(pid) = rustix::process::Pid::from_child(&self.child).into() {
                // The group may be gone already (everything exited): nothing to do then.
                let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
            }
        }
    }
}

impl Drop for Process {
    /// Nothing outlives its run: a process dropped on an error path is killed with its group.
    fn drop(&mut self) {
        if !self.reaped {
            self.kill();
        }
    }
}

/// Reads `pipe` to its end, keeping the bytes `capture` says in `kept`.
fn read_bounded(mut pipe: impl Read, capture: Capture, kept: &Mutex<Vec<u8>>) {
    let mut buffer = [0u8; 8192];
    loop {
        let n = match pipe.read(&mut buffer) {
            Ok(0) | Err(_) => return,
            Ok(n) => n,
        };
        let mut kept = kept.lock().unwrap_or_else(|e| e.into_inner());
        match capture {
            Capture::Nothing => {}
            Capture::Head(limit) => {
                let room = limit.saturating_sub(kept.len()).min(n);
                kept.extend_from_slice(&buffer[..room]);
            }
            Capture::Tail(limit) => {
                kept.extend_from_slice(&buffer[..n]);
                if kept.len() > limit {
                    let excess = kept.len() - limit;
                    kept.drain(..excess);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sh(script: &str) -> Command {
        let mut c = Command::new("sh");
        c.arg("-c")
            .arg(script)
            .stdin(Stdio::null())
            .stdout(Stdio::null());
        c
    }

    #[test]
    fn head_keeps_the_first_bytes_and_tail_the_last() {
        let script = "i=0; while [ $i -lt 2000 ]; do echo line$i >&2; i=$((i+1)); done";
        let mut p = Process::spawn(sh(script), Capture::Head(12)).expect("sh");
        let ended = p.wait(Duration::from_secs(20), Duration::from_millis(5), || false);
        assert!(matches!(ended, Ok(Ended::Exited(s)) if s.success()));
        assert_eq!(p.finish(), b"line0\nline1\n");
        let mut p = Process::spawn(sh(script), Capture::Tail(10)).expect("sh");
        let _ = p.wait(Duration::from_secs(20), Duration::from_millis(5), || false);
        assert_eq!(p.finish(), b"\nline1999\n");
    }

    #[test]
    fn a_deadline_kills_every_descendant_and_a_held_pipe_does_not_hang() {
        // The grandchild holds standard error open and would run for a minute.
        let started = Instant::now();
        let mut p = Process::spawn(sh("sleep 60 & sleep 60"), Capture::Tail(100)).expect("sh");
        let ended = p.wait(Duration::from_millis(200), Duration::from_millis(5), || {
            false
        });
        assert_eq!(ended.ok(), Some(Ended::TimedOut));
        let _ = p.finish();
        assert!(started.elapsed() < Duration::from_secs(10));
        // Both sleeps were in the group: none of it runs on (the orphaned sleep may stay a
        // zombie until init reaps it).
        let group = p.child.id() as i32;
        let deadline = Instant::now() + Duration::from_secs(5);
        while running_in_group(group) > 0 && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(20));
        }
        assert_eq!(running_in_group(group), 0, "the process group still runs");
    }

    /// Processes of process group `group` that are not zombies, from /proc.
    fn running_in_group(group: i32) -> usize {
        let Ok(entries) = std::fs::read_dir("/proc") else {
            return 0;
        };
        entries
            .flatten()
            .filter_map(|e| std::fs::read_to_string(e.path().join("stat")).ok())
            .filter(|stat| {
                // After the name's closing parenthesis: state, parent, group.
                let Some(end) = stat.rfind(')') else {
                    return false;
                };
                let fields: Vec<&str> = stat[end + 1..].split_whitespace().collect();
                fields.len() > 2 && fields[0] != "Z" && fields[2] == group.to_string()
            })
            .count()
    }

    #[test]
    fn stop_kills_at_once() {
        let mut p = Process::spawn(sh("sleep 60"), Capture::Nothing).expect("sh");
        let ended = p.wait(Duration::from_secs(60), Duration::from_millis(5), || true);
        assert_eq!(ended.ok(), Some(Ended::Stopped));
    }
}
