//! Outputs appear whole or not at all: each is written to a temporary file beside its target
//! and renamed over it only when complete, so a failed or interrupted run never leaves a partial
//! file and never clobbers a previous good one.
//!
//! Targets that are not regular files keep what they are: a symlink keeps its link (the file it
//! points to is replaced), a character device or FIFO (`/dev/null`, a named pipe) is written
//! straight through at commit from an unnamed temporary file, and anything else (a directory, a
//! block device, a socket) is refused. Named temporary files are registered with `interrupt`,
//! which removes them if a signal ends the process before they are renamed or dropped (a
//! dropped file removes itself; its stale registration then names nothing).

use std::fs::{File, OpenOptions};
use std::io::{Seek, SeekFrom};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

use whitted_core::error::{Error, Result};
use whitted_core::interrupt;

/// An output file being written. Dropping it without `commit` deletes the temporary file and
/// leaves the target untouched.
pub struct AtomicFile {
    temp: Temp,
    /// The path as the user gave it, for messages.
    target: PathBuf,
}

enum Temp {
    /// Beside the file it will replace (the symlink's target, if the path is a link).
    Named {
        file: NamedTempFile,
        replaces: PathBuf,
    },
    /// For a device or FIFO: copied into it at commit.
    Unnamed { file: File, device: PathBuf },
}

/// What a path is, after following symlinks.
enum Kind {
    /// A regular file, or nothing yet: written by rename. The path has its links resolved.
    Replaceable(PathBuf),
    /// A character device or FIFO: written through.
    Device(PathBuf),
}

/// Follows `target` through symlinks (even dangling ones, whose file is then created) and says
/// how it can be written.
fn classify(target: &Path) -> Result<Kind> {
    let refuse = |what: &str| {
        Error::io(
            target,
            "cannot write output",
            std::io::Error::other(format!(
                "it is {what}; outputs are regular files, character devices or FIFOs"
            )),
        )
    };
    // What is there, as the kernel resolves it (also through /proc's magic links, such as
    // /dev/stdout, whose link text is not a path).
    let Ok(meta) = std::fs::metadata(target) else {
        return Ok(Kind::Replaceable(dangling_target(target)?));
    };
    let kind = meta.file_type();
    if kind.is_file() {
        let real = std::fs::canonicalize(target)
            .map_err(|e| Error::io(target, "cannot write output", e))?;
        return Ok(Kind::Replaceable(real));
    }
    if kind.is_dir() {
        return Err(refuse("a directory"));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() || kind.is_fifo() {
            return Ok(Kind::Device(target.to_path_buf()));
        }
        if kind.is_block_device() {
            return Err(refuse("a block device"));
        }
        if kind.is_socket() {
            return Err(refuse("a socket"));
        }
    }
    Err(refuse("not a regular file"))
}

/// Where a path that names nothing yet will be created: itself, or the end of the chain of
/// (dangling) symlinks it starts.
fn dangling_target(target: &Path) -> Result<PathBuf> {
    let mut path = target.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&path) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = std::fs::read_link(&path)
                    .map_err(|e| Error::io(target, "cannot write output", e))?;
                path = match path.parent() {
                    Some(dir) => dir.join(link),
                    None => link,
                };
            }
            _ => return Ok(path),
        }
    }
    Err(Error::io(
        target,
        "cannot write output",
        std::io::Error::other("it is a loop of symbolic links"),
    ))
}

impl AtomicFile {
    /// Creates the temporary file now, so an unwritable destination fails before any work is
    /// done rather than after a long render.
    pub fn create(target: &Path) -> Result<Self> {
        let cannot = |e| Error::io(target, "cannot write output", e);
        let temp = match classify(target)? {
            Kind::Replaceable(replaces) => {
                let dir = match replaces.parent() {
                    Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
                    _ => PathBuf::from("."),
                };
                let mut builder = tempfile::Builder::new();
                builder.prefix(".whitted-").suffix(".part");
                // Like any newly created file (rw-r--r--), not the private 0600 of a temporary
                // file.
                #[cfg(unix)]
                {
                    use std::os::unix::fs::PermissionsExt;
                    builder.permissions(std::fs::Permissions::from_mode(0o644));
                }
                let file = builder.tempfile_in(dir).map_err(cannot)?;
                interrupt::register_temp(file.path());
                Temp::Named { file, replaces }
            }
            Kind::Device(device) => {
                // Checked now, so that an unwritable device fails before the work (a FIFO is
                // not opened yet: that would wait for a reader).
                if !is_fifo(&device) {
                    OpenOptions::new()
                        .write(true)
                        .open(&device)
                        .map_err(cannot)?;
                }
                Temp::Unnamed {
                    file: tempfile::tempfile().map_err(cannot)?,
                    device,
                }
            }
        };
        Ok(AtomicFile {
            temp,
            target: target.to_path_buf(),
        })
    }

    /// The target path as given.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// The temporary file to write the content into.
    pub fn file(&mut self) -> &mut File {
        match &mut self.temp {
            Temp::Named { file, .. } => file.as_file_mut(),
            Temp::Unnamed { file, .. } => file,
        }
    }

    /// Makes the written content durable and puts it in place: renamed over the file, or
    /// copied into the device. Refused (and the temporary file removed) once a signal asked
    /// the run to stop, so an interrupted run never publishes.
    pub fn commit(self) -> Result<()> {
        let target = self.target;
        let cannot = |e| Error::io(&target, "cannot write output", e);
        match self.temp {
            Temp::Named { file, replaces } => {
                file.as_file().sync_all().map_err(cannot)?;
                let temp_path = file.path().to_path_buf();
                let published =
                    interrupt::while_not_stopping(|| file.persist(&replaces).map_err(|e| e.error));
                interrupt::unregister_temp(&temp_path);
                published?.map_err(cannot)?;
                Ok(())
            }
            Temp::Unnamed { mut file, device } => {
                interrupt::check()?;
                file.seek(SeekFrom::Start(0)).map_err(cannot)?;
                let mut out = OpenOptions::new()
                    .write(true)
                    .open(&device)
                    .map_err(cannot)?;
                std::io::copy(&mut file, &mut out).map_err(cannot)?;
                Ok(())
            }
        }
    }
}

fn is_fifo(path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        std::fs::metadata(path).is_ok_and(|m| m.file_type().is_fifo())
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        false
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
