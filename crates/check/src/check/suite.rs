//! The scenes `whitted check --program` runs a student's program on (`scenes/check/`,
//! compiled in so that an installed binary has them). Only what the course's loader reads:
//! spheres, planes, point and ambient lights with their attributes, no materials or names,
//! so that a correct program renders every one. Our own scenes separate the mistakes that the
//! course's two scenes cannot: lights behind and beyond objects, overlapping spheres, mirrors
//! facing each other, a plane close under the camera (see docs/check.md).

use std::borrow::Cow;

use std::path::Path;
use whitted_core::course::Course;

use crate::check::star_option::{self, StarOption};

use whitted_core::error::{Error, Result};

/// What a case is for, which decides what counts towards a grade and what a student may see.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// One of the course's own scenes (`tick2.xml`, `specular_test.xml`): the image the
    /// course's tester wants.
    Course,
    /// One of whitted's scenes that separate the mistakes (`shadows.xml`, `mirrors.xml`): it
    /// informs the diagnosis and the report, and scores nothing unless asked.
    Diagnostic,
    /// A scene the people running the course keep from students (`grade --scenes`): reported
    /// to them by name and verdict only.
    Hidden,
    /// The handout's scene of a Tick 1* option, run instead of the suite for a Tick 1*
    /// program (`star_option.rs`): judged by its option's own check.
    Star(StarOption),
}

impl Role {
    pub fn name(self) -> &'static str {
        match self {
            Role::Course => "course",
            Role::Diagnostic => "diagnostic",
            Role::Hidden => "hidden",
            Role::Star(_) => "tick1-star",
        }
    }
}

/// One case: a scene at a bounce count.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SuiteCase {
    /// The scene's file name: in `scenes/check/`, or of a scene `grade --scenes` adds.
    pub file: Cow<'static, str>,
    pub xml: Cow<'static, str>,
    pub bounces: u32,
    pub role: Role,
    /// The year whose loader reads the scene and whose rules render it.
    pub course: Course,
}

impl SuiteCase {
    /// The size option the year's program takes, `--resolution WxH` (2023-24's `-r`): the
    /// year's own size (a Tick 1* scene's reduced one), asked for explicitly where the
    /// program has the option.
    pub fn size_option(&self) -> Option<[String; 2]> {
        takes_resolution(self.course).then(|| {
            let (w, h) = self.expected_size();
            ["--resolution".to_string(), format!("{w}x{h}")]
        })
    }

    /// The size the case's image must have.
    pub fn expected_size(&self) -> (u32, u32) {
        match self.role {
            Role::Star(_) => star_option::size(self.course),
            _ => self.course.size(),
        }
    }

    /// The scene as written into the case's folder `dir`: a Tick 1* scene's files named by
    /// their paths there, since the program runs in the user's folder, not the case's.
    pub fn xml_in(&self, dir: &Path) -> Cow<'_, str> {
        match self.role {
            Role::Star(option) => Cow::Owned(option.xml_in(dir)),
            _ => Cow::Borrowed(&self.xml),
        }
    }

    /// The files the scene reads beside it (a Tick 1* bump map), by name.
    pub fn assets(&self) -> &'static [(&'static str, &'static [u8])] {
        match self.role {
            Role::Star(option) => option.assets(),
            _ => &[],
        }
    }

    /// `tick2.xml -b 2`.
    pub fn name(&self) -> String {
        format!("{} -b {}", self.file, self.bounces)
    }

    /// The name of the PNG a rerun of this case writes: `shadows_b1.png`.
    pub fn output_name(&self) -> String {
        format!(
            "{}_b{}.png",
            self.file.trim_end_matches(".xml"),
            self.bounces
        )
    }
}

/// Whether `course`'s program takes `--resolution WxH` (2023-24's `-r`).
pub fn takes_resolution(course: Course) -> bool {
    course == Course::Y2023
}

/// Writes every scene of `course`'s suite into `dir` (made if missing), so that a student can
/// rerun and explain each case from their own directory. A file of the same name and content
/// is left as it is; one with other content (another year's) is refused, never replaced.
pub fn write_scenes(dir: &Path, course: Course) -> Result<()> {
    let mut files: Vec<SuiteCase> = cases_of(course);
    files.dedup_by(|a, b| a.file == b.file);
    let files: Vec<(&str, &[u8])> = files
        .iter()
        .map(|case| (&*case.file, case.xml.as_bytes()))
        .collect();
    write_files(dir, &files)
}

