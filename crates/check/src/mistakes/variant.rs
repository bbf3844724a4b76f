//! The model a student's program renders: the course's rules with a set of catalogue entries
//! broken ([`Mistakes`]) and at most one of the model's numbers changed ([`Number`]). One
//! implementation of [`Model`] for every candidate the diagnosis tries, so a variant is a
//! parameter of the course's shading, never a copy of it.

use glam::DVec3;

use super::{Bug, Mistakes};
use whitted_core::course::{Course, Rules, ShadowBias};
use whitted_core::geometry::{normalise, sphere_near_else_far_hit, Ray, SphereTerms, EPSILON};
use whitted_core::model::rounding::{plane_root_taken, sphere_root_taken, SelfHit};
use whitted_core::model::{mirror_direction, Model, Tick};
use whitted_core::scene::PointLight;

/// A number of the model a student can get wrong (docs/check.md, "The model's numbers").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Parameter {
    /// The specular exponent n on spheres (the planes' 0 stays).
    SpecularExponent,
    /// The offset of shadow and reflected rays.
    Epsilon,
    /// p in `I / (4 pi d^p)`.
    FalloffPower,
    /// A factor on every object's reflectivity.
    Reflectivity,
    /// A factor on the ambient term.
    Ambient,
}

impl Parameter {
    pub const ALL: [Parameter; 5] = [
        Parameter::SpecularExponent,
        Parameter::Epsilon,
        Parameter::FalloffPower,
        Parameter::Reflectivity,
        Parameter::Ambient,
    ];

    /// The stable name of docs/check.md.
    pub fn name(self) -> &'static str {
        match self {
            Parameter::SpecularExponent => "specular-exponent",
            Parameter::Epsilon => "epsilon",
            Parameter::FalloffPower => "falloff-power",
            Parameter::Reflectivity => "reflectivity",
            Parameter::Ambient => "ambient",
        }
    }

    /// What the number is, in words for the report.
    pub fn words(self) -> &'static str {
        match self {
            Parameter::SpecularExponent => "the specular exponent",
            Parameter::Epsilon => "EPSILON (the offset of shadow and reflected rays)",
            Parameter::FalloffPower => "the power of d in the light's falloff 1/(4 pi d^p)",
            Parameter::Reflectivity => "a factor on the reflectivity",
            Parameter::Ambient => "a factor on the ambient term",
        }
    }

    /// Which constant of the course's code to look at.
    pub fn place(self) -> &'static str {
        match self {
            Parameter::SpecularExponent => "the exponent n in Renderer.illuminate's Math.pow(Math.max(0, R.dot(V)), n): object.getPhong_n(), 10 on spheres",
            Parameter::Epsilon => "Renderer.EPSILON (the course's 0.0001), where shadow and reflected rays start",
            Parameter::FalloffPower => "the light's falloff in Renderer.illuminate: use light.getIlluminationAt(d), c k / (4 pi d^2)",
            Parameter::Reflectivity => "the reflectivity r in Renderer.trace: object.getReflectivity() as it is",
            Parameter::Ambient => "the ambient term in Renderer.illuminate: scene.getAmbientLighting().scale(object.getColour()) as it is",
        }
    }

    /// The course's value.
    pub fn course(self) -> f64 {
        match self {
            Parameter::SpecularExponent => 10.0,
            Parameter::Epsilon => EPSILON,
            Parameter::FalloffPower => 2.0,
            Parameter::Reflectivity | Parameter::Ambient => 1.0,
        }
    }

    /// The values a first search tries, over what a student could plausibly have written.
    pub fn grid(self) -> Vec<f64> {
        match self {
            Parameter::SpecularExponent => {
                (0..=16).map(|i| 2f64.powf(f64::from(i) / 2.0)).collect()
            }
            Parameter::Epsilon => (0..=16)
                .map(|i| 10f64.powf(-9.0 + f64::from(i) / 2.0))
                .collect(),
            Parameter::FalloffPower => (0..=16).map(|i| f64::from(i) / 4.0).collect(),
            Parameter::Reflectivity | Parameter::Ambient => {
                (0..=16).map(|i| f64::from(i) / 4.0).collect()
            }
        }
    }

    /// Whether the grid is geometric (refined by factors) rather than arithmetic.
    pub fn geometric(self) -> bool {
        matches!(self, Parameter::SpecularExponent | Parameter::Epsilon)
    }

    /// The catalogue stage whose code holds this number (for `progress`).
    pub fn stage(self) -> super::Stage {
        match self {
            Parameter::SpecularExponent | Parameter::FalloffPower | Parameter::Ambient => {
                super::Stage::Lights
            }
            Parameter::Epsilon => super::Stage::Shadows,
            Parameter::Reflectivity => super::Stage::Reflection,
        }
    }
}

