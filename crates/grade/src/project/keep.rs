//! A build's classes kept beside the suite's scenes (`check DIR --suite-dir S` writes them to
//! `S/classes`): the rerun commands then name classes that exist and are the ones checked.
//! Written to a sibling first and renamed into place, so an interrupted copy never leaves a
//! half set of classes under the name.

use std::path::{Path, PathBuf};

use whitted_core::error::{Error, Result};

/// `from`'s tree copied to `to`, replacing `to`; returns `to`.
pub fn classes(from: &Path, to: &Path) -> Result<PathBuf> {
    let staging = to.with_extension("partial");
    let _ = std::fs::remove_dir_all(&staging);
    copy_tree(from, &staging)?;
    if to.exists() {
        std::fs::remove_dir_all(to).map_err(|e| Error::io(to, "cannot replace", e))?;
    }
    std::fs::rename(&staging, to).map_err(|e| Error::io(to, "cannot write", e))?;
    Ok(to.to_path_buf())
}

/// A recursive copy of files and folders (a build holds nothing else; anything else is skipped).
fn copy_tree(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).map_err(|e| Error::io(to, "cannot create", e))?;
    let entries = std::fs::read_dir(from).map_err(|e| Error::io(from, "cannot read", e))?;
    for entry in entries {
        let entry = entry.map_err(|e| Error::io(from, "cannot read", e))?;
        let kind = entry
            .file_type()
            .map_err(|e| Error::io(entry.path(), "cannot read", e))?;
        let target = to.join(entry.file_name());
        if kind.is_dir() {
            copy_tree(&entry.path(), &target)?;
        } else if kind.is_file() {
            std::fs::copy(entry.path(), &target)
                .map_err(|e| Error::io(&target, "cannot write", e))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tree_is_copied_whole_and_replaces_the_last_one() {
        let d = tempfile::tempdir().expect("tempdir");
        let from = d.path().join("build");
        std::fs::create_dir_all(from.join("a/b")).expect("mkdir");
        std::fs::write(from.join("a/b/Tick1.class"), b"new").expect("write");
        let to = d.path().join("suite/classes");
        std::fs::create_dir_all(to.join("old")).expect("mkdir");
        std::fs::write(to.join("old/Stale.class"), b"old").expect("write");
        assert_eq!(classes(&from, &to).expect("copied"), to);
        assert_eq!(
            std::fs::read(to.join("a/b/Tick1.class")).expect("read"),
            b"new"
        );
        assert!(!to.join("old").exists());
        assert!(!d.path().join("suite/classes.partial").exists());
    }
}
