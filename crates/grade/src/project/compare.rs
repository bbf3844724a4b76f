//! Whether a project's own copies of the course's classes (the loader, `Tick1`, the camera:
//! everything but the files the student hands in) are the year's, since an edit there changes
//! images in ways no mistake of theirs explains, and the course's tester uses its own.
//!
//! Two ways, by cost. **Members** (always; milliseconds): each class's visible methods,
//! constructors and fields against the year's clean-room class, which has exactly the course's
//! (docs/grade.md), and `Tick1`'s size. **Renders** (only when a case fails, on that one case):
//! the student's own files compiled on the year's clean-room classes beside the whole project;
//! where the two render the case differently, the difference is in a class they were not
//! meant to change, and it is found by putting the project's copy of one class at a time
//! among the year's, first those whose members already differ. A project that passes costs
//! nothing more than its compile.

use std::path::{Path, PathBuf};

use super::find::Found;
use super::javac::{self, Build};
use super::members::{blank, members, Member};
use crate::archive;
use crate::package;
use crate::skeleton::Skeleton;
use whitted_check::check::program::{self, Plain};
use whitted_check::check::student_png::Rgb8;
use whitted_check::check::suite::SuiteCase;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

/// Classes whose differences do not reach an image: the unit tests.
const NOT_RENDERED: [&str; 1] = ["Tick1Tests.java"];

/// The order classes are tried in when members say nothing: those students are known to edit
/// first (docs/grade.md: `Tick1`, `SceneLoader`), then the rest.
const LIKELY: [&str; 12] = [
    "Tick1.java",
    "Tick2.java",
    "SceneLoader.java",
    "Scene.java",
    "Camera.java",
    "SceneObject.java",
    "PointLight.java",
    "Sphere.java",
    "Ray.java",
    "RaycastHit.java",
    "Vector3.java",
    "ColorRGB.java",
];

/// One of the year's classes a project has (or lacks) its own copy of.
struct CourseClass {
    /// Its file's name, `SceneLoader.java`.
    name: String,
    /// The year's source, in the project's package.
    year: Vec<u8>,
    /// The project's source, if it has the class.
    own: Option<Vec<u8>>,
}

/// The year's classes but the student's own files and the unit tests, each with the project's
/// copy.
fn course_classes(found: &Found, course: Course) -> Result<Vec<CourseClass>> {
    let skeleton = Skeleton::clean_room(course)?;
    let package = package_of(found, &skeleton);
    let theirs = archive::submitted(course);
    Ok(skeleton
        .files
        .iter()
        .filter(|(name, _)| !theirs.contains(&name.as_str()))
        .filter(|(name, _)| !NOT_RENDERED.contains(&name.as_str()))
        .map(|(name, bytes)| CourseClass {
            name: name.clone(),
            year: package::moved(bytes, skeleton.package.as_deref(), package),
            own: found.file(name).and_then(|p| std::fs::read(p).ok()),
        })
        .collect())
}

/// The package the project's classes are in: the student's own from 2017-18, 2016-17's
/// `gfx.tick2` otherwise.
fn package_of<'a>(found: &'a Found, skeleton: &'a Skeleton) -> Option<&'a str> {
    match found.main {
        super::find::Main::Tick1 => found.package.as_deref(),
        super::find::Main::Tick2 => skeleton.package.as_deref(),
    }
}

