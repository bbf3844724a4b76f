//! `check --program` on a Tick 1* program: instead of the Tick 1 suite (whose cases would run
//! out of time one after another, and whose byte-for-byte check no random image passes), the
//! handout's scene of each option once (`star_option.rs`), at a size and a time that fit. Each
//! image written goes to its option's judge.

use std::sync::Arc;
use std::time::Duration;

use crate::check::bump::BumpFinding;
use crate::check::bump_judge::{self, BumpVerdict};
use crate::check::program::{run_programs, CaseOutcome, Launch, Ran, RunStatus, SuiteRun};
use crate::check::star_both::BumpDraw;
use crate::check::star_detail;
use crate::check::star_draw::{self, DrawCheck, Process};
use crate::check::star_not_done;
use crate::check::star_option::{self, StarOption};
use crate::check::student_png::{self, Rgb8};
use crate::check::suite::SuiteCase;
use crate::check::tick1_star::{StarSeen, Tick1Star};
use crate::check::Findings;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::scene::{self, Scene};
use whitted_core::star::{BumpMap, BumpedSphere, Star};

/// A Tick 1* option's image and what its judge said of it.
#[derive(Debug, Clone)]
pub struct StarImage {
    pub option: StarOption,
    pub image: Rgb8,
    pub verdict: StarVerdict,
    /// The render the image was compared with, where its verdict has one (option 1's
    /// handout method under the parametrisation found: `star_detail.rs`), for the report
    /// page to show beside it.
    pub reference: Option<Rgb8>,
}

impl StarImage {
    /// The case's `"tick1_star"` object in the JSON.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "option": self.option.name(),
            "width": self.image.width,
            "height": self.image.height,
            "verdict": self.verdict.name(),
            "line": self.verdict.line(),
            "fits": match &self.verdict {
                StarVerdict::Draw(d) => d
                    .fits
                    .iter()
                    .map(|f| {
                        serde_json::json!({
                            "process": f.process.name(),
                            "statistic": f.statistic,
                            "stride": f.stride,
                        })
                    })
                    .collect::<Vec<_>>(),
                StarVerdict::BumpDraw(b) => vec![serde_json::json!({
                    "process": "bump-soft-dof",
                    "parametrisation": b.parametrisation,
                    "mistake": b.mistake.map(|m| m.name()),
                    "statistic": b.statistic,
                })],
                StarVerdict::Bump(_)
                | StarVerdict::NotDone { .. }
                | StarVerdict::NotJudged(_) => Vec::new(),
            },
        })
    }
}

/// What a Tick 1* option's judge says of an image.
#[derive(Debug, Clone, PartialEq)]
pub enum StarVerdict {
    /// Option 1's image: the parametrisation and mistake it follows (`bump.rs`).
    Bump(BumpFinding),
    /// Option 2's image scored as a draw of the course's process and its variants.
    Draw(DrawCheck),
    /// Option 1's image with both options on: a draw of the bumped scene (`star_both.rs`).
    BumpDraw(BumpDraw),
    /// The option's scene rendered by the Tick 1 renderer: the option not done
    /// (`star_not_done.rs`); `neither`: the other option's image was too.
    NotDone { option: StarOption, neither: bool },
    /// No judge of this option's images is built into this whitted: why, in words.
    NotJudged(&'static str),
}

impl StarVerdict {
    /// The JSON value.
    pub fn name(&self) -> &'static str {
        match self {
            StarVerdict::Bump(b) => bump_judge::rendered_name(b),
            StarVerdict::Draw(d) => match d.drawn_from() {
                Some(Process::Course) => "course-draw",
                Some(p) if p.accepted() => "accepted-variant-draw",
                Some(_) => "variant-draw",
                None => "not-a-draw",
            },
            StarVerdict::BumpDraw(b) => bump_judge::drawn_name(b),
            StarVerdict::NotDone { .. } => "option-not-done",
            StarVerdict::NotJudged(_) => "not-judged",
        }
    }

    /// Whether nothing wrong was found (the exit status).
    pub fn passes(&self) -> bool {
        match self {
            StarVerdict::Bump(b) => b.passes(),
            StarVerdict::Draw(d) => d.passes(),
            StarVerdict::BumpDraw(b) => b.passes(),
            // One option is enough; neither is not.
            StarVerdict::NotDone { neither, .. } => !neither,
            StarVerdict::NotJudged(_) => true,
        }
    }

    /// The verdict in a line.
    pub fn line(&self) -> String {
        match self {
            // The case's line names the option already.
            StarVerdict::Bump(b) => b.finding(),
            StarVerdict::Draw(d) => d.line(),
            StarVerdict::BumpDraw(b) => b.sentence(),
            StarVerdict::NotDone { option, neither } => star_not_done::sentence(*option, *neither),
            StarVerdict::NotJudged(why) => format!("not judged: {why}"),
        }
    }
}

