//! The year a project is of, read from its own classes (docs/grade.md, "The Tick 1 skeleton's
//! API": T1 2017-18, T2 2018-19, T3 2019-20 to 2022-23, T4 2023-24; docs/courses.md): which
//! members `ColorRGB` and `SceneObject` have, whether `SceneLoader` reads materials, the size
//! `Tick1.java` renders and whether it takes `-r`, and two things only some years' copies show
//! (BumpySphere's `heightMap`, 2020-21's extra unit tests). Each clue is a set of years; the
//! year is the one every clue fits, a clue that contradicts the more trusted ones is said and
//! set aside (an edited class), and where the clues leave more than one year (2019-20 and
//! 2020-21 ship the same classes) the latest is taken and said.

use super::find::{Found, Main};
use super::members::{blank, members, Kind};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

/// The year chosen, the report's line saying why, and what else the shape said.
#[derive(Debug, Clone, PartialEq)]
pub struct Year {
    pub course: Course,
    /// None when `--course` chose it and the project agrees.
    pub why: Option<String>,
    /// Clues set aside, or the project's disagreement with `--course`.
    pub notes: Vec<String>,
}

/// One thing the project says about its year: the years it fits and how a reader says it.
#[derive(Debug, Clone)]
struct Clue {
    years: Vec<Course>,
    words: String,
}

/// The project's year: `asked` (`--course`) when given, else what its classes say.
pub fn year(found: &Found, asked: Option<Course>) -> Result<Year> {
    if found.main == Main::Tick2 {
        return tick2(asked);
    }
    if asked == Some(Course::Y2016) {
        return Err(Error::Usage(format!(
            "{} is a Tick 1 project (2017-18 or later), not the 2016-17 Tick 2: give --course \
             with a later year, or leave it out and the project's classes say which",
            found.main_class()
        )));
    }
    let clues = clues(found);
    let (fits, set_aside) = narrow(&clues);
    let course = *fits.last().unwrap_or(&Course::Y2023);
    let mut notes: Vec<String> = set_aside
        .iter()
        .map(|c| {
            format!(
                "{}, which no {} project has: an edited class? (set aside)",
                c.words,
                names(&fits)
            )
        })
        .collect();
    let reasons = reasons(&clues, &set_aside, &fits);
    if let Some(asked) = asked {
        if !fits.contains(&asked) {
            notes.push(format!(
                "the project's classes look like {}'s ({reasons}); checked as {asked}, as \
                 --course asks",
                names(&fits)
            ));
        }
        return Ok(Year {
            course: asked,
            why: None,
            notes,
        });
    }
    let why = match (fits.len(), clues.is_empty()) {
        (_, true) => format!(
            "course: {course}, because the project has none of the classes that tell the years \
             apart (ColorRGB, SceneLoader, SceneObject, Tick1's size): the latest year is taken \
             (--course YEAR checks against another year)"
        ),
        (1, false) => format!(
            "course: {course}, because {reasons} (--course YEAR checks against another year)"
        ),
        _ => format!(
            "course: {course}, because {reasons}, as in {}: their classes are the same, so the \
             latest is taken (--course {} if the project is that year's)",
            names(&fits),
            fits[0]
        ),
    };
    Ok(Year {
        course,
        why: Some(why),
        notes,
    })
}

/// 2016-17's Tick 2: its main class says the year.
fn tick2(asked: Option<Course>) -> Result<Year> {
    match asked {
        Some(course) if !course.is_default() => Err(Error::Usage(format!(
            "the project's main class is Tick2.java, the 2016-17 Tick 2, not {course}'s Tick 1: \
             give --course 2016-17 or leave it out"
        ))),
        Some(course) => Ok(Year {
            course,
            why: None,
            notes: Vec::new(),
        }),
        None => Ok(Year {
            course: Course::Y2016,
            why: Some(
                "course: 2016-17, because the main class is Tick2.java, the 2016-17 Tick 2 \
                 (later years' is Tick1.java)"
                    .into(),
            ),
            notes: Vec::new(),
        }),
    }
}

