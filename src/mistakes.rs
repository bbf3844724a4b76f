//! The catalogue of classic Tick 2 mistakes (docs/check.md): each is one rule of the model
//! done wrong, with a stable id. [`Mistakes`] is a set of them and a [`Model`] that breaks
//! exactly those rules; every other rule is the course's own ([`Tick`]'s default). Sets, not
//! one type per mistake, because students often have two at once and the diagnosis ranks
//! every pair: one monomorphised model whose rules test a bit, instead of 21 x 21 types.

use glam::DVec3;

use crate::frame::limits::MAX_BOUNCES;
use crate::frame::{Acceleration, FrameSpec};
use crate::geometry::{normalise, sphere_far_hit, Ray, SphereTerms};
use crate::model::{mirror_direction, Model, Tick};
use crate::scene::PointLight;

/// One catalogued mistake. The order is the catalogue's (`whitted check --list-bugs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Bug {
    ReflectUnclamped,
    SpecularGated,
    ViewFromRayOrigin,
    ViewFlipped,
    LightUnnormalised,
    NoFalloff,
    NoAmbient,
    DiffuseNoColour,
    SpecularObjectColour,
    FirstLightOnly,
    LastLightWins,
    NoShadows,
    NoShadowBias,
    ShadowAnyHit,
    NoReflectionBias,
    ReflectionWrongSign,
    ReflectionUnweighted,
    BouncesPlusOne,
    BouncesMinusOne,
    PlaneBehind,
    SphereFarRoot,
}

impl Bug {
    /// Every mistake, in catalogue order.
    pub const ALL: [Bug; 21] = [
        Bug::ReflectUnclamped,
        Bug::SpecularGated,
        Bug::ViewFromRayOrigin,
        Bug::ViewFlipped,
        Bug::LightUnnormalised,
        Bug::NoFalloff,
        Bug::NoAmbient,
        Bug::DiffuseNoColour,
        Bug::SpecularObjectColour,
        Bug::FirstLightOnly,
        Bug::LastLightWins,
        Bug::NoShadows,
        Bug::NoShadowBias,
        Bug::ShadowAnyHit,
        Bug::NoReflectionBias,
        Bug::ReflectionWrongSign,
        Bug::ReflectionUnweighted,
        Bug::BouncesPlusOne,
        Bug::BouncesMinusOne,
        Bug::PlaneBehind,
        Bug::SphereFarRoot,
    ];

    /// The stable id of docs/check.md.
    pub fn id(self) -> &'static str {
        self.entry().0
    }

    /// The mistake in one line, stated against docs/rendering.md.
    pub fn description(self) -> &'static str {
        self.entry().1
    }

    fn entry(self) -> (&'static str, &'static str) {
        match self {
            Bug::ReflectUnclamped => ("reflect-unclamped", "specular mirror direction R built from the unclamped N.L (the plain reflection of L)"),
            Bug::SpecularGated => ("specular-gated", "specular added only where N.L > 0"),
            Bug::ViewFromRayOrigin => ("view-from-ray-origin", "V points to the ray's origin, not to the camera, for reflected rays"),
            Bug::ViewFlipped => ("view-flipped", "V = normalise(P) instead of normalise(-P)"),
            Bug::LightUnnormalised => ("light-unnormalised", "L = light position - P, not normalised (in N.L and R)"),
            Bug::NoFalloff => ("no-falloff", "light intensity without the 1/(4 pi d^2) falloff"),
            Bug::NoAmbient => ("no-ambient", "ambient term missing"),
            Bug::DiffuseNoColour => ("diffuse-no-colour", "diffuse term not multiplied by the object colour"),
            Bug::SpecularObjectColour => ("specular-object-colour", "specular term multiplied by the object colour"),
            Bug::FirstLightOnly => ("first-light-only", "only the first point light is used"),
            Bug::LastLightWins => ("last-light-wins", "each light replaces the colour (ambient + its terms) instead of adding to it"),
            Bug::NoShadows => ("no-shadows", "shadow rays never cast"),
            Bug::NoShadowBias => ("no-shadow-bias", "shadow ray starts at P, without the EPSILON offset (shadow acne)"),
            Bug::ShadowAnyHit => ("shadow-any-hit", "in shadow whenever the shadow ray hits anything, even beyond the light"),
            Bug::NoReflectionBias => ("no-reflection-bias", "reflected ray starts at P, without the EPSILON offset"),
            Bug::ReflectionWrongSign => ("reflection-wrong-sign", "reflected direction is D mirrored in N, without negating D first"),
            Bug::ReflectionUnweighted => ("reflection-unweighted", "returns direct + reflectivity * reflected (direct not scaled by 1 - r)"),
            Bug::BouncesPlusOne => ("bounces-plus-one", "one more reflection bounce than --bounces"),
            Bug::BouncesMinusOne => ("bounces-minus-one", "one bounce fewer than --bounces"),
            Bug::PlaneBehind => ("plane-behind", "plane hits with s < 0 accepted (planes behind the ray's origin)"),
            Bug::SphereFarRoot => ("sphere-far-root", "the sphere takes the far root when the near one is not > 0, so a ray from inside hits it"),
        }
    }

    /// The mistake with this id.
    pub fn from_id(id: &str) -> Option<Bug> {
        Bug::ALL.into_iter().find(|b| b.id() == id)
    }

    fn bit(self) -> u32 {
        1 << self as u32
    }
}

