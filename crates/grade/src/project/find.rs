//! A student's project folder, as students have one: the main class (`Tick1.java`, or
//! 2016-17's `Tick2.java`) in any package (every student renames `crsid`), under IntelliJ's
//! `src/`, Maven's `src/main/java/`, Eclipse's `src/` or a plain folder. IDE folders that hold
//! no sources of the student's (`.idea/`, `out/`, `bin/`, `target/`, `.git/`) are not
//! searched, so their copies are never mistaken for the project; a second copy elsewhere is
//! said, and the one beside the most of the course's classes is taken.

use std::path::{Path, PathBuf};

use super::super::package;
use whitted_core::error::{Error, Result};

/// Folders a search looks into, at most, and how deep.
const MAX_FOLDERS: usize = 10_000;
const MAX_DEPTH: usize = 12;
/// A project's source file larger than this is not one a student wrote.
const MAX_SOURCE: u64 = 1 << 20;

/// Folders that hold an IDE's or a build's output or settings, never the sources compiled.
const NOT_SOURCES: [&str; 8] = [
    ".idea",
    "out",
    "bin",
    "target",
    "build",
    "node_modules",
    ".gradle",
    ".settings",
];

/// Which exercise the main class is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Main {
    /// `Tick1.java`: 2017-18 on.
    Tick1,
    /// `Tick2.java`: 2016-17.
    Tick2,
}

impl Main {
    pub fn class(self) -> &'static str {
        match self {
            Main::Tick1 => "Tick1",
            Main::Tick2 => "Tick2",
        }
    }
}

/// A project found: its main class and the sources compiled with it.
#[derive(Debug, Clone)]
pub struct Found {
    /// The folder given.
    pub root: PathBuf,
    pub main: Main,
    /// The package it declares (None: the default package).
    pub package: Option<String>,
    /// The folder of the main class: its package's classes, each `Name.java`.
    pub folder: PathBuf,
    /// Where its package's folders start (`src/`, `src/main/java/`), when they match it.
    pub source_root: Option<PathBuf>,
    /// Every `.java` file of that folder, by name.
    pub sources: Vec<(String, PathBuf)>,
    /// What the search saw that the student should know: copies, files left out.
    pub warnings: Vec<String>,
}

impl Found {
    /// The main class, qualified.
    pub fn main_class(&self) -> String {
        package::qualified(self.package.as_deref(), self.main.class())
    }

    /// The project's own copy of `name` (`SceneLoader.java`), if it has one.
    pub fn file(&self, name: &str) -> Option<&Path> {
        self.sources
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_path())
    }

    /// `path` as the student can use it where they ran whitted: under the folder they gave.
    pub fn shown(&self, path: &Path) -> String {
        shown(path)
    }
}

/// Whether `dir` holds a main class anywhere a project would (for `whitted check` with no
/// argument: the current folder is a project or the usage is said).
pub fn is_project(dir: &Path) -> bool {
    !mains(dir).is_empty()
}

