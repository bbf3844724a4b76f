//! `whitted grade` and the machine it runs on (docs/grade.md, "The sandbox"): it grades
//! wherever its temporary folder is and whatever the umask, and a student's files show nothing
//! of the grading machine (its temporary paths, the sandbox's command line, the skeleton's
//! path on its disk).

use std::path::Path;
use std::process::Command;

use crate::common::*;
use crate::grade::{records, submission};

/// A student folder of `files` (Plane.java, Renderer.java) in `class`.
pub fn student(class: &Path, id: &str, files: (String, String)) {
    let dir = class.join(id).join("src/gfx/tick2");
    std::fs::create_dir_all(&dir).expect("mkdir");
    std::fs::write(dir.join("Plane.java"), files.0).expect("Plane.java");
    std::fs::write(dir.join("Renderer.java"), files.1).expect("Renderer.java");
}

/// `whitted grade -q ARGS` in `dir`, with `TMPDIR` and, through sh, `umask`.
fn grade_with(dir: &Path, tmpdir: &Path, umask: &str, args: &[&str]) -> std::process::Output {
    Command::new("sh")
        .args(["-c", "umask \"$0\" && exec \"$@\"", umask])
        .arg(env!("CARGO_BIN_EXE_whitted"))
        .args(["grade", "-q"])
        .args(args)
        .current_dir(dir)
        .env("TMPDIR", tmpdir)
        .output()
        .expect("grade runs")
}

/// Run as root, each sandbox runs as a user of its own, who cannot pass a private folder: a
/// `TMPDIR` under one (root's home is 0700) used to stop the class with "bubblewrap cannot make
/// a sandbox here", and a umask of 077 made every student a compile error (javac could not
/// read their sources). Both grade the class now; as another user they always did.
#[test]
fn a_private_tmpdir_and_a_strict_umask_still_grade_the_class() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    student(&d.join("class"), "good", submission(&[]));
    let private = d.join("private");
    let tmp = private.join("tmp");
    std::fs::create_dir_all(&tmp).expect("mkdir");
    let chmod = |path: &Path, mode: u32| {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode)).expect("chmod");
    };
    chmod(&private, 0o700);
    for (umask, out) in [("022", "out-private"), ("077", "out-umask")] {
        let run = grade_with(d, &tmp, umask, &["class", "-o", out, "--timeout", "30"]);
        assert!(run.status.success(), "umask {umask}: {}", stderr(&run));
        let rows = records(&d.join(out).join("class.csv"));
        assert_eq!(rows.len(), 1);
        assert_eq!(rows[0]["status"], "graded", "umask {umask}: {:?}", rows[0]);
        assert_eq!(rows[0]["passed"], "5", "umask {umask}: {:?}", rows[0]);
        assert_eq!(rows[0]["grade"], "100", "umask {umask}: {:?}", rows[0]);
        // The work folder is gone, wherever it was made.
        let left: Vec<_> = std::fs::read_dir(&tmp).expect("tmp").flatten().collect();
        assert!(left.is_empty(), "left in TMPDIR: {left:?}");
    }
    chmod(&private, 0o755);
}
