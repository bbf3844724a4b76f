//! Outputs appear whole or not at all: each is written to a temporary file beside its target
//! and renamed over it only when complete, so a failed or interrupted run never leaves a partial
//! file and never clobbers a previous good one.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

use crate::error::{Error, Result};

/// An output file being written. Dropping it without `commit` deletes the temporary file and
/// leaves the target untouched.
pub struct AtomicFile {
    temp: NamedTempFile,
    target: PathBuf,
}

impl AtomicFile {
    /// Creates the temporary file now, so an unwritable destination fails before any work is
    /// done rather than after a long render.
    pub fn create(target: &Path) -> Result<Self> {
        if target.is_dir() {
            return Err(Error::io(
                target,
                "cannot write output",
                std::io::Error::other("it is a directory"),
            ));
        }
        let dir = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let mut builder = tempfile::Builder::new();
        builder.prefix(".whitted-").suffix(".part");
        // Like any newly created file (rw-r--r--), not the private 0600 of a temporary file.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o644));
        }
        let temp = builder
            .tempfile_in(dir)
            .map_err(|e| Error::io(target, "cannot write output", e))?;
        Ok(AtomicFile {
            temp,
            target: target.to_path_buf(),
        })
    }

    /// The target path this file will be renamed to.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Writes the whole content with `write` into the temporary file, then renames it over the
    /// target.
    pub fn write_with(
        mut self,
        write: impl FnOnce(&mut BufWriter<&mut File>) -> Result<()>,
    ) -> Result<()> {
        let target = self.target.clone();
        let fail = |e| Error::io(&target, "cannot write output", e);
        {
            let mut out = BufWriter::new(self.temp.as_file_mut());
            write(&mut out)?;
            out.flush().map_err(fail)?;
        }
        self.temp.as_file().sync_all().map_err(fail)?;
        self.temp
            .persist(&self.target)
            .map_err(|e| Error::io(&target, "cannot write output", e.error))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commit_replaces_and_drop_leaves_the_target_alone() {
        let dir = tempfile::tempdir().expect("tempdir");
        let target = dir.path().join("out.bin");
        std::fs::write(&target, b"old").expect("write");

        let abandoned = AtomicFile::create(&target).expect("create");
        drop(abandoned);
        assert_eq!(std::fs::read(&target).expect("read"), b"old");

        let failed = AtomicFile::create(&target).expect("create");
        let result = failed.write_with(|w| {
            w.write_all(b"partial").expect("write");
            Err(crate::error::Error::Usage("boom".into()))
        });
        assert!(result.is_err());
        assert_eq!(std::fs::read(&target).expect("read"), b"old");

        AtomicFile::create(&target)
            .expect("create")
            .write_with(|w| w.write_all(b"new").map_err(|e| Error::io("x", "w", e)))
            .expect("commit");
        assert_eq!(std::fs::read(&target).expect("read"), b"new");
        let leftovers: Vec<_> = std::fs::read_dir(dir.path()).expect("ls").collect();
        assert_eq!(leftovers.len(), 1, "temporary files left behind");
    }

    #[test]
    fn missing_directory_and_directory_target_fail_early() {
        let dir = tempfile::tempdir().expect("tempdir");
        assert!(AtomicFile::create(&dir.path().join("no/such/dir/out.png")).is_err());
        let err = AtomicFile::create(dir.path())
            .err()
            .expect("a directory is refused");
        assert!(err.to_string().contains("it is a directory"), "{err}");
    }
}
