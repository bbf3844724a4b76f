//! The catalogue of docs/check.md: the classic Tick 2 mistakes and the unfinished stages of
//! the handout, each one rule of the model done wrong (or not yet done), with a stable id.
//! [`Mistakes`] is a set of them; [`Variant`] is the model a program with such a set (and
//! perhaps one wrong number) renders. Sets, not one type per mistake, because students often
//! have two or three at once and the diagnosis ranks combinations: one monomorphised model
//! whose rules test a bit, instead of a type per combination.

mod catalogue;
mod variant;
mod year_words;

pub use variant::{Number, Output, Parameter, Rounding, Variant};

use std::borrow::Cow;

use whitted_core::course::Course;
use whitted_core::frame::limits::MAX_BOUNCES;
use whitted_core::frame::{Acceleration, FrameSpec};

/// One catalogue entry: a mistake in written code or a stage not written yet. The order is
/// the catalogue's (`whitted check --list-bugs`).
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
    RvUnclamped,
    PlanesMissing,
    LightsMissing,
    ReflectionMissing,
    ReflectionIgnored,
    ViewToCamera,
    NoGate,
    SpecularWhite,
    ShadowBiasAlongN,
    ShadowBiasAlongL,
    ReflectionBiasAlongN,
    TonemapMissing,
    TonemapTwice,
    BackgroundChanged,
    SpheresMissing,
    ShadingMissing,
}

/// A stage of the handout: the code a student writes, in the order they write it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    /// `Sphere.intersectionWith`: a student's own code from 2017-18 on.
    Spheres,
    /// `Plane.intersectionWith` (and the intersection rules a student can break).
    Planes,
    /// `Renderer.illuminate`: ambient, diffuse and specular per light.
    Lights,
    /// The shadow test inside `illuminate`.
    Shadows,
    /// `Renderer.trace`: reflected rays and the bounce count.
    Reflection,
}

impl Stage {
    /// The 2016-17 handout's stages, in its order.
    pub const ALL: [Stage; 4] = [
        Stage::Planes,
        Stage::Lights,
        Stage::Shadows,
        Stage::Reflection,
    ];

    /// The later years' handout (Tick 1, docs/courses.md "Stages"): spheres, shading, planes,
    /// shadows, reflection.
    pub const TICK1: [Stage; 5] = [
        Stage::Spheres,
        Stage::Lights,
        Stage::Planes,
        Stage::Shadows,
        Stage::Reflection,
    ];

    /// The stages of `course`'s handout, in its order.
    pub fn of(course: Course) -> &'static [Stage] {
        if course.is_default() {
            &Stage::ALL
        } else {
            &Stage::TICK1
        }
    }

    /// The entries that say this stage is not written yet: what a program renders before its
    /// student gets there (the later years' and 2016-17's, where they differ).
    pub fn missing_entries(self) -> &'static [Bug] {
        match self {
            Stage::Spheres => &[Bug::SpheresMissing],
            Stage::Planes => &[Bug::PlanesMissing],
            Stage::Lights => &[Bug::ShadingMissing, Bug::LightsMissing],
            Stage::Shadows => &[Bug::NoShadows],
            Stage::Reflection => &[Bug::ReflectionIgnored, Bug::ReflectionMissing],
        }
    }

    /// The key of the `progress` object (docs/check.md; the later years call the lights'
    /// stage `shading`, as their handout does).
    pub fn key(self, course: Course) -> &'static str {
        match self {
            Stage::Spheres => "spheres",
            Stage::Planes => "planes",
            Stage::Lights if course.is_default() => "lights",
            Stage::Lights => "shading",
            Stage::Shadows => "shadows",
            Stage::Reflection => "reflection",
        }
    }
}

impl Bug {
    /// Every entry, in catalogue order: the mistakes, then the unfinished stages.
    pub const ALL: [Bug; 37] = [
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
        Bug::RvUnclamped,
        Bug::PlanesMissing,
        Bug::LightsMissing,
        Bug::ReflectionMissing,
        Bug::ReflectionIgnored,
        Bug::ViewToCamera,
        Bug::NoGate,
        Bug::SpecularWhite,
        Bug::ShadowBiasAlongN,
        Bug::ShadowBiasAlongL,
        Bug::ReflectionBiasAlongN,
        Bug::TonemapMissing,
        Bug::TonemapTwice,
        Bug::BackgroundChanged,
        Bug::SpheresMissing,
        Bug::ShadingMissing,
    ];

