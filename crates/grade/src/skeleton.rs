//! The course's classes a submission compiles against: by default whitted's clean-room
//! skeleton of the year (compiled into the binary): 2016-17's `skeleton/gfx/tick2`, or from
//! 2017-18 the year's Tick 1 skeleton (T1 to T4, selected from the one set of sources in
//! `skeleton/tick1`); or the course's own sources with `--skeleton DIR`. Never a submission's:
//! only the files the year's handout says to submit (`archive::submitted`) come from there.

mod template;

use std::path::{Path, PathBuf};

use super::archive::{self, MAX_SOURCE};
use super::package;
use whitted_core::course::{Api, Course};
use whitted_core::error::{Error, Result};

/// The skeleton's files: (name, bytes), sorted by name.
#[derive(Debug, Clone)]
pub struct Skeleton {
    pub files: Vec<(String, Vec<u8>)>,
    /// Where it came from, for the reports.
    pub source: String,
    /// The package its files declare (`gfx.tick2`; a later year's with the course's own
    /// placeholder for the user id), which each student's package replaces.
    pub package: Option<String>,
    /// The main class's simple name: `Tick2`, or `Tick1` from 2017-18.
    pub main: &'static str,
}

/// Folders a search for the later skeleton's `Tick1.java` looks into, at most.
const MAX_FOLDERS: usize = 10_000;
/// How deep it goes.
const MAX_DEPTH: usize = 16;

macro_rules! ours {
    ($($name:literal),*) => {
        [$(($name, include_bytes!(concat!("../skeleton/gfx/tick2/", $name)).as_slice())),*]
    };
}

/// The package the Tick 1 skeleton's sources declare: the course's placeholder for the user id.
pub const TICK1_PACKAGE: &str = "uk.ac.cam.cl.gfxintro.crsid.tick1";

macro_rules! tick1 {
    ($($name:literal),*) => {
        [$(($name, include_str!(concat!("../skeleton/tick1/", $name)))),*]
    };
}

/// whitted's own Tick 1 classes, every year's in one set of sources (docs/grade.md, "The Tick 1
/// skeleton's API"): `Tick1Tests` too, since it pins signatures in the student's files.
const TICK1: [(&str, &str); 12] = tick1!(
    "BumpySphere.java",
    "Camera.java",
    "ColorRGB.java",
    "PointLight.java",
    "Ray.java",
    "RaycastHit.java",
    "Scene.java",
    "SceneLoader.java",
    "SceneObject.java",
    "Tick1.java",
    "Tick1Tests.java",
    "Vector3.java"
);

/// whitted's own: the API of docs/grade.md, the arithmetic of docs/rendering.md.
const CLEAN_ROOM: [(&str, &[u8]); 10] = ours!(
    "Camera.java",
    "PointLight.java",
    "Ray.java",
    "RaycastHit.java",
    "Scene.java",
    "SceneLoader.java",
    "SceneObject.java",
    "Sphere.java",
    "Tick2.java",
    "Vector3.java"
);

impl Skeleton {
    /// whitted's clean-room skeleton of `course`'s classes.
    pub fn clean_room(course: Course) -> Result<Skeleton> {
        let api = course.api();
        if api == Api::Tick2 {
            return Ok(Skeleton::tick2());
        }
        let mut files = Vec::new();
        for (name, text) in TICK1 {
            let text = select(text, course).map_err(|why| {
                Error::Environment(format!(
                    "whitted's skeleton/tick1/{name} is malformed: {why}"
                ))
            })?;
            files.push((name.to_string(), text.into_bytes()));
        }
        Ok(Skeleton {
            files,
            source: format!("whitted's clean-room {course} skeleton ({api})"),
            package: Some(TICK1_PACKAGE.into()),
            main: "Tick1",
        })
    }

    /// 2016-17's `gfx.tick2` classes.
    fn tick2() -> Skeleton {
        Skeleton {
            files: CLEAN_ROOM
                .iter()
                .map(|(name, bytes)| (name.to_string(), bytes.to_vec()))
                .collect(),
            source: "whitted's clean-room skeleton".into(),
            package: Some("gfx.tick2".into()),
            main: "Tick2",
        }
    }

