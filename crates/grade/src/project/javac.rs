//! A project compiled by `javac` into a private temporary folder (mode 0700, removed when the
//! build is dropped, Ctrl-C included): the student's own program, run as `check --program`
//! runs one. Not sandboxed: it is the student's own code on their own machine, as their IDE
//! runs it. When it does not compile, javac's first errors are the message (paths as the
//! student knows them), once, with the cause where it is a known one.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use super::find::Found;
use whitted_core::error::{Error, Result};
use whitted_process::{Capture, Ended, Process};

/// Seconds javac may take.
const DEADLINE: u64 = 120;
/// Bytes of javac's messages kept: the first ones.
const MESSAGES: usize = 64 << 10;
/// Errors shown of javac's messages.
const SHOWN_ERRORS: usize = 3;

/// A compiled program: its classes in a temporary folder, removed when this is dropped.
#[derive(Debug)]
pub struct Build {
    dir: tempfile::TempDir,
    /// The main class, qualified.
    pub main: String,
}

impl Build {
    pub fn classes(&self) -> PathBuf {
        self.dir.path().join("classes")
    }

    /// The words that run it: `java -cp CLASSES MAIN`.
    pub fn command(&self, java: &Path) -> Vec<String> {
        vec![
            java.display().to_string(),
            "-Djava.awt.headless=true".into(),
            "-cp".into(),
            self.classes().display().to_string(),
            self.main.clone(),
        ]
    }
}

/// `java` or `javac` from PATH, or a message saying what to install.
pub fn jdk_tool(name: &str) -> Result<PathBuf> {
    which::which(name).map_err(|_| {
        Error::Environment(format!(
            "whitted check compiles and runs a project folder with the JDK: `{name}` is not on \
             PATH (install a JDK: `apt install default-jdk-headless`, or your IDE's JDK's bin/ \
             on PATH); or compile it yourself and give --program 'java -cp CLASSES MAIN'"
        ))
    })
}

/// The project's sources as they are, compiled: the folder of the main class, with the rest
/// of its source tree on javac's `-sourcepath`. A compilation error is the error returned.
pub fn project(found: &Found) -> Result<Build> {
    let javac = jdk_tool("javac")?;
    let dir = private_dir()?;
    // javac runs where whitted was run, on the paths as found, so that its messages name the
    // files as the student reaches them from there.
    let files: Vec<PathBuf> = found
        .sources
        .iter()
        .map(|(_, p)| PathBuf::from(found.shown(p)))
        .collect();
    let source_root = found
        .source_root
        .as_ref()
        .map(|r| PathBuf::from(found.shown(r)));
    match run(&javac, None, &dir, source_root.as_deref(), &files)? {
        None => Ok(Build {
            dir,
            main: found.main_class(),
        }),
        Some(messages) => Err(Error::Usage(failed(found, &messages))),
    }
}

/// `sources` (paths under a source root, and their bytes) written to a private folder and
/// compiled there: the build, or javac's first errors.
pub fn sources(
    sources: &[(String, Vec<u8>)],
    main: String,
) -> Result<std::result::Result<Build, String>> {
    let javac = jdk_tool("javac")?;
    let dir = private_dir()?;
    let src = dir.path().join("src");
    let mut files = Vec::new();
    for (name, bytes) in sources {
        let path = src.join(name);
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|e| Error::io(folder, "cannot create", e))?;
        }
        std::fs::write(&path, bytes).map_err(|e| Error::io(&path, "cannot write", e))?;
        files.push(PathBuf::from(name));
    }
    Ok(match run(&javac, Some(&src), &dir, None, &files)? {
        None => Ok(Build { dir, main }),
        Some(messages) => Err(first_errors(&messages)),
    })
}

/// A temporary folder only its owner can enter, with an empty `classes/`.
fn private_dir() -> Result<tempfile::TempDir> {
    let dir = tempfile::Builder::new()
        .prefix("whitted-project-")
        .tempdir()
        .map_err(|e| Error::io(std::env::temp_dir(), "cannot create a temporary folder", e))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o700))
            .map_err(|e| Error::io(dir.path(), "cannot make private", e))?;
    }
    let classes = dir.path().join("classes");
    std::fs::create_dir(&classes).map_err(|e| Error::io(&classes, "cannot create", e))?;
    Ok(dir)
}

/// javac over `files` (relative to `cwd`, or to this process's folder) into `dir/classes`:
/// None when it compiled, else its messages.
fn run(
    javac: &Path,
    cwd: Option<&Path>,
    dir: &tempfile::TempDir,
    source_root: Option<&Path>,
    files: &[PathBuf],
) -> Result<Option<String>> {
    let mut command = Command::new(javac);
    if let Some(cwd) = cwd {
        command.current_dir(cwd);
    }
    command
        .args([
            "-proc:none",
            "-encoding",
            "UTF-8",
            "-Xmaxerrs",
            "20",
            "-nowarn",
        ])
        .arg("-implicit:class")
        .arg("-d")
        .arg(dir.path().join("classes"));
    if let Some(root) = source_root {
        command.arg("-sourcepath").arg(root);
    }
    command
        .args(files)
        .stdin(Stdio::null())
        .stdout(Stdio::null());
    let mut process = Process::spawn(command, Capture::Head(MESSAGES))
        .map_err(|e| Error::Environment(format!("cannot run {}: {e}", javac.display())))?;
    let ended = process
        .wait(
            Duration::from_secs(DEADLINE),
            Duration::from_millis(20),
            whitted_core::interrupt::requested,
        )
        .map_err(|e| Error::Environment(format!("cannot wait for javac: {e}")))?;
    whitted_core::interrupt::check()?;
    let messages = String::from_utf8_lossy(&process.finish()).into_owned();
    match ended {
        Ended::Exited(s) if s.success() => Ok(None),
        Ended::Exited(s) if messages.trim().is_empty() => {
            Ok(Some(format!("javac failed without a message ({s})")))
        }
        Ended::Exited(_) => Ok(Some(messages)),
        Ended::TimedOut | Ended::Stopped => Err(Error::Environment(format!(
            "javac was still compiling the project after {DEADLINE} s"
        ))),
    }
}