/// Writes each `(name, bytes)` into `dir` (made if missing), as `--suite-dir` does: a file
/// of the same name and content is left as it is; if any has other content, every file is
/// refused before one is written, and none is ever replaced.
pub fn write_files(dir: &Path, files: &[(&str, &[u8])]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, "cannot create the directory", e))?;
    let mut missing = Vec::new();
    for &(name, bytes) in files {
        let path = dir.join(name);
        match std::fs::read(&path) {
            Ok(there) if there == bytes => {}
            Ok(_) => {
                return Err(Error::Usage(format!(
                    "{} exists with other content; not replaced (choose another --suite-dir)",
                    path.display()
                )))
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => missing.push((path, bytes)),
            Err(e) => return Err(Error::io(&path, "cannot read", e)),
        }
    }
    for (path, bytes) in missing {
        let mut file = tempfile::NamedTempFile::new_in(dir)
            .map_err(|e| Error::io(dir, "cannot write into", e))?;
        std::io::Write::write_all(&mut file, bytes)
            .map_err(|e| Error::io(&path, "cannot write", e))?;
        file.persist_noclobber(&path)
            .map_err(|e| Error::io(&path, "cannot write", e.error))?;
    }
    Ok(())
}

const TICK2: &str = include_str!("../../scenes/check/tick2.xml");
const SPECULAR_TEST: &str = include_str!("../../scenes/check/specular_test.xml");
const SHADOWS: &str = include_str!("../../scenes/check/shadows.xml");
const MIRRORS: &str = include_str!("../../scenes/check/mirrors.xml");

/// The suite of 2016-17, in the order it runs and is reported.
pub fn cases() -> Vec<SuiteCase> {
    cases_of(Course::Y2016)
}

/// `course`'s suite, in the order it runs and is reported. 2016-17: the course's tick2.xml at
/// 0 to 3 bounces and specular_test.xml, and two scenes of ours that separate mistakes the
/// course's scenes render alike. Later years: the year's own test1 at 0, 1 and 2 bounces (the
/// unfinished reflection renders as 0 does), test2 at the default 2, and the same two scenes
/// of ours.
pub fn cases_of(course: Course) -> Vec<SuiteCase> {
    let case = |file, xml, bounces, role| SuiteCase {
        file: Cow::Borrowed(file),
        xml: Cow::Borrowed(xml),
        bounces,
        role,
        course,
    };
    let Some((test1, test2)) = course_scenes(course) else {
        return vec![
            case("tick2.xml", TICK2, 0, Role::Course),
            case("tick2.xml", TICK2, 1, Role::Course),
            case("tick2.xml", TICK2, 2, Role::Course),
            case("tick2.xml", TICK2, 3, Role::Course),
            case("specular_test.xml", SPECULAR_TEST, 2, Role::Course),
            case("shadows.xml", SHADOWS, 1, Role::Diagnostic),
            case("mirrors.xml", MIRRORS, 3, Role::Diagnostic),
        ];
    };
    let mut suite = vec![
        case("test1.xml", test1, 0, Role::Course),
        case("test1.xml", test1, 1, Role::Course),
        case("test1.xml", test1, 2, Role::Course),
    ];
    suite.extend(test2.map(|xml| case("test2.xml", xml, 2, Role::Course)));
    // Ours, in the attributes every year's loader reads alike: what the year's own scenes
    // cannot show (a plane behind the camera, acne, a mirror's self-reflection).
    suite.push(case("shadows.xml", SHADOWS, 1, Role::Diagnostic));
    suite.push(case("mirrors.xml", MIRRORS, 3, Role::Diagnostic));
    suite
}

