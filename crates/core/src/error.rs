//! One error type for everything a user can get wrong, so `main` has exactly one place that
//! turns failures into a message and an exit status.

use std::path::PathBuf;

/// Everything that can stop a run, by cause. Every variant is the user's input or environment,
/// never a bug: bugs panic with a message, everything else comes back as one of these and
/// exits with status 2 (130 for an interruption).
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scene file that does not say what the scene format allows. `line` and `col` are 1-based;
    /// `col` counts characters, not bytes, so editors jump to the right place.
    #[error("{file}:{line}:{col}: {msg}")]
    Scene {
        file: String,
        line: usize,
        col: usize,
        msg: String,
    },
    /// A file that cannot be read or written.
    #[error("{}: {what}: {source}", path.display())]
    Io {
        path: PathBuf,
        what: &'static str,
        source: std::io::Error,
    },
    /// An OpenEXR file that cannot be read or written.
    #[error("{}: {msg}", path.display())]
    Exr { path: PathBuf, msg: String },
    /// A PNG file that cannot be encoded.
    #[error("{}: {msg}", path.display())]
    Png { path: PathBuf, msg: String },
    /// A PNG, JPEG, TIFF or Radiance HDR file that cannot be decoded.
    #[error("{}: {msg}", path.display())]
    Raster { path: PathBuf, msg: String },
    /// A command line that asks for something impossible: the user's mistake only.
    #[error("{0}")]
    Usage(String),
    /// The machine refused what a valid request needs: a port to listen on, worker threads.
    #[error("{0}")]
    Environment(String),
    /// Memory that was needed and could not be had, with the numbers.
    #[error("cannot allocate {} for {what}", crate::numbers::gib(*bytes))]
    Allocation { what: String, bytes: u64 },
    /// A signal (Ctrl-C, SIGTERM, SIGHUP, SIGQUIT) stopped the run; nothing was written.
    #[error("interrupted by signal {signal}; no output was written")]
    Interrupted { signal: i32 },
}

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// The process exit status for this error: 128 + the signal for an interruption (130 for
    /// Ctrl-C, as shells report it), 2 for everything else.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Interrupted { signal } => u8::try_from(128 + signal).unwrap_or(130),
            _ => 2,
        }
    }

    /// Shorthand for an I/O failure on `path` while doing `what` ("cannot read", ...).
    pub fn io(path: impl Into<PathBuf>, what: &'static str, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            what,
            source,
        }
    }
}