/// One of the model's numbers set to `value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number {
    pub parameter: Parameter,
    pub value: f64,
}

/// Below this EPSILON a fitted offset leaves self-roots within reach of rounding
/// (`whitted_core::model::rounding`): its pixels hinge on the program's last bits too.
const ROUNDING_EPSILON: f64 = 1e-8;

/// Lights whose shadow rays' rounding is tried one at a time (each light two renders).
const MAX_LIGHTS_APART: usize = 4;

/// How a candidate takes the roots that hinge on rounding (`whitted_core::model::rounding`):
/// the ways a student's program can go where the model's own arithmetic goes one way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub enum Rounding {
    /// As the model's own arithmetic has them.
    #[default]
    Exact,
    /// Every ray takes them `SelfHit::Hit` or `SelfHit::Miss`.
    All(SelfHit),
    /// The shadow rays towards light `light` take them `how`, every other ray the other way:
    /// a pixel lit by two lights can self-shadow towards one of them only.
    OneLight { light: u8, how: SelfHit },
}

impl Rounding {
    /// How every ray but the one light's shadow rays takes them.
    fn elsewhere(self) -> SelfHit {
        match self {
            Rounding::Exact => SelfHit::Exact,
            Rounding::All(how) => how,
            Rounding::OneLight { how, .. } => match how {
                SelfHit::Hit => SelfHit::Miss,
                SelfHit::Miss => SelfHit::Hit,
                SelfHit::Exact => SelfHit::Exact,
            },
        }
    }
}

/// A candidate program: the course's model with `mistakes` and perhaps one number changed;
/// `rounding` says how roots that hinge on rounding are taken (exactly as the model's own
/// arithmetic has them, except when the diagnosis asks for the other ways). `course` is the
/// year whose rules every rule not broken follows (the renderer sets it to its case's).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Variant {
    pub mistakes: Mistakes,
    pub number: Option<Number>,
    pub rounding: Rounding,
    pub course: Course,
}

impl From<Mistakes> for Variant {
    fn from(mistakes: Mistakes) -> Self {
        Variant {
            mistakes,
            ..Variant::default()
        }
    }
}

/// How a program turns its linear colour into the PNG's bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    /// The year's own tone map.
    Course,
    /// Clamped and scaled, without a tone map (2016-17's output).
    Untonemapped,
    /// The year's tone map applied to its own result once more.
    Twice,
}

impl Variant {
    fn has(&self, bug: Bug) -> bool {
        self.mistakes.has(bug)
    }

    /// The year's rules, for every rule this program does not break.
    #[inline]
    fn rules(&self) -> Rules {
        self.course.rules()
    }

    /// How this program writes its bytes.
    pub fn output(&self) -> Output {
        if self.has(Bug::TonemapMissing) {
            Output::Untonemapped
        } else if self.has(Bug::TonemapTwice) {
            Output::Twice
        } else {
            Output::Course
        }
    }

    /// This program under `course`'s rules.
    pub fn in_course(self, course: Course) -> Variant {
        Variant { course, ..self }
    }

    /// The changed value of `parameter`, if this variant changes it.
    fn value(&self, parameter: Parameter) -> Option<f64> {
        self.number
            .filter(|n| n.parameter == parameter)
            .map(|n| n.value)
    }

    /// Whether two variants are the same candidate (numbers compared bit for bit).
    pub fn same(&self, other: &Variant) -> bool {
        let bits = |v: &Variant| v.number.map(|n| (n.parameter, n.value.to_bits()));
        self.mistakes == other.mistakes
            && bits(self) == bits(other)
            && self.rounding == other.rounding
    }

    /// Whether some of this program's pixels hinge on rounding: a shadow or reflected ray
    /// that starts on its surface (no offset, or one too small to clear rounding).
    pub fn hinges_on_rounding(&self) -> bool {
        self.has(Bug::NoShadowBias)
            || self.has(Bug::NoReflectionBias)
            || self
                .value(Parameter::Epsilon)
                .is_some_and(|e| e < ROUNDING_EPSILON)
    }

