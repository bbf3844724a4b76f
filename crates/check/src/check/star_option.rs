//! The two options of Tick 1* (docs/courses.md, "Tick 1*") as cases a Tick 1* program is run
//! on instead of the Tick 1 suite: the handout's own scene of each, once. Option 1 (bump
//! mapping) renders `bump.xml`, which reads `bumpmap.png` from the working directory; option 2
//! (distributed ray tracing) renders `distributed.xml`. Neither image is unique (a
//! parametrisation of the student's choice; random rays), so each goes to its own judge, not
//! to the suite's reference.

use std::borrow::Cow;
use std::path::Path;

use crate::check::suite::{self, takes_resolution, Role, SuiteCase};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

const BUMP: &str = include_str!("../../scenes/tick1star/bump.xml");
const DISTRIBUTED: &str = include_str!("../../scenes/tick1star/distributed.xml");
const BUMP_MAP: &[u8] = include_bytes!("../../scenes/tick1star/bumpmap.png");

/// The size a Tick 1* scene is asked for where the program takes `--resolution` (2023-24):
/// a fifth of the year's 800x600 each way, so that 50 lens rays of 10 shadow rays a pixel take
/// seconds, not minutes. Other years' programs render their own size (640x480 or 800x600).
pub const REDUCED: (u32, u32) = (160, 120);

/// At least this long, in seconds, for a Tick 1* case at a year's own size: a correct program
/// takes two to three minutes at 800x600 on a laptop; more when the machine is shared.
pub const LONG_TIMEOUT: u64 = 900;

/// The bounces a Tick 1* case is run with: the skeleton's default, as the handout's
/// screenshot is rendered.
const BOUNCES: u32 = 2;

/// One of Tick 1*'s two options.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StarOption {
    /// Option 1: `BumpySphere.getNormalAt`, on `bump.xml`.
    Bump,
    /// Option 2: soft shadows and depth of field in `Renderer`, on `distributed.xml`.
    Distributed,
}

impl StarOption {
    pub const ALL: [StarOption; 2] = [StarOption::Bump, StarOption::Distributed];

    /// The JSON value and the `--star` argument.
    pub fn name(self) -> &'static str {
        match self {
            StarOption::Bump => "bump",
            StarOption::Distributed => "distributed",
        }
    }

    /// The handout's scene file.
    pub fn file(self) -> &'static str {
        match self {
            StarOption::Bump => "bump.xml",
            StarOption::Distributed => "distributed.xml",
        }
    }

    pub fn xml(self) -> &'static str {
        match self {
            StarOption::Bump => BUMP,
            StarOption::Distributed => DISTRIBUTED,
        }
    }

    /// The files the scene reads beside it, by name: the bump map.
    pub fn assets(self) -> &'static [(&'static str, &'static [u8])] {
        match self {
            StarOption::Bump => &[("bumpmap.png", BUMP_MAP)],
            StarOption::Distributed => &[],
        }
    }

    /// The scene with each file it reads named by its path in `dir` (escaped for XML), for
    /// a program that runs elsewhere.
    pub fn xml_in(self, dir: &Path) -> String {
        self.assets()
            .iter()
            .fold(self.xml().to_string(), |xml, (name, _)| {
                let path = dir.join(name).display().to_string();
                let path = path
                    .replace('&', "&amp;")
                    .replace('"', "&quot;")
                    .replace('<', "&lt;");
                xml.replace(&format!("\"{name}\""), &format!("\"{path}\""))
            })
    }

    /// What the option is, in the report's words.
    pub fn what(self) -> &'static str {
        match self {
            StarOption::Bump => "option 1, bump mapping",
            StarOption::Distributed => "option 2, soft shadows and depth of field",
        }
    }

    /// The option whose handout scene `xml` is, by its content (whitespace aside): a copy of
    /// `distributed.xml` under any name is option 2's random scene, which no deterministic
    /// Tick 1 check can judge. The bump scene is known by its `<bumpy-sphere>` already.
    pub fn of_content(xml: &[u8]) -> Option<StarOption> {
        let bare = |b: &[u8]| -> Vec<u8> {
            b.iter()
                .copied()
                .filter(|c| !c.is_ascii_whitespace())
                .collect()
        };
        let given = bare(xml);
        StarOption::ALL
            .into_iter()
            .find(|o| bare(o.xml().as_bytes()) == given)
    }

    /// The option whose handout scene `file` is (`bump.xml`, `distributed.xml`).
    pub fn of_file(file: &str) -> Option<StarOption> {
        StarOption::ALL.into_iter().find(|o| o.file() == file)
    }
}

/// The size a Tick 1* case of `course` is rendered at: reduced where the program takes
/// `--resolution`, the year's own elsewhere.
pub fn size(course: Course) -> (u32, u32) {
    match takes_resolution(course) {
        true => REDUCED,
        false => course.size(),
    }
}

