//! Every JVM grade starts (the student's program, javac, the warm javac) gets its options from
//! the limits here, in one place.

use super::sandbox::Limits;

/// javac's own time limit, at least: `--timeout` is a case's, and a busy machine can take
/// seconds to start a JVM; a source that keeps javac busy for a minute is a timeout all the same.
pub const COMPILE_SECONDS: u64 = 60;

/// The JVM's options under `limits`:
/// - the heap gets half the memory (at least 32 MiB), the rest is the JVM's own;
/// - C1 alone (`TieredStopAtLevel=1`): a case runs for under a second and javac for about one,
///   so C2's compiler threads would cost more CPU than they save (4 cases of tick2: 2.5 s of CPU
///   instead of 4.3, the same wall time alone; over 48 compilations C1 alone costs half the CPU
///   of both compilers). Java's arithmetic is the same at every tier (strict since Java 17; the
///   interpreter and both compilers share Math.pow's stub): the bytes do not change;
/// - the serial collector and no perf data file: one thread, nothing written to /tmp.
pub fn options(limits: Limits) -> Vec<String> {
    vec![
        format!("-Xmx{}m", (limits.memory_mib / 2).max(32)),
        "-XX:TieredStopAtLevel=1".into(),
        "-XX:+UseSerialGC".into(),
        "-XX:-UsePerfData".into(),
    ]
}

/// [`options`] as javac takes them: each through `-J`.
pub fn javac_options(limits: Limits) -> Vec<String> {
    options(limits)
        .into_iter()
        .map(|o| format!("-J{o}"))
        .collect()
}

/// The limits a compilation runs under: the case's, with at least [`COMPILE_SECONDS`] (and the
/// CPU backstop that goes with it).
pub fn compiling(limits: Limits) -> Limits {
    Limits {
        seconds: limits.seconds.max(COMPILE_SECONDS),
        ..limits
    }
}