/// The project in `dir`: its main class, preferring `want` when both kinds are there.
pub fn find(dir: &Path, want: Option<Main>) -> Result<Found> {
    if !dir.is_dir() {
        return Err(Error::Usage(format!("{}: not a folder", dir.display())));
    }
    let all = mains(dir);
    let kinds: Vec<&PathBuf> = match want {
        Some(kind) => all
            .iter()
            .filter(|p| {
                p.file_name()
                    .is_some_and(|n| *n == *format!("{}.java", kind.class()))
            })
            .collect(),
        None => {
            let tick1: Vec<&PathBuf> = all.iter().filter(|p| is_named(p, "Tick1.java")).collect();
            match tick1.is_empty() {
                true => all.iter().collect(),
                false => tick1,
            }
        }
    };
    let Some(best) = kinds.iter().copied().max_by_key(|p| rank(p)) else {
        let what = match want {
            Some(kind) => format!("{}.java", kind.class()),
            None => "Tick1.java (Tick 1, 2017-18 on) or Tick2.java (Tick 2, 2016-17)".into(),
        };
        return Err(Error::Usage(format!(
            "{}: no {what} in this folder or below it (IDE output folders such as out/ and \
             bin/ are not searched): give the project's folder, or an IMAGE.png, or \
             --program 'CMD ARGS'",
            dir.display()
        )));
    };
    let main = match is_named(best, "Tick1.java") {
        true => Main::Tick1,
        false => Main::Tick2,
    };
    let folder = best.parent().unwrap_or(dir).to_path_buf();
    let text = read(best)?;
    let package = package::declared(&text)
        .map_err(|why| Error::Usage(format!("{}: {why}", best.display())))?;
    let mut warnings = Vec::new();
    let others: Vec<String> = kinds
        .iter()
        .filter(|p| **p != best)
        .map(|p| shown(p))
        .collect();
    if !others.is_empty() {
        warnings.push(format!(
            "{} copies of {}.java: using {} (beside the most of the course's classes{}), not {}",
            others.len() + 1,
            main.class(),
            shown(best),
            match kinds.iter().any(|p| is_star(p)) && !is_star(best) {
                true => "; a tick1star copy is Tick 1*, whose images are random",
                false => "",
            },
            others.join(", ")
        ));
    }
    let sources = sources(&folder, &mut warnings)?;
    for (name, path) in &sources {
        copies_elsewhere(dir, &folder, name, path, &mut warnings);
    }
    let source_root = source_root(&folder, package.as_deref());
    Ok(Found {
        root: dir.to_path_buf(),
        main,
        package,
        folder,
        source_root,
        sources,
        warnings,
    })
}

/// `path` without a leading `./` (a search from `.` gives `./src/...`); `.` for the folder
/// itself.
pub fn shown(path: &Path) -> String {
    let path = path.strip_prefix(".").unwrap_or(path);
    match path.as_os_str().is_empty() {
        true => ".".into(),
        false => path.display().to_string(),
    }
}

fn is_named(path: &Path, name: &str) -> bool {
    path.file_name().is_some_and(|n| n == name)
}

fn is_star(path: &Path) -> bool {
    path.components().any(|c| c.as_os_str() == "tick1star")
}

/// How likely a main class is the project's: not Tick 1* (random images), beside the most of
/// the course's classes, under a source folder, then the shallowest.
fn rank(path: &Path) -> (bool, usize, bool, std::cmp::Reverse<usize>) {
    let folder = path.parent().unwrap_or(path);
    let beside = COURSE_CLASSES
        .iter()
        .filter(|c| folder.join(c).is_file())
        .count();
    let under_src = path.components().any(|c| c.as_os_str() == "src");
    let depth = path.components().count();
    (!is_star(path), beside, under_src, std::cmp::Reverse(depth))
}

/// The course's classes a main class sits beside (any year's).
const COURSE_CLASSES: [&str; 10] = [
    "Renderer.java",
    "Sphere.java",
    "Plane.java",
    "Scene.java",
    "SceneLoader.java",
    "SceneObject.java",
    "Camera.java",
    "Ray.java",
    "RaycastHit.java",
    "Vector3.java",
];

/// The files under `dir`, outside the folders that hold no sources (and hidden ones), up to
/// `MAX_FOLDERS` folders and `MAX_DEPTH` deep.
fn walk(dir: &Path) -> impl Iterator<Item = walkdir::DirEntry> {
    let mut folders = 0;
    walkdir::WalkDir::new(dir)
        .max_depth(MAX_DEPTH)
        .sort_by_file_name()
        .into_iter()
        .filter_entry(|e| {
            let name = e.file_name().to_string_lossy();
            let skipped = NOT_SOURCES.contains(&name.as_ref()) || name.starts_with('.');
            e.depth() == 0 || !(e.file_type().is_dir() && skipped)
        })
        .flatten()
        .take_while(move |e| {
            folders += usize::from(e.file_type().is_dir());
            folders <= MAX_FOLDERS
        })
        .filter(|e| e.file_type().is_file())
}