/// The course's own test scenes of a later year: test1 and, where the year has one, test2
/// (2017-18's scene is 2016-17's tick2.xml, 2018-19's its tick1.xml).
fn course_scenes(course: Course) -> Option<(&'static str, Option<&'static str>)> {
    match course {
        Course::Y2016 => None,
        Course::Y2017 => Some((TICK2, None)),
        Course::Y2018 => Some((course.default_scene().0, None)),
        Course::Y2019 => Some((
            include_str!("../../scenes/courses/2019-20/test1.xml"),
            Some(include_str!("../../scenes/courses/2019-20/test2.xml")),
        )),
        Course::Y2020 => Some((
            include_str!("../../scenes/courses/2020-21/test1.xml"),
            Some(include_str!("../../scenes/courses/2020-21/test2.xml")),
        )),
        Course::Y2021 | Course::Y2023 => Some((
            include_str!("../../scenes/courses/2021-24/test1.xml"),
            Some(include_str!("../../scenes/courses/2021-24/test2.xml")),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::difference::difference;
    use crate::check::pass_rule::PassRule;
    use crate::check::renderer::Renderer;
    use crate::check::student_png::Rgb8;
    use crate::mistakes::{Bug, Mistakes};

    /// Every case's reference and every mistake's image, at the course's size.
    fn images() -> Vec<(Rgb8, Vec<Rgb8>)> {
        cases()
            .iter()
            .map(|case| {
                let scene = whitted_core::scene::parse_str(&case.file, &case.xml).expect("scene");
                let r = Renderer::new(&scene, 640, 480, case.bounces).expect("renderer");
                let each = Bug::offered(Course::Y2016)
                    .iter()
                    .map(|&b| r.image(Mistakes::of(&[b])).expect("image"))
                    .collect();
                (r.reference().expect("reference"), each)
            })
            .collect()
    }

    #[test]
    fn the_suite_separates_every_mistake() {
        let images = images();
        let catalogue = Bug::offered(Course::Y2016);
        for (i, bug) in catalogue.iter().enumerate() {
            let fails = images.iter().any(|(reference, each)| {
                !difference(&each[i], reference, PassRule::strict(2))
                    .verdict
                    .passes()
            });
            assert!(fails, "{} passes every case of the suite", bug.id());
            for (j, other) in catalogue.iter().enumerate().skip(i + 1) {
                let apart = images.iter().any(|(_, each)| each[i] != each[j]);
                assert!(
                    apart,
                    "{} and {} render the suite alike",
                    bug.id(),
                    other.id()
                );
            }
        }
    }

    #[test]
    fn the_suite_uses_only_what_the_course_loader_reads() {
        let allowed = [
            ("sphere", &["x", "y", "z", "radius", "colour"][..]),
            ("plane", &["x", "y", "z", "nx", "ny", "nz", "colour"][..]),
            ("point-light", &["x", "y", "z", "colour", "intensity"][..]),
            ("ambient-light", &["colour"][..]),
        ];
        for case in cases() {
            for line in case.xml.lines().map(str::trim) {
                let Some(tag) = line.strip_prefix('<').filter(|l| !l.starts_with('/')) else {
                    continue;
                };
                let name = tag
                    .split_whitespace()
                    .next()
                    .unwrap_or("")
                    .trim_end_matches(['>', '/']);
                if name == "scene" {
                    continue;
                }
                let attributes = allowed
                    .iter()
                    .find(|(element, _)| *element == name)
                    .unwrap_or_else(|| panic!("{}: <{name}>", case.file))
                    .1;
                for word in tag.split_whitespace().skip(1) {
                    let attribute = word.split('=').next().unwrap_or("");
                    assert!(
                        attributes.contains(&attribute),
                        "{}: {name} {attribute}",
                        case.file
                    );
                }
            }
        }
    }

    #[test]
    fn a_suite_dir_with_one_clash_is_refused_before_any_file_is_written() {
        let dir = tempfile::tempdir().expect("tempdir");
        std::fs::write(dir.path().join("b.xml"), "other").expect("write");
        let files: [(&str, &[u8]); 2] = [("a.xml", b"a"), ("b.xml", b"b")];
        let refused = write_files(dir.path(), &files);
        assert!(
            matches!(&refused, Err(Error::Usage(m)) if m.contains("b.xml exists with other content")),
            "{refused:?}"
        );
        assert!(!dir.path().join("a.xml").exists());
        // The same content again is no clash: written once, left alone after.
        std::fs::write(dir.path().join("b.xml"), "b").expect("write");
        write_files(dir.path(), &files).expect("written");
        write_files(dir.path(), &files).expect("left alone");
        assert_eq!(std::fs::read(dir.path().join("a.xml")).expect("a"), b"a");
    }

    #[test]
    fn the_course_scenes_are_the_course_s() {
        assert_eq!(TICK2, whitted_core::scene::EMBEDDED_TICK2);
        assert_eq!(
            SPECULAR_TEST,
            include_str!("../../scenes/specular_test.xml")
        );
    }
}
