//! The scene as plain data: validated once when loaded, trusted by everything after.

pub mod input;
pub mod xml;

pub use xml::{load, parse_bytes, parse_str, read_file};

/// The course's Tick 2 scene, compiled in so that `whitted` with no arguments has a scene.
pub const EMBEDDED_TICK2: &str = include_str!("../scenes/tick2.xml");

/// The name messages and EXR headers use for the embedded scene.
pub const EMBEDDED_NAME: &str = "tick2.xml (embedded)";

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
