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

/// A program that prints what it can see of the machine to its standard error and crashes:
/// its folder, its class path, its own command line, the sandbox's (`/proc/1/cmdline`) and
/// the mounts that hold the grader's folders. The report shows that standard error; none of
/// it names the grader's temporary folder or the sandbox's options, and the result names the
/// skeleton given with --skeleton by its fingerprint, not its path.
#[test]
fn a_student_s_report_shows_nothing_of_the_grading_machine() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let spy = "try { \
        java.util.function.Function<String, String> read = p -> { try { return new \
        String(java.nio.file.Files.readAllBytes(java.nio.file.Path.of(p))).replace('\\0', ' ')\
        .replace('\\n', ' '); } catch (java.io.IOException e) { return \"unreadable \" + p; } }; \
        String mounts = java.util.Arrays.stream(read.apply(\"/proc/self/mountinfo\").split(\" \
        [0-9]+ [0-9]+ [0-9]+:[0-9]+ \")).filter(l -> l.contains(\"whitted\")).findFirst()\
        .orElse(\"none\"); \
        System.err.println(\"spy-mount=\" + mounts); \
        System.err.println(\"spy-cwd=\" + new java.io.File(\".\").getCanonicalPath()); \
        System.err.println(\"spy-cp=\" + System.getProperty(\"java.class.path\")); \
        System.err.println(\"spy-self=\" + read.apply(\"/proc/self/cmdline\")); \
        System.err.println(\"spy-pid1=\" + read.apply(\"/proc/1/cmdline\")); \
        } catch (java.io.IOException e) { throw new RuntimeException(e); } \
        System.exit(3);";
    student(&d.join("class"), "spy", crate::grade::hostile(spy));
    let tmp = d.join("grader-tmp");
    std::fs::create_dir_all(&tmp).expect("mkdir");
    let skeleton = root().join("skeleton");
    let run = grade_with(
        d,
        &tmp,
        "022",
        &[
            "class",
            "-o",
            "out",
            "--timeout",
            "30",
            "--skeleton",
            s(&skeleton),
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let out = d.join("out/students/spy");
    let result = std::fs::read_to_string(out.join("result.json")).expect("result.json");
    let report = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    // The program did print what it saw, with the work folder's place taken out.
    for said in [
        "spy-cwd=&lt;work&gt;/cases/",
        "spy-cp=&lt;work&gt;/students/spy/classes",
    ] {
        assert!(report.contains(said), "{said} not in the report: {report}");
    }
    for said in [
        "spy-cwd=<work>/cases/",
        "spy-self=",
        "spy-pid1=",
        "bwrap --args ",
    ] {
        assert!(result.contains(said), "{said} not in result.json: {result}");
    }
    let grader = [
        s(&tmp).to_string(),
        "whitted-grade-".to_string(),
        "--ro-bind".to_string(),
        "--unshare-all".to_string(),
        "--seccomp".to_string(),
        s(&skeleton).to_string(),
    ];
    for text in [&result, &report] {
        for secret in &grader {
            assert!(!text.contains(secret.as_str()), "{secret} shown: {text}");
        }
    }
    let result: serde_json::Value = serde_json::from_str(&result).expect("json");
    let named = result["extra_data"]["skeleton"].as_str().expect("skeleton");
    assert!(
        named.starts_with("the course's skeleton given with --skeleton ("),
        "{named}"
    );
}
