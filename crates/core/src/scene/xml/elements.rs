//! One function per scene element: read its attributes, check what the format requires, add
//! it to the scene being built.

use std::collections::HashMap;

use glam::DVec3;
use quick_xml::events::BytesStart;

use super::attributes::{read_attributes, trimmed};
use super::key::Key;
use super::source::{shown, Source};
use crate::error::Result;
use crate::geometry::{normalise, Shape};
use crate::numbers::exact;
use crate::scene::{Material, Object, PointLight, Scene};
use crate::suggest;

pub(super) const ELEMENTS: [&str; 4] = ["sphere", "plane", "point-light", "ambient-light"];
const MATERIAL_ATTRIBUTES: [Key; 4] = [Key::KD, Key::KS, Key::N, Key::Reflectivity];
const SPHERE_ATTRIBUTES: [Key; 5] = [Key::X, Key::Y, Key::Z, Key::Radius, Key::Colour];
const PLANE_ATTRIBUTES: [Key; 7] = [
    Key::X,
    Key::Y,
    Key::Z,
    Key::Nx,
    Key::Ny,
    Key::Nz,
    Key::Colour,
];
const LIGHT_ATTRIBUTES: [Key; 6] = [
    Key::X,
    Key::Y,
    Key::Z,
    Key::Colour,
    Key::Intensity,
    Key::Name,
];
const AMBIENT_ATTRIBUTES: [Key; 1] = [Key::Colour];

/// Longest light name (docs/scene-format.md): names become EXR layer names such as
/// `unshadowed_<name>`, and this keeps them short.
pub const MAX_LIGHT_NAME: usize = 16;

/// A plane normal shorter than this cannot be normalised meaningfully.
const MIN_NORMAL_LENGTH: f64 = 1e-12;

/// The scene as it is being read, plus what is needed to reject repeats.
#[derive(Default)]
pub(super) struct SceneBuilder {
    pub(super) objects: Vec<Object>,
    pub(super) lights: Vec<PointLight>,
    ambient: Option<DVec3>,
    ambient_at: Option<usize>,
    light_names: HashMap<String, usize>,
}

/// An element inside `<scene>`: its tag and where its `<` is.
pub(super) struct Element<'e, 'a> {
    pub(super) tag: &'e BytesStart<'e>,
    pub(super) name: &'e str,
    pub(super) offset: usize,
    pub(super) source: Source<'a>,
}

impl SceneBuilder {
    /// Adds the element `e` to the scene, or says why it cannot be.
    pub(super) fn add(&mut self, e: &Element) -> Result<()> {
        if let Some(object) = object(e) {
            self.objects.push(object?);
            return Ok(());
        }
        match e.name {
            "point-light" => self.point_light(e),
            "ambient-light" => self.ambient_light(e),
            other => {
                let hint = match suggest::nearest(other, &ELEMENTS) {
                    Some(s) => format!("did you mean <{s}>? "),
                    None => String::new(),
                };
                Err(e.source.error_at(
                    e.offset,
                    format!(
                        "unknown element <{}> ({hint}expected one of <{}>){}",
                        shown(other),
                        ELEMENTS.join(">, <"),
                        if other == "bumpy-sphere" {
                            "; <bumpy-sphere> is the course's Tick 1*: give --course YEAR \
                             (docs/courses.md)"
                        } else {
                            ""
                        }
                    ),
                ))
            }
        }
    }
}

/// Whether an element named `name` counts towards `MAX_ELEMENTS`: objects and lights.
pub(super) fn is_counted(name: &str) -> bool {
    is_object(name) || name == "point-light"
}

/// Whether an element named `name` is an object (`object` reads it).
fn is_object(name: &str) -> bool {
    matches!(name, "sphere" | "plane")
}

/// The object an element describes, if it is one (`<sphere>`, `<plane>`): these need nothing
/// from the rest of the scene, so many can be read at once.
pub(super) fn object(e: &Element) -> Option<Result<Object>> {
    match e.name {
        "sphere" => Some(sphere(e)),
        "plane" => Some(plane(e)),
        _ => None,
    }
}

