//! A Tick 1* program (docs/courses.md, "Tick 1*"; docs/check.md): soft shadows and depth of
//! field trace hundreds of random rays a pixel, so a case takes minutes and its image is a
//! random draw no byte-for-byte check can pass. Said once, at the top of the report, with what
//! to do, however it was recognised: rather than a row of timeouts, or noise diagnosed.

/// How the program was recognised as Tick 1*.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StarSeen {
    /// Its main class is in a `tick1star` package, as the handout has students copy it.
    Package,
    /// Its `Renderer.java` declares `SHADOW_RAY_COUNT` or `DOF_RAY_COUNT` (option 2's rays).
    RayCounts,
    /// Run twice on one case, it wrote two different images (`noise.rs`).
    TwoRunsDiffer,
    /// Its first case, the suite's quickest, ran out of time.
    FirstCaseTimedOut,
    /// A hand-in of its option's file alone (`BumpySphere.java`, or a Tick 1* `Renderer.java`
    /// without the Tick 1 files), as the handout asks students to submit: `grade` completes
    /// it with whitted's finished Tick 1, so neither its package nor its ray counts are what
    /// the report should name.
    HandIn,
}

impl StarSeen {
    /// The JSON value.
    pub fn name(self) -> &'static str {
        match self {
            StarSeen::Package => "package",
            StarSeen::RayCounts => "ray-counts",
            StarSeen::TwoRunsDiffer => "two-runs-differ",
            StarSeen::FirstCaseTimedOut => "first-case-timed-out",
            StarSeen::HandIn => "hand-in",
        }
    }
}

impl StarSeen {
    /// How it was recognised, in the report's words.
    pub fn why(self) -> &'static str {
        match self {
            StarSeen::Package => "its package is tick1star",
            StarSeen::RayCounts => "its Renderer has SHADOW_RAY_COUNT or DOF_RAY_COUNT",
            StarSeen::TwoRunsDiffer => "run twice on one case, it wrote two different images",
            StarSeen::FirstCaseTimedOut => "its first case, the quickest, ran out of time",
            StarSeen::HandIn => {
                "a hand-in of its option's file alone, completed with whitted's finished Tick 1"
            }
        }
    }
}

/// What the check knows of a Tick 1* program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tick1Star {
    pub seen: StarSeen,
    /// The time each case was given, in seconds.
    pub timeout: u64,
    /// Whether the suite was stopped at its first case out of time.
    pub stopped: bool,
    /// How its options' scenes were run instead of the suite (`star_option::plan`), when
    /// it was recognised before running.
    pub plan: Option<String>,
}

/// Whether `program` (its command line) runs a class of the course's `tick1star` package.
pub fn in_package(program: &str) -> bool {
    program.contains(".tick1star.")
}

/// Whether the sources of a program (file name and bytes; `package` the one they declare)
/// are a Tick 1* submission, and by what: the `tick1star` package, or a `Renderer` that
/// declares option 2's ray counts. A `BumpySphere.java` says nothing: every 2023-24 project
/// holds the skeleton's stub of it, edited or not.
pub fn in_sources(package: Option<&str>, sources: &[(&str, &[u8])]) -> Option<StarSeen> {
    if package.is_some_and(|p| p == "tick1star" || p.ends_with(".tick1star")) {
        return Some(StarSeen::Package);
    }
    let rays = |text: &[u8]| {
        let text = String::from_utf8_lossy(text);
        text.contains("SHADOW_RAY_COUNT") || text.contains("DOF_RAY_COUNT")
    };
    sources
        .iter()
        .any(|(name, text)| *name == "Renderer.java" && rays(text))
        .then_some(StarSeen::RayCounts)
}

