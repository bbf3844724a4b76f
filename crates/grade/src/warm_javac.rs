//! A warm javac shared by a few grading slots (`WarmJavac.java`, in the sandbox): a student
//! then costs a compilation, not a JVM's start and warm-up. Measured on the 24-student bench
//! class: ~1.1 s of CPU per student with a javac of its own, ~0.08 s warm.
//!
//! The compiler sees one student at a time: their sources are laid out in the slot's `src`
//! (bound read-only), the classes come back in its `classes` (the only folder it may write),
//! and both are emptied before the next student. It runs no student code (`-proc:none`), so
//! what it keeps between students is javac's own state. Its verdict is final where it gave
//! one (ok, errors, timeout); where it could give none (it died: out of memory, a stack
//! overflow on a hostile source, the CPU limit) the caller compiles that student with a javac
//! of their own (`compile::compile`), which names what happened.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{ChildStdin, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use super::compile::{first_lines, javac_options, Compiled, MESSAGES};
use super::jvm;
use super::sandbox::{Area, Limits, Priority, RunGuard, Sandbox};
use whitted_core::error::{Error, Result};
use whitted_process::{Capture, Process};

const SOURCE: &str = include_str!("WarmJavac.java");

/// Students one JVM compiles before it is replaced: bounds what javac's caches may grow to
/// and the CPU time its `RLIMIT_CPU` counts.
const COMPILATIONS_PER_JVM: usize = 50;

/// Failures to start or answer after which a slot stops trying and compiles every student
/// with a javac of their own.
const GIVE_UP_AFTER: usize = 3;

/// How often a compilation is looked at (and Ctrl-C noticed).
const POLL: Duration = Duration::from_millis(10);
/// How long the warm compiler spends on one student: a Tick 2's two files take a tenth of a
/// second once it is warm, and every student of its slots waits while it works. Past it the
/// student is compiled by a javac of their own, which yields the CPU to every other run
/// (`Priority::Background`): the warm compiler does not, so this is how long a source that
/// makes javac work for minutes takes CPU from the students beside it at full priority.
const WARM_DEADLINE: Duration = Duration::from_secs(2);
/// How long a new compiler may take to start and compile [`WARM_UP`]: a JVM's start and
/// javac's first compilation, seconds of CPU on a busy machine.
const START_DEADLINE: Duration = Duration::from_secs(10);
/// What a new compiler compiles first, so that javac's classes are loaded and compiled before
/// a student's sources are timed against [`WARM_DEADLINE`].
const WARM_UP: (&str, &[u8]) = (
    "Warm.java",
    b"class Warm { double f(double[] x) { double s = 0; for (double v : x) s += v * v; \
      return Math.sqrt(s); } }",
);

/// A slot's warm compiler, started on its first student.
pub struct WarmJavac<'a> {
    sandbox: &'a Sandbox,
    java: &'a Path,
    /// The slot's folder: `WarmJavac.java`, `src`, `classes`.
    dir: PathBuf,
    slot: usize,
    limits: Limits,
    running: Option<Server>,
    failures: usize,
}

struct Server {
    /// The JVM, the leader of its process group: dropping it kills the group.
    process: Process,
    stdin: ChildStdin,
    replies: Receiver<Reply>,
    compiled: usize,
    /// Its memory limit's cgroup, removed after it (fields drop after `stop` killed it).
    _run: RunGuard,
}

/// What the warm compiler made of a student.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Warm {
    /// Its verdict, final.
    Done(Compiled),
    /// There is none to ask (it could not start, or the slot gave up on it): compile the
    /// student otherwise, as any other.
    Unavailable,
    /// It was warm and running, and this source kept it past its deadline or ended it (out of
    /// memory, a stack overflow): compile the student otherwise, yielding the CPU to everyone
    /// else (`Priority::Background`), since the source may make javac work for minutes.
    Suspect,
}

/// One answer read from the compiler.
enum Reply {
    Done {
        ok: bool,
        messages: Vec<u8>,
    },
    /// It closed its output or said something that is not the protocol.
    Gone,
}

