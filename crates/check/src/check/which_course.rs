//! Never the wrong course in silence (docs/courses.md, "Choosing the profile"). Without
//! `--course`, what a check is given can say which year it belongs to: the image's size (the
//! later years render 800x600), the scene (the course's own test scenes, or the attributes
//! only the later years' loader reads) and the program's main class (`gfx.tick2.Tick2` is
//! 2016-17's, `uk.ac.cam.cl.gfxintro.<crsid>.tick1.Tick1` every later year's). The check then
//! runs under the one year that fits, or the first of years that render alike, and says so;
//! where years that render differently fit, it refuses and lists them.

use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

/// The year a check runs under, and why when it was not asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct Chosen {
    pub course: Course,
    /// A line for the report: which year was picked and from what.
    pub why: Option<String>,
}

impl Chosen {
    fn asked(course: Course) -> Chosen {
        Chosen { course, why: None }
    }
}

/// The course's own test scenes of the later years, and the years that ship each.
const KNOWN_SCENES: [(&str, &[Course]); 5] = [
    (
        include_str!("../../scenes/courses/2018-19/tick1.xml"),
        &[Course::Y2018],
    ),
    (
        include_str!("../../scenes/courses/2019-20/test1.xml"),
        &[Course::Y2019],
    ),
    (
        include_str!("../../scenes/courses/2019-20/test2.xml"),
        &[Course::Y2019, Course::Y2020],
    ),
    (
        include_str!("../../scenes/courses/2020-21/test1.xml"),
        &[Course::Y2020, Course::Y2021, Course::Y2023],
    ),
    (
        include_str!("../../scenes/courses/2021-24/test2.xml"),
        &[Course::Y2021, Course::Y2023],
    ),
];

/// The years a scene can be of, and why; None when it could be any year's.
fn scene_years(xml: &[u8]) -> Option<(Vec<Course>, String)> {
    if let Some((_, years)) = KNOWN_SCENES.iter().find(|(k, _)| k.as_bytes() == xml) {
        return Some((
            years.to_vec(),
            "the scene is the course's own test scene of".into(),
        ));
    }
    let later = whitted_core::scene::xml::has_later_year_attributes(xml);
    later.then(|| {
        (
            Course::ALL
                .into_iter()
                .filter(|c| c.dialect().materials)
                .collect(),
            "the scene has attributes (alphaS, the ambient light's intensity) only the loader of"
                .into(),
        )
    })
}

/// The years whose programs write an image of this size, and why; None for any.
fn size_years((width, height): (u32, u32)) -> Option<(Vec<Course>, String)> {
    let years: Vec<Course> = Course::ALL
        .into_iter()
        .filter(|c| c.size() == (width, height))
        .collect();
    // A size no year renders by default says nothing (2023-24's `-r` renders any).
    (width, height)
        .ne(&Course::Y2016.size())
        .then_some(years)
        .filter(|y| !y.is_empty())
        .map(|years| (years, format!("{width}x{height} is the image size of")))
}

/// Whether two years render every scene both read to the same image.
fn renders_alike(a: Course, b: Course) -> bool {
    let (da, db) = (a.dialect(), b.dialect());
    a.rules() == b.rules()
        && a.tonemap() == b.tonemap()
        && a.row_step() == b.row_step()
        && da.materials == db.materials
        && da.ambient_intensity == db.ambient_intensity
        && da.sphere == db.sphere
        && da.plane == db.plane
}

/// Names for a list of years: "2021-22 and 2023-24".
fn names(years: &[Course]) -> String {
    let names: Vec<&str> = years.iter().map(|c| c.name()).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.join(""),
    }
}

/// The year that fits every piece of evidence: the default when nothing points elsewhere,
/// the one year that fits, or the first of years that render alike; else an error listing
/// the `--course` values that fit.
fn choose(evidence: &[(Vec<Course>, String)]) -> Result<Chosen> {
    if evidence.is_empty() {
        return Ok(Chosen::asked(Course::default()));
    }
    let fits: Vec<Course> = Course::ALL
        .into_iter()
        .filter(|c| evidence.iter().all(|(years, _)| years.contains(c)))
        .collect();
    let reasons: Vec<String> = evidence
        .iter()
        .map(|(years, why)| format!("{why} {}", names(years)))
        .collect();
    let reasons = reasons.join("; ");
    match fits.as_slice() {
        [] => Err(Error::Usage(format!(
            "no year of the course fits: {reasons}; give --course YEAR ({})",
            Course::names()
        ))),
        [first, rest @ ..] if rest.iter().all(|&c| renders_alike(*first, c)) => {
            let alike = if rest.is_empty() {
                String::new()
            } else {
                format!(" ({} render alike)", names(&fits))
            };
            Ok(Chosen {
                course: *first,
                why: Some(format!(
                    "course: {}{alike}, because {reasons} (--course YEAR checks against another year)",
                    first.name()
                )),
            })
        }
        _ => Err(Error::Usage(format!(
            "{reasons}: give --course with one of {} (their rules differ)",
            names(&fits)
        ))),
    }
}