impl Tick1Star {
    /// The report's one line: what it is, why whitted thinks so, what to do.
    pub fn sentence(&self) -> String {
        if let Some(plan) = &self.plan {
            return format!(
                "a Tick 1* program ({}): whitted {plan}. Each image is \
                 judged as its option's (the bump map under the parametrisations students \
                 choose; the random image as a draw of the course's distribution; an image of \
                 the Tick 1 renderer as that option not done), not against the Tick 1 suite. \
                 To check your ray tracer itself, run your Tick 1 code (package tick1).",
                self.seen.why()
            );
        }
        let why = match self.seen {
            StarSeen::Package | StarSeen::RayCounts | StarSeen::HandIn => {
                self.seen.why().to_string()
            }
            StarSeen::TwoRunsDiffer => {
                "run twice on one case, it wrote two different images".to_string()
            }
            StarSeen::FirstCaseTimedOut => format!(
                "its first case, the quickest, ran out of time ({} s); if it is not Tick 1*, it \
                 never finishes",
                self.timeout
            ),
        };
        // The longer time is worth saying only where a case ran out of it.
        let time = match self.stopped {
            true => format!(
                " The suite stopped at its first case out of time. To see its images, give it a \
                 longer --timeout (this run allowed {} s a case).",
                self.timeout
            ),
            false => String::new(),
        };
        format!(
            "a Tick 1* program ({why}): soft shadows and depth of field trace hundreds of random \
             rays a pixel, so a case takes minutes and its image is a random draw that no \
             byte-for-byte check passes.{time} To check your ray tracer, run your Tick 1 code \
             (package tick1, without the Tick 1* additions); of the Tick 1* code itself \
             whitted checks today only whether its images are noise around the reference \
             (compared blurred), not the method."
        )
    }

    /// A case not run after the suite stopped.
    pub fn not_run(&self) -> String {
        match self.seen {
            StarSeen::FirstCaseTimedOut => {
                "the first case ran out of time, so the rest were not run (see above)".into()
            }
            _ => "the Tick 1* program ran out of time on an earlier case (see above)".into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_says_what_it_is_and_what_to_do() {
        let star = Tick1Star {
            seen: StarSeen::FirstCaseTimedOut,
            timeout: 3,
            stopped: true,
            plan: None,
        };
        let line = star.sentence();
        for words in [
            "Tick 1*",
            "ran out of time (3 s)",
            "--timeout",
            "random",
            "allowed 3 s",
        ] {
            assert!(line.contains(words), "{words}: {line}");
        }
        assert!(in_package(
            "java -cp out uk.ac.cam.cl.gfxintro.ab1.tick1star.Tick1"
        ));
        assert!(!in_package(
            "java -cp out uk.ac.cam.cl.gfxintro.ab1.tick1.Tick1"
        ));
    }

    #[test]
    fn a_submission_is_tick1_star_by_its_package_or_its_ray_counts() {
        let renderer = |text: &'static str| ("Renderer.java", text.as_bytes());
        let plain = [renderer("class Renderer { int x; }")];
        assert_eq!(
            in_sources(Some("uk.ac.cam.cl.gfxintro.ab1.tick1"), &plain),
            None
        );
        assert_eq!(
            in_sources(Some("uk.ac.cam.cl.gfxintro.ab1.tick1star"), &plain),
            Some(StarSeen::Package)
        );
        // Every 2023-24 project holds the skeleton's BumpySphere: it says nothing.
        let bumpy = [("BumpySphere.java", &b"class BumpySphere {}"[..])];
        assert_eq!(in_sources(None, &bumpy), None);
        let rays = [renderer("static final int SHADOW_RAY_COUNT = 10;")];
        assert_eq!(in_sources(None, &rays), Some(StarSeen::RayCounts));
        // The constant named in another file is not the Renderer's.
        let elsewhere = [("Plane.java", &b"// DOF_RAY_COUNT"[..])];
        assert_eq!(in_sources(None, &elsewhere), None);
    }

    #[test]
    fn a_planned_run_says_what_was_run_instead_of_the_suite() {
        let star = Tick1Star {
            seen: StarSeen::Package,
            timeout: 60,
            stopped: false,
            plan: Some("ran the handout's scenes once each".into()),
        };
        let line = star.sentence();
        assert!(
            line.contains("whitted ran the handout's scenes once each"),
            "{line}"
        );
        assert!(!line.contains("--timeout"), "{line}");
    }
}