    /// The skeleton `course` is graded against: `--skeleton DIR` when given, else the
    /// clean-room one of that year.
    pub fn of(course: Course, dir: Option<&Path>) -> Result<Skeleton> {
        match dir {
            Some(dir) => Skeleton::from_dir(dir, course),
            None => Skeleton::clean_room(course),
        }
    }

    /// The `.java` files of the folder holding the main class (`Tick2.java` in `dir`, its
    /// `gfx/tick2` or `src/gfx/tick2`; `Tick1.java` anywhere under `dir` from 2017-18), but
    /// those a submission gives.
    fn from_dir(dir: &Path, course: Course) -> Result<Skeleton> {
        let main = if course.is_default() {
            "Tick2"
        } else {
            "Tick1"
        };
        let found = match course.is_default() {
            true => ["src/gfx/tick2", "gfx/tick2", ""]
                .iter()
                .map(|sub| dir.join(sub))
                .find(|d| d.join("Tick2.java").is_file()),
            false => find_folder_of(dir, "Tick1.java"),
        };
        let package = found.ok_or_else(|| {
            let where_ = match course.is_default() {
                true => "there, nor in gfx/tick2 or src/gfx/tick2",
                false => "anywhere under it",
            };
            Error::Usage(format!(
                "--skeleton {}: no {main}.java {where_}",
                dir.display()
            ))
        })?;
        let submitted = archive::submitted(course);
        let mut files = Vec::new();
        let entries =
            std::fs::read_dir(&package).map_err(|e| Error::io(&package, "cannot read", e))?;
        let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
        paths.sort();
        for path in paths {
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            if !name.ends_with(".java") || submitted.contains(&name.as_str()) || !path.is_file() {
                continue;
            }
            let len = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
            if len > MAX_SOURCE {
                return Err(Error::Usage(format!(
                    "{}: larger than {MAX_SOURCE} bytes",
                    path.display()
                )));
            }
            let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, "cannot read", e))?;
            files.push((name, bytes));
        }
        let declared = files
            .iter()
            .find(|(name, _)| *name == format!("{main}.java"))
            .map_or(Ok(None), |(_, bytes)| package::declared(bytes))
            .map_err(|why| Error::Usage(format!("{}/{main}.java: {why}", package.display())))?;
        Ok(Skeleton {
            files,
            source: package.display().to_string(),
            package: declared,
            main,
        })
    }

    /// The skeleton's files moved into `to`, each at its path under the source root: what is
    /// compiled with a student's files in that package.
    pub fn sources_in(&self, to: Option<&str>) -> Vec<(String, Vec<u8>)> {
        let folder = package::folder(to);
        self.files
            .iter()
            .map(|(name, bytes)| {
                let bytes = package::moved(bytes, self.package.as_deref(), to);
                (format!("{folder}{name}"), bytes)
            })
            .collect()
    }
}

/// `text` in the template's markers as `course`'s API has it, at the year's size.
pub fn select(text: &str, course: Course) -> std::result::Result<String, String> {
    template::select(text, course.api(), course.size())
}

/// The folder under `dir` (breadth first, links not followed) that holds a file `name`.
fn find_folder_of(dir: &Path, name: &str) -> Option<PathBuf> {
    let mut queue = std::collections::VecDeque::from([(dir.to_path_buf(), 0)]);
    let mut seen = 0;
    while let Some((folder, depth)) = queue.pop_front() {
        seen += 1;
        if seen > MAX_FOLDERS {
            return None;
        }
        if folder.join(name).is_file() {
            return Some(folder);
        }
        let Ok(entries) = std::fs::read_dir(&folder) else {
            continue;
        };
        let mut subfolders: Vec<PathBuf> = entries
            .flatten()
            .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
            .map(|e| e.path())
            .collect();
        subfolders.sort();
        if depth < MAX_DEPTH {
            queue.extend(subfolders.into_iter().map(|f| (f, depth + 1)));
        }
    }
    None
}