impl<'a> WarmJavac<'a> {
    /// The compiler of slot `slot`, in `root/<slot>`; nothing is started yet.
    pub fn new(
        sandbox: &'a Sandbox,
        java: &'a Path,
        root: &Path,
        slot: usize,
        limits: Limits,
    ) -> Self {
        WarmJavac {
            sandbox,
            java,
            dir: root.join(slot.to_string()),
            slot,
            limits,
            running: None,
            failures: 0,
        }
    }

    /// Compiles `sources` (file name, bytes; all in package gfx.tick2) into `into`
    /// (`into/gfx/tick2/*.class`), or says why it could not.
    pub fn compile(&mut self, sources: &[(&str, &[u8])], into: &Path) -> Result<Warm> {
        if self.failures >= GIVE_UP_AFTER {
            return Ok(Warm::Unavailable);
        }
        let verdict = match self.ready() {
            Ok(true) => self.lay_out(sources).and_then(|()| self.ask(WARM_DEADLINE)),
            Ok(false) => return Ok(Warm::Unavailable),
            Err(e) => Err(e),
        };
        let verdict = match verdict {
            Ok(verdict) => verdict,
            Err(e) => {
                self.stop();
                return Err(e);
            }
        };
        match verdict {
            // A running, warm compiler that did not answer on this source in time.
            None => {
                self.failures += 1;
                self.stop();
                Ok(Warm::Suspect)
            }
            Some(Compiled::Ok) => {
                copy_tree(&self.dir.join("classes"), into)?;
                Ok(Warm::Done(Compiled::Ok))
            }
            Some(other) => Ok(Warm::Done(other)),
        }
    }

    /// The slot's `src` holding exactly `sources`, its `classes` empty. Both folders are
    /// emptied, never replaced: the running compiler sees them through bind mounts.
    fn lay_out(&self, sources: &[(&str, &[u8])]) -> Result<()> {
        let (src, classes) = (self.dir.join("src"), self.dir.join("classes"));
        for dir in [&src, &classes] {
            std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, "cannot create", e))?;
            empty(dir)?;
        }
        super::source_tree::write_sources(&src, sources)?;
        super::work_area::open_up(&self.dir)
    }

    /// Whether a warm compiler is running: the one running unless it is worn out, else a new
    /// one, started and warmed up on a source of its own ([`WARM_UP`]) within
    /// [`START_DEADLINE`], so that no student's compilation pays for a JVM's start.
    fn ready(&mut self) -> Result<bool> {
        if self
            .running
            .as_ref()
            .is_some_and(|s| s.compiled >= COMPILATIONS_PER_JVM)
        {
            self.stop();
        }
        if self.running.is_some() {
            return Ok(true);
        }
        self.lay_out(&[WARM_UP])?;
        self.running = self.start().ok();
        match self.ask(START_DEADLINE)? {
            Some(Compiled::Ok) => Ok(true),
            _ => {
                self.stop();
                Ok(false)
            }
        }
    }

    /// One compilation by the running compiler, within `deadline`. None: there is none, or it
    /// did not answer in time (it is then stopped).
    fn ask(&mut self, deadline: Duration) -> Result<Option<Compiled>> {
        let Some(server) = self.running.as_mut() else {
            return Ok(None);
        };
        if server
            .stdin
            .write_all(b"compile\n")
            .and_then(|()| server.stdin.flush())
            .is_err()
        {
            return Ok(None);
        }
        server.compiled += 1;
        let started = Instant::now();
        loop {
            whitted_core::interrupt::check()?;
            if started.elapsed() > deadline {
                // Slow here, so not for the warm compiler, which other students wait for: the
                // student is compiled by a javac of their own, with the full deadline.
                self.stop();
                return Ok(None);
            }
            match server.replies.recv_timeout(POLL) {
                Ok(Reply::Done { ok: true, .. }) => return Ok(Some(Compiled::Ok)),
                Ok(Reply::Done {
                    ok: false,
                    messages,
                }) => {
                    let src = self.dir.join("src");
                    return Ok(Some(Compiled::Errors(first_lines(&messages, &src))));
                }
                Ok(Reply::Gone) | Err(RecvTimeoutError::Disconnected) => return Ok(None),
                Err(RecvTimeoutError::Timeout) => {}
            }
        }
    }

    /// Starts the compiler in the sandbox, with a reader of its answers.
    fn start(&self) -> Result<Server> {
        let source = self.dir.join("WarmJavac.java");
        std::fs::write(&source, SOURCE).map_err(|e| Error::io(&source, "cannot write", e))?;
        super::work_area::open_up(&source)?;
        let (src, classes) = (self.dir.join("src"), self.dir.join("classes"));
        let mut program = vec![self.java.display().to_string()];
        program.extend(jvm::options(self.limits));
        program.extend([source.display().to_string(), src.display().to_string()]);
        program.extend(javac_options(&classes));
        // Its CPU limit is a compilation's time limit: the JVM is replaced long before it
        // could add up to that.
        let limits = jvm::compiling(self.limits);
        let (mut command, run) = self.sandbox.command(
            &program,
            &[&src, &source],
            &classes,
            Area::Folder,
            self.slot,
            limits,
            Priority::Normal,
        )?;
        command.stdin(Stdio::piped()).stdout(Stdio::piped());
        let mut process = Process::spawn(command, Capture::Nothing)
            .map_err(|e| Error::Environment(format!("cannot start javac: {e}")))?;
        let child = process.child_mut();
        let (Some(stdin), Some(stdout)) = (child.stdin.take(), child.stdout.take()) else {
            process.kill();
            return Err(Error::Environment("cannot talk to javac".into()));
        };
        let (send, replies) = mpsc::channel();
        std::thread::spawn(move || {
            let mut stdout = BufReader::new(stdout);
            loop {
                let reply = read_reply(&mut stdout);
                let gone = matches!(reply, Reply::Gone);
                if send.send(reply).is_err() || gone {
                    return;
                }
            }
        });
        Ok(Server {
            process,
            stdin,
            replies,
            compiled: 0,
            _run: run,
        })
    }

    /// Kills the running compiler with everything in its sandbox.
    fn stop(&mut self) {
        if let Some(mut server) = self.running.take() {
            server.process.kill();
        }
    }
}