/// Every `Tick1.java` and `Tick2.java` under `dir`, outside the folders that hold no sources.
fn mains(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in walk(dir) {
        let name = entry.file_name();
        if name == "Tick1.java" || name == "Tick2.java" {
            found.push(entry.into_path());
        }
    }
    found
}

/// The `.java` files of the main class's folder; names that are no Java class (`Renderer
/// (1).java`, an editor's backup) are left out and said, since javac would refuse them.
fn sources(folder: &Path, warnings: &mut Vec<String>) -> Result<Vec<(String, PathBuf)>> {
    let entries = std::fs::read_dir(folder).map_err(|e| Error::io(folder, "cannot read", e))?;
    let mut out = Vec::new();
    let mut left_out = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(stem) = name.strip_suffix(".java") else {
            continue;
        };
        let path = entry.path();
        if !path.is_file() {
            continue;
        }
        let identifier = stem
            .chars()
            .next()
            .is_some_and(|c| c.is_alphabetic() || c == '_' || c == '$')
            && stem
                .chars()
                .all(|c| c.is_alphanumeric() || c == '_' || c == '$');
        let len = std::fs::metadata(&path).map_or(0, |m| m.len());
        if !identifier || len > MAX_SOURCE {
            left_out.push(name);
            continue;
        }
        out.push((name, path));
    }
    out.sort();
    left_out.sort();
    if !left_out.is_empty() {
        warnings.push(format!(
            "left out of the compilation: {} (not a Java class's file name, or over 1 MiB)",
            left_out.join(", ")
        ));
    }
    Ok(out)
}

/// Says where the project holds another copy of the student's `name` outside `folder` that
/// differs from it: the one beside the main class is compiled, and the student may be editing
/// the other.
fn copies_elsewhere(
    dir: &Path,
    folder: &Path,
    name: &str,
    path: &Path,
    warnings: &mut Vec<String>,
) {
    if !["Sphere.java", "Plane.java", "Renderer.java"].contains(&name) {
        return;
    }
    let ours = std::fs::read(path).unwrap_or_default();
    for entry in walk(dir) {
        let other = entry.path();
        let Some(other_folder) = other.parent() else {
            continue;
        };
        if entry.file_name() != name || other_folder == folder {
            continue;
        }
        // The student's Tick 1* is a copy of their Tick 1 in a package of its own, changed
        // on purpose: it is another program, not a stale copy.
        if other_folder
            .file_name()
            .is_some_and(|f| f.to_string_lossy().ends_with("tick1star"))
        {
            let note = format!(
                "a Tick 1* copy at {}: `whitted check {}` checks it",
                shown(other_folder),
                shown(other_folder)
            );
            if !warnings.contains(&note) {
                warnings.push(note);
            }
            continue;
        }
        if std::fs::read(other).is_ok_and(|bytes| !same_but_package(&bytes, &ours)) {
            warnings.push(format!(
                "another {name} at {} differs from {}: the one beside the main class is compiled",
                shown(other),
                shown(path)
            ));
        }
    }
}

/// Whether two Java files are the same but for their package line (a copy moved to another
/// package, as a student copies a tick into the next one's).
fn same_but_package(a: &[u8], b: &[u8]) -> bool {
    let code = |bytes: &[u8]| -> Vec<String> {
        String::from_utf8_lossy(bytes)
            .lines()
            .filter(|line| !line.trim_start().starts_with("package "))
            .map(str::to_owned)
            .collect()
    };
    code(a) == code(b)
}

/// The folder the package's folders start from, when the main class's folder ends in them
/// (`src/uk/ac/.../tick1` for `uk.ac....tick1`): javac's `-sourcepath`, so classes of the
/// project's other packages are found.
fn source_root(folder: &Path, package: Option<&str>) -> Option<PathBuf> {
    let mut root = folder.to_path_buf();
    for part in package?.split('.').rev() {
        if root.file_name()? != part {
            return None;
        }
        root = root.parent()?.to_path_buf();
    }
    Some(root)
}

