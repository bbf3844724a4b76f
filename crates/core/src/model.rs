//! The seam in the tick model (docs/rendering.md): every rule a student's Tick 2 can get wrong
//! is one method of [`Model`], and the default method *is* the course's rule. `trace`, `shade`
//! and the hit searches are generic over the model and monomorphised, so [`Tick`] compiles to
//! the renderer's own code, while [`whitted_check::mistakes::Mistakes`] overrides the rules a
//! student got wrong (`whitted check`) without a second copy of the shading.
//!
//! Mistakes that are options rather than rules (one bounce more or fewer, no shadow rays)
//! change the frame instead (`Mistakes::frame_spec`).

pub mod rounding;
pub mod search;

use glam::DVec3;

use crate::geometry::{
    divide_by_length, normalise, plane_parameter, sphere_hit, Ray, SphereTerms, EPSILON,
};
use crate::scene::PointLight;
use crate::trace::java_max_zero;

/// The radiance of every ray that leaves the scene under the course's 2016-17 rules.
pub const BACKGROUND: DVec3 = DVec3::splat(0.1);

/// The course's rules, one method each. Each default is the rule of docs/rendering.md in its
/// operation order; an implementation overrides only the rules it changes.
pub trait Model: Sync {
    /// Whether the hierarchy's exactness argument (`accel/margin.rs`) covers this model's
    /// hits: it assumes sphere hits at a root of the course's quadratic (near, or far as the
    /// later years take it) and planes ahead of the ray. A model that accepts other hits is
    /// rendered with brute force.
    fn hierarchy_exact(&self) -> bool {
        true
    }

    /// The ray parameter at which `ray` hits the sphere, if it does: the near root, if > 0.
    fn sphere_root(
        &self,
        ray: &Ray,
        terms: &SphereTerms,
        centre: DVec3,
        radius_squared: f64,
    ) -> Option<f64> {
        sphere_hit(ray, terms, centre, radius_squared)
    }

    /// Whether a ray that starts inside a sphere hits it (the far root when the near one is
    /// not > 0). Only the rounding rule asks (`rounding::sphere_root_taken`): `sphere_root`
    /// is what the hit search calls.
    fn far_root(&self) -> bool {
        false
    }

    /// Whether a plane hit at parameter `s` counts: finite and not behind the ray.
    fn plane_accepts(&self, s: f64) -> bool {
        s.is_finite() && s >= 0.0
    }

    /// The parameter at which `ray` hits the plane through `point` with `normal`, if it
    /// counts: `s = ((Q - O).N) / (D.N)` when [`Model::plane_accepts`] it.
    fn plane_root(&self, ray: &Ray, point: DVec3, normal: DVec3) -> Option<f64> {
        let s = plane_parameter(point, normal, ray);
        self.plane_accepts(s).then_some(s)
    }

    /// How the shadow ray towards light `_light` (its index in the scene) takes roots that
    /// hinge on rounding (`rounding.rs`): as the model's own arithmetic has them.
    fn self_hits_toward(&self, _light: usize) -> rounding::SelfHit {
        rounding::SelfHit::Exact
    }

    /// `max(0, R.V)` before the specular exponent, as Java's `Math.max(0, x)` does.
    fn clamp_r_dot_v(&self, r_dot_v: f64) -> f64 {
        java_max_zero(r_dot_v)
    }

    /// The radiance of a ray that leaves the scene: 0.1 on every channel.
    fn background(&self) -> DVec3 {
        BACKGROUND
    }

    /// Whether a light reaches a point at all, from the raw (unclamped) `N.L`: always. A model
    /// that says no adds neither diffuse nor specular for it and casts no shadow ray.
    fn reaches(&self, _n_dot_l: f64) -> bool {
        true
    }