impl Drop for WarmJavac<'_> {
    fn drop(&mut self) {
        self.stop();
    }
}

/// One answer: `ok N` or `errors N`, then N bytes.
fn read_reply(stdout: &mut impl BufRead) -> Reply {
    let mut header = Vec::new();
    match stdout.take(64).read_until(b'\n', &mut header) {
        Ok(n) if n > 0 && header.ends_with(b"\n") => {}
        _ => return Reply::Gone,
    }
    let header = String::from_utf8_lossy(&header);
    let parsed = match header.trim_end().split_once(' ') {
        Some(("ok", n)) => n.parse::<u64>().ok().map(|n| (true, n)),
        Some(("errors", n)) => n.parse::<u64>().ok().map(|n| (false, n)),
        _ => None,
    };
    let Some((ok, length)) = parsed.filter(|(_, n)| *n <= MESSAGES as u64) else {
        return Reply::Gone;
    };
    let mut messages = Vec::new();
    match stdout.take(length).read_to_end(&mut messages) {
        Ok(n) if n as u64 == length => Reply::Done { ok, messages },
        _ => Reply::Gone,
    }
}

/// Removes everything inside `dir`, keeping `dir`.
fn empty(dir: &Path) -> Result<()> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::io(dir, "cannot read", e))?;
    for entry in entries.flatten() {
        let path = entry.path();
        let removed = match entry.file_type() {
            Ok(t) if t.is_dir() => std::fs::remove_dir_all(&path),
            _ => std::fs::remove_file(&path),
        };
        removed.map_err(|e| Error::io(&path, "cannot remove", e))?;
    }
    Ok(())
}