/// Per class of the course's the project changed the members of (or lacks), a line saying
/// what differs from `course`'s.
pub fn members_differ(found: &Found, course: Course) -> Result<Vec<(String, String)>> {
    let mut out = Vec::new();
    for CourseClass { name, year, own } in course_classes(found, course)? {
        // Tick 1*'s BumpySphere is the year's class only as a stub the student fills in, with
        // whatever helpers: theirs, not the course's.
        if archive::OPTIONAL.contains(&name.as_str()) {
            continue;
        }
        let Some(own) = own else {
            out.push((
                name.clone(),
                format!("the project has no {name}, one of {course}'s course classes"),
            ));
            continue;
        };
        let (year, own) = (
            String::from_utf8_lossy(&year),
            String::from_utf8_lossy(&own),
        );
        let visible = |source: &str| -> Vec<Member> {
            let mut m: Vec<Member> = members(source)
                .into_iter()
                .filter(Member::visible)
                .collect();
            for member in &mut m {
                // Public or protected: the API is who can call it, not how widely.
                member.visibility = super::members::Visibility::Public;
            }
            m.sort();
            m.dedup();
            m
        };
        let (year_members, own_members) = (visible(&year), visible(&own));
        let added: Vec<String> = own_members
            .iter()
            .filter(|m| !year_members.contains(m))
            .map(Member::shown)
            .collect();
        let lacks: Vec<String> = year_members
            .iter()
            .filter(|m| !own_members.contains(m))
            .map(Member::shown)
            .collect();
        let mut what = Vec::new();
        if !added.is_empty() {
            what.push(format!(
                "it has {} that {course}'s has not",
                added.join(", ")
            ));
        }
        if !lacks.is_empty() {
            what.push(format!("it lacks {}", lacks.join(", ")));
        }
        if name == "Tick1.java" {
            if let (Some(a), Some(b)) = (
                super::year::size_of(&blank(&own, false)),
                super::year::size_of(&blank(&year, false)),
            ) {
                if a != b {
                    what.push(format!(
                        "it renders {}x{}, {course}'s {}x{}",
                        a.0, a.1, b.0, b.1
                    ));
                }
            }
        }
        if !what.is_empty() {
            out.push((
                name.clone(),
                format!("{name} is not {course}'s: {}", what.join("; ")),
            ));
        }
    }
    Ok(out)
}

/// What one run of a case gave: its image, or why there is none.
#[derive(Debug, Clone, PartialEq)]
pub enum Rendered {
    Image(Rgb8),
    Nothing,
}

impl Rendered {
    /// How `other` differs from this, in words ("12034 pixels differ").
    fn against(&self, other: &Rendered) -> String {
        match (self, other) {
            (Rendered::Image(a), Rendered::Image(b)) if a.bytes.len() == b.bytes.len() => {
                let pixels = a
                    .bytes
                    .chunks(3)
                    .zip(b.bytes.chunks(3))
                    .filter(|(x, y)| x != y)
                    .count();
                format!("{pixels} pixels differ")
            }
            (Rendered::Image(a), Rendered::Image(b)) => {
                format!("{}x{} against {}x{}", a.width, a.height, b.width, b.height)
            }
            (Rendered::Nothing, Rendered::Image(_)) => {
                "one writes no image of the year's size".into()
            }
            (Rendered::Image(_), Rendered::Nothing) => {
                "one writes no image of the year's size".into()
            }
            (Rendered::Nothing, Rendered::Nothing) => "neither writes an image".into(),
        }
    }
}

/// The student's own files compiled among `course`'s clean-room classes, with at most one of
/// the project's copies of a course class swapped in: the builds both comparisons run a failing
/// case on (the pixels of a Tick 1 case here; the verdicts of a Tick 1* case, `star_verdicts.rs`).
pub struct OnYear {
    pub course: Course,
    classes: Vec<CourseClass>,
    /// The student's files, each by its path in the build.
    student: Vec<(String, Vec<u8>)>,
    folder: String,
    main: String,
    pub java: PathBuf,
}

impl OnYear {
    /// None when the project lacks one of the files a student hands in (nothing to build).
    pub fn new(found: &Found, course: Course) -> Result<Option<OnYear>> {
        let java = javac::jdk_tool("java")?;
        let classes = course_classes(found, course)?;
        let skeleton = Skeleton::clean_room(course)?;
        let package = package_of(found, &skeleton).map(str::to_string);
        let folder = package::folder(package.as_deref());
        let main = package::qualified(package.as_deref(), skeleton.main);
        let mut student = Vec::new();
        for name in archive::submitted(course) {
            let Some(path) = found.file(name) else {
                return Ok(None);
            };
            let bytes = std::fs::read(path).map_err(|e| Error::io(path, "cannot read", e))?;
            let bytes = bytes
                .strip_prefix(b"\xEF\xBB\xBF")
                .unwrap_or(&bytes)
                .to_vec();
            student.push((format!("{folder}{name}"), bytes));
        }
        Ok(Some(OnYear {
            course,
            classes,
            student,
            folder,
            main,
            java,
        }))
    }