/// The time a Tick 1* case is given: `asked` where the size is reduced, at least
/// [`LONG_TIMEOUT`] at a year's own size.
pub fn timeout(course: Course, asked: u64) -> u64 {
    match takes_resolution(course) {
        true => asked,
        false => asked.max(LONG_TIMEOUT),
    }
}

/// The cases a Tick 1* program of `course` runs: each option's handout scene, once.
pub fn cases(course: Course) -> Vec<SuiteCase> {
    StarOption::ALL
        .into_iter()
        .map(|option| SuiteCase {
            file: Cow::Borrowed(option.file()),
            xml: Cow::Borrowed(option.xml()),
            bounces: BOUNCES,
            role: Role::Star(option),
            course,
        })
        .collect()
}

/// Writes what a Tick 1* program is run on into `dir` (`--suite-dir`, made if missing): each
/// option's handout scene and the files it reads, refused where a file of the same name holds
/// other content, as the Tick 1 suite's are. bump.xml names its map by its whole path in
/// `dir`: the course's program reads the map from the folder it runs in and whitted reads it
/// beside the scene, and only a whole path is found by both, from anywhere.
pub fn write_scenes(dir: &Path) -> Result<()> {
    let whole = std::path::absolute(dir).map_err(|e| Error::io(dir, "cannot resolve", e))?;
    let scenes: Vec<(StarOption, String)> = StarOption::ALL
        .into_iter()
        .map(|option| (option, option.xml_in(&whole)))
        .collect();
    let mut files: Vec<(&str, &[u8])> = Vec::new();
    for (option, xml) in &scenes {
        files.push((option.file(), xml.as_bytes()));
        files.extend(option.assets().iter().copied());
    }
    suite::write_files(dir, &files)
}

/// What the report says up front of how the options were run.
pub fn plan(course: Course, asked: u64) -> String {
    let (w, h) = size(course);
    let how = match takes_resolution(course) {
        true => format!(
            "at {w}x{h} (--resolution {w}x{h}), {} s each",
            timeout(course, asked)
        ),
        false => format!(
            "at the program's own {w}x{h} (its year has no --resolution), up to {} s each",
            timeout(course, asked)
        ),
    };
    format!(
        "ran the handout's scenes once each instead of the Tick 1 suite: bump.xml (option 1) \
         and distributed.xml (option 2), {how}"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distributed_scene_is_known_by_its_content_under_any_layout() {
        let edited = DISTRIBUTED.replace("    ", "\t").replace("\n", "\r\n");
        assert_eq!(
            StarOption::of_content(edited.as_bytes()),
            Some(StarOption::Distributed)
        );
        let moved = DISTRIBUTED.replace("z=\"12\"", "z=\"13\"");
        assert_eq!(StarOption::of_content(moved.as_bytes()), None);
    }

    #[test]
    fn the_suite_dir_holds_each_scene_and_the_map_named_by_its_whole_path() {
        let dir = tempfile::tempdir().expect("tempdir");
        let suite = dir.path().join("suite");
        write_scenes(&suite).expect("written");
        let bump = std::fs::read_to_string(suite.join("bump.xml")).expect("bump.xml");
        let map = suite.join("bumpmap.png");
        assert!(
            bump.contains(&format!("bump-map=\"{}\"", map.display())),
            "{bump}"
        );
        assert_eq!(std::fs::read(&map).expect("map"), BUMP_MAP);
        assert_eq!(
            std::fs::read_to_string(suite.join("distributed.xml")).expect("distributed"),
            DISTRIBUTED
        );
        // Written again: the same files, left alone.
        write_scenes(&suite).expect("again");
    }

    #[test]
    fn each_option_runs_its_handout_scene_once_at_a_size_that_fits() {
        let cases = cases(Course::Y2023);
        let files: Vec<&str> = cases.iter().map(|c| &*c.file).collect();
        assert_eq!(files, ["bump.xml", "distributed.xml"]);
        assert_eq!(
            cases[0].size_option(),
            Some(["--resolution".to_string(), "160x120".to_string()])
        );
        assert_eq!(cases[1].expected_size(), (160, 120));
        let older = super::cases(Course::Y2020);
        assert_eq!(older[0].size_option(), None);
        assert_eq!(older[1].expected_size(), (640, 480));
        assert_eq!(timeout(Course::Y2020, 60), LONG_TIMEOUT);
        assert_eq!(timeout(Course::Y2023, 60), 60);
        assert!(plan(Course::Y2020, 60).contains("up to 900 s"));
        assert_eq!(StarOption::of_file("bump.xml"), Some(StarOption::Bump));
        // The map the bump scene reads is a PNG, shipped beside it and named by its path.
        assert!(StarOption::Bump.assets()[0].1.starts_with(b"\x89PNG"));
        let xml = StarOption::Bump.xml_in(Path::new("/tmp/a&b"));
        assert!(
            xml.contains("bump-map=\"/tmp/a&amp;b/bumpmap.png\""),
            "{xml}"
        );
    }
}
