//! The data folder (`./whitted-serve/`, or `--data DIR`): the database and the uploads, private
//! to the user that serves (0700: the students' work and the links' secrets are in it).
//!
//! An upload is received into `incoming/`, a folder of its own, and moved into `uploads/`
//! under a name whitted chooses (never one the upload gives) only once every byte is on disk:
//! a half-received upload leaves nothing but a folder in `incoming/`, which the next start
//! empties. Only then is its attempt recorded; a folder in `uploads/` that no attempt names
//! (the service was killed between the move and the record) is removed at the next start too.

use std::collections::HashSet;
use std::fs;
use std::io::Write;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

use whitted_core::error::{Error, Result};

pub const DATABASE: &str = "whitted-serve.sqlite";
const UPLOADS: &str = "uploads";
const INCOMING: &str = "incoming";

/// The data folder, made and made private.
#[derive(Debug, Clone)]
pub struct Data {
    pub dir: PathBuf,
}

impl Data {
    pub fn open(dir: &Path) -> Result<Data> {
        fs::create_dir_all(dir).map_err(|e| Error::io(dir, "cannot create", e))?;
        // Absolute: a project's run (a process of its own, or a Slurm job on a node) is
        // given its folder by this path.
        let dir = &std::path::absolute(dir).map_err(|e| Error::io(dir, "cannot resolve", e))?;
        fs::set_permissions(dir, fs::Permissions::from_mode(0o700))
            .map_err(|e| Error::io(dir, "cannot make private", e))?;
        for sub in [UPLOADS, INCOMING] {
            let path = dir.join(sub);
            fs::create_dir_all(&path).map_err(|e| Error::io(&path, "cannot create", e))?;
        }
        Ok(Data {
            dir: dir.to_path_buf(),
        })
    }

    /// Opens an existing data folder (for `links` and `backup`), refusing one that is not.
    pub fn existing(dir: &Path) -> Result<Data> {
        if !dir.join(DATABASE).is_file() {
            return Err(Error::Usage(format!(
                "{}: not a data folder of `whitted serve` (no {DATABASE} in it)",
                dir.display()
            )));
        }
        Ok(Data {
            dir: dir.to_path_buf(),
        })
    }

    pub fn database(&self) -> PathBuf {
        self.dir.join(DATABASE)
    }

    /// The folder of an attempt's files.
    pub fn upload(&self, folder: &str) -> PathBuf {
        self.dir.join(UPLOADS).join(folder)
    }

    /// A new folder to receive an upload into.
    pub fn receive(&self) -> Result<Receiving> {
        let incoming = self.dir.join(INCOMING);
        let dir = tempfile::Builder::new()
            .prefix("upload-")
            .tempdir_in(&incoming)
            .map_err(|e| Error::io(&incoming, "cannot create a folder in", e))?;
        Ok(Receiving {
            dir,
            uploads: self.dir.join(UPLOADS),
        })
    }

    /// At a start: empties `incoming/` and removes the folders of `uploads/` that no attempt
    /// names (`known`). Returns how many it removed.
    pub fn sweep(&self, known: &HashSet<String>) -> Result<usize> {
        let mut removed = 0;
        for (sub, keep) in [(INCOMING, false), (UPLOADS, true)] {
            let path = self.dir.join(sub);
            let entries = fs::read_dir(&path).map_err(|e| Error::io(&path, "cannot read", e))?;
            for entry in entries.flatten() {
                let name = entry.file_name().to_string_lossy().into_owned();
                if keep && known.contains(&name) {
                    continue;
                }
                let _ = fs::remove_dir_all(entry.path()).or_else(|_| fs::remove_file(entry.path()));
                removed += 1;
            }
        }
        Ok(removed)
    }
}

/// An upload being received.
pub struct Receiving {
    dir: tempfile::TempDir,
    uploads: PathBuf,
}

impl Receiving {
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Writes `bytes` as `name` (a name whitted chose) and syncs it.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<()> {
        let path = self.dir.path().join(name);
        let mut file = fs::File::create(&path).map_err(|e| Error::io(&path, "cannot create", e))?;
        file.write_all(bytes)
            .and_then(|()| file.sync_all())
            .map_err(|e| Error::io(&path, "cannot write", e))
    }

    /// Moves the received folder into `uploads/` under a new random name, synced; returns
    /// the name. Dropped without this, the folder is removed.
    pub fn keep(self) -> Result<String> {
        let name = format!("a-{}", super::secret::new());
        let to = self.uploads.join(&name);
        let from = self.dir.keep();
        fs::rename(&from, &to).map_err(|e| Error::io(&to, "cannot move an upload to", e))?;
        if let Ok(dir) = fs::File::open(&self.uploads) {
            let _ = dir.sync_all();
        }
        Ok(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_folder_is_private_and_a_start_removes_what_no_attempt_names() {
        let root = tempfile::tempdir().expect("dir");
        let dir = root.path().join("data");
        let data = Data::open(&dir).expect("open");
        let mode = fs::metadata(&dir).expect("meta").permissions().mode() & 0o777;
        assert_eq!(mode, 0o700);
        let kept = data.receive().expect("r");
        kept.write("image-1.png", b"png").expect("w");
        let name = kept.keep().expect("keep");
        assert!(data.upload(&name).join("image-1.png").is_file());
        let orphan = data.receive().expect("r");
        let orphan_name = orphan.keep().expect("keep");
        let half = data.receive().expect("r");
        half.write("image-1.png", b"half").expect("w");
        std::mem::forget(half); // the process dies while receiving
        let known = HashSet::from([name.clone()]);
        assert_eq!(data.sweep(&known).expect("sweep"), 2);
        assert!(data.upload(&name).is_dir());
        assert!(!data.upload(&orphan_name).exists());
        assert_eq!(fs::read_dir(dir.join(INCOMING)).expect("read").count(), 0);
    }
}