/// The years a clue keeps, applied from the most trusted on: the years every clue fits, and the
/// clues that would have left none (set aside).
fn narrow(clues: &[Clue]) -> (Vec<Course>, Vec<Clue>) {
    let mut fits: Vec<Course> = later();
    let mut set_aside = Vec::new();
    for clue in clues {
        let kept: Vec<Course> = fits
            .iter()
            .copied()
            .filter(|c| clue.years.contains(c))
            .collect();
        match kept.is_empty() {
            true => set_aside.push(clue.clone()),
            false => fits = kept,
        }
    }
    (fits, set_aside)
}

/// The clues a reader needs, in the order they read best (Tick1's size first): each that rules
/// out a year the ones before it left, until only `fits` is left.
fn reasons(clues: &[Clue], set_aside: &[Clue], fits: &[Course]) -> String {
    let mut shown: Vec<&Clue> = clues
        .iter()
        .filter(|c| !set_aside.iter().any(|s| s.words == c.words))
        .collect();
    shown.sort_by_key(|c| READING_ORDER.iter().position(|w| c.words.starts_with(w)));
    let mut left = later();
    let mut words = Vec::new();
    for clue in shown {
        if left.len() == fits.len() {
            break;
        }
        if left.iter().any(|c| !clue.years.contains(c)) {
            left.retain(|c| clue.years.contains(c));
            words.push(clue.words.clone());
        }
    }
    match words.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => words.join(""),
    }
}

/// How the reasons are ordered in the line: by the start of their words.
const READING_ORDER: [&str; 7] = [
    "Tick1.java renders",
    "ColorRGB",
    "SceneLoader",
    "SceneObject",
    "Tick1.java takes",
    "BumpySphere",
    "Tick1Tests",
];

/// Every year from 2017-18.
fn later() -> Vec<Course> {
    Course::ALL
        .into_iter()
        .filter(|c| !c.is_default())
        .collect()
}

fn years(test: impl Fn(Course) -> bool) -> Vec<Course> {
    later().into_iter().filter(|&c| test(c)).collect()
}

/// What the project's classes say, the most trusted first: the course classes' API, then the
/// loader, then `Tick1.java` (which students edit), then what only some copies show.
fn clues(found: &Found) -> Vec<Clue> {
    let text = |name: &str| {
        found
            .file(name)
            .and_then(|p| std::fs::read(p).ok())
            .map(|b| String::from_utf8_lossy(&b).into_owned())
    };
    let has_method = |source: &str, name: &str| {
        members(source)
            .iter()
            .any(|m| m.kind == Kind::Method && m.name == name && m.visible())
    };
    let mut clues = Vec::new();
    if let Some((class, source)) = text("ColorRGB.java")
        .map(|s| ("ColorRGB", s))
        .or_else(|| text("Vector3.java").map(|s| ("Vector3", s)))
    {
        let power = has_method(&source, "power") && has_method(&source, "inv");
        let zero = has_method(&source, "isZero");
        clues.push(match (power, zero) {
            (_, true) => Clue {
                years: vec![Course::Y2023],
                words: format!("{class} has isZero()"),
            },
            (true, false) => Clue {
                years: years(|c| c >= Course::Y2018 && c < Course::Y2023),
                words: format!("{class} has power()/inv() but no isZero()"),
            },
            (false, false) => Clue {
                years: vec![Course::Y2017],
                words: format!("{class} has no power()/inv()"),
            },
        });
    }
    if let Some(source) = text("SceneObject.java") {
        let transmissive = has_method(&source, "getTransmittance");
        clues.push(Clue {
            years: years(|c| (c >= Course::Y2023) == transmissive),
            words: match transmissive {
                true => "SceneObject has getTransmittance()".into(),
                false => "SceneObject has no transmittance".into(),
            },
        });
    }
    if let Some(source) = text("SceneLoader.java") {
        let materials = blank(&source, false).contains("\"alphaS\"");
        clues.push(Clue {
            years: years(|c| c.dialect().materials == materials),
            words: match materials {
                true => "SceneLoader reads materials (alphaS)".into(),
                false => "SceneLoader reads no materials".into(),
            },
        });
    }
    if let Some(source) = text("Tick1.java") {
        let code = blank(&source, false);
        let resolution = code.contains("\"--resolution\"") || code.contains("\"-r\"");
        clues.push(Clue {
            years: years(|c| (c >= Course::Y2023) == resolution),
            words: match resolution {
                true => "Tick1.java takes -r WxH".into(),
                false => "Tick1.java takes no -r".into(),
            },
        });
        if let Some((w, h)) = size_of(&code) {
            let fit = years(|c| c.size() == (w, h));
            if !fit.is_empty() {
                clues.push(Clue {
                    years: fit,
                    words: format!("Tick1.java renders {w}x{h}"),
                });
            }
        }
    }
    if let Some(source) = text("BumpySphere.java") {
        if members(&source).iter().any(|m| m.name == "heightMap") {
            clues.push(Clue {
                years: years(|c| c >= Course::Y2021),
                words: "BumpySphere's map is called heightMap".into(),
            });
        }
    }
    if let Some(source) = text("Tick1Tests.java") {
        if source.contains("no occluder") || source.contains("cos(theta)") {
            clues.push(Clue {
                years: years(|c| c >= Course::Y2020),
                words: "Tick1Tests has 2020-21's shadow tests".into(),
            });
        }
    }
    clues
}