/// A set of mistakes, and the model that makes exactly those. The empty set is the course's
/// model (the same bits as [`Tick`], a little slower: every rule tests its bit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct Mistakes(u32);

impl Mistakes {
    pub const NONE: Mistakes = Mistakes(0);

    pub fn of(bugs: &[Bug]) -> Self {
        Mistakes(bugs.iter().fold(0, |set, b| set | b.bit()))
    }

    pub fn has(self, bug: Bug) -> bool {
        self.0 & bug.bit() != 0
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The mistakes in catalogue order.
    pub fn bugs(self) -> Vec<Bug> {
        Bug::ALL.into_iter().filter(|&b| self.has(b)).collect()
    }

    /// The ids, in catalogue order.
    pub fn ids(self) -> Vec<&'static str> {
        self.bugs().into_iter().map(Bug::id).collect()
    }

    /// The frame a program with these mistakes renders when asked for `spec`: the
    /// option-shaped mistakes change it (bounces, shadows), and a model the hierarchy is not
    /// exact for is traced by brute force.
    pub fn frame_spec(self, spec: &FrameSpec) -> FrameSpec {
        let mut bounces = spec.bounces;
        if self.has(Bug::BouncesPlusOne) {
            // At the limit a program cannot be asked for more: there it is the same as asked.
            bounces = (bounces + 1).min(MAX_BOUNCES);
        }
        if self.has(Bug::BouncesMinusOne) {
            bounces = bounces.saturating_sub(1);
        }
        FrameSpec {
            bounces,
            shadows: spec.shadows && !self.has(Bug::NoShadows),
            acceleration: if self.hierarchy_exact() {
                spec.acceleration
            } else {
                Acceleration::BruteForce
            },
            ..spec.clone()
        }
    }
}

impl Model for Mistakes {
    fn hierarchy_exact(&self) -> bool {
        !self.has(Bug::PlaneBehind) && !self.has(Bug::SphereFarRoot)
    }

    fn sphere_root(
        &self,
        ray: &Ray,
        terms: &SphereTerms,
        centre: DVec3,
        radius_squared: f64,
    ) -> Option<f64> {
        // The handout read literally: the near root if positive, else the far one.
        let near = Tick.sphere_root(ray, terms, centre, radius_squared);
        if self.has(Bug::SphereFarRoot) {
            near.or_else(|| sphere_far_hit(ray, terms, centre, radius_squared))
        } else {
            near
        }
    }

    fn plane_accepts(&self, s: f64) -> bool {
        if self.has(Bug::PlaneBehind) {
            s.is_finite()
        } else {
            Tick.plane_accepts(s)
        }
    }

