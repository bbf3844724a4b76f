//! A scene read for a command, as a course year reads scenes: whitted's strict format for
//! 2016-17, the year's own lenient loader otherwise, or the year's own scene when no file is
//! given. It sits above both the scene and the course (which takes its materials from the
//! scene), so that neither depends on the other.

use crate::course::Course;
use crate::error::Result;
use crate::scene::xml::course::BumpRef;
use crate::scene::xml::{self, parse_bytes, read_file};
use crate::scene::Scene;

/// A scene read for a command: the scene, the file's bytes (which an EXR's render identity
/// fingerprints), its name as given, and what a course year's loader ignored in it.
pub struct Input {
    pub scene: Scene,
    pub bytes: Vec<u8>,
    pub name: String,
    /// One line each, `file:line:col: ...` (empty under 2016-17, whose format is strict).
    pub warnings: Vec<String>,
    /// The scene's bumped spheres (Tick 1*), whose maps a command that renders them reads.
    pub bumps: Vec<BumpRef>,
}

impl Input {
    /// Tells the user, on stderr, what the year's loader ignored, and that bumped spheres are
    /// rendered smooth.
    pub fn report_warnings(&self) {
        for warning in self
            .warnings
            .iter()
            .chain(&BumpRef::smooth_warning(&self.bumps))
        {
            eprintln!("warning: {warning}");
        }
    }

    /// `report_warnings` for a command that applies the bump maps.
    pub fn report_warnings_applying_bumps(&self) {
        for warning in &self.warnings {
            eprintln!("warning: {warning}");
        }
    }
}

/// The scene file at `path` read as `course` reads scenes (whitted's strict format for
/// 2016-17, the year's loader otherwise), or the year's own scene when there is none.
pub fn load_input(path: Option<&std::path::Path>, course: Course) -> Result<Input> {
    let read = path.map(read_file).transpose()?;
    input_of(path, read, course)
}

/// As [`load_input`], with the file at `path` already read into `read` (both None: the
/// course's own scene): a caller that looked at the bytes first (which year is this
/// scene?) does not read the file twice.
pub fn input_of(
    path: Option<&std::path::Path>,
    read: Option<Vec<u8>>,
    course: Course,
) -> Result<Input> {
    let (embedded, embedded_name) = course.default_scene();
    let bytes = read.unwrap_or_else(|| embedded.as_bytes().to_vec());
    let name = path.map_or(embedded_name.to_string(), |p| p.display().to_string());
    let (scene, mut warnings, bumps) = parse_with_bumps(&name, &bytes, course)?;
    if path.is_none() {
        // The course's own file, read as the course read it: nothing for the user to fix.
        warnings.clear();
    }
    Ok(Input {
        scene,
        bytes,
        name,
        warnings,
        bumps,
    })
}

/// Parses scene bytes named `name` as `course` reads scenes: the scene, and the warnings of a
/// course year's loader.
/// Bumped spheres are rendered smooth, with a warning.
pub fn parse_for_course(name: &str, bytes: &[u8], course: Course) -> Result<(Scene, Vec<String>)> {
    let (scene, mut warnings, bumps) = parse_with_bumps(name, bytes, course)?;
    warnings.extend(BumpRef::smooth_warning(&bumps));
    Ok((scene, warnings))
}

/// `parse_for_course` with the bumped spheres apart, for a command that renders their maps.
pub fn parse_with_bumps(
    name: &str,
    bytes: &[u8],
    course: Course,
) -> Result<(Scene, Vec<String>, Vec<BumpRef>)> {
    if !course.dialect().course_loader {
        return Ok((parse_bytes(name, bytes)?, Vec::new(), Vec::new()));
    }
    let text = xml::utf8(name, bytes)?;
    let read = xml::course::parse(name, text, course)?;
    Ok((read.scene, read.warnings, read.bumps))
}
