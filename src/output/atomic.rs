//! Outputs appear whole or not at all: each is written to a temporary file beside its target
//! and renamed over it only when complete, so a failed or interrupted run never leaves a partial
//! file and never clobbers a previous good one.

use std::fs::File;
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

    /// The temporary file to write the content into.
    pub fn file(&mut self) -> &mut File {
        self.temp.as_file_mut()
    }

    /// Makes the written content durable and renames it over the target.
    pub fn commit(self) -> Result<()> {
        let target = self.target.clone();
        self.temp
            .as_file()
            .sync_all()
            .map_err(|e| Error::io(&target, "cannot write output", e))?;
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
        use std::io::Write;
        let dir = tempfile::tempdir().expect("tempdir");
        let target = dir.path().join("out.bin");
        std::fs::write(&target, b"old").expect("write");

        let mut abandoned = AtomicFile::create(&target).expect("create");
        abandoned.file().write_all(b"partial").expect("write");
        drop(abandoned);
        assert_eq!(std::fs::read(&target).expect("read"), b"old");

        let mut file = AtomicFile::create(&target).expect("create");
        file.file().write_all(b"new").expect("write");
        file.commit().expect("commit");
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