    /// Whether this program searches for hits by the course's own rules: the same
    /// `sphere_root`, `plane_accepts` and `plane_root` below as the program with no mistake,
    /// and every root taken as its own arithmetic has it. Its traces can then be answered
    /// from the searches the course's trace recorded (`whitted_core::hits::tape`), for the
    /// rays that are the same. Keep in step with those three methods: the replay test in
    /// `check::tests_courses` fails for an entry that changes a hit and is let through here.
    pub fn intersects_as_course(&self) -> bool {
        !self.has(Bug::SpheresMissing)
            && !self.has(Bug::PlanesMissing)
            && !self.has(Bug::PlaneBehind)
            && self.far_root() == self.rules().far_root
            && self.rounding == Rounding::Exact
    }

    /// The sphere's root when roots within the band are taken `how` (kept out of line: the
    /// search's hot path is the model's own arithmetic).
    #[cold]
    #[inline(never)]
    fn sphere_root_rounded(
        &self,
        how: SelfHit,
        ray: &Ray,
        terms: &SphereTerms,
        centre: DVec3,
        radius_squared: f64,
    ) -> Option<f64> {
        sphere_root_taken(how, ray, terms, centre, radius_squared, self.far_root())
    }

    /// This program with its rounding-dependent roots taken as `rounding` says.
    pub fn rounded(&self, rounding: Rounding) -> Variant {
        Variant { rounding, ..*self }
    }

    /// The ways this program's rounding can go besides its own arithmetic, for a scene with
    /// `lights` lights: every such root a hit, none, and (where shadow rays start on their
    /// surface and two or more lights could each go their own way) each light's shadow rays
    /// one way and every other ray the other. With three lights that is every combination.
    pub fn rounding_ways(&self, lights: usize) -> Vec<Rounding> {
        let mut ways = vec![Rounding::All(SelfHit::Hit), Rounding::All(SelfHit::Miss)];
        let shadows_hinge = self.has(Bug::NoShadowBias)
            || self
                .value(Parameter::Epsilon)
                .is_some_and(|e| e < ROUNDING_EPSILON);
        if shadows_hinge && lights >= 2 {
            for light in 0..lights.min(MAX_LIGHTS_APART) as u8 {
                for how in [SelfHit::Hit, SelfHit::Miss] {
                    ways.push(Rounding::OneLight { light, how });
                }
            }
        }
        ways
    }
}

impl Model for Variant {
    #[inline]
    fn hierarchy_exact(&self) -> bool {
        self.mistakes.hierarchy_exact()
    }

    #[inline(always)]
    fn sphere_root(
        &self,
        ray: &Ray,
        terms: &SphereTerms,
        centre: DVec3,
        radius_squared: f64,
    ) -> Option<f64> {
        if self.has(Bug::SpheresMissing) {
            return None;
        }
        let how = self.rounding.elsewhere();
        if how != SelfHit::Exact {
            return self.sphere_root_rounded(how, ray, terms, centre, radius_squared);
        }
        // The handout read literally: the near root if positive, else the far one.
        if self.far_root() {
            sphere_near_else_far_hit(ray, terms, centre, radius_squared)
        } else {
            Tick.sphere_root(ray, terms, centre, radius_squared)
        }
    }

    #[inline]
    fn far_root(&self) -> bool {
        self.has(Bug::SphereFarRoot) || self.rules().far_root
    }

    #[inline]
    fn plane_accepts(&self, s: f64) -> bool {
        if self.has(Bug::PlanesMissing) {
            false
        } else if self.has(Bug::PlaneBehind) {
            s.is_finite()
        } else {
            Tick.plane_accepts(s)
        }
    }

    #[inline]
    fn plane_root(&self, ray: &Ray, point: DVec3, normal: DVec3) -> Option<f64> {
        plane_root_taken(self.rounding.elsewhere(), ray, point, normal, |s| {
            self.plane_accepts(s)
        })
    }

    #[inline]
    fn self_hits_toward(&self, light: usize) -> SelfHit {
        match self.rounding {
            Rounding::OneLight { light: one, how } if usize::from(one) == light => how,
            _ => SelfHit::Exact,
        }
    }

    #[inline]
    fn clamp_r_dot_v(&self, r_dot_v: f64) -> f64 {
        if self.has(Bug::RvUnclamped) {
            r_dot_v
        } else {
            Tick.clamp_r_dot_v(r_dot_v)
        }
    }

