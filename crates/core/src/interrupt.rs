//! Stopping on a signal (SIGINT, SIGTERM, SIGHUP, SIGQUIT) without losing anything: the first
//! signal asks the work to stop (the render checks at every pixel), so the run unwinds
//! normally, its temporary files are deleted, no output is touched, and the process exits with
//! 128 + the signal's number. If the work has not unwound within `GRACE` (a long EXR write
//! cannot be cut short), or on a second signal, the signal thread removes every registered
//! temporary file itself and exits at once.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicI32, Ordering};
use std::sync::Mutex;
use std::time::Duration;

use signal_hook::consts::{SIGHUP, SIGINT, SIGQUIT, SIGTERM};
use signal_hook::iterator::Signals;

/// The signal that asked to stop, or 0.
static SIGNAL: AtomicI32 = AtomicI32::new(0);

/// Named temporary files not yet renamed into place. Publishing an output holds this lock, so
/// a forced exit never races a rename.
static TEMPORARY_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// How long the work has to unwind by itself after the first signal.
const GRACE: Duration = Duration::from_millis(300);

/// Installs the handlers. Failing to install them is not fatal: a signal then just ends the
/// process, as it would anyway.
pub fn install() {
    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM, SIGHUP, SIGQUIT]) else {
        return;
    };
    std::thread::spawn(move || {
        for signal in signals.forever() {
            if SIGNAL.swap(signal, Ordering::SeqCst) != 0 {
                exit_now(signal);
            }
            std::thread::spawn(move || {
                std::thread::sleep(GRACE);
                exit_now(signal);
            });
        }
    });
}

/// Removes every registered temporary file and exits with 128 + `signal`.
fn exit_now(signal: i32) -> ! {
    let files = TEMPORARY_FILES
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    for path in files.iter() {
        let _ = std::fs::remove_file(path);
    }
    crate::progress::clear_line();
    std::process::exit(128 + signal)
}

/// Whether a signal asked to stop.
pub fn requested() -> bool {
    SIGNAL.load(Ordering::Relaxed) != 0
}

/// `Err(Interrupted)` once a signal asked to stop.
pub fn check() -> crate::Result<()> {
    match SIGNAL.load(Ordering::SeqCst) {
        0 => Ok(()),
        signal => Err(crate::Error::Interrupted { signal }),
    }
}

/// Records a temporary file to delete if the process is ended by a signal.
pub fn register_temp(path: &Path) {
    lock().push(path.to_path_buf());
}

/// Forgets a temporary file (renamed into place, or deleted).
pub fn unregister_temp(path: &Path) {
    lock().retain(|p| p != path);
}

/// Runs `publish` (a rename into place) unless a signal asked to stop; no forced exit can
/// happen while it runs.
pub fn while_not_stopping<T>(publish: impl FnOnce() -> T) -> crate::Result<T> {
    let _guard = lock();
    check()?;
    Ok(publish())
}

fn lock() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    TEMPORARY_FILES
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}