    fn lights<'a>(&self, lights: &'a [PointLight]) -> &'a [PointLight] {
        if self.has(Bug::FirstLightOnly) {
            &lights[..lights.len().min(1)]
        } else {
            lights
        }
    }

    fn illumination(&self, light: &PointLight, d: f64) -> DVec3 {
        if self.has(Bug::NoFalloff) {
            light.colour * light.intensity
        } else {
            Tick.illumination(light, d)
        }
    }

    fn to_light(&self, to_light: DVec3, d: f64) -> DVec3 {
        if self.has(Bug::LightUnnormalised) {
            to_light
        } else {
            Tick.to_light(to_light, d)
        }
    }

    fn view(&self, p: DVec3, ray_origin: DVec3) -> DVec3 {
        if self.has(Bug::ViewFlipped) {
            normalise(p)
        } else if self.has(Bug::ViewFromRayOrigin) {
            normalise(ray_origin - p)
        } else {
            Tick.view(p, ray_origin)
        }
    }

    fn specular_mirror(&self, n: DVec3, l: DVec3, n_dot_l: f64) -> DVec3 {
        if self.has(Bug::ReflectUnclamped) {
            n * (2.0 * n.dot(l)) - l
        } else {
            Tick.specular_mirror(n, l, n_dot_l)
        }
    }

    fn ambient(&self, ambient_light: DVec3, colour: DVec3) -> DVec3 {
        if self.has(Bug::NoAmbient) {
            DVec3::ZERO
        } else {
            Tick.ambient(ambient_light, colour)
        }
    }

    fn diffuse(&self, colour: DVec3, illumination: DVec3, kd: f64, n_dot_l: f64) -> DVec3 {
        if self.has(Bug::DiffuseNoColour) {
            (illumination * kd) * n_dot_l
        } else {
            Tick.diffuse(colour, illumination, kd, n_dot_l)
        }
    }

    fn specular(
        &self,
        illumination: DVec3,
        ks: f64,
        phong: f64,
        colour: DVec3,
        n_dot_l: f64,
    ) -> DVec3 {
        // The clamped N.L is 0 where the raw one is <= 0; a NaN one adds no specular either.
        let lit = n_dot_l.partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater);
        let gated = self.has(Bug::SpecularGated) && !lit;
        let specular = if gated {
            DVec3::ZERO
        } else {
            Tick.specular(illumination, ks, phong, colour, n_dot_l)
        };
        if self.has(Bug::SpecularObjectColour) {
            specular * colour
        } else {
            specular
        }
    }

    fn shadow_ray(&self, p: DVec3, l: DVec3) -> Ray {
        if self.has(Bug::NoShadowBias) {
            Ray::new(p, l)
        } else {
            Tick.shadow_ray(p, l)
        }
    }

    fn shadow_reach(&self, d: f64) -> f64 {
        if self.has(Bug::ShadowAnyHit) {
            f64::INFINITY
        } else {
            Tick.shadow_reach(d)
        }
    }

    fn add_light(&self, colour: DVec3, ambient: DVec3, diffuse: DVec3, specular: DVec3) -> DVec3 {
        let base = if self.has(Bug::LastLightWins) {
            ambient
        } else {
            colour
        };
        Tick.add_light(base, ambient, diffuse, specular)
    }

    fn mirror_ray(&self, p: DVec3, d: DVec3, n: DVec3) -> Ray {
        let direction = if self.has(Bug::ReflectionWrongSign) {
            normalise(n * (2.0 * n.dot(d)) - d)
        } else {
            mirror_direction(d, n)
        };
        if self.has(Bug::NoReflectionBias) {
            Ray::new(p, direction)
        } else {
            Ray::offset_from(p, direction)
        }
    }

    fn blend(&self, direct: DVec3, reflected: DVec3, r: f64) -> DVec3 {
        if self.has(Bug::ReflectionUnweighted) {
            direct + reflected * r
        } else {
            Tick.blend(direct, reflected, r)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_unique_and_round_trip() {
        let mut ids: Vec<&str> = Bug::ALL.iter().map(|b| b.id()).collect();
        for (i, bug) in Bug::ALL.iter().enumerate() {
            assert_eq!(Bug::from_id(bug.id()), Some(*bug));
            assert_eq!(*bug as usize, i, "ALL is in declaration order");
        }
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), 21);
    }

    #[test]
    fn sets_hold_their_bugs_in_catalogue_order() {
        let set = Mistakes::of(&[Bug::SphereFarRoot, Bug::NoAmbient]);
        assert_eq!(set.bugs(), vec![Bug::NoAmbient, Bug::SphereFarRoot]);
        assert!(!set.hierarchy_exact());
        assert!(Mistakes::NONE.is_empty() && Mistakes::NONE.hierarchy_exact());
    }

    #[test]
    fn option_shaped_mistakes_change_the_frame() {
        let spec = FrameSpec::default();
        let plus = Mistakes::of(&[Bug::BouncesPlusOne, Bug::NoShadows]).frame_spec(&spec);
        assert_eq!((plus.bounces, plus.shadows), (3, false));
        let zero = FrameSpec {
            bounces: 0,
            ..FrameSpec::default()
        };
        assert_eq!(
            Mistakes::of(&[Bug::BouncesMinusOne])
                .frame_spec(&zero)
                .bounces,
            0
        );
        let far = Mistakes::of(&[Bug::SphereFarRoot]).frame_spec(&spec);
        assert_eq!(far.acceleration, Acceleration::BruteForce);
    }

    #[test]
    fn the_far_root_is_taken_from_inside() {
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::Z);
        let terms = SphereTerms::of(&ray);
        let centre = DVec3::new(0.0, 0.0, 5.0);
        assert_eq!(Tick.sphere_root(&ray, &terms, centre, 1.0), None);
        let far = Mistakes::of(&[Bug::SphereFarRoot]).sphere_root(&ray, &terms, centre, 1.0);
        assert_eq!(far, Some(1.0));
    }
}