fn read(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| Error::io(path, "cannot read", e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(root: &Path, path: &str, text: &str) {
        let path = root.join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, text).expect("write");
    }

    #[test]
    fn the_main_class_is_found_past_ide_folders_and_a_copy_is_said() {
        let dir = tempfile::tempdir().expect("tempdir");
        let d = dir.path();
        let pkg = "package uk.ac.cam.cl.gfxintro.ab123.tick1;\n";
        for file in [
            "Tick1.java",
            "Renderer.java",
            "Sphere.java",
            "SceneLoader.java",
        ] {
            write(
                d,
                &format!("src/uk/ac/cam/cl/gfxintro/ab123/tick1/{file}"),
                pkg,
            );
        }
        write(
            d,
            "out/production/p/uk/ac/cam/cl/gfxintro/ab123/tick1/Tick1.java",
            pkg,
        );
        write(d, ".idea/Tick1.java", pkg);
        write(d, "old/Tick1.java", pkg);
        write(d, "old/Renderer.java", "// an older try\n");
        write(
            d,
            "src/uk/ac/cam/cl/gfxintro/ab123/tick1/Renderer (1).java",
            pkg,
        );
        let found = find(d, None).expect("found");
        assert_eq!(found.main, Main::Tick1);
        assert_eq!(
            found.main_class(),
            "uk.ac.cam.cl.gfxintro.ab123.tick1.Tick1"
        );
        assert_eq!(found.source_root.as_deref(), Some(d.join("src").as_path()));
        assert_eq!(found.sources.len(), 4);
        let said = found.warnings.join("\n");
        let d = d.display();
        assert!(
            said.contains(&format!("2 copies of Tick1.java: using {d}/src/")),
            "{said}"
        );
        assert!(said.contains(&format!("not {d}/old/Tick1.java")), "{said}");
        assert!(said.contains("Renderer (1).java"), "{said}");
        assert!(
            said.contains(&format!("another Renderer.java at {d}/old/Renderer.java")),
            "{said}"
        );
        assert!(!said.contains("out/"), "{said}");
    }

    /// A student's Tick 1 and the Tick 1* they copied from it, side by side as the handout
    /// says; and an untouched copy in a third package.
    #[test]
    fn a_tick1star_copy_is_pointed_to_and_a_moved_copy_is_no_difference() {
        let dir = tempfile::tempdir().expect("tempdir");
        let d = dir.path();
        let base = "src/uk/ac/cam/cl/gfxintro/ab123";
        let code = "public class Renderer { /* shading */ }\n";
        for file in ["Tick1.java", "SceneLoader.java", "Sphere.java"] {
            write(
                d,
                &format!("{base}/tick1/{file}"),
                "package uk.ac.cam.cl.gfxintro.ab123.tick1;\n",
            );
        }
        let package = |p: &str| format!("package uk.ac.cam.cl.gfxintro.ab123.{p};\n{code}");
        write(d, &format!("{base}/tick1/Renderer.java"), &package("tick1"));
        write(
            d,
            &format!("{base}/backup/Renderer.java"),
            &package("backup"),
        );
        write(
            d,
            &format!("{base}/tick1star/Renderer.java"),
            "package uk.ac.cam.cl.gfxintro.ab123.tick1star;\n// soft shadows\n",
        );
        let found = find(d, None).expect("found");
        let said = found.warnings.join("\n");
        let star = format!("{}/{base}/tick1star", d.display());
        assert!(
            said.contains(&format!(
                "a Tick 1* copy at {star}: `whitted check {star}` checks it"
            )),
            "{said}"
        );
        assert!(!said.contains("differs"), "{said}");
    }

    #[test]
    fn a_folder_without_a_main_class_is_refused_with_what_was_looked_for() {
        let dir = tempfile::tempdir().expect("tempdir");
        write(dir.path(), "out/Tick1.java", "");
        assert!(!is_project(dir.path()));
        let Err(Error::Usage(message)) = find(dir.path(), None) else {
            panic!("no project");
        };
        assert!(message.contains("no Tick1.java"), "{message}");
    }
}
