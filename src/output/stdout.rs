//! Writing to standard output without panicking. A reader that went away (`| head -1`, a
//! broken pipe) ends the writing quietly: the command keeps the status it would have had. A
//! closed (`>&-`) or full (`> /dev/full`) standard output is an error.

use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::{Error, Result};

/// Whether descriptor 1 was closed when the process started.
static CLOSED: AtomicBool = AtomicBool::new(false);

/// Finds out whether the process was started with descriptor 1 closed (`>&-`). Rust's
/// runtime reopens a closed standard descriptor on `/dev/null` before `main`, read-write,
/// where a shell's `> /dev/null` opens it write-only; Linux shows both in `/proc`.
pub fn probe() {
    #[cfg(target_os = "linux")]
    {
        let target = std::fs::read_link("/proc/self/fd/1");
        let info = std::fs::read_to_string("/proc/self/fdinfo/1").unwrap_or_default();
        let read_write = info
            .lines()
            .find_map(|l| l.strip_prefix("flags:"))
            .and_then(|f| u32::from_str_radix(f.trim(), 8).ok())
            .is_some_and(|flags| flags & 0o3 == 0o2);
        let closed = match target {
            Ok(path) => path == std::path::Path::new("/dev/null") && read_write,
            Err(_) => std::path::Path::new("/proc/self/fd").is_dir(),
        };
        CLOSED.store(closed, Ordering::Relaxed);
    }
}

/// Writes `bytes` to standard output and flushes it.
pub fn write_all(bytes: &[u8]) -> Result<()> {
    if CLOSED.load(Ordering::Relaxed) {
        return Err(fail(std::io::Error::other("it is closed")));
    }
    let mut out = std::io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        other => other.map_err(fail),
    }
}

/// Prints `text` and a newline.
pub fn print_line(text: &str) -> Result<()> {
    write_all(format!("{text}\n").as_bytes())
}

fn fail(e: std::io::Error) -> Error {
    Error::io("-", "cannot write to standard output", e)
}
