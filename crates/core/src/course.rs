//! Course profiles (docs/courses.md): every year of the exercise as data. A profile chooses the
//! model's rules ([`Rules`], which implements [`crate::model::Model`]), the scene reader's
//! dialect and defaults ([`Dialect`]), the camera's row step, the tone map and the default
//! size. There is one renderer; a year is a parameter of it, never a copy.

pub mod api;
pub mod rules;

pub use api::Api;
pub use rules::Rules;

use crate::scene::Material;
use crate::tonemap::ToneMap;
use glam::DVec3;

/// A year of the course, as `--course` names it. A closed set, in time order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub enum Course {
    /// The 2016-17 Tick 2: whitted's own rules of docs/rendering.md, its strict scene format.
    #[default]
    Y2016,
    /// 2017-18: the ray tracer becomes Tick 1; V from the ray's origin, coloured specular.
    Y2017,
    /// 2018-19: 2019-20's renderer with 2017-18's loader (planes kD .6).
    Y2018,
    /// 2019-20: tone map, N.L gate, background 0.001, planes with the sphere's materials.
    Y2019,
    /// 2020-21: 2019-20 with the shadow ray moved along N.
    Y2020,
    /// 2021-22 (and presumably 2022-23): 2020-21's arithmetic at 800x600.
    Y2021,
    /// 2023-24: 2021-22 with `-r WxH` and transmittance attributes (not rendered).
    Y2023,
}

/// How the view vector V is taken (docs/courses.md, "view vector V").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// `normalise(-P)`: towards the camera at the origin, even for reflected rays.
    ToCamera,
    /// `normalise(O - P)`: towards the origin of the ray that found the point.
    FromRayOrigin,
}

/// Along which vector a shadow ray's origin is moved off the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadowBias {
    AlongL,
    AlongN,
}

/// How far the camera steps between rows of pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowStep {
    /// The column step (square pixels), as 2016-17 computes it.
    Columns,
    /// The image plane's height over the row count, computed on its own: one ulp from the
    /// column step at some sizes (1024x768).
    PlaneHeight,
}

/// Which scene format a profile reads (docs/courses.md, "Scenes (the loader)").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dialect {
    /// `false`: whitted's own strict format (2016-17). `true`: the year's loader, lenient.
    pub course_loader: bool,
    /// Whether spheres and planes read `kD kS alphaS reflectivity`.
    pub materials: bool,
    /// Whether `<ambient-light>` reads `intensity`.
    pub ambient_intensity: bool,
    /// Whether spheres read `tr tg tb` (2023-24; transmittance, not rendered).
    pub transmittance: bool,
    /// The material a sphere gets (its colour aside) before any attribute.
    pub sphere: Material,
    /// The material a plane gets (its colour aside) before any attribute.
    pub plane: Material,
}

impl Course {
    /// Every profile, in time order.
    pub const ALL: [Course; 7] = [
        Course::Y2016,
        Course::Y2017,
        Course::Y2018,
        Course::Y2019,
        Course::Y2020,
        Course::Y2021,
        Course::Y2023,
    ];