fn sphere(e: &Element) -> Result<Object> {
    let allowed = [&SPHERE_ATTRIBUTES[..], &MATERIAL_ATTRIBUTES];
    let a = read_attributes(e.source, e.tag, e.name, &allowed)?;
    let colour = a.required_colour(e.offset)?;
    let radius = a.length(Key::Radius, 1.0)?;
    if radius <= 0.0 {
        return Err(a.error(
            Key::Radius,
            format!("`radius` must be > 0, got {}", exact(radius)),
        ));
    }
    let shape = Shape::Sphere {
        centre: a.position()?,
        radius,
    };
    let material = a.material(Material::sphere(colour))?;
    Ok(Object { shape, material })
}

fn plane(e: &Element) -> Result<Object> {
    let allowed = [&PLANE_ATTRIBUTES[..], &MATERIAL_ATTRIBUTES];
    let a = read_attributes(e.source, e.tag, e.name, &allowed)?;
    let colour = a.required_colour(e.offset)?;
    let n = DVec3::new(
        a.number(Key::Nx, 0.0)?,
        a.number(Key::Ny, 0.0)?,
        a.number(Key::Nz, 0.0)?,
    );
    if n.length().is_infinite() {
        return Err(e.source.error_at(
            e.offset,
            format!(
                "<plane> normal (nx, ny, nz) = ({}, {}, {}) is too long to normalise (its \
                     length overflows; scale it down, only its direction matters)",
                exact(n.x),
                exact(n.y),
                exact(n.z)
            ),
        ));
    }
    if n.length().is_nan() || n.length() <= MIN_NORMAL_LENGTH {
        return Err(e.source.error_at(
            e.offset,
            format!(
                "<plane> normal (nx, ny, nz) = ({}, {}, {}) has (near) zero length \
                     (give nx, ny, nz for a non-zero normal)",
                exact(n.x),
                exact(n.y),
                exact(n.z)
            ),
        ));
    }
    let shape = Shape::Plane {
        point: a.position()?,
        normal: normalise(n),
    };
    let material = a.material(Material::plane(colour))?;
    Ok(Object { shape, material })
}

impl SceneBuilder {
    fn point_light(&mut self, e: &Element) -> Result<()> {
        let a = read_attributes(e.source, e.tag, e.name, &[&LIGHT_ATTRIBUTES])?;
        let colour = a.required_colour(e.offset)?;
        let intensity = a.number(Key::Intensity, 100.0)?;
        if intensity < 0.0 {
            return Err(a.error(
                Key::Intensity,
                format!("`intensity` must be >= 0, got {}", exact(intensity)),
            ));
        }
        let index = self.lights.len();
        let name = match a.get(Key::Name) {
            Some(attr) => {
                let name = trimmed(&attr.value);
                self.check_light_name(&e.source, name, attr.offset)?;
                name.to_string()
            }
            None => index.to_string(),
        };
        let position = a.position()?;
        self.lights.push(PointLight {
            position,
            colour,
            intensity,
            name,
        });
        Ok(())
    }

    fn ambient_light(&mut self, e: &Element) -> Result<()> {
        let a = read_attributes(e.source, e.tag, e.name, &[&AMBIENT_ATTRIBUTES])?;
        if let Some(first) = self.ambient_at {
            return Err(e.source.error_at(
                e.offset,
                format!(
                    "a second <ambient-light> (the first is at {}; a scene has at most one)",
                    e.source.position(first)
                ),
            ));
        }
        self.ambient = Some(a.required_colour(e.offset)?);
        self.ambient_at = Some(e.offset);
        Ok(())
    }

    pub(super) fn check_light_name(
        &mut self,
        source: &Source,
        name: &str,
        offset: usize,
    ) -> Result<()> {
        let mut chars = name.chars();
        let well_formed = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
            && name.len() <= MAX_LIGHT_NAME;
        if !well_formed {
            return Err(source.error_at(
                offset,
                format!(
                    "light name `{}` must be a letter followed by letters, digits or _ \
                     ([A-Za-z][A-Za-z0-9_]*), at most {MAX_LIGHT_NAME} characters",
                    shown(name)
                ),
            ));
        }
        if let Some(&first) = self.light_names.get(name) {
            return Err(source.error_at(
                offset,
                format!(
                    "duplicate light name `{name}` (first used at {}; names must be unique)",
                    source.position(first)
                ),
            ));
        }
        self.light_names.insert(name.to_string(), offset);
        Ok(())
    }

    pub(super) fn finish(self) -> Scene {
        Scene {
            objects: self.objects,
            lights: self.lights,
            ambient: self.ambient.unwrap_or(DVec3::ONE),
        }
    }
}
