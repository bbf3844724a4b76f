//! `javac` over a student's two files and the skeleton, in the sandbox: the first errors it
//! prints are what the student's report shows for `compile-error`. A JVM of its own per
//! student: what the warm compiler (`warm_javac.rs`) falls back to, and what names the end of
//! a compilation that killed it.

use std::io::Read;
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

use super::sandbox::{Area, Limits, Sandbox};
use whitted_check::check::program::kill_group;
use whitted_core::error::{Error, Result};

/// Bytes of javac's messages kept (the first ones: the first error is the one to fix).
pub const MESSAGES: u64 = 64 << 10;
/// javac's own time limit, at least: `--timeout` is a case's, and a busy machine can take
/// seconds to start a JVM; a source that keeps javac busy for a minute is a timeout all the same.
pub const COMPILE_SECONDS: u64 = 60;
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
    // Its own deadline, whatever --timeout says, and the CPU backstop that goes with it.
    let limits = Limits {
        seconds: limits.seconds.max(COMPILE_SECONDS),
        ..limits
    };
    let mut program = vec![
        javac.display().to_string(),
        format!("-J-Xmx{}m", (limits.memory_mib / 2).max(32)),
        // javac runs for about a second: the C2 compiler would cost more CPU than it saves.
        "-J-XX:TieredStopAtLevel=1".into(),
        "-J-XX:+UseSerialGC".into(),
        "-J-XX:-UsePerfData".into(),
    ];
    program.extend(javac_options(&work.join("classes")));
    program.extend(sources.iter().cloned());
    let (src, classes) = (work.join("src"), work.join("classes"));
    let (mut command, run) =
        sandbox.command(&program, &[&src], &classes, Area::Folder, slot, limits)?;
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
    let timeout = Duration::from_secs(limits.seconds);
    let status = loop {
        if whitted_core::interrupt::requested() || started.elapsed() > timeout {
            kill_group(&child);
            let _ = child.wait();
            whitted_core::interrupt::check()?;
            break None;
        }
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => {
                kill_group(&child);
                return Err(Error::Environment(format!("cannot wait for javac: {e}")));
            }
        }
    };
    let messages = reader.join().unwrap_or_default();
    Ok(match status {
        None => Compiled::Timeout,
        Some(s) if s.success() => Compiled::Ok,
        Some(_) if run.oom_killed() => Compiled::Errors(format!(
            "javac was killed at its memory limit (--memory {} MiB)",
            limits.memory_mib
        )),
        // Stopped at its CPU time limit (SIGXCPU): as out of time as a timeout.
        Some(s) if std::os::unix::process::ExitStatusExt::signal(&s) == Some(SIGXCPU) => {
            Compiled::Timeout
        }
        Some(s) if messages.is_empty() => {
            Compiled::Errors(format!("javac failed without a message ({s})"))
        }
        Some(_) => Compiled::Errors(first_lines(&messages, &src)),
    })
}

const SIGXCPU: i32 = 24;

/// What javac is told besides its sources: no annotation processors (they would run code
/// from the classpath), the course's encoding, the first 20 errors, where the classes go.
pub fn javac_options(classes: &Path) -> Vec<String> {
    let options = ["-proc:none", "-encoding", "UTF-8", "-Xmaxerrs", "20", "-d"];
    let mut all: Vec<String> = options.iter().map(|o| o.to_string()).collect();
    all.push(classes.display().to_string());
    all
}

/// javac's first `SHOWN_LINES` lines, paths relative to the sources' folder `src`.
pub fn first_lines(messages: &[u8], src: &Path) -> String {
    let text = String::from_utf8_lossy(messages);
    // javac's own crash on a source too deeply nested for its stack asks the reader to file a
    // bug against the compiler: the student's fix is in their code, so say that instead.
    if text.contains("java.lang.StackOverflowError") {
        return "javac ran out of stack on this source: an expression or a block nested too \
                deeply (a long chain of + or of nested calls); write it in steps"
            .to_string();
    }
    let prefix = format!("{}/", src.display());
    text.lines()
        .take(SHOWN_LINES)
        .map(|l| l.replace(&prefix, ""))
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn javac_s_own_stack_overflow_is_the_student_s_nesting_not_a_compiler_bug() {
        let crash = b"An exception has occurred in the compiler (17.0.15). Please file a bug \
            against the Java compiler via the Java bug reporting page\njava.lang.\
            StackOverflowError\n\tat jdk.compiler/com.sun.tools.javac.comp.Attr.visitBinary";
        let said = first_lines(crash, Path::new("/w/src"));
        assert!(said.contains("nested too deeply"), "{said}");
        assert!(!said.contains("file a bug"), "{said}");
        let error = b"/w/src/gfx/tick2/Renderer.java:3: error: ';' expected";
        assert_eq!(
            first_lines(error, Path::new("/w/src")),
            "gfx/tick2/Renderer.java:3: error: ';' expected"
        );
    }
}