/// The size `Tick1.java`'s constants give: the first integer assigned to a name with `WIDTH`
/// in it, and to one with `HEIGHT`.
pub fn size_of(code: &str) -> Option<(u32, u32)> {
    let constant = |key: &str| {
        code.match_indices('=').find_map(|(i, _)| {
            let before = code[..i].trim_end();
            let name_start = before
                .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
                .map_or(0, |j| j + 1);
            let name = &before[name_start..];
            if !name.to_ascii_uppercase().contains(key) {
                return None;
            }
            let after = code[i + 1..].trim_start();
            let digits: String = after.chars().take_while(char::is_ascii_digit).collect();
            let rest = after[digits.len()..].trim_start();
            (rest.starts_with(';') && !digits.is_empty())
                .then(|| digits.parse().ok())
                .flatten()
        })
    };
    Some((constant("WIDTH")?, constant("HEIGHT")?))
}

/// Names for a list of years: "2019-20 and 2020-21".
fn names(years: &[Course]) -> String {
    let names: Vec<&str> = years.iter().map(|c| c.name()).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.join(""),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick1_s_size_is_read_from_its_constants() {
        let code = "int w = 3; private static final int WIDTH_PX = 800;\n\
                    private static final int HEIGHT_PX = 600; int width = WIDTH_PX;";
        assert_eq!(size_of(code), Some((800, 600)));
        assert_eq!(
            size_of("static final int DEFAULT_WIDTH_PX = 640; static final int DEFAULT_HEIGHT_PX = 480;"),
            Some((640, 480))
        );
        assert_eq!(size_of("int width = WIDTH_PX;"), None);
    }

    #[test]
    fn a_clue_that_contradicts_the_trusted_ones_is_set_aside_and_the_reasons_are_the_few_needed() {
        let colour = Clue {
            years: years(|c| c >= Course::Y2018 && c < Course::Y2023),
            words: "ColorRGB has power()/inv() but no isZero()".into(),
        };
        let loader = Clue {
            years: years(|c| c >= Course::Y2019),
            words: "SceneLoader reads materials (alphaS)".into(),
        };
        let size = Clue {
            years: vec![Course::Y2021, Course::Y2023],
            words: "Tick1.java renders 800x600".into(),
        };
        let edited = Clue {
            years: vec![Course::Y2017],
            words: "Tick1.java takes nothing".into(),
        };
        let clues = [colour, loader, edited, size];
        let (fits, aside) = narrow(&clues);
        assert_eq!(fits, [Course::Y2021]);
        assert_eq!(aside.len(), 1);
        assert_eq!(
            reasons(&clues, &aside, &fits),
            "Tick1.java renders 800x600 and ColorRGB has power()/inv() but no isZero()"
        );
    }
}