/// The year an image check runs under: `asked`, else what the image's size and the scene's
/// bytes (None: the year's own test scene) say.
pub fn for_image(asked: Option<Course>, size: (u32, u32), scene: Option<&[u8]>) -> Result<Chosen> {
    if let Some(course) = asked {
        return Ok(Chosen::asked(course));
    }
    let evidence: Vec<(Vec<Course>, String)> = size_years(size)
        .into_iter()
        .chain(scene.and_then(scene_years))
        .collect();
    choose(&evidence)
}

/// Whether the command names a later year's main class, `...gfxintro.<crsid>.tick1.Tick1`.
fn is_tick1(program: &str) -> bool {
    program
        .split_whitespace()
        .any(|w| w.ends_with(".tick1.Tick1") || w.ends_with("/tick1/Tick1"))
}

/// Whether the command names 2016-17's main class, `gfx.tick2.Tick2`.
fn is_tick2(program: &str) -> bool {
    program
        .split_whitespace()
        .any(|w| w.ends_with("gfx.tick2.Tick2") || w.ends_with("gfx/tick2/Tick2"))
}

/// The year a `--program` check runs under: `asked` unless the main class says it is
/// another year's program; without `--course`, a Tick 1 program is refused with the years it
/// can be (they render differently, and only the images would tell).
pub fn for_program(asked: Option<Course>, program: &str) -> Result<Chosen> {
    let later: Vec<Course> = Course::ALL
        .into_iter()
        .filter(|c| !c.is_default())
        .collect();
    match asked {
        Some(course) if course.is_default() && is_tick1(program) => Err(Error::Usage(format!(
            "the main class is a Tick 1 program of 2017-18 or later, not 2016-17's \
             gfx.tick2.Tick2: give --course with one of {}",
            names(&later)
        ))),
        Some(course) if !course.is_default() && is_tick2(program) => Err(Error::Usage(format!(
            "the main class gfx.tick2.Tick2 is a 2016-17 program, not {course}'s Tick 1: \
                 give --course 2016-17"
        ))),
        Some(course) => Ok(Chosen::asked(course)),
        None if is_tick1(program) => choose(&[(
            later,
            "the main class is a Tick 1 program (...gfxintro.<crsid>.tick1.Tick1), of".into(),
        )]),
        None => Ok(Chosen::asked(Course::default())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_800x600_image_is_checked_as_2021_22_and_says_so() {
        let chosen = for_image(None, (800, 600), None).expect("fits");
        assert_eq!(chosen.course, Course::Y2021);
        let why = chosen.why.expect("a line");
        assert!(
            why.contains("800x600") && why.contains("2023-24 render alike"),
            "{why}"
        );
    }

    #[test]
    fn the_default_stays_silent_and_asking_wins() {
        assert_eq!(
            for_image(None, (640, 480), None).expect("fits"),
            Chosen::asked(Course::Y2016)
        );
        assert_eq!(
            for_image(Some(Course::Y2019), (800, 600), None).expect("asked"),
            Chosen::asked(Course::Y2019)
        );
    }

    #[test]
    fn a_later_scene_at_640x480_is_refused_with_the_years_that_fit() {
        let scene = include_str!("../../scenes/courses/2019-20/test2.xml");
        let Err(Error::Usage(message)) = for_image(None, (640, 480), Some(scene.as_bytes())) else {
            panic!("2019-20 and 2020-21 render test2 differently");
        };
        assert!(message.contains("2019-20 and 2020-21"), "{message}");
        let test1 = include_str!("../../scenes/courses/2019-20/test1.xml");
        let chosen = for_image(None, (640, 480), Some(test1.as_bytes())).expect("one year");
        assert_eq!(chosen.course, Course::Y2019);
        let unknown = r##"<scene><ambient-light colour="#010101" intensity="2"/></scene>"##;
        let chosen = for_image(None, (800, 600), Some(unknown.as_bytes())).expect("fits");
        assert_eq!(chosen.course, Course::Y2021);
        // Materials are whitted's own format too: they point at no year.
        let own = r##"<scene><sphere x="0" y="0" z="5" radius="1" colour="#ff0000" kD="0.5" kS="0.2" reflectivity="0"/></scene>"##;
        let chosen = for_image(None, (640, 480), Some(own.as_bytes())).expect("whitted's own");
        assert_eq!(chosen, Chosen::asked(Course::Y2016));
    }

    #[test]
    fn programs_say_their_year_by_their_main_class() {
        let tick1 = "java -cp out uk.ac.cam.cl.gfxintro.zc344.tick1.Tick1";
        let Err(Error::Usage(message)) = for_program(None, tick1) else {
            panic!("a Tick 1 program needs its year");
        };
        assert!(
            message.contains("2017-18") && message.contains("2023-24"),
            "{message}"
        );
        assert!(for_program(Some(Course::Y2016), tick1).is_err());
        assert_eq!(
            for_program(Some(Course::Y2021), tick1)
                .expect("asked")
                .course,
            Course::Y2021
        );
        assert!(for_program(Some(Course::Y2021), "java -cp out gfx.tick2.Tick2").is_err());
        assert_eq!(
            for_program(None, "java -cp out gfx.tick2.Tick2")
                .expect("2016")
                .course,
            Course::Y2016
        );
    }
}
