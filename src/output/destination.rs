//! Where an output goes: a file (written atomically) or standard output (`-`).

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::output::atomic::AtomicFile;
use crate::output::png::{write_png, PngImage};

/// What `-o -` means.
pub const STDOUT: &str = "-";

/// An output being prepared. Nothing becomes visible until `commit`: a file stays a hidden
/// temporary file, and bytes for standard output are held back, so a run that fails half-way
/// shows nothing of its work.
pub enum Destination {
    Stdout(Vec<u8>),
    File(AtomicFile),
}

impl Destination {
    /// Opens `path` (`-` for standard output); a file path that cannot be written fails now.
    pub fn open(path: &Path) -> Result<Self> {
        if path.as_os_str() == STDOUT {
            Ok(Destination::Stdout(Vec::new()))
        } else {
            Ok(Destination::File(AtomicFile::create(path)?))
        }
    }

    /// The name used in messages.
    pub fn name(&self) -> String {
        match self {
            Destination::Stdout(_) => "standard output".into(),
            Destination::File(f) => f.target().display().to_string(),
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