/// Copies the regular files and folders under `from` to `to` (javac's output: no links).
fn copy_tree(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).map_err(|e| Error::io(to, "cannot create", e))?;
    let entries = std::fs::read_dir(from).map_err(|e| Error::io(from, "cannot read", e))?;
    for entry in entries.flatten() {
        let (source, target) = (entry.path(), to.join(entry.file_name()));
        match entry.file_type() {
            Ok(t) if t.is_dir() => copy_tree(&source, &target)?,
            Ok(t) if t.is_file() => {
                std::fs::copy(&source, &target)
                    .map_err(|e| Error::io(&source, "cannot copy", e))?;
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reply(bytes: &[u8]) -> Reply {
        read_reply(&mut std::io::BufReader::new(bytes))
    }

    #[test]
    fn replies_are_read_by_their_length_and_anything_else_is_gone() {
        match reply(b"errors 5\nab\ncdok 0\n") {
            Reply::Done { ok, messages } => assert!(!ok && messages == b"ab\ncd"),
            Reply::Gone => panic!("a reply was refused"),
        }
        assert!(matches!(reply(b"ok 0\n"), Reply::Done { ok: true, .. }));
        for bad in [
            &b""[..],
            b"ok",
            b"ok x\n",
            b"fine 0\n",
            b"errors 10\nshort",
            b"errors 99999999\n",
        ] {
            assert!(matches!(reply(bad), Reply::Gone), "{bad:?}");
        }
    }

    /// A warm compiler in `root`, unsandboxed, with the JDK's `java` (the grade tests need a
    /// JDK; tools/test installs it).
    fn warm(root: &Path) -> WarmJavac<'static> {
        static NO_SANDBOX: Sandbox = Sandbox::None;
        static JAVA: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
        let java =
            JAVA.get_or_init(|| crate::sandbox::find_in_path("java").expect("a JDK on PATH"));
        let limits = Limits {
            memory_mib: 512,
            seconds: 60,
        };
        WarmJavac::new(&NO_SANDBOX, java, root, 0, limits)
    }

    #[test]
    fn one_jvm_compiles_student_after_student_and_says_what_a_single_javac_says() {
        let root = tempfile::tempdir().expect("tempdir");
        let mut javac = warm(root.path());
        let good = b"package gfx.tick2; public class A { int f() { return 1; } }";
        let bad = b"package gfx.tick2; public class A { int f() { return 1 } }";
        for round in 0..3 {
            let into = root.path().join(format!("out{round}"));
            let compiled = javac
                .compile(&[("gfx/tick2/A.java", good)], &into)
                .expect("compile");
            assert_eq!(compiled, Warm::Done(Compiled::Ok));
            assert!(into.join("gfx/tick2/A.class").is_file());
            let refused = javac
                .compile(&[("gfx/tick2/A.java", bad)], &into)
                .expect("compile");
            let Warm::Done(Compiled::Errors(messages)) = refused else {
                panic!("{refused:?}");
            };
            // The slot's folders are out of the messages: the path is the package's.
            assert!(
                messages.starts_with("gfx/tick2/A.java:1: error: ';' expected"),
                "{messages}"
            );
        }
        // Its warm-up, then the six students.
        assert_eq!(javac.running.as_ref().map(|s| s.compiled), Some(7));
    }

    #[test]
    fn a_compiler_that_died_is_replaced_and_the_student_is_compiled_otherwise() {
        let root = tempfile::tempdir().expect("tempdir");
        let mut javac = warm(root.path());
        let good = b"package gfx.tick2; public class A {}";
        let into = root.path().join("out");
        assert_eq!(
            javac
                .compile(&[("gfx/tick2/A.java", good)], &into)
                .expect("compile"),
            Warm::Done(Compiled::Ok)
        );
        if let Some(server) = &mut javac.running {
            server.process.kill();
        }
        // The dead one cannot answer: the caller is told to compile this student itself.
        assert_eq!(
            javac
                .compile(&[("gfx/tick2/A.java", good)], &into)
                .expect("compile"),
            Warm::Suspect
        );
        // The next student gets a new one.
        assert_eq!(
            javac
                .compile(&[("gfx/tick2/A.java", good)], &into)
                .expect("compile"),
            Warm::Done(Compiled::Ok)
        );
    }
}