    /// The lights that shade a point: all of them, in file order.
    fn lights<'a>(&self, lights: &'a [PointLight]) -> &'a [PointLight] {
        lights
    }

    /// `I` at distance `d`: `c * (k / (4 pi d^2))`.
    fn illumination(&self, light: &PointLight, d: f64) -> DVec3 {
        light.illumination_at(d)
    }

    /// `L` from `X - P` and its length `d`: normalised.
    fn to_light(&self, to_light: DVec3, d: f64) -> DVec3 {
        divide_by_length(to_light, d)
    }

    /// `V` at `p`, hit by a ray from `_ray_origin`: towards the camera at the origin, even for
    /// reflected rays (the reference does this).
    fn view(&self, p: DVec3, _ray_origin: DVec3) -> DVec3 {
        normalise(-p)
    }

    /// `R`, the mirror of `L` for the specular term, from the clamped `N.L`.
    fn specular_mirror(&self, n: DVec3, l: DVec3, n_dot_l: f64) -> DVec3 {
        n * (2.0 * n_dot_l) - l
    }

    /// The offset along a shadow or reflected ray at which it starts: `EPSILON`.
    fn epsilon(&self) -> f64 {
        EPSILON
    }

    /// The specular exponent used for a material whose exponent is `n`: `n` itself.
    fn specular_exponent(&self, n: f64) -> f64 {
        n
    }

    /// The reflectivity used for a material whose reflectivity is `r`: `r` itself.
    fn reflectivity(&self, r: f64) -> f64 {
        r
    }

    /// The ambient term `I_a * C`.
    fn ambient(&self, ambient_light: DVec3, colour: DVec3) -> DVec3 {
        ambient_light * colour
    }

    /// `((C * I) * kD) * max(0, N.L)`.
    fn diffuse(&self, colour: DVec3, illumination: DVec3, kd: f64, n_dot_l: f64) -> DVec3 {
        ((colour * illumination) * kd) * n_dot_l
    }

    /// `(I * kS) * max(0, R.V)^n`, white; `light`, `colour` and `n_dot_l` are there for the
    /// rules that differ (later years colour it with the light's colour).
    fn specular(
        &self,
        _light: &PointLight,
        illumination: DVec3,
        ks: f64,
        phong: f64,
        _colour: DVec3,
        _n_dot_l: f64,
    ) -> DVec3 {
        illumination * ks * phong
    }

    /// The shadow ray towards a light along `l` from `p` with normal `_n`: started `EPSILON`
    /// along `l`.
    fn shadow_ray(&self, p: DVec3, l: DVec3, _n: DVec3) -> Ray {
        Ray::offset_by(p, l, self.epsilon())
    }

    /// How far along the shadow ray a hit shadows the point: up to the light, `d`.
    fn shadow_reach(&self, d: f64) -> f64 {
        d
    }

    /// The colour after a light that is not in shadow: `(colour + diffuse) + specular`.
    fn add_light(&self, colour: DVec3, _ambient: DVec3, diffuse: DVec3, specular: DVec3) -> DVec3 {
        (colour + diffuse) + specular
    }

    /// The reflected ray at `p` with normal `n` for a ray along `d`: `-d` mirrored about `n`,
    /// started `EPSILON` along it.
    fn mirror_ray(&self, p: DVec3, d: DVec3, n: DVec3) -> Ray {
        Ray::offset_by(p, mirror_direction(d, n), self.epsilon())
    }

    /// A mirror's colour from its own shading and what it reflects:
    /// `direct * (1 - r) + reflected * r`.
    fn blend(&self, direct: DVec3, reflected: DVec3, r: f64) -> DVec3 {
        direct * (1.0 - r) + reflected * r
    }
}

/// The course's model, every rule as docs/rendering.md states it: what `render` draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tick;

impl Model for Tick {}

/// The direction a ray along `d` leaves a mirror with normal `n`: `-d` reflected about `n`,
/// `2 (n . -d) n - (-d)`, normalised as the course does.
#[inline]
pub fn mirror_direction(d: DVec3, n: DVec3) -> DVec3 {
    let to_eye = -d;
    normalise(n * (2.0 * n.dot(to_eye)) - to_eye)
}
