//! Where an output goes: a file (written atomically) or standard output (`-`).

use std::fs::File;
use std::io::{BufWriter, IsTerminal, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::output::atomic::AtomicFile;
use crate::output::png::{write_png, PngEncoding, PngImage, PngStream};
use crate::output::stdout;
use whitted_core::error::{Error, Result};

/// What `-o -` means.
pub const STDOUT: &str = "-";

/// Whether two paths name the same file, so that one output cannot overwrite another or an
/// input: the same device and inode when both exist (whatever links or `..` lead there),
/// else the same path once the parent directory is resolved (`a.png`, `./a.png` and
/// `dir/../a.png` all are).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    if let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) {
        use std::os::unix::fs::MetadataExt;
        return (x.dev(), x.ino()) == (y.dev(), y.ino());
    }
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

/// Refuses outputs that are one of the inputs or each other: `whitted tonemap a.exr -o a.exr`
/// must not replace its own input. Standard output (`-`) is never a clash.
pub fn refuse_clashes(inputs: &[&Path], outputs: &[&Path]) -> Result<()> {
    let outputs: Vec<&Path> = outputs
        .iter()
        .copied()
        .filter(|p| p.as_os_str() != STDOUT)
        .collect();
    for (i, output) in outputs.iter().enumerate() {
        if let Some(input) = inputs.iter().find(|input| same_file(output, input)) {
            return Err(Error::Usage(format!(
                "the output `{}` is the input `{}`; give another path",
                output.display(),
                input.display()
            )));
        }
        if let Some(other) = outputs[..i].iter().find(|o| same_file(output, o)) {
            return Err(Error::Usage(format!(
                "the outputs `{}` and `{}` are the same file; give different paths",
                other.display(),
                output.display()
            )));
        }
    }
    Ok(())
}

/// An output being prepared. Nothing becomes visible until `commit`: a file stays a hidden
/// temporary file, and bytes for standard output are held back, so a run that fails half-way
/// shows nothing of its work.
pub enum Destination {
    /// An anonymous temporary file, copied to standard output on commit.
    Stdout(File),
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
            let file = tempfile::tempfile().map_err(|e| {
                Error::io("-", "cannot create a temporary file for standard output", e)
            })?;
            Ok(Destination::Stdout(file))
        } else {
            Ok(Destination::File(AtomicFile::create(path)?))
        }
    }

    pub fn path(&self) -> PathBuf {
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
        let mut out = BufWriter::new(self.file());
        write_png(&mut out, image).map_err(|e| fail(e.to_string()))?;
        out.flush().map_err(|e| fail(e.to_string()))
    }

    /// Writes `bytes` (a page, a document) into this destination as they are.
    pub fn write_bytes(&mut self, bytes: &[u8]) -> Result<()> {
        let path = self.path();
        self.file()
            .write_all(bytes)
            .and_then(|()| self.file().flush())
            .map_err(|e| Error::io(&path, "cannot write", e))
    }

    /// A PNG written into this destination as its rows arrive.
    pub fn stream_png(
        &mut self,
        width: u32,
        height: u32,
        encoding: PngEncoding,
    ) -> Result<PngStream> {
        let path = self.path();
        let file = self
            .file()
            .try_clone()
            .map_err(|e| Error::io(&path, "cannot write", e))?;
        PngStream::new(file, width, height, encoding).map_err(|e| Error::Png {
            path,
            msg: e.to_string(),
        })
    }

    fn file(&mut self) -> &mut File {
        match self {
            Destination::Stdout(file) => file,
            Destination::File(file) => file.file(),
        }
    }

    /// Makes the output visible: renames the file into place, or copies the temporary file
    /// to standard output.
    pub fn commit(self) -> Result<()> {
        match self {
            Destination::File(file) => file.commit(),
            Destination::Stdout(mut file) => {
                whitted_core::interrupt::check()?;
                let mut bytes = Vec::new();
                file.seek(SeekFrom::Start(0))
                    .and_then(|_| file.read_to_end(&mut bytes))
                    .map_err(|e| {
                        Error::io("-", "cannot read back the output for standard output", e)
                    })?;
                stdout::write_all(&bytes)
            }
        }
    }
}