    /// The mistakes in written code, the most common first: the order in which a report
    /// names the ones an image cannot rule out. From the course's students' histories
    /// (docs/check.md): the specular R and its gate, then the offsets, the view vector, the
    /// specular clamp, the light's terms, reflection, and the rarer intersection rules.
    pub const BY_COMMONNESS: [Bug; 30] = [
        Bug::ReflectUnclamped,
        Bug::SpecularGated,
        Bug::ReflectionBiasAlongN,
        Bug::NoGate,
        Bug::NoShadowBias,
        Bug::NoReflectionBias,
        Bug::ShadowBiasAlongL,
        Bug::ShadowBiasAlongN,
        Bug::ViewToCamera,
        Bug::SpecularWhite,
        Bug::ViewFromRayOrigin,
        Bug::RvUnclamped,
        Bug::ReflectionWrongSign,
        Bug::ReflectionUnweighted,
        Bug::LightUnnormalised,
        Bug::ViewFlipped,
        Bug::SpecularObjectColour,
        Bug::DiffuseNoColour,
        Bug::NoFalloff,
        Bug::NoAmbient,
        Bug::ShadowAnyHit,
        Bug::FirstLightOnly,
        Bug::LastLightWins,
        Bug::BouncesPlusOne,
        Bug::BouncesMinusOne,
        Bug::PlaneBehind,
        Bug::SphereFarRoot,
        Bug::TonemapMissing,
        Bug::TonemapTwice,
        Bug::BackgroundChanged,
    ];

    /// The entries `course`'s catalogue offers (docs/courses.md, "The catalogue per
    /// profile"), in catalogue order: an entry that is the year's own rule, or whose code the
    /// year's skeleton does not have, is not a mistake there.
    pub fn offered(course: Course) -> Vec<Bug> {
        Bug::ALL
            .into_iter()
            .filter(|&b| b.offered_in(course))
            .collect()
    }

    /// Whether `course`'s catalogue offers this entry.
    pub fn offered_in(self, course: Course) -> bool {
        use Bug::*;
        let later_only = matches!(
            self,
            ViewToCamera
                | NoGate
                | SpecularWhite
                | ShadowBiasAlongN
                | ShadowBiasAlongL
                | ReflectionBiasAlongN
                | TonemapMissing
                | TonemapTwice
                | BackgroundChanged
                | SpheresMissing
                | ShadingMissing
        );
        if course.is_default() {
            return !later_only;
        }
        let tone_mapped = course >= Course::Y2018;
        match self {
            // The later years' rules, or unknown for 2017-18 (docs/courses.md).
            ViewFromRayOrigin | ReflectUnclamped | SphereFarRoot | SpecularGated => false,
            // No such half-written code in the later skeletons.
            LightsMissing | ReflectionMissing => false,
            NoGate | TonemapMissing | TonemapTwice => tone_mapped,
            ShadowBiasAlongN => course < Course::Y2020,
            ShadowBiasAlongL => course >= Course::Y2020,
            _ => true,
        }
    }

    /// The stable id of docs/check.md.
    pub fn id(self) -> &'static str {
        catalogue::entry(self).id
    }

    /// The entry in one line, stated against docs/rendering.md, in `course`'s names.
    pub fn description(self, course: Course) -> Cow<'static, str> {
        year_words::in_year(catalogue::entry(self).description, course)
    }

    /// The stage of the handout whose code this entry is in.
    pub fn stage(self) -> Stage {
        catalogue::entry(self).stage
    }

    /// The class and method of the course's code the entry is in (the same in every year).
    pub fn place(self) -> &'static str {
        catalogue::entry(self).place
    }

    /// What the wrong code typically looks like; for a stage, what is not written yet.
    pub fn looks_like(self, course: Course) -> Cow<'static, str> {
        year_words::in_year(catalogue::entry(self).looks_like, course)
    }

    /// The course's formula and the line that computes it, in `course`'s names.
    pub fn fix(self, course: Course) -> Cow<'static, str> {
        year_words::in_year(catalogue::entry(self).fix, course)
    }

    /// Where and how to fix it, as two lines of a report: where (and what the wrong code
    /// looks like, or which TODO is open), then the fix.
    pub fn advice(self, course: Course) -> [String; 2] {
        let looks_like = self.looks_like(course);
        let place = if self.is_unfinished() {
            format!("where: {}, not written yet: {looks_like}", self.place())
        } else {
            format!("where: {}, often `{looks_like}`", self.place())
        };
        [place, format!("fix: {}", self.fix(course))]
    }

    /// Whether the code this mistake is made in exists only once `stage` is written, so that
    /// the mistake can show only then: its own stage's, and the view vector's mistakes, which
    /// differ from the course's only for reflected rays. An unfinished stage implies none.
    pub fn implies(self, stage: Stage) -> bool {
        let through_reflection = matches!(self, Bug::ViewToCamera | Bug::ViewFromRayOrigin);
        !self.is_unfinished()
            && (self.stage() == stage || (through_reflection && stage == Stage::Reflection))
    }

    /// Whether this entry is a stage not written yet rather than a mistake in written code.
    pub fn is_unfinished(self) -> bool {
        catalogue::entry(self).unfinished
    }

    /// The entry with this id.
    pub fn from_id(id: &str) -> Option<Bug> {
        Bug::ALL.into_iter().find(|b| b.id() == id)
    }

    /// Whether a program cannot have both: an unfinished stage has none of the code its
    /// mistakes are made in, and the bounce count is off one way or the other.
    pub fn excludes(self, other: Bug) -> bool {
        let one_way = |a: Bug, b: Bug| match a {
            Bug::PlanesMissing => b == Bug::PlaneBehind,
            // No light is shaded, so no shadow ray is cast either.
            Bug::LightsMissing => matches!(b.stage(), Stage::Lights | Stage::Shadows) && b != a,
            Bug::NoShadows => b.stage() == Stage::Shadows && b != a,
            // The skeleton's trace still weights direct by 1 - r and stops at the bounce
            // count: only the reflected ray's own code is missing.
            Bug::ReflectionMissing => matches!(
                b,
                Bug::NoReflectionBias | Bug::ReflectionWrongSign | Bug::ReflectionUnweighted
            ),
            Bug::ReflectionIgnored => b.stage() == Stage::Reflection && b != a,
            Bug::BouncesPlusOne => b == Bug::BouncesMinusOne,
            // Every lit object its flat colour: no light, so no shadow ray either.
            Bug::ShadingMissing => {
                matches!(b.stage(), Stage::Lights | Stage::Shadows)
                    && !matches!(
                        b,
                        Bug::ShadingMissing | Bug::TonemapMissing | Bug::TonemapTwice
                    )
            }
            Bug::SpheresMissing => b.stage() == Stage::Spheres && b != a,
            // One shadow ray's origin, one reflected ray's, one view vector, one tone map.
            Bug::ShadowBiasAlongN => matches!(b, Bug::ShadowBiasAlongL | Bug::NoShadowBias),
            Bug::ShadowBiasAlongL => b == Bug::NoShadowBias,
            Bug::ReflectionBiasAlongN => b == Bug::NoReflectionBias,
            Bug::ViewToCamera => matches!(b, Bug::ViewFlipped | Bug::ViewFromRayOrigin),
            Bug::TonemapMissing => b == Bug::TonemapTwice,
            _ => false,
        };
        one_way(self, other) || one_way(other, self)
    }

    fn bit(self) -> u64 {
        1 << self as u64
    }
}

