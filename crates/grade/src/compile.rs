//! `javac` over a student's two files and the skeleton, in the sandbox: the first errors it
//! prints are what the student's report shows for `compile-error`. A JVM of its own per
//! student: what the warm compiler (`warm_javac.rs`) falls back to, and what names the end of
//! a compilation that killed it. A source the warm compiler could not finish is compiled in
//! the background (`Priority::Background`: nice 19, its deadline in CPU seconds), so that the
//! minute it may keep javac busy is not taken from the students graded beside it.

use std::path::Path;
use std::process::Stdio;
use std::time::Duration;

use super::jvm;
use super::sandbox::{hit_cpu_limit, Area, Limits, Priority, Sandbox};
use whitted_core::error::{Error, Result};
use whitted_process::{Capture, Ended, Process};

/// Bytes of javac's messages kept (the first ones: the first error is the one to fix).
pub const MESSAGES: usize = 64 << 10;
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
/// `work/classes` (the only folder it may write), at `priority`.
pub fn compile(
    sandbox: &Sandbox,
    javac: &Path,
    work: &Path,
    sources: &[String],
    slot: usize,
    limits: Limits,
    priority: Priority,
) -> Result<Compiled> {
    // Its own deadline, whatever --timeout says: wall-clock seconds, or CPU seconds for one
    // that yields the CPU to every other run (`Priority::Background`), with a wall-clock
    // backstop.
    let limits = jvm::compiling(limits);
    let wall = match priority {
        Priority::Normal => limits.seconds,
        Priority::Background => limits.seconds.saturating_mul(WALL_PER_CPU_SECOND),
    };
    let mut program = vec![javac.display().to_string()];
    program.extend(jvm::javac_options(limits));
    program.extend(javac_options(&work.join("classes")));
    program.extend(sources.iter().cloned());
    let (src, classes) = (work.join("src"), work.join("classes"));
    let (mut command, run) = sandbox.command(
        &program,
        &[&src],
        &classes,
        Area::Folder,
        slot,
        limits,
        priority,
    )?;
    command.stdin(Stdio::null()).stdout(Stdio::null());
    let mut javac = Process::spawn(command, Capture::Head(MESSAGES))
        .map_err(|e| Error::Environment(format!("cannot run javac: {e}")))?;
    let ended = javac
        .wait(
            Duration::from_secs(wall),
            Duration::from_millis(20),
            whitted_core::interrupt::requested,
        )
        .map_err(|e| Error::Environment(format!("cannot wait for javac: {e}")))?;
    whitted_core::interrupt::check()?;
    let messages = javac.finish();
    Ok(match ended {
        Ended::TimedOut | Ended::Stopped => Compiled::Timeout,
        Ended::Exited(s) if s.success() => Compiled::Ok,
        Ended::Exited(_) if run.oom_killed() => Compiled::Errors(format!(
            "javac was killed at its memory limit (--memory {} MiB)",
            limits.memory_mib
        )),
        // Stopped at its CPU time limit (SIGXCPU): its deadline.
        Ended::Exited(s) if hit_cpu_limit(s) => Compiled::Timeout,
        Ended::Exited(s) if messages.is_empty() => {
            Compiled::Errors(format!("javac failed without a message ({s})"))
        }
        Ended::Exited(_) => Compiled::Errors(first_lines(&messages, &src)),
    })
}

/// The wall-clock backstop of a compilation, in seconds per CPU second of its deadline: a
/// javac that yields the CPU gets little of it on a machine busy with other students' programs
/// (nice 19 against two busy JVMs on its core: ~1%), and a Tick 2's ~1.1 s of CPU must still
/// fit (the deadline is 60 CPU seconds, so 300 s of wall time).
const WALL_PER_CPU_SECOND: u64 = 5;

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