    /// The name `--course` takes and EXR headers record.
    pub fn name(self) -> &'static str {
        match self {
            Course::Y2016 => "2016-17",
            Course::Y2017 => "2017-18",
            Course::Y2018 => "2018-19",
            Course::Y2019 => "2019-20",
            Course::Y2020 => "2020-21",
            Course::Y2021 => "2021-22",
            Course::Y2023 => "2023-24",
        }
    }

    /// The profile called `name` (a year as `--course` writes it; `2022-23` is `2021-22`'s).
    pub fn from_name(name: &str) -> Option<Course> {
        if name == "2022-23" {
            return Some(Course::Y2021);
        }
        Course::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Whether this is whitted's own default, the 2016-17 Tick 2.
    pub fn is_default(self) -> bool {
        self == Course::Y2016
    }

    /// The model's rules under this profile.
    pub fn rules(self) -> Rules {
        let later = self >= Course::Y2018;
        Rules {
            view: match self {
                Course::Y2016 => View::ToCamera,
                _ => View::FromRayOrigin,
            },
            light_coloured_specular: !self.is_default(),
            gate: later,
            reflect_unclamped: !self.is_default(),
            shadow_bias: if self >= Course::Y2020 {
                ShadowBias::AlongN
            } else {
                ShadowBias::AlongL
            },
            far_root: !self.is_default(),
            background: if later { 0.001 } else { 0.1 },
        }
    }

    /// The course classes' API a submission of this year compiles against (docs/grade.md).
    pub fn api(self) -> Api {
        match self {
            Course::Y2016 => Api::Tick2,
            Course::Y2017 => Api::T1,
            Course::Y2018 => Api::T2,
            Course::Y2019 | Course::Y2020 | Course::Y2021 => Api::T3,
            Course::Y2023 => Api::T4,
        }
    }

    /// How the camera steps between rows.
    pub fn row_step(self) -> RowStep {
        match self {
            Course::Y2016 => RowStep::Columns,
            _ => RowStep::PlaneHeight,
        }
    }

    /// The PNG's tone map.
    pub fn tonemap(self) -> ToneMap {
        if self >= Course::Y2018 {
            ToneMap::Sigmoid
        } else {
            ToneMap::Tick
        }
    }

    /// The size the year's program renders by default.
    pub fn size(self) -> (u32, u32) {
        if self >= Course::Y2021 {
            (800, 600)
        } else {
            (640, 480)
        }
    }

    /// The scene reader's dialect and defaults.
    pub fn dialect(self) -> Dialect {
        let colourless = DVec3::ZERO;
        let sphere_ks = if self >= Course::Y2018 { 1.2 } else { 0.8 };
        let sphere = Material {
            ks: sphere_ks,
            ..Material::sphere(colourless)
        };
        let plane = match self {
            Course::Y2016 | Course::Y2017 => Material::plane(colourless),
            Course::Y2018 => Material {
                kd: 0.6,
                ..Material::plane(colourless)
            },
            _ => sphere,
        };
        Dialect {
            course_loader: !self.is_default(),
            materials: self >= Course::Y2019,
            ambient_intensity: self >= Course::Y2019,
            transmittance: self >= Course::Y2023,
            sphere,
            plane,
        }
    }

    /// The scene a program of this year renders when given none: the course's own, compiled
    /// in, and its name for messages and headers.
    pub fn default_scene(self) -> (&'static str, &'static str) {
        match self {
            Course::Y2016 | Course::Y2017 => {
                (crate::scene::EMBEDDED_TICK2, crate::scene::EMBEDDED_NAME)
            }
            Course::Y2018 => (
                include_str!("../scenes/courses/2018-19/tick1.xml"),
                "2018-19 tick1.xml (embedded)",
            ),
            Course::Y2019 => (
                include_str!("../scenes/courses/2019-20/test1.xml"),
                "2019-20 test1.xml (embedded)",
            ),
            // One scene (the same bytes) for three years, each named as its own year's: a
            // 2023-24 student's report must not speak of 2020-21.
            Course::Y2020 | Course::Y2021 | Course::Y2023 => (
                include_str!("../scenes/courses/2020-21/test1.xml"),
                match self {
                    Course::Y2020 => "2020-21 test1.xml (embedded)",
                    Course::Y2021 => "2021-22 test1.xml (embedded)",
                    _ => "2023-24 test1.xml (embedded)",
                },
            ),
        }
    }

    /// Every name `--course` accepts, for messages.
    pub fn names() -> String {
        Course::ALL.map(Course::name).join(", ")
    }
}

impl std::fmt::Display for Course {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_2022_23_is_2021_22() {
        for course in Course::ALL {
            assert_eq!(Course::from_name(course.name()), Some(course));
        }
        assert_eq!(Course::from_name("2022-23"), Some(Course::Y2021));
        assert_eq!(Course::from_name("2016"), None);
        assert_eq!(Course::default(), Course::Y2016);
    }

    #[test]
    fn the_years_differ_where_the_spec_says() {
        assert_eq!(Course::Y2019.rules().shadow_bias, ShadowBias::AlongL);
        assert_eq!(Course::Y2020.rules().shadow_bias, ShadowBias::AlongN);
        assert_eq!(Course::Y2020.rules(), Course::Y2023.rules());
        assert_eq!(Course::Y2018.rules(), Course::Y2019.rules());
        assert!(!Course::Y2017.rules().gate);
        assert_eq!(Course::Y2017.rules().background, 0.1);
        assert_eq!(Course::Y2019.rules().background, 0.001);
        assert_eq!(Course::Y2021.size(), (800, 600));
        assert_eq!(Course::Y2020.size(), (640, 480));
        assert_eq!(Course::Y2018.dialect().plane.kd, 0.6);
        assert_eq!(
            Course::Y2019.dialect().plane,
            Course::Y2019.dialect().sphere
        );
        assert_eq!(Course::Y2019.dialect().sphere.ks, 1.2);
        assert_eq!(Course::Y2017.dialect().sphere.ks, 0.8);
        assert_eq!(Course::Y2017.tonemap(), ToneMap::Tick);
        assert_eq!(Course::Y2018.tonemap(), ToneMap::Sigmoid);
    }

    #[test]
    fn each_year_names_its_embedded_scene_as_its_own() {
        for course in [Course::Y2019, Course::Y2020, Course::Y2021, Course::Y2023] {
            let (_, name) = course.default_scene();
            assert!(name.starts_with(course.name()), "{course}: {name}");
        }
        assert_eq!(
            Course::Y2021.default_scene().0,
            Course::Y2023.default_scene().0
        );
    }
}
