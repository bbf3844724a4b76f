//! The scene as plain data: validated once when loaded, trusted by everything after.

pub mod xml;

pub use xml::{load, parse_bytes, parse_str, read_file};

use crate::course::Course;

/// The course's Tick 2 scene, compiled in so that `whitted` with no arguments has a scene.
pub const EMBEDDED_TICK2: &str = include_str!("../scenes/tick2.xml");

/// The name messages and EXR headers use for the embedded scene.
pub const EMBEDDED_NAME: &str = "tick2.xml (embedded)";

/// A scene read for a command: the scene, the file's bytes (which an EXR's render identity
/// fingerprints), its name as given, and what a course year's loader ignored in it.
pub struct Input {
    pub scene: Scene,
    pub bytes: Vec<u8>,
    pub name: String,
    /// One line each, `file:line:col: ...` (empty under 2016-17, whose format is strict).
    pub warnings: Vec<String>,
}

impl Input {
    /// Tells the user, on stderr, what the year's loader ignored.
    pub fn report_warnings(&self) {
        for warning in &self.warnings {
            eprintln!("warning: {warning}");
        }
    }
}

/// The scene file at `path` read as `course` reads scenes (whitted's strict format for
/// 2016-17, the year's loader otherwise), or the year's own scene when there is none.
pub fn load_input(path: Option<&std::path::Path>, course: Course) -> crate::Result<Input> {
    let (embedded, embedded_name) = course.default_scene();
    let bytes = match path {
        Some(path) => read_file(path)?,
        None => embedded.as_bytes().to_vec(),
    };
    let name = path.map_or(embedded_name.to_string(), |p| p.display().to_string());
    let (scene, mut warnings) = parse_for_course(&name, &bytes, course)?;
    if path.is_none() {
        // The course's own file, read as the course read it: nothing for the user to fix.
        warnings.clear();
    }
    Ok(Input {
        scene,
        bytes,
        name,
        warnings,
    })
}

/// Parses scene bytes named `name` as `course` reads scenes: the scene, and the warnings of a
/// course year's loader.
pub fn parse_for_course(
    name: &str,
    bytes: &[u8],
    course: Course,
) -> crate::Result<(Scene, Vec<String>)> {
    if !course.dialect().course_loader {
        return Ok((parse_bytes(name, bytes)?, Vec::new()));
    }
    let text = xml::utf8(name, bytes)?;
    let read = xml::course::parse(name, text, course)?;
    Ok((read.scene, read.warnings))
}

use glam::DVec3;

/// Everything the renderer needs to know about the world. Objects and lights keep file order,
/// which decides ties between equally distant hits and the order light terms are summed in.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub lights: Vec<PointLight>,
    /// `I_a`, multiplied component-wise with each surface colour.
    pub ambient: DVec3,
}

/// A shape with its surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    pub shape: crate::geometry::Shape,
    pub material: Material,
}

/// Phong coefficients and mirror reflectivity of a surface; `colour` is the diffuse colour C
/// (the specular colour is always white, as in the course).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    pub colour: DVec3,
    pub kd: f64,
    pub ks: f64,
    /// Specular exponent.
    pub n: f64,
    /// Fraction of the outgoing radiance that comes from the mirror direction, in [0, 1].
    pub reflectivity: f64,
}

impl Material {
    /// The course's fixed sphere material (docs/rendering.md, Materials).
    pub const fn sphere(colour: DVec3) -> Self {
        Material {
            colour,
            kd: 0.8,
            ks: 0.8,
            n: 10.0,
            reflectivity: 0.3,
        }
    }

    /// The course's fixed plane material (docs/rendering.md, Materials).
    pub const fn plane(colour: DVec3) -> Self {
        Material {
            colour,
            kd: 0.9,
            ks: 0.0,
            n: 0.0,
            reflectivity: 0.1,
        }
    }
}

/// An isotropic point light. `name` is what its EXR layers are called: the `name` attribute,
/// or its index among point lights when the scene gives none.
#[derive(Debug, Clone, PartialEq)]
pub struct PointLight {
    pub position: DVec3,
    /// Colour c, each channel byte / 255.
    pub colour: DVec3,
    /// Intensity k (power-like; the illumination falls off as k / (4 pi d^2)).
    pub intensity: f64,
    pub name: String,
}

impl PointLight {
    /// Illumination arriving at distance `d`: `c * (k / (PI * 4 * d^2))`, with the scalar
    /// evaluated first and in this order, as the course does (docs/rendering.md, Lights).
    pub fn illumination_at(&self, d: f64) -> DVec3 {
        let falloff = self.intensity / (std::f64::consts::PI * 4.0 * d * d);
        self.colour * falloff
    }
}
