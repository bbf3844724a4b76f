//! The folder a class is graded in (`whitted-grade-*`): the students' sources and classes
//! (`students/`), the warm compilers' folders (`javac/`) and every case's folder (`cases/`),
//! removed when the run ends.
//!
//! Run as root, each sandbox runs as a user of its own (`sandbox.rs`), and bubblewrap opens
//! the folders it binds as that user: the work folder and every folder above it must let other
//! users pass (the execute bit for others), and what a sandbox reads must be readable by them,
//! whatever the grader's umask. `TMPDIR` is used when they can pass it; a private one (under a
//! 0700 folder, as root's home is, or a batch job's own) is passed over for the system's shared
//! temporary folders, which every user can pass. Where every sandbox runs as the grader itself
//! (not root, or `--no-sandbox`), `TMPDIR` is used as it is.

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

use whitted_core::error::{Error, Result};

/// Where a private `TMPDIR` is replaced from, in order: the shared temporary folders that
/// every user may pass on a Linux system (`/tmp` is usually a tmpfs, `/var/tmp` a disk).
const SHARED: [&str; 3] = ["/tmp", "/var/tmp", "/dev/shm"];

/// The work folder and the folders in it: others may pass, not list (the students' ids).
const PASSABLE: u32 = 0o711;
/// What a sandbox reads (sources, classes, scenes): others may read.
const READABLE_DIR: u32 = 0o755;
const READABLE_FILE: u32 = 0o644;

/// The folders of a work area, made with it.
pub const STUDENTS: &str = "students";
pub const COMPILERS: &str = "javac";
pub const CASES: &str = "cases";

/// A class's work folder, removed when dropped.
pub struct WorkArea {
    dir: tempfile::TempDir,
}

impl WorkArea {
    /// A new work folder, in `TMPDIR` or, when `others` (sandboxes run as other users) and
    /// they cannot pass it, in the first shared temporary folder they can.
    pub fn create(others: bool) -> Result<WorkArea> {
        let asked = std::env::temp_dir();
        let mut candidates = vec![asked.clone()];
        if others {
            candidates.retain(|c| passable(c));
            candidates.extend(SHARED.iter().map(PathBuf::from).filter(|c| passable(c)));
        }
        let mut last = None;
        for candidate in &candidates {
            match WorkArea::create_in(candidate) {
                Ok(area) => return Ok(area),
                Err(e) => last = Some(e),
            }
        }
        Err(last.unwrap_or_else(|| {
            Error::Environment(format!(
                "no temporary folder that the sandbox's users can reach: TMPDIR ({}) is \
                 private to root, and none of {} can be passed by other users; give a TMPDIR \
                 that every user may pass (mode 0711 or wider on it and each folder above it)",
                asked.display(),
                SHARED.join(", ")
            ))
        }))
    }

    fn create_in(parent: &Path) -> Result<WorkArea> {
        let dir = tempfile::Builder::new()
            .prefix("whitted-grade-")
            .tempdir_in(parent)
            .map_err(|e| Error::io(parent, "cannot create a folder", e))?;
        set_mode(dir.path(), PASSABLE)?;
        for sub in [STUDENTS, COMPILERS, CASES] {
            let path = dir.path().join(sub);
            std::fs::create_dir(&path).map_err(|e| Error::io(&path, "cannot create", e))?;
            set_mode(&path, PASSABLE)?;
        }
        Ok(WorkArea { dir })
    }

    pub fn path(&self) -> &Path {
        self.dir.path()
    }
}

/// Whether every user may pass `folder` and each folder above it (the execute bit for
/// others), which a sandbox run as a user of its own needs to reach what is under it.
pub fn passable(folder: &Path) -> bool {
    let Ok(real) = folder.canonicalize() else {
        return false;
    };
    real.ancestors().all(|p| {
        std::fs::metadata(p).is_ok_and(|m| m.is_dir() && m.permissions().mode() & 0o001 != 0)
    })
}

/// Lets every user read `root` and what is under it (folders 0755, files 0644; links are left
/// as they are): what a sandbox run as a user of its own reads there, whatever the umask.
pub fn open_up(root: &Path) -> Result<()> {
    for entry in walkdir::WalkDir::new(root).follow_links(false) {
        let entry = entry.map_err(|e| {
            let path = e.path().unwrap_or(root).to_path_buf();
            Error::io(&path, "cannot read", e.into())
        })?;
        let kind = entry.file_type();
        if kind.is_dir() {
            set_mode(entry.path(), READABLE_DIR)?;
        } else if kind.is_file() {
            set_mode(entry.path(), READABLE_FILE)?;
        }
    }
    Ok(())
}

fn set_mode(path: &Path, mode: u32) -> Result<()> {
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode))
        .map_err(|e| Error::io(path, "cannot set the permissions of", e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_folder_under_a_private_one_cannot_be_passed_and_is_opened_up_below_the_area() {
        let dir = tempfile::tempdir().expect("tempdir");
        let private = dir.path().join("private");
        let inside = private.join("tmp");
        std::fs::create_dir_all(&inside).expect("mkdir");
        set_mode(dir.path(), 0o755).expect("chmod");
        set_mode(&private, 0o700).expect("chmod");
        assert!(!passable(&inside));
        set_mode(&private, 0o711).expect("chmod");
        assert!(passable(&inside));
        assert!(!passable(&dir.path().join("missing")));

        let tree = inside.join("src/gfx");
        std::fs::create_dir_all(&tree).expect("mkdir");
        std::fs::write(tree.join("A.java"), "class A {}").expect("write");
        set_mode(&tree.join("A.java"), 0o600).expect("chmod");
        set_mode(&tree, 0o700).expect("chmod");
        open_up(&inside.join("src")).expect("open up");
        let mode = |p: &Path| std::fs::metadata(p).expect("stat").permissions().mode() & 0o777;
        assert_eq!(mode(&tree), 0o755);
        assert_eq!(mode(&tree.join("A.java")), 0o644);
    }

    #[test]
    fn a_work_area_has_its_folders_passable_and_goes_when_dropped() {
        let area = WorkArea::create(false).expect("work area");
        let root = area.path().to_path_buf();
        for sub in [STUDENTS, COMPILERS, CASES] {
            let m = std::fs::metadata(root.join(sub)).expect(sub);
            assert_eq!(m.permissions().mode() & 0o777, PASSABLE, "{sub}");
        }
        drop(area);
        assert!(!root.exists());
    }
}
