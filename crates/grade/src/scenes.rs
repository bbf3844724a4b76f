//! `--scenes DIR`: the course's hidden scene(s) added to the suite, each at the bounces its
//! name says (`hidden_b2.xml` at 2; 2 when the name says none), checked as the suite's own.

use std::borrow::Cow;
use std::path::Path;

use whitted_check::check::suite::{Role, SuiteCase};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::scene::input::parse_for_course;

/// Scenes read from one folder at most.
const MAX_SCENES: usize = 64;
/// A scene file larger than this is refused.
const MAX_BYTES: u64 = 4 << 20;

/// The bounces a scene's file name gives: the number after the last `_b`, else 2.
pub fn bounces_of(file: &str) -> u32 {
    let stem = file.strip_suffix(".xml").unwrap_or(file);
    stem.rsplit_once("_b")
        .and_then(|(_, n)| n.parse::<u32>().ok())
        .filter(|&n| n <= whitted_core::frame::limits::MAX_BOUNCES)
        .unwrap_or(2)
}

/// The `*.xml` scenes of `dir`, by name, each parsed as `course`'s loader reads them (to make
/// sure it can).
pub fn read(dir: &Path, course: Course) -> Result<Vec<SuiteCase>> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::io(dir, "cannot read", e))?;
    let mut paths: Vec<_> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "xml") && p.is_file())
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(Error::Usage(format!(
            "--scenes {}: no .xml scene there",
            dir.display()
        )));
    }
    if paths.len() > MAX_SCENES {
        return Err(Error::Usage(format!(
            "--scenes {}: more than {MAX_SCENES} scenes",
            dir.display()
        )));
    }
    let mut cases = Vec::new();
    for path in paths {
        let len = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        if len > MAX_BYTES {
            return Err(Error::Usage(format!(
                "{}: larger than {MAX_BYTES} bytes",
                path.display()
            )));
        }
        let xml = std::fs::read_to_string(&path).map_err(|e| Error::io(&path, "cannot read", e))?;
        let file = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        parse_for_course(&path.display().to_string(), xml.as_bytes(), course)?;
        cases.push(SuiteCase {
            bounces: bounces_of(&file),
            file: Cow::Owned(file),
            xml: Cow::Owned(xml),
            role: Role::Hidden,
            course,
        });
    }
    Ok(cases)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_name_says_the_bounces() {
        assert_eq!(bounces_of("hidden_b2.xml"), 2);
        assert_eq!(bounces_of("hidden_b0.xml"), 0);
        assert_eq!(bounces_of("big_scene_b5.xml"), 5);
        assert_eq!(bounces_of("hidden.xml"), 2);
        assert_eq!(bounces_of("hidden_bx.xml"), 2);
        assert_eq!(bounces_of("hidden_b99999999999.xml"), 2);
    }
}