    /// The build with the project's copy of `swapped` (if any) among the year's classes; or
    /// javac's errors.
    pub fn build(&self, swapped: Option<&str>) -> Result<std::result::Result<Build, String>> {
        let mut sources: Vec<(String, Vec<u8>)> = self
            .classes
            .iter()
            .map(|class| {
                // The student's own BumpySphere always: it is theirs (`members_differ`).
                let theirs = archive::OPTIONAL.contains(&class.name.as_str());
                let bytes = match (swapped == Some(class.name.as_str()) || theirs, &class.own) {
                    (true, Some(own)) => own.clone(),
                    _ => class.year.clone(),
                };
                (format!("{}{}", self.folder, class.name), bytes)
            })
            .collect();
        // Tick1Tests is not rendered, but the student's files may be written against it.
        sources.extend(self.student.iter().cloned());
        javac::sources(&sources, self.main.clone())
    }

    /// The line when the student's files do not compile among the year's classes: `errors`,
    /// javac's.
    pub fn not_compiling(&self, errors: &str) -> String {
        let course = self.course;
        let first = errors.lines().next().unwrap_or("");
        format!(
            "your {} do not compile beside {course}'s own classes, as the course's tester \
             compiles them: they lean on a change to the course's classes ({first})",
            self.submitted()
        )
    }

    /// The course classes whose project copy is not the year's code, in the order they are
    /// tried: `suspects` (those whose members differ) first, then [`LIKELY`]'s.
    pub fn edited<'a>(&'a self, suspects: &'a [String]) -> Vec<&'a str> {
        let mut order: Vec<&str> = suspects.iter().map(String::as_str).collect();
        order.extend(LIKELY.iter().filter(|n| !suspects.iter().any(|s| s == *n)));
        order
            .into_iter()
            .filter(|name| {
                self.classes.iter().any(|c| {
                    c.name == *name && c.own.as_ref().is_some_and(|own| !same_code(&c.year, own))
                })
            })
            .collect()
    }

    /// "Sphere.java, Plane.java and Renderer.java": the student's files in the builds, in
    /// words, with their own BumpySphere where it is not the year's stub (Tick 1*'s option 1).
    pub fn submitted(&self) -> String {
        let mut names: Vec<&str> = match archive::submitted(self.course) {
            [a, b, c] => vec![c, a, b],
            other => other.to_vec(),
        };
        names.extend(
            self.classes
                .iter()
                .filter(|c| archive::OPTIONAL.contains(&c.name.as_str()))
                .filter(|c| c.own.as_ref().is_some_and(|own| !same_code(&c.year, own)))
                .map(|c| c.name.as_str()),
        );
        match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
            _ => names.join(", "),
        }
    }
}

/// The case run on the student's own files and `course`'s classes, against `theirs` (what the
/// whole project rendered); where they differ, the course classes of the project's that make
/// the difference, found one at a time (`suspects` first). Lines for the report.
pub fn renders_differ(
    found: &Found,
    course: Course,
    case: &SuiteCase,
    theirs: &Rendered,
    suspects: &[String],
    timeout: u64,
) -> Result<Vec<String>> {
    let Some(on) = OnYear::new(found, course)? else {
        return Ok(Vec::new());
    };
    let java = &on.java;
    let case_name = case.name();
    let year_build = match on.build(None)? {
        Ok(b) => b,
        Err(errors) => return Ok(vec![on.not_compiling(&errors)]),
    };
    let on_year = render(&year_build, java, case, timeout)?;
    if on_year == *theirs {
        return Ok(Vec::new());
    }
    let mut lines = Vec::new();
    for name in on.edited(suspects) {
        let Ok(swapped) = on.build(Some(name))? else {
            continue;
        };
        let with_theirs = render(&swapped, java, case, timeout)?;
        if with_theirs != on_year {
            lines.push(format!(
                "{name} is not {course}'s: with your {name} among {course}'s own classes, your \
                 {} render {case_name} otherwise than with {course}'s ({}); the course's tester \
                 uses its own {name}, so that difference is not a mistake of yours to find \
                 below: undo the change to {name}",
                on.submitted(),
                with_theirs.against(&on_year)
            ));
            if with_theirs == *theirs {
                break;
            }
        }
    }
    if lines.is_empty() {
        lines.push(format!(
            "your project renders {case_name} otherwise than your {} do on {course}'s own \
             classes ({}), but no one of its course classes alone makes the difference",
            on.submitted(),
            theirs.against(&on_year)
        ));
    }
    Ok(lines)
}

