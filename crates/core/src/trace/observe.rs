//! What `trace` can tell an observer while it works: every vertex of the mirror chain and
//! every light's terms there, exactly the values the beauty is made of. The renderer observes
//! nothing (`Silent`, compiled away); `explain` records a pixel's ray tree.

use glam::DVec3;

use crate::geometry::{Hit, Ray};
use crate::scene::Material;

/// One surface point of a mirror chain.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexRecord {
    /// 0 for the camera's hit, k after k reflections.
    pub depth: u32,
    pub ray: Ray,
    /// Index into the scene's objects.
    pub object: usize,
    pub distance: f64,
    pub point: DVec3,
    pub normal: DVec3,
    pub material: Material,
    /// `w_k`: the share of the pixel this vertex's shading makes up.
    pub weight: f64,
    /// The reflected ray as the trace spawned it, where the chain goes on from here (a mirror
    /// with bounces left).
    pub spawned: Option<Ray>,
    /// The ambient term as the trace computed it.
    pub ambient: DVec3,
    /// The shaded colour (ambient plus every light that is not in shadow).
    pub colour: DVec3,
}

/// One light's terms at a vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct LightRecord {
    pub depth: u32,
    /// Index into the scene's lights.
    pub light: usize,
    /// `d`, `I = c * k / (4 pi d^2)`, `L`, `max(0, N.L)`, `max(0, R.V)`.
    pub distance: f64,
    pub illumination: DVec3,
    pub to_light: DVec3,
    pub n_dot_l: f64,
    /// `R`, the mirror of `L` the specular term uses, and `V`, towards the viewer.
    pub mirror: DVec3,
    pub view: DVec3,
    pub r_dot_v: f64,
    pub diffuse: DVec3,
    pub specular: DVec3,
    /// Whether the light reaches the point at all (`Model::reaches`): where it does not, its
    /// terms are zero and no shadow ray is cast.
    pub reaches: bool,
    /// The shadow ray as spawned, if shadows are tested, and whether something blocks it.
    pub shadow_ray: Option<Ray>,
    pub in_shadow: bool,
    /// What blocks it: the nearest hit before the light, for an observer that
    /// `RECORDS_OCCLUDERS` (else `None`).
    pub occluder: Option<Hit>,
}

/// One step of the beauty's fold, far end first: `result = colour * (1 - r) + reflected * r`
/// where the chain continues (`reflectivity` is `Some(r)`), else `result = colour`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldStep {
    pub depth: u32,
    pub colour: DVec3,
    pub reflectivity: Option<f64>,
    /// What arrives from further along the chain.
    pub reflected: DVec3,
    pub result: DVec3,
}

/// Receives what `trace` computes; every method does nothing by default.
pub trait Observer {
    /// Whether the shadow test should find the nearest occluder (a full closest-hit search)
    /// instead of stopping at the first one: the same answer, for an observer that shows it.
    const RECORDS_OCCLUDERS: bool = false;

    /// Whether the observer reads a shadowed light's terms. The renderer's does not: a light
    /// in shadow adds nothing to the pixel, so its diffuse and specular terms (the specular's
    /// `pow` among them) are then left at zero in the record rather than computed.
    const READS_SHADOWED_TERMS: bool = true;

    fn fold(&mut self, _step: FoldStep) {}
    fn light(&mut self, _record: LightRecord) {}
    fn vertex(&mut self, _record: VertexRecord) {}
    /// The chain left the scene at this depth along `ray`.
    fn miss(&mut self, _depth: u32, _ray: Ray) {}
}

/// The renderer's observer: nothing.
pub struct Silent;

impl Observer for Silent {
    const READS_SHADOWED_TERMS: bool = false;
}
