//! The scenes `whitted check --program` runs a student's program on (`scenes/check/`,
//! compiled in so that an installed binary has them). Only what the course's loader reads:
//! spheres, planes, point and ambient lights with their attributes, no materials or names,
//! so that a correct program renders every one. Our own scenes separate the mistakes that the
//! course's two scenes cannot: lights behind and beyond objects, overlapping spheres, mirrors
//! facing each other, a plane close under the camera (see docs/check.md).

/// One case: a scene at a bounce count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SuiteCase {
    /// The scene's file name in `scenes/check/`.
    pub file: &'static str,
    pub xml: &'static str,
    pub bounces: u32,
}

impl SuiteCase {
    /// `tick2.xml -b 2`.
    pub fn name(&self) -> String {
        format!("{} -b {}", self.file, self.bounces)
    }
}

const TICK2: &str = include_str!("../../scenes/check/tick2.xml");
const SPECULAR_TEST: &str = include_str!("../../scenes/check/specular_test.xml");
const SHADOWS: &str = include_str!("../../scenes/check/shadows.xml");
const MIRRORS: &str = include_str!("../../scenes/check/mirrors.xml");

/// The suite, in the order it runs and is reported.
pub fn cases() -> Vec<SuiteCase> {
    let case = |file, xml, bounces| SuiteCase { file, xml, bounces };
    vec![
        case("tick2.xml", TICK2, 0),
        case("tick2.xml", TICK2, 1),
        case("tick2.xml", TICK2, 2),
        case("tick2.xml", TICK2, 3),
        case("specular_test.xml", SPECULAR_TEST, 2),
        case("shadows.xml", SHADOWS, 1),
        case("mirrors.xml", MIRRORS, 3),
    ]
}