// Every entry is one bit of `Mistakes`.
const _: () = assert!(Bug::ALL.len() <= u64::BITS as usize);

/// A set of catalogue entries. The empty set is the course's program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct Mistakes(u64);

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

    /// How many entries the set holds.
    pub fn len(self) -> usize {
        self.0.count_ones() as usize
    }

    /// The set with `bug` added.
    pub fn with(self, bug: Bug) -> Self {
        Mistakes(self.0 | bug.bit())
    }

    /// Every set with one entry of this one left out.
    pub fn one_smaller(self) -> Vec<Mistakes> {
        self.bugs()
            .into_iter()
            .map(|b| Mistakes(self.0 & !b.bit()))
            .collect()
    }

    /// Whether `bug` can join the set: not in it, and excluded by none of its members.
    pub fn admits(self, bug: Bug) -> bool {
        !self.has(bug) && self.bugs().iter().all(|&m| !m.excludes(bug))
    }

    /// The entries in catalogue order.
    pub fn bugs(self) -> Vec<Bug> {
        Bug::ALL.into_iter().filter(|&b| self.has(b)).collect()
    }

    /// The ids, in catalogue order.
    pub fn ids(self) -> Vec<&'static str> {
        self.bugs().into_iter().map(Bug::id).collect()
    }

    /// `a+b` for a pair.
    pub fn name(self) -> String {
        self.ids().join("+")
    }

    /// Whether the hierarchy's exactness argument covers these rules (`Model::hierarchy_exact`).
    pub fn hierarchy_exact(self) -> bool {
        !self.has(Bug::PlaneBehind) && !self.has(Bug::SphereFarRoot)
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
        if self.has(Bug::ReflectionIgnored) {
            bounces = 0;
        }
        FrameSpec {
            bounces,
            shadows: spec.shadows && !self.has(Bug::NoShadows) && !self.has(Bug::LightsMissing),
            acceleration: if self.hierarchy_exact() {
                spec.acceleration
            } else {
                Acceleration::BruteForce
            },
            ..spec.clone()
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
        assert_eq!(ids.len(), Bug::ALL.len());
    }

    #[test]
    fn every_mistake_in_written_code_has_a_place_in_the_commonness_order() {
        let mut order = Bug::BY_COMMONNESS.to_vec();
        order.sort_unstable();
        order.dedup();
        let mistakes: Vec<Bug> = Bug::ALL
            .into_iter()
            .filter(|b| !b.is_unfinished())
            .collect();
        assert_eq!(order, mistakes);
    }

    #[test]
    fn sets_hold_their_bugs_in_catalogue_order() {
        let set = Mistakes::of(&[Bug::SphereFarRoot, Bug::NoAmbient]);
        assert_eq!(set.bugs(), vec![Bug::NoAmbient, Bug::SphereFarRoot]);
        assert!(!set.hierarchy_exact());
        assert!(Mistakes::NONE.is_empty() && Mistakes::NONE.hierarchy_exact());
        assert_eq!(set.len(), 2);
        assert_eq!(set.name(), "no-ambient+sphere-far-root");
        assert_eq!(
            set.one_smaller(),
            vec![
                Mistakes::of(&[Bug::SphereFarRoot]),
                Mistakes::of(&[Bug::NoAmbient])
            ]
        );
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
}
