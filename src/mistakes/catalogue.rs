//! Each catalogue entry's stable id, its one-line statement against docs/rendering.md, and the
//! stage of the handout it belongs to: one table, so that `--list-bugs`, the report and the
//! progress line can never disagree.

use super::{Bug, Stage};

/// What the catalogue says of one entry.
pub(super) struct Entry {
    pub id: &'static str,
    pub description: &'static str,
    pub stage: Stage,
    /// An unfinished stage (the skeleton's TODO left as it is), not a mistake in written code.
    pub unfinished: bool,
}

const fn mistake(id: &'static str, stage: Stage, description: &'static str) -> Entry {
    Entry {
        id,
        description,
        stage,
        unfinished: false,
    }
}

const fn unfinished(id: &'static str, stage: Stage, description: &'static str) -> Entry {
    Entry {
        id,
        description,
        stage,
        unfinished: true,
    }
}

pub(super) fn entry(bug: Bug) -> Entry {
    use Stage::*;
    match bug {
        Bug::ReflectUnclamped => mistake("reflect-unclamped", Lights, "specular mirror direction R built from the unclamped N.L (the plain reflection of L)"),
        Bug::SpecularGated => mistake("specular-gated", Lights, "specular added only where N.L > 0"),
        Bug::ViewFromRayOrigin => mistake("view-from-ray-origin", Lights, "V points to the ray's origin, not to the camera, for reflected rays"),
        Bug::ViewFlipped => mistake("view-flipped", Lights, "V = normalise(P) instead of normalise(-P)"),
        Bug::LightUnnormalised => mistake("light-unnormalised", Lights, "L = light position - P, not normalised (in N.L and R)"),
        Bug::NoFalloff => mistake("no-falloff", Lights, "light intensity without the 1/(4 pi d^2) falloff"),
        Bug::NoAmbient => mistake("no-ambient", Lights, "ambient term missing"),
        Bug::DiffuseNoColour => mistake("diffuse-no-colour", Lights, "diffuse term not multiplied by the object colour"),
        Bug::SpecularObjectColour => mistake("specular-object-colour", Lights, "specular term multiplied by the object colour"),
        Bug::FirstLightOnly => mistake("first-light-only", Lights, "only the first point light is used"),
        Bug::LastLightWins => mistake("last-light-wins", Lights, "each light replaces the colour (ambient + its terms) instead of adding to it"),
        Bug::NoShadows => unfinished("no-shadows", Shadows, "shadow rays never cast (inShadow stays false: the shadow stage not written yet)"),
        Bug::NoShadowBias => mistake("no-shadow-bias", Shadows, "shadow ray starts at P, without the EPSILON offset (shadow acne)"),
        Bug::ShadowAnyHit => mistake("shadow-any-hit", Shadows, "in shadow whenever the shadow ray hits anything, even beyond the light"),
        Bug::NoReflectionBias => mistake("no-reflection-bias", Reflection, "reflected ray starts at P, without the EPSILON offset"),
        Bug::ReflectionWrongSign => mistake("reflection-wrong-sign", Reflection, "reflected direction is D mirrored in N, without negating D first"),
        Bug::ReflectionUnweighted => mistake("reflection-unweighted", Reflection, "returns direct + reflectivity * reflected (direct not scaled by 1 - r)"),
        Bug::BouncesPlusOne => mistake("bounces-plus-one", Reflection, "one more reflection bounce than --bounces"),
        Bug::BouncesMinusOne => mistake("bounces-minus-one", Reflection, "one bounce fewer than --bounces"),
        Bug::PlaneBehind => mistake("plane-behind", Planes, "plane hits with s < 0 accepted (planes behind the ray's origin)"),
        Bug::SphereFarRoot => mistake("sphere-far-root", Planes, "the sphere takes the far root when the near one is not > 0, so a ray from inside hits it"),
        Bug::PlanesMissing => unfinished("planes-missing", Planes, "Plane.intersectionWith still returns the empty hit: no plane is ever hit (no floor, no plane shadows or reflections)"),
        Bug::LightsMissing => unfinished("lights-missing", Lights, "Renderer.illuminate adds the ambient term only: no diffuse or specular from any light"),
        Bug::ReflectionMissing => unfinished("reflection-missing", Reflection, "Renderer.trace leaves reflectedIllumination at black: a reflective surface shows direct * (1 - r) and nothing reflected"),
        Bug::ReflectionIgnored => unfinished("reflection-ignored", Reflection, "trace returns the direct illumination unscaled at every hit (what --bounces 0 renders)"),
    }
}