/// Whether two sources are the same code: comments and spacing aside.
fn same_code(a: &[u8], b: &[u8]) -> bool {
    let squeeze = |bytes: &[u8]| -> String {
        blank(&String::from_utf8_lossy(bytes), false)
            .split_whitespace()
            .collect()
    };
    squeeze(a) == squeeze(b)
}

/// One case run on `build`: its image when it wrote one of the year's size. Run as check runs
/// every case (`program::image_of_one_case`), so the two builds are compared on equal terms.
pub fn render(build: &Build, java: &Path, case: &SuiteCase, timeout: u64) -> Result<Rendered> {
    let launch = Plain(build.command(java));
    Ok(match program::image_of_one_case(&launch, case, timeout)? {
        Some(image) => Rendered::Image(image),
        None => Rendered::Nothing,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A clean project of `course` with the student's files (read, never compiled here).
    fn with_student_files(course: Course) -> (tempfile::TempDir, Found) {
        let (dir, found) = super::super::clean_project(course);
        for name in archive::submitted(course) {
            let class = name.trim_end_matches(".java");
            std::fs::write(found.folder.join(name), format!("class {class} {{}}\n"))
                .expect("write");
        }
        let found = super::super::find::find(dir.path(), None).expect("found");
        (dir, found)
    }

    #[test]
    fn only_classes_not_the_year_s_code_are_tried_and_a_bumpy_sphere_is_the_student_s() {
        let (_dir, found) = with_student_files(Course::Y2023);
        let on = OnYear::new(&found, Course::Y2023)
            .expect("read")
            .expect("the student's files");
        assert!(on.edited(&[]).is_empty());
        // The year's stub is not said: it is no work of the student's.
        assert_eq!(on.submitted(), "Sphere.java, Plane.java and Renderer.java");
        let edit = |name: &str, how: &dyn Fn(&str) -> String| {
            let path = found.file(name).expect("a course class");
            let text = std::fs::read_to_string(path).expect("read");
            let edited = how(&text);
            assert_ne!(edited, text, "{name}");
            std::fs::write(path, edited).expect("write");
        };
        edit("SceneLoader.java", &|t| {
            t.replacen("number(e, \"kS\", 1.2)", "0", 1)
        });
        edit("BumpySphere.java", &|t| {
            t.replacen("return new Vector3(0);", "return position;", 1)
        });
        // A comment and blank lines are no edit.
        edit("Camera.java", &|t| format!("// mine\n\n{t}\n\n"));
        let on = OnYear::new(&found, Course::Y2023)
            .expect("read")
            .expect("the student's files");
        assert_eq!(
            on.submitted(),
            "Sphere.java, Plane.java, Renderer.java and BumpySphere.java"
        );
        // A suspect whose code is the year's is not tried; the edited one is, after it.
        assert_eq!(
            on.edited(&["Scene.java".to_string()]),
            vec!["SceneLoader.java"]
        );
        let (_dir, found) = with_student_files(Course::Y2021);
        let on = OnYear::new(&found, Course::Y2021)
            .expect("read")
            .expect("the student's files");
        assert_eq!(on.submitted(), "Sphere.java, Plane.java and Renderer.java");
    }
}
