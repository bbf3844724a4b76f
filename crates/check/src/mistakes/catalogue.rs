//! Each catalogue entry's stable id, its one-line statement against docs/rendering.md, the
//! stage of the handout it belongs to, and where and how a student fixes it in the course's
//! code (the skeleton's `gfx.tick2` API): one table, so that `--list-bugs`, every report and
//! the progress line can never disagree.

use super::{Bug, Stage};

/// What the catalogue says of one entry.
pub(super) struct Entry {
    pub id: &'static str,
    pub description: &'static str,
    pub stage: Stage,
    /// An unfinished stage (the skeleton's TODO left as it is), not a mistake in written code.
    pub unfinished: bool,
    /// The class and method of the course's code where it is.
    pub place: &'static str,
    /// What the wrong code typically looks like (for a stage: what is not written yet).
    pub looks_like: &'static str,
    /// The course's formula, and the line that computes it.
    pub fix: &'static str,
}

/// The place, the wrong line and the fix of an entry.
struct Where(&'static str, &'static str, &'static str);

const fn mistake(id: &'static str, stage: Stage, description: &'static str, w: Where) -> Entry {
    Entry {
        id,
        description,
        stage,
        unfinished: false,
        place: w.0,
        looks_like: w.1,
        fix: w.2,
    }
}

const fn unfinished(id: &'static str, stage: Stage, description: &'static str, w: Where) -> Entry {
    Entry {
        id,
        description,
        stage,
        unfinished: true,
        place: w.0,
        looks_like: w.1,
        fix: w.2,
    }
}

const ILLUMINATE: &str = "Renderer.illuminate";
/// The later years' names (docs/courses.md): `illuminate(scene, object, P, N, O)`.
const ILLUMINATE_O: &str = "Renderer.illuminate(..., O)";
const RENDER: &str = "Renderer.render";
const TRACE: &str = "Renderer.trace";

pub(super) fn entry(bug: Bug) -> Entry {
    use Stage::*;
    match bug {
        Bug::ViewToCamera => mistake("view-to-camera", Lights, "V = normalise(-P), towards the camera, not towards the origin O of the ray that found P (wrong for reflected rays)",
            Where(ILLUMINATE_O, "Vector3 V = P.scale(-1).normalised();", "V = normalise(O - P): Vector3 V = O.subtract(P).normalised();")),
        // The diffuse's own max(0, N.L) already gates it, so the image shows only the
        // specular lit from behind: the line to point at is the specular's, not a missing test
        // of the whole light.
        Bug::NoGate => mistake("no-gate", Lights, "the specular term added where N.L < 0 (the light is behind the surface): only the diffuse is cut off there, by its max(0, N.L)",
            Where(ILLUMINATE_O, "ColorRGB specular = C_spec.scale(I).scale(kS * Math.pow(Math.max(0, R.dot(V)), alpha));  // added whatever N.L is", "skip the light where N.L < 0, its specular too: if (N.dot(L) < 0) continue;")),
        Bug::SpecularWhite => mistake("specular-white", Lights, "specular term without the light's colour: I kS (R.V)^n instead of C_light I kS (R.V)^n",
            Where(ILLUMINATE_O, "ColorRGB specular = I.scale(kS * Math.pow(...));", "multiply by the light's colour too: ColorRGB specular = light.getColour().scale(I).scale(kS * Math.pow(Math.max(0, R.dot(V)), object.getPhong_alpha()));")),
        Bug::ShadowBiasAlongN => mistake("shadow-bias-along-n", Shadows, "shadow ray moved off the surface along N, not along L",
            Where(ILLUMINATE_O, "Ray shadowRay = new Ray(P.add(N.scale(EPSILON)), L);", "move it along L: Ray shadowRay = new Ray(P.add(L.scale(EPSILON)), L);")),
        Bug::ShadowBiasAlongL => mistake("shadow-bias-along-l", Shadows, "shadow ray moved off the surface along L, not along N as this year's course does",
            Where(ILLUMINATE_O, "Ray shadowRay = new Ray(P.add(L.scale(EPSILON)), L);", "move it along N: Ray shadowRay = new Ray(P.add(N.scale(EPSILON)), L);")),
        Bug::ReflectionBiasAlongN => mistake("reflection-bias-along-n", Reflection, "reflected ray moved off the surface along N (as the handout's words suggest), not along R",
            Where(TRACE, "Ray reflectedRay = new Ray(P.add(N.scale(EPSILON)), R);", "move it along R: Ray reflectedRay = new Ray(P.add(R.scale(EPSILON)), R);")),
        Bug::TonemapMissing => mistake("tonemap-missing", Lights, "the linear colour written without the tone map: each channel clamped to [0, 1] and scaled to 255",
            Where(RENDER, "image.setRGB(x, y, colour.toRGB());  // without tonemap", "tone-map each pixel before writing it: ColorRGB mapped = tonemap(colour);")),
        Bug::TonemapTwice => mistake("tonemap-twice", Lights, "the tone map applied twice: to the linear colour, then again to its result",
            Where(RENDER, "tonemap(tonemap(colour))", "tone-map the linear colour once, just before writing the pixel")),
        Bug::BackgroundChanged => mistake("background-changed", Lights, "a ray that hits nothing returns another background than the course's (0.001 from 2018-19, 0.1 before); the entry renders the other value (0.1, or 0.001 where the course's is 0.1)",
            Where(TRACE, "return new ColorRGB(0.1);  // when the ray hits nothing", "the course's background for a ray that hits nothing: 0.001 on every channel from 2018-19 (byte 9 after the tone map), 0.1 in 2017-18")),
        Bug::SpheresMissing => unfinished("spheres-missing", Spheres, "Sphere.intersectionWith still returns the empty hit: no sphere is ever hit",
            Where("Sphere.intersectionWith", "the intersection (it returns new RaycastHit(), no hit)", "solve |O + sD - C|^2 = r^2; the near root if > 0, else the far one if > 0; a hit there with normal (P - C)/r")),
        Bug::ShadingMissing => unfinished("shading-missing", Lights, "Renderer.illuminate still returns object.getColour(): every lit object is flat, without ambient, diffuse, specular or shadows",
            Where(ILLUMINATE_O, "the shading (it returns object.getColour())", "ambient I_a C plus, per light, C I kD max(0, N.L) + C_light I kS max(0, R.V)^n, as the handout's Phong model")),
        Bug::ReflectUnclamped => mistake("reflect-unclamped", Lights, "specular mirror direction R built from the unclamped N.L (the plain reflection of L)",
            Where(ILLUMINATE, "Vector3 R = L.reflectIn(N);", "R = 2 max(0, N.L) N - L: Vector3 R = N.scale(2 * Math.max(0, N.dot(L))).subtract(L);")),
        Bug::SpecularGated => mistake("specular-gated", Lights, "specular added only where N.L > 0",
            Where(ILLUMINATE, "if (N.dot(L) > 0) { ... add the specular term ... }", "add I kS max(0, R.V)^n wherever the light is not in shadow, whatever N.L is (R uses the clamped N.L)")),
        Bug::ViewFromRayOrigin => mistake("view-from-ray-origin", Lights, "V points to the ray's origin, not to the camera, for reflected rays",
            Where(ILLUMINATE, "Vector3 V = ray.getOrigin().subtract(P).normalised();", "V = normalise(-P), towards the camera at the origin, for reflected rays too: Vector3 V = P.scale(-1).normalised();")),
        Bug::ViewFlipped => mistake("view-flipped", Lights, "V = normalise(P) instead of normalise(-P)",
            Where(ILLUMINATE, "Vector3 V = P.normalised();", "V = normalise(-P): Vector3 V = P.scale(-1).normalised();")),
        Bug::LightUnnormalised => mistake("light-unnormalised", Lights, "L = light position - P, not normalised (in N.L and R)",
            Where(ILLUMINATE, "Vector3 L = light.getPosition().subtract(P);", "L = normalise(X - P): Vector3 L = light.getPosition().subtract(P).normalised();")),
        Bug::NoFalloff => mistake("no-falloff", Lights, "light intensity without the 1/(4 pi d^2) falloff",
            Where(ILLUMINATE, "Vector3 I = light.getColour().scale(light.getIntensity());", "I = c k / (4 pi d^2), d = |X - P|: Vector3 I = light.getIlluminationAt(d);")),
        Bug::NoAmbient => mistake("no-ambient", Lights, "ambient term missing",
            Where(ILLUMINATE, "Vector3 colour = new Vector3(0);", "start from I_a C: Vector3 colour = scene.getAmbientLighting().scale(object.getColour());")),
        Bug::DiffuseNoColour => mistake("diffuse-no-colour", Lights, "diffuse term not multiplied by the object colour",
            Where(ILLUMINATE, "Vector3 diffuse = I.scale(kD * Math.max(0, N.dot(L)));", "diffuse = C I kD max(0, N.L): Vector3 diffuse = C.scale(I).scale(kD).scale(Math.max(0, N.dot(L)));")),
        Bug::SpecularObjectColour => mistake("specular-object-colour", Lights, "specular term multiplied by the object colour",
            Where(ILLUMINATE, "Vector3 specular = C.scale(I).scale(kS * ...);", "the specular term is white: I kS max(0, R.V)^n, without C")),
        Bug::FirstLightOnly => mistake("first-light-only", Lights, "only the first point light is used",
            Where(ILLUMINATE, "PointLight light = scene.getPointLight();", "add every light's terms: for (PointLight light : scene.getPointLights()) { ... }")),
        Bug::LastLightWins => mistake("last-light-wins", Lights, "each light replaces the colour (ambient + its terms) instead of adding to it",
            Where(ILLUMINATE, "colour = ambient.add(diffuse).add(specular);  // inside the light loop", "colour = colour.add(diffuse).add(specular);")),
        Bug::NoShadows => unfinished("no-shadows", Shadows, "shadow rays never cast (inShadow stays false: the shadow stage not written yet)",
            Where(ILLUMINATE, "the shadow test (inShadow is never set)", "cast Ray(P + EPSILON L, L); the light is blocked when it hits something nearer than d = |X - P|")),
        Bug::NoShadowBias => mistake("no-shadow-bias", Shadows, "shadow ray starts at P, without the EPSILON offset (shadow acne)",
            Where(ILLUMINATE, "Ray shadowRay = new Ray(P, L);", "start it EPSILON along L: Ray shadowRay = new Ray(P.add(L.scale(EPSILON)), L);")),
        Bug::ShadowAnyHit => mistake("shadow-any-hit", Shadows, "in shadow whenever the shadow ray hits anything, even beyond the light",
            Where(ILLUMINATE, "inShadow = scene.findClosestIntersection(shadowRay).getObjectHit() != null;", "only a hit nearer than the light shadows: inShadow = hit.getObjectHit() != null && hit.getDistance() < d;")),
        Bug::NoReflectionBias => mistake("no-reflection-bias", Reflection, "reflected ray starts at P, without the EPSILON offset",
            Where(TRACE, "Ray reflectedRay = new Ray(P, R);", "start it EPSILON along R: Ray reflectedRay = new Ray(P.add(R.scale(EPSILON)), R);")),
        Bug::ReflectionWrongSign => mistake("reflection-wrong-sign", Reflection, "reflected direction is D mirrored in N, without negating D first",
            Where(TRACE, "Vector3 R = D.reflectIn(N);", "R mirrors -D in N: Vector3 R = D.scale(-1).reflectIn(N).normalised();")),
        Bug::ReflectionUnweighted => mistake("reflection-unweighted", Reflection, "returns direct + reflectivity * reflected (direct not scaled by 1 - r)",
            Where(TRACE, "return direct.add(reflected.scale(r));", "direct (1 - r) + reflected r: return direct.scale(1 - r).add(reflected.scale(r));")),
        Bug::BouncesPlusOne => mistake("bounces-plus-one", Reflection, "one more reflection bounce than --bounces",
            Where(TRACE, "if (bouncesLeft < 0) return direct;  or  trace(scene, reflectedRay, bouncesLeft)", "reflect only while bouncesLeft > 0, and recurse with bouncesLeft - 1")),
        Bug::BouncesMinusOne => mistake("bounces-minus-one", Reflection, "one bounce fewer than --bounces",
            Where(TRACE, "if (bouncesLeft <= 1) return direct;  or  trace(scene, reflectedRay, bouncesLeft - 2)", "reflect only while bouncesLeft > 0, and recurse with bouncesLeft - 1")),
        Bug::PlaneBehind => mistake("plane-behind", Planes, "plane hits with s < 0 accepted (planes behind the ray's origin)",
            Where("Plane.intersectionWith", "return new RaycastHit(this, s, ray.evaluateAt(s), normal);  // s never checked", "s = (Q - O).N / (D.N); no hit unless s >= 0: if (s < 0) return new RaycastHit();")),
        Bug::SphereFarRoot => mistake("sphere-far-root", Planes, "the sphere takes the far root when the near one is not > 0, so a ray from inside hits it",
            Where("Sphere.intersectionWith", "if (s1 > 0) return hit at s1; else return hit at s2;", "only the near root s1 = (-b - sqrt(b^2 - 4ac)) / 2a, and only when s1 > 0")),
        Bug::RvUnclamped => mistake("rv-unclamped", Lights, "specular pow(R.V, n) without max(0, .): an even n lights the far side of each highlight, an odd n darkens it",
            Where(ILLUMINATE, "Math.pow(R.dot(V), n)", "clamp before the power: Math.pow(Math.max(0, R.dot(V)), n)")),
        Bug::PlanesMissing => unfinished("planes-missing", Planes, "Plane.intersectionWith still returns the empty hit: no plane is ever hit (no floor, no plane shadows or reflections)",
            Where("Plane.intersectionWith", "the intersection (it returns new RaycastHit(), no hit)", "s = (Q - O).N / (D.N); a hit at ray.evaluateAt(s) with the plane's normal when s >= 0")),
        Bug::LightsMissing => unfinished("lights-missing", Lights, "Renderer.illuminate adds the ambient term only: no diffuse or specular from any light",
            Where(ILLUMINATE, "the loop over scene.getPointLights()", "for each light: colour += C I kD max(0, N.L) + I kS max(0, R.V)^n, with I = light.getIlluminationAt(d)")),
        Bug::ReflectionMissing => unfinished("reflection-missing", Reflection, "Renderer.trace leaves reflectedIllumination at black: a reflective surface shows direct * (1 - r) and nothing reflected",
            Where(TRACE, "the reflected ray (reflectedIllumination stays new Vector3(0))", "reflectedIllumination = trace(scene, new Ray(P.add(R.scale(EPSILON)), R), bouncesLeft - 1), R = -D mirrored in N")),
        Bug::ReflectionIgnored => unfinished("reflection-ignored", Reflection, "trace returns the direct illumination unscaled at every hit (what --bounces 0 renders)",
            Where(TRACE, "the reflection (it returns directIllumination at every hit)", "when bouncesLeft > 0 and r > 0: return direct.scale(1 - r).add(reflected.scale(r));")),
    }
}