/// javac's first errors: each error's lines (the located message, the source line, the caret),
/// and how many more there are.
pub fn first_errors(messages: &str) -> String {
    let lines: Vec<&str> = messages
        .lines()
        .filter(|l| !l.starts_with("Note:") && !l.contains(": warning:"))
        .collect();
    let starts: Vec<usize> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.contains(": error:") || l.starts_with("error:"))
        .map(|(i, _)| i)
        .collect();
    let Some(&first) = starts.first() else {
        return lines.join("\n");
    };
    let end = starts.get(SHOWN_ERRORS).copied().unwrap_or_else(|| {
        // The last error's block ends before javac's count ("3 errors").
        lines
            .iter()
            .rposition(|l| !is_count(l))
            .map_or(lines.len(), |i| i + 1)
    });
    let mut out: Vec<String> = lines[first..end].iter().map(|l| l.to_string()).collect();
    if starts.len() > SHOWN_ERRORS {
        out.push(format!(
            "... and {} more errors (javac stops at 20)",
            starts.len() - SHOWN_ERRORS
        ));
    }
    out.join("\n")
}

fn is_count(line: &str) -> bool {
    let line = line.trim();
    line.ends_with(" error")
        || line.ends_with(" errors")
        || line.ends_with(" warning")
        || line.ends_with(" warnings")
}

/// The message of a project that does not compile: javac's first errors, then the cause when
/// it is a known one.
fn failed(found: &Found, messages: &str) -> String {
    let shown = first_errors(messages);
    let cause = known_cause(messages).unwrap_or_default();
    format!(
        "{} does not compile; javac says:\n{shown}{cause}",
        found.shown(&found.folder)
    )
}

/// What a known first error means, as a paragraph to add.
fn known_cause(messages: &str) -> Option<String> {
    let first = messages.lines().find(|l| l.contains(": error:"))?;
    let file = first.split(':').next()?.rsplit('/').next()?;
    if file == "BumpySphere.java" && first.contains("missing return statement") {
        return Some(
            "\nThis is the 2023-24 skeleton as shipped: its BumpySphere.getNormalAt has no \
             return statement, so nothing compiles until it has one. Give it one, e.g. `return \
             super.getNormalAt(position);` (the smooth sphere's normal) until Tick 1* asks for \
             the bumped one; the course's tester uses its own BumpySphere."
                .into(),
        );
    }
    let theirs = ["Sphere.java", "Plane.java", "Renderer.java"];
    let course_class = !theirs.contains(&file) && !file.starts_with("Tick1Tests");
    course_class.then(|| {
        format!(
            "\nThe first error is in {file}, one of the course's classes, which the handout \
             says to leave alone: an edit there, or a class of the wrong year beside it."
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_errors_are_kept_with_their_source_lines_and_the_rest_counted() {
        let messages = "Note: x uses unchecked operations.\n\
            src/a/Renderer.java:3: error: ';' expected\n  int x\n       ^\n\
            src/a/Renderer.java:9: error: cannot find symbol\n  y();\n  ^\n  symbol: method y()\n\
            src/a/Plane.java:1: error: a\nb\n^\n\
            src/a/Plane.java:2: error: b\nc\n^\n5 errors\n";
        let shown = first_errors(messages);
        assert!(
            shown.starts_with("src/a/Renderer.java:3: error: ';' expected"),
            "{shown}"
        );
        assert!(shown.contains("symbol: method y()"), "{shown}");
        assert!(shown.contains("Plane.java:1"), "{shown}");
        assert!(!shown.contains("Plane.java:2"), "{shown}");
        assert!(
            shown.ends_with("... and 1 more errors (javac stops at 20)"),
            "{shown}"
        );
        assert!(!first_errors("a/B.java:1: error: x\n^\n1 error\n").contains("1 error\n"));
    }

    #[test]
    fn the_build_folder_is_private_and_goes_with_the_build() {
        use std::os::unix::fs::PermissionsExt;
        let dir = private_dir().expect("dir");
        let mode = std::fs::metadata(dir.path())
            .expect("meta")
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o700);
        let build = Build {
            dir,
            main: "a.Tick1".into(),
        };
        let classes = build.classes();
        assert!(classes.is_dir());
        drop(build);
        assert!(!classes.exists());
    }

    #[test]
    fn the_2023_24_bumpy_sphere_is_named_as_the_known_cause() {
        let messages =
            "src/x/BumpySphere.java:47: error: missing return statement\n    }\n    ^\n1 error\n";
        let cause = known_cause(messages).expect("known");
        assert!(
            cause.contains("2023-24") && cause.contains("getNormalAt"),
            "{cause}"
        );
        let theirs = "src/x/Renderer.java:4: error: missing return statement\n";
        assert_eq!(known_cause(theirs), None);
        let loader = "src/x/SceneLoader.java:4: error: cannot find symbol\n";
        assert!(known_cause(loader)
            .expect("course class")
            .contains("SceneLoader.java"));
    }
}