/// The judge of `option`'s image of its handout scene, rendered under `course` at `bounces`:
/// option 1's in `bump_judge.rs`'s order (the one `check -i bump.xml` follows too); option
/// 2's first whether it is the Tick 1 render (the option not done), then as a draw.
pub fn judge(
    option: StarOption,
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<StarVerdict> {
    let (scene, star) = handout_scene(option, course)?;
    let not_done = StarVerdict::NotDone {
        option,
        neither: false,
    };
    Ok(match option {
        StarOption::Bump => {
            match bump_judge::judge(&scene, &star, image, bounces, course)?.verdict {
                BumpVerdict::NotDone => not_done,
                BumpVerdict::Rendered(finding) => StarVerdict::Bump(finding),
                BumpVerdict::Drawn(draw) => StarVerdict::BumpDraw(draw),
            }
        }
        StarOption::Distributed => {
            if star_not_done::is_tick1_render(&scene, image, bounces, course)? {
                return Ok(not_done);
            }
            StarVerdict::Draw(star_draw::check(&scene, image, bounces, course)?)
        }
    })
}

/// The judge of one image of a Tick 1* case (one of `star_option::cases`), as [`run`] judges
/// it: for a caller that renders the case again on another build of the same program and
/// compares verdicts, a random image's only fair comparison (`check DIR`'s second build). None
/// for a case of no option's scene.
pub fn judge_case(case: &SuiteCase, image: &Rgb8) -> Result<Option<StarVerdict>> {
    match StarOption::of_file(&case.file) {
        Some(option) => judge(option, image, case.bounces, case.course).map(Some),
        None => Ok(None),
    }
}

/// The option's handout scene as `course` reads it, and a star holding its bumped spheres,
/// each with the handout's map (none for option 2's scene): what the judge and `--verbose`
/// render.
pub(crate) fn handout_scene(option: StarOption, course: Course) -> Result<(Scene, Star)> {
    let (scene, _, bumps) =
        scene::input::parse_with_bumps(option.file(), option.xml().as_bytes(), course)?;
    let bumps = match bumps.is_empty() {
        true => Vec::new(),
        false => {
            let map = Arc::new(handout_map(option)?);
            bumps
                .iter()
                .map(|b| BumpedSphere {
                    object: b.object,
                    map: Arc::clone(&map),
                })
                .collect()
        }
    };
    let star = Star {
        bumps,
        ..Star::default()
    };
    Ok((scene, star))
}

/// The handout's bump map, shipped with its scene, read as the course reads it.
pub(crate) fn handout_map(option: StarOption) -> Result<BumpMap> {
    let bad = |why: String| Error::Usage(format!("the handout's bump map: {why}"));
    let (_, bytes) = option
        .assets()
        .first()
        .ok_or_else(|| bad("missing".into()))?;
    let rgb = student_png::decode(bytes).map_err(bad)?;
    let texels: Vec<[u8; 3]> = rgb
        .bytes
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    BumpMap::from_rgb8(rgb.width as usize, rgb.height as usize, &texels)
        .ok_or_else(|| bad("empty".into()))
}

/// Runs the Tick 1* program `launch` starts (shown as `program`, recognised by `seen`) on
/// each option's handout scene of `course`, once, giving each `asked` seconds (at least
/// `LONG_TIMEOUT` at a year's own size); one option out of time does not stop the other.
pub fn run(
    launch: &dyn Launch,
    program: &str,
    course: Course,
    asked: u64,
    seen: StarSeen,
) -> Result<SuiteRun> {
    let cases = star_option::cases(course);
    let timeout = star_option::timeout(course, asked);
    let (finished, _) = run_programs(launch, &cases, Duration::from_secs(timeout), false)?;
    let mut outcomes = Vec::new();
    for (case, (ran, stderr_tail)) in cases.iter().zip(finished) {
        let status = match (ran, StarOption::of_file(&case.file)) {
            (Ran::Image(image), Some(option)) => {
                let verdict = judge(option, &image, case.bounces, course)?;
                let reference =
                    star_detail::reference(option, &verdict, &image, case.bounces, course)?;
                RunStatus::Star(Box::new(StarImage {
                    option,
                    verdict,
                    image,
                    reference,
                }))
            }
            (Ran::Image(_), None) => RunStatus::Crashed("not a Tick 1* scene".into()),
            (Ran::Failed(status), _) => status,
        };
        outcomes.push(CaseOutcome {
            name: case.name(),
            case: case.clone(),
            status,
            stderr_tail,
            said_above: false,
        });
    }
    // Neither option done: each image is the Tick 1 render, and that is no Tick 1*.
    let not_done = |o: &CaseOutcome| matches!(&o.status, RunStatus::Star(s) if matches!(s.verdict, StarVerdict::NotDone { .. }));
    if outcomes.iter().all(not_done) {
        for outcome in &mut outcomes {
            if let RunStatus::Star(s) = &mut outcome.status {
                if let StarVerdict::NotDone { neither, .. } = &mut s.verdict {
                    *neither = true;
                }
            }
        }
    }
    let mut findings = Findings::of_star(course);
    findings.tick1_star = Some(Tick1Star {
        seen,
        timeout,
        stopped: false,
        plan: Some(star_option::plan(course, asked)),
    });
    Ok(SuiteRun {
        program: program.to_string(),
        cases: outcomes,
        findings,
    })
}
