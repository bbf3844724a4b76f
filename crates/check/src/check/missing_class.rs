//! A program whose classes did not all compile (docs/check.md, "A program that did not
//! compile"). An IDE writes the classes that compile and leaves out the rest, so the program
//! starts and dies on its first use of a missing one, in every case alike, each with the same
//! stack trace. The suite says so once, with the class and, where the course is known to cause
//! it, the fix; each case's line then only names the class.

use whitted_core::course::Course;

/// How the JVM said that a class is not there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Symptom {
    /// `NoClassDefFoundError` or `ClassNotFoundException`: a class the program uses.
    Missing,
    /// `Could not find or load main class`: the program's own main class.
    MainClass,
    /// `Unresolved compilation problem`: the class was written with its errors in it (an
    /// IDE that compiles past errors).
    Unresolved,
}

/// A class the program needed and did not have, over the suite.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MissingClass {
    /// Its simple name (`BumpySphere`).
    pub class: String,
    /// Its full name, dotted, as the JVM named it.
    pub qualified: String,
    pub symptom: Symptom,
    /// How many cases failed on it, of how many.
    pub cases: usize,
    pub of: usize,
    /// The course's known cause and its fix, where there is one.
    pub known_cause: Option<&'static str>,
}

/// What 2023-24's zip does: its BumpySphere does not compile as shipped (docs/courses.md).
const BUMPY_2023: &str = "2023-24's BumpySphere.java as the course ships it does not compile: \
     its getNormalAt has no return statement; add one at its end (`return normal;`, or \
     `return super.getNormalAt(position);` until you do Tick 1*) and compile every class again";

/// The class a standard error tail says is missing, and how it said so; None when it does
/// not say so.
pub fn in_tail(tail: &str) -> Option<(String, Symptom)> {
    const MARKERS: [(&str, Symptom); 4] = [
        ("Could not find or load main class ", Symptom::MainClass),
        ("java.lang.NoClassDefFoundError: ", Symptom::Missing),
        ("java.lang.ClassNotFoundException: ", Symptom::Missing),
        ("Unresolved compilation problem", Symptom::Unresolved),
    ];
    let (at, symptom) = MARKERS
        .iter()
        .filter_map(|&(marker, symptom)| tail.find(marker).map(|i| (i + marker.len(), symptom)))
        .min_by_key(|&(at, _)| at)?;
    let name = match symptom {
        // The class is the one whose method threw: the first frame after the message.
        Symptom::Unresolved => {
            let frame = tail[at..]
                .lines()
                .find_map(|l| l.trim().strip_prefix("at "))?;
            let method = frame.split('(').next()?;
            method.rsplit_once('.')?.0.to_string()
        }
        _ => tail[at..].split_whitespace().next()?.to_string(),
    };
    let name = name
        .trim_end_matches(|c: char| !c.is_alphanumeric() && c != '_' && c != '$')
        .replace('/', ".");
    (!name.is_empty()).then_some((name, symptom))
}

impl MissingClass {
    /// The class most cases of `tails` (each case's standard error tail, None for a case that
    /// wrote its image) failed on, if any did; `course` names the known causes.
    pub fn of_suite(tails: &[Option<&str>], course: Course) -> Option<MissingClass> {
        let found: Vec<(String, Symptom)> =
            tails.iter().flatten().filter_map(|t| in_tail(t)).collect();
        let (qualified, symptom) = found.first()?.clone();
        let cases = found.iter().filter(|(q, _)| *q == qualified).count();
        let class = qualified
            .rsplit('.')
            .next()
            .unwrap_or(&qualified)
            .to_string();
        let known_cause = (course == Course::Y2023 && class == "BumpySphere").then_some(BUMPY_2023);
        Some(MissingClass {
            class,
            qualified,
            symptom,
            cases,
            of: tails.len(),
            known_cause,
        })
    }

    /// The suite's one line about it.
    pub fn sentence(&self) -> String {
        let cases = match self.cases == self.of {
            true => format!("every case ({})", self.of),
            false => format!("{} of {} cases", self.cases, self.of),
        };
        let what = match self.symptom {
            Symptom::MainClass => format!(
                "the main class {} was not found: the program did not compile (or -cp does not \
                 name the folder its classes were written to)",
                self.qualified
            ),
            Symptom::Missing => format!(
                "class {} is missing: it did not compile, and the IDE wrote the other classes \
                 without it",
                self.class
            ),
            Symptom::Unresolved => format!(
                "class {} was written with compile errors in it (an IDE that compiles past \
                 errors)",
                self.class
            ),
        };
        let cause = match self.known_cause {
            Some(cause) => cause.to_string(),
            None => format!(
                "compile again and read the compiler's first error in {}.java",
                self.class
            ),
        };
        format!("{cases} crashed the same way: {what}; {cause}")
    }

    /// A failing case's own line, once the suite's says why.
    pub fn case_message(&self, status: &str) -> String {
        format!("{status}: class {} missing (see above)", self.class)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const NO_CLASS: &str = "Loading scene 'x'\nException in thread \"main\" java.lang.NoClassDefFoundError: uk/ac/cam/cl/gfxintro/ab1/tick1/BumpySphere\n\tat uk.ac.cam.cl.gfxintro.ab1.tick1.Tick1.main(Tick1.java:70)\nCaused by: java.lang.ClassNotFoundException: uk.ac.cam.cl.gfxintro.ab1.tick1.BumpySphere\n";

    #[test]
    fn the_missing_class_is_read_from_the_jvm_s_words() {
        assert_eq!(
            in_tail(NO_CLASS),
            Some((
                "uk.ac.cam.cl.gfxintro.ab1.tick1.BumpySphere".to_string(),
                Symptom::Missing
            ))
        );
        let main = "Error: Could not find or load main class a.b.Tick1\nCaused by: java.lang.ClassNotFoundException: a.b.Tick1";
        assert_eq!(
            in_tail(main),
            Some(("a.b.Tick1".to_string(), Symptom::MainClass))
        );
        let eclipse = "Exception in thread \"main\" java.lang.Error: Unresolved compilation problem: \n\tThis method must return a result of type Vector3\n\n\tat a.b.BumpySphere.getNormalAt(BumpySphere.java:40)\n";
        assert_eq!(
            in_tail(eclipse),
            Some(("a.b.BumpySphere".to_string(), Symptom::Unresolved))
        );
        assert_eq!(
            in_tail("Exception in thread \"main\" java.lang.NullPointerException"),
            None
        );
    }

    #[test]
    fn the_suite_says_it_once_with_the_known_cause() {
        let tails = vec![Some(NO_CLASS); 6];
        let missing = MissingClass::of_suite(&tails, Course::Y2023).expect("missing");
        assert_eq!(
            (missing.class.as_str(), missing.cases, missing.of),
            ("BumpySphere", 6, 6)
        );
        let line = missing.sentence();
        assert!(
            line.starts_with("every case (6) crashed the same way: class BumpySphere is missing"),
            "{line}"
        );
        assert!(line.contains("return normal;"), "{line}");
        // Another year, another class: no known cause, the compiler's error to read.
        let other =
            MissingClass::of_suite(&[Some(NO_CLASS), None], Course::Y2021).expect("missing");
        assert!(other.known_cause.is_none());
        assert!(
            other.sentence().starts_with("1 of 2 cases"),
            "{}",
            other.sentence()
        );
        assert!(MissingClass::of_suite(&[None, Some("boom")], Course::Y2021).is_none());
    }
}