    #[inline]
    fn background(&self) -> DVec3 {
        let course = self.rules().background;
        match self.has(Bug::BackgroundChanged) {
            // The other era's value: a later student writing 2016-17's grey, or the reverse.
            true if course == 0.1 => DVec3::splat(0.001),
            true => DVec3::splat(0.1),
            false => DVec3::splat(course),
        }
    }

    #[inline]
    fn reaches(&self, n_dot_l: f64) -> bool {
        self.has(Bug::NoGate) || self.rules().reaches(n_dot_l)
    }

    #[inline]
    fn lights<'a>(&self, lights: &'a [PointLight]) -> &'a [PointLight] {
        if self.has(Bug::LightsMissing) || self.has(Bug::ShadingMissing) {
            &[]
        } else if self.has(Bug::FirstLightOnly) {
            &lights[..lights.len().min(1)]
        } else {
            lights
        }
    }

    #[inline]
    fn illumination(&self, light: &PointLight, d: f64) -> DVec3 {
        if self.has(Bug::NoFalloff) {
            light.colour * light.intensity
        } else if let Some(p) = self.value(Parameter::FalloffPower) {
            light.colour * (light.intensity / (std::f64::consts::PI * 4.0 * d.powf(p)))
        } else {
            Tick.illumination(light, d)
        }
    }

    #[inline]
    fn to_light(&self, to_light: DVec3, d: f64) -> DVec3 {
        if self.has(Bug::LightUnnormalised) {
            to_light
        } else {
            Tick.to_light(to_light, d)
        }
    }

    #[inline]
    fn view(&self, p: DVec3, ray_origin: DVec3) -> DVec3 {
        if self.has(Bug::ViewFlipped) {
            normalise(p)
        } else if self.has(Bug::ViewFromRayOrigin) {
            normalise(ray_origin - p)
        } else if self.has(Bug::ViewToCamera) {
            Tick.view(p, ray_origin)
        } else {
            self.rules().view(p, ray_origin)
        }
    }

    #[inline]
    fn specular_mirror(&self, n: DVec3, l: DVec3, n_dot_l: f64) -> DVec3 {
        if self.has(Bug::ReflectUnclamped) {
            n * (2.0 * n.dot(l)) - l
        } else {
            self.rules().specular_mirror(n, l, n_dot_l)
        }
    }

    #[inline]
    fn epsilon(&self) -> f64 {
        self.value(Parameter::Epsilon).unwrap_or(EPSILON)
    }

    #[inline]
    fn specular_exponent(&self, n: f64) -> f64 {
        match self.value(Parameter::SpecularExponent) {
            // Only the spheres' exponent: the planes' 0 makes no highlight to change.
            Some(fitted) if n != 0.0 => fitted,
            _ => n,
        }
    }

    #[inline]
    fn reflectivity(&self, r: f64) -> f64 {
        self.value(Parameter::Reflectivity).map_or(r, |f| r * f)
    }

    #[inline]
    fn ambient(&self, ambient_light: DVec3, colour: DVec3) -> DVec3 {
        if self.has(Bug::ShadingMissing) {
            // The skeleton's illuminate: the object's own colour, flat.
            colour
        } else if self.has(Bug::NoAmbient) {
            DVec3::ZERO
        } else {
            let ambient = Tick.ambient(ambient_light, colour);
            self.value(Parameter::Ambient)
                .map_or(ambient, |f| ambient * f)
        }
    }

    #[inline]
    fn diffuse(&self, colour: DVec3, illumination: DVec3, kd: f64, n_dot_l: f64) -> DVec3 {
        if self.has(Bug::DiffuseNoColour) {
            (illumination * kd) * n_dot_l
        } else {
            Tick.diffuse(colour, illumination, kd, n_dot_l)
        }
    }

    #[inline]
    fn specular(
        &self,
        light: &PointLight,
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
        } else if self.has(Bug::SpecularWhite) {
            Tick.specular(light, illumination, ks, phong, colour, n_dot_l)
        } else {
            self.rules()
                .specular(light, illumination, ks, phong, colour, n_dot_l)
        };
        if self.has(Bug::SpecularObjectColour) {
            specular * colour
        } else {
            specular
        }
    }

    #[inline]
    fn shadow_ray(&self, p: DVec3, l: DVec3, n: DVec3) -> Ray {
        let along = if self.has(Bug::NoShadowBias) {
            return Ray::new(p, l);
        } else if self.has(Bug::ShadowBiasAlongN) {
            ShadowBias::AlongN
        } else if self.has(Bug::ShadowBiasAlongL) {
            ShadowBias::AlongL
        } else {
            self.rules().shadow_bias
        };
        match along {
            ShadowBias::AlongL => Ray::offset_by(p, l, self.epsilon()),
            ShadowBias::AlongN => Ray::new(p + n * self.epsilon(), l),
        }
    }

    #[inline]
    fn shadow_reach(&self, d: f64) -> f64 {
        if self.has(Bug::ShadowAnyHit) {
            f64::INFINITY
        } else {
            Tick.shadow_reach(d)
        }
    }

    #[inline]
    fn add_light(&self, colour: DVec3, ambient: DVec3, diffuse: DVec3, specular: DVec3) -> DVec3 {
        let base = if self.has(Bug::LastLightWins) {
            ambient
        } else {
            colour
        };
        Tick.add_light(base, ambient, diffuse, specular)
    }

    #[inline]
    fn mirror_ray(&self, p: DVec3, d: DVec3, n: DVec3) -> Ray {
        let direction = if self.has(Bug::ReflectionWrongSign) {
            normalise(n * (2.0 * n.dot(d)) - d)
        } else {
            mirror_direction(d, n)
        };
        if self.has(Bug::NoReflectionBias) {
            Ray::new(p, direction)
        } else if self.has(Bug::ReflectionBiasAlongN) {
            Ray::new(p + n * self.epsilon(), direction)
        } else {
            Ray::offset_by(p, direction, self.epsilon())
        }
    }

    #[inline]
    fn blend(&self, direct: DVec3, reflected: DVec3, r: f64) -> DVec3 {
        if self.has(Bug::ReflectionMissing) {
            // The skeleton's reflectedIllumination, never assigned: black.
            Tick.blend(direct, DVec3::ZERO, r)
        } else if self.has(Bug::ReflectionUnweighted) {
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
    fn the_far_root_is_taken_from_inside() {
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::Z);
        let terms = SphereTerms::of(&ray);
        let centre = DVec3::new(0.0, 0.0, 5.0);
        assert_eq!(Tick.sphere_root(&ray, &terms, centre, 1.0), None);
        let far = Variant::from(Mistakes::of(&[Bug::SphereFarRoot]));
        assert_eq!(far.sphere_root(&ray, &terms, centre, 1.0), Some(1.0));
    }

    #[test]
    fn the_course_s_numbers_render_the_course_s_terms() {
        let light = PointLight {
            position: DVec3::ZERO,
            colour: DVec3::ONE,
            intensity: 100.0,
            name: String::new(),
        };
        for parameter in Parameter::ALL {
            let course = Variant {
                mistakes: Mistakes::NONE,
                number: Some(Number {
                    parameter,
                    value: parameter.course(),
                }),
                rounding: Rounding::Exact,
                course: Course::Y2016,
            };
            assert_eq!(
                course.illumination(&light, 3.0),
                Tick.illumination(&light, 3.0)
            );
            assert_eq!(course.epsilon(), Tick.epsilon());
            assert_eq!(course.specular_exponent(10.0), 10.0);
            assert_eq!(course.reflectivity(0.3), 0.3);
            assert_eq!(
                course.ambient(DVec3::ONE, DVec3::splat(0.5)),
                DVec3::splat(0.5)
            );
            assert!(parameter.grid().len() > 10);
        }
        let linear = Variant {
            mistakes: Mistakes::NONE,
            number: Some(Number {
                parameter: Parameter::FalloffPower,
                value: 1.0,
            }),
            rounding: Rounding::Exact,
            course: Course::Y2016,
        };
        let expected = 100.0 / (std::f64::consts::PI * 4.0 * 3.0);
        assert_eq!(linear.illumination(&light, 3.0), DVec3::splat(expected));
    }

    #[test]
    fn unfinished_stages_render_what_the_skeleton_does() {
        let lights = [PointLight {
            position: DVec3::ZERO,
            colour: DVec3::ONE,
            intensity: 1.0,
            name: String::new(),
        }];
        let no_lights = Variant::from(Mistakes::of(&[Bug::LightsMissing]));
        assert!(no_lights.lights(&lights).is_empty());
        assert!(!Variant::from(Mistakes::of(&[Bug::PlanesMissing])).plane_accepts(1.0));
        let black = Variant::from(Mistakes::of(&[Bug::ReflectionMissing]));
        let direct = DVec3::new(0.5, 0.25, 1.0);
        assert_eq!(black.blend(direct, DVec3::ONE, 0.3), direct * (1.0 - 0.3));
    }
}
