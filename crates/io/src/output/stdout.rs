//! Writing to standard output without panicking. A reader that went away (`| head -1`, a
//! broken pipe) ends the writing quietly: the command keeps the status it would have had. A
//! closed (`>&-`) or full (`> /dev/full`) standard output is an error.

use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

use whitted_core::error::{Error, Result};

/// Whether descriptor 1 was closed when the process started.
static CLOSED: AtomicBool = AtomicBool::new(false);

/// Finds out whether the process was started with descriptor 1 closed (`>&-`). It must run
/// before Rust's runtime, which reopens a closed standard descriptor on `/dev/null` read-write,
/// exactly as Python's `subprocess.DEVNULL` opens it: afterwards the two cannot be told apart.
/// The binary calls it from an `.init_array` constructor (src/main.rs).
pub fn probe() {
    #[cfg(target_os = "linux")]
    {
        let closed = std::fs::read_link("/proc/self/fd/1").is_err()
            && std::path::Path::new("/proc/self/fd").is_dir();
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
