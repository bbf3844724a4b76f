//! Where an output goes: a file (written atomically) or standard output (`-`).

use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::output::atomic::AtomicFile;
use crate::output::png::{write_png, PngImage};

/// What `-o -` means.
pub const STDOUT: &str = "-";

/// Whether two paths name the same file once resolved (`a.png`, `./a.png` and `dir/../a.png`
/// all do), so that one output cannot overwrite another or the input. The parent directory
/// is resolved through symlinks when it exists.
pub fn same_file(a: &Path, b: &Path) -> bool {
    fn resolved(p: &Path) -> Option<PathBuf> {
        let parent = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        Some(parent.canonicalize().ok()?.join(p.file_name()?))
    }
    match (resolved(a), resolved(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
}

/// An output being prepared. Nothing becomes visible until `commit`: a file stays a hidden
/// temporary file, and bytes for standard output are held back, so a run that fails half-way
/// shows nothing of its work.
pub enum Destination {
    Stdout(Vec<u8>),
    File(AtomicFile),
}

impl Destination {
    /// Opens `path` (`-` for standard output); a file path that cannot be written fails now.
    /// Binary output is not sent to a terminal, where it would only garble the screen.
    pub fn open(path: &Path) -> Result<Self> {
        if path.as_os_str() == STDOUT {
            if std::io::stdout().is_terminal() {
                return Err(Error::Usage(
                    "standard output is a terminal; redirect it (`> out.png`) or give a file name"
                        .into(),
                ));
            }
            Ok(Destination::Stdout(Vec::new()))
        } else {
            Ok(Destination::File(AtomicFile::create(path)?))
        }
    }

    fn path(&self) -> PathBuf {
        match self {
            Destination::Stdout(_) => PathBuf::from(STDOUT),
            Destination::File(f) => f.target().to_path_buf(),
        }
    }

    /// Encodes `image` as a PNG into this destination.
    pub fn write_png(&mut self, image: &PngImage) -> Result<()> {
        let path = self.path();
        let fail = |msg: String| Error::Png {
            path: path.clone(),
            msg,
        };
        match self {
            Destination::Stdout(bytes) => {
                write_png(&mut *bytes, image).map_err(|e| fail(e.to_string()))
            }
            Destination::File(file) => {
                let mut out = BufWriter::new(file.file());
                write_png(&mut out, image).map_err(|e| fail(e.to_string()))?;
                out.flush().map_err(|e| fail(e.to_string()))
            }
        }
    }

    /// Makes the output visible: renames the file into place, or writes the bytes to stdout.
    pub fn commit(self) -> Result<()> {
        match self {
            Destination::File(file) => file.commit(),
            Destination::Stdout(bytes) => {
                let mut out = std::io::stdout().lock();
                out.write_all(&bytes)
                    .and_then(|()| out.flush())
                    .map_err(|e| Error::io(STDOUT, "cannot write to standard output", e))
            }
        }
    }
}
