//! A failing Tick 1* case of `check DIR`, explained as `compare.rs` explains a Tick 1 case, but
//! by verdicts, not pixels: a Tick 1* image is random, so two runs of one build differ pixel
//! for pixel whatever the classes, while the judge's verdict on each does not (a draw of the
//! course's process stays one). The case is rendered again on the student's own files among
//! the year's clean-room classes and judged by the same judge; only where that verdict is not
//! the project's did a course class of the project's change the image beyond chance, and the
//! class is found one at a time, each try a whole render and a judge, so few are tried.

use super::compare::{render, OnYear, Rendered};
use super::find::Found;
use super::javac::Build;
use whitted_check::check::star_draw::Process;
use whitted_check::check::star_option;
use whitted_check::check::star_run::{judge_case, StarVerdict};
use whitted_check::check::suite::SuiteCase;
use whitted_core::course::Course;
use whitted_core::error::Result;

/// Classes tried one at a time at most: each try renders the case again (minutes at a year's
/// own size) and judges it; the likeliest come first (`OnYear::edited`).
const MOST_TRIED: usize = 3;

/// What a verdict says, its numbers aside: two images whose verdicts say the same are judged
/// alike, however their statistics differ from draw to draw.
fn says(verdict: &StarVerdict) -> String {
    let what = match verdict {
        StarVerdict::Draw(d) => d.drawn_from().map_or("", Process::name).to_string(),
        StarVerdict::Bump(b) => format!("{} {:?}", b.parametrisation, b.mistake),
        StarVerdict::BumpDraw(b) => format!("{} {:?}", b.parametrisation, b.mistake),
        // Whether the other option was done too is the other case's: not this image's.
        StarVerdict::NotDone { option, .. } => option.name().to_string(),
        StarVerdict::NotJudged(_) => String::new(),
    };
    format!("{} {what}", verdict.name())
}

/// The verdict in the report's words: its name, and the variant or mistake it names.
fn shown(verdict: &StarVerdict) -> String {
    let named = match verdict {
        StarVerdict::Draw(d) => d
            .drawn_from()
            .filter(|p| *p != Process::Course)
            .map(Process::name),
        StarVerdict::Bump(b) if !b.passes() => b.mistake.map(|m| m.name()),
        StarVerdict::BumpDraw(b) => b.mistake.map(|m| m.name()),
        _ => None,
    };
    match named {
        Some(n) => format!("{} ({n})", verdict.name()),
        None => verdict.name().to_string(),
    }
}

/// The failing Tick 1* `case`, whose image the whole project rendered and its judge gave
/// `theirs`, rendered and judged again on the student's own files among `course`'s classes;
/// where the verdicts differ, the course class of the project's that gives its verdict, tried
/// one at a time (`suspects` first, at most [`MOST_TRIED`]). `say` hears, before each render,
/// what is run and why (each takes as long as the project's). Lines for the report: none when
/// the verdicts agree.
pub fn verdicts_differ(
    found: &Found,
    course: Course,
    case: &SuiteCase,
    theirs: &StarVerdict,
    suspects: &[String],
    asked: u64,
    say: &dyn Fn(&str),
) -> Result<Vec<String>> {
    let Some(on) = OnYear::new(found, course)? else {
        return Ok(Vec::new());
    };
    // As the project's case was given (`star_run::run`).
    let timeout = star_option::timeout(course, asked);
    let scene = &case.file;
    let year_build = match on.build(None)? {
        Ok(b) => b,
        Err(errors) => return Ok(vec![on.not_compiling(&errors)]),
    };
    say(&format!(
        "rendering {scene} again, on your {} among {course}'s own classes, to see whether a \
         course class of your project changes its verdict (up to {timeout} s, as the first \
         render)",
        on.submitted()
    ));
    let judged = |build: &Build| -> Result<Option<StarVerdict>> {
        Ok(match render(build, &on.java, case, timeout)? {
            Rendered::Image(image) => judge_case(case, &image)?,
            Rendered::Nothing => None,
        })
    };
    let Some(on_year) = judged(&year_build)? else {
        return Ok(vec![format!(
            "your {} among {course}'s own classes write no image of {scene} of its size, where \
             your project's is judged {}: a course class of your project is what makes it run",
            on.submitted(),
            shown(theirs)
        )]);
    };
    if says(&on_year) == says(theirs) {
        return Ok(Vec::new());
    }
    let mut lines = vec![format!(
        "your project's image of {scene} is judged {}, but your {} among {course}'s own \
         classes render one judged {}: a course class of your project changes the verdict, \
         and the course's tester uses its own",
        shown(theirs),
        on.submitted(),
        shown(&on_year)
    )];
    let edited = on.edited(suspects);
    let mut tried = Vec::new();
    for name in edited.iter().take(MOST_TRIED) {
        let Ok(swapped) = on.build(Some(name))? else {
            continue;
        };
        tried.push(*name);
        say(&format!(
            "rendering {scene} with your {name} among {course}'s own classes (try {} of at \
             most {MOST_TRIED})",
            tried.len()
        ));
        let Some(with_theirs) = judged(&swapped)? else {
            continue;
        };
        if says(&with_theirs) == says(theirs) {
            lines.push(format!(
                "{name} is not {course}'s: with your {name} among {course}'s own classes, your \
                 {} render {scene} judged {}, as your project does; the course's tester uses \
                 its own {name}, so that verdict may not be your renderer's: undo the change \
                 to {name}",
                on.submitted(),
                shown(&with_theirs)
            ));
            return Ok(lines);
        }
    }
    let untried: Vec<&str> = edited.iter().skip(MOST_TRIED).copied().collect();
    lines.push(format!(
        "no one of your project's course classes tried alone ({}) gives its verdict{}",
        match tried.is_empty() {
            true => "none could be".to_string(),
            false => tried.join(", "),
        },
        match untried.is_empty() {
            true => String::new(),
            false => format!(
                "; not tried, each try being a render and a judge: {}",
                untried.join(", ")
            ),
        }
    ));
    Ok(lines)
}

#[cfg(test)]
mod tests {
    use super::*;
    use whitted_check::check::star_option::StarOption;

    #[test]
    fn an_option_not_done_says_the_same_whether_or_not_the_other_was() {
        let not_done = |neither| StarVerdict::NotDone {
            option: StarOption::Distributed,
            neither,
        };
        assert_eq!(says(&not_done(true)), says(&not_done(false)));
        let other = StarVerdict::NotDone {
            option: StarOption::Bump,
            neither: false,
        };
        assert_ne!(says(&not_done(false)), says(&other));
        assert_ne!(says(&not_done(false)), says(&StarVerdict::NotJudged("why")));
        assert_eq!(shown(&not_done(true)), "option-not-done");
    }
}
