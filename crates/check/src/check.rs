//! `whitted check`: the tester a student runs at home (docs/check.md). It renders the
//! reference at the student's image size, compares every byte, and, where they differ, names
//! the catalogue entries (mistakes and unfinished stages, up to three at once) that reproduce
//! the student's images best (`check::diagnose`), or else the terms of the model
//! (`check::terms`) or the wrong number (`check::numbers`) the difference lives in, and where
//! the student is in the handout (`check::progress`). `--program` runs the student's own
//! program over a suite of scenes and diagnoses every case at once.

pub mod another_scene;
pub mod bump;
pub mod bump_judge;
pub mod case;
pub mod diagnose;
pub mod difference;
pub mod image_cache;
pub mod missing_class;
pub mod noise;
pub mod numbers;
pub mod outside;
pub mod pass_rule;
pub mod pixel_sample;
pub mod print;
pub mod program;
pub mod progress;
pub mod renderer;
pub mod report;
pub mod reproduce;
pub mod result;
pub mod score;
pub mod star_both;
pub mod star_detail;
pub mod star_draw;
pub mod star_fix;
pub mod star_not_done;
pub mod star_option;
pub mod star_prepass;
pub mod star_reference;
pub mod star_reference_file;
pub mod star_run;
pub mod student_png;
pub mod suite;
pub mod summary;
pub mod terms;
pub mod tick1_star;
pub mod which_course;
pub mod words;

use crate::check::case::Case;
use crate::check::diagnose::{CaseFinding, Diagnosis, Search};
use crate::check::difference::{difference, Difference};
use crate::check::image_cache::ImageCache;
use crate::check::missing_class::MissingClass;
use crate::check::noise::Noise;
use crate::check::numbers::NumberFit;
use crate::check::outside::Outside;
use crate::check::pass_rule::PassRule;
use crate::check::progress::{Evidence, Stages};
use crate::check::renderer::{Renderer, SharedScene};
use crate::check::student_png::Rgb8;
use crate::check::terms::{TermCase, TermFit};
use crate::check::tick1_star::Tick1Star;
use crate::mistakes::Mistakes;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene::Scene;
use whitted_core::tonemap::ToneMap;

/// Below this share of differing pixels explained, the best catalogued candidate is not a
/// good explanation: the term and number fits run, and the report says so first.
pub const GOOD_EXPLANATION: f64 = 0.9;

/// A number fit that reproduces this share of the differing pixels is the whole story: the
/// weak candidates are not printed.
pub const SETTLED: f64 = 0.99;

/// The share the best entries must explain for a number to be fitted on top of them too.
const PART_EXPLAINED: f64 = 0.3;

/// What the diagnosis found over one or more cases.
#[derive(Debug, Clone)]
pub struct Findings {
    /// Best first; empty when every image is identical or nothing explains them better than
    /// the reference does.
    pub diagnosis: Vec<Diagnosis>,
    /// Per case, what the best explanation says of it.
    pub per_case: Vec<CaseFinding>,
    /// Where no candidate explains the images well: the model's terms they differ in.
    pub terms: Vec<TermFit>,
    /// Where no candidate explains the images well: the model's numbers that do.
    pub parameters: Vec<NumberFit>,
    pub progress: Stages,
    /// Some case is noisy as random sampling makes it (Tick 1*): nothing is diagnosed.
    pub not_reproducible: Option<Noise>,
    /// `--program`: the cases died on a class that did not compile (said once, at the top).
    pub missing_class: Option<MissingClass>,
    /// `--program`: the program is a Tick 1* one (said once, at the top).
    pub tick1_star: Option<Tick1Star>,
    /// Where no candidate explains the images well: where what it leaves lies.
    pub outside: Option<Outside>,
    /// A Tick 1* bump-mapped image: what option 1's judge found (`bump_judge.rs`): option 1
    /// not done, the parametrisation and mistake a deterministic image follows, or what a
    /// draw with both options on is a draw of.
    pub bump: Option<bump_judge::BumpVerdict>,
    /// An image checked against the default scene that looks like another scene's
    /// (`another_scene.rs`): the note, said in place of a diagnosis that would assume the
    /// default scene.
    pub another_scene: Option<String>,
}

impl Findings {
    /// Whether no catalogued candidate explains `GOOD_EXPLANATION` of the differing pixels.
    pub fn weak(&self) -> bool {
        weak(&self.diagnosis)
    }

    /// The number fit that explains the images better than any catalogued candidate, if one
    /// does: then it is the report's story.
    pub fn by_number(&self) -> Option<&NumberFit> {
        by_number(&self.diagnosis, &self.parameters)
    }

    /// Whether a fit beyond the catalogue explains so much (`SETTLED`) that weak candidates
    /// would only distract.
    pub fn settled_by_fit(&self) -> bool {
        settled(&self.diagnosis, &self.parameters)
    }

    /// Nothing diagnosed because the images are noisy (`noise.rs`).
    pub fn not_reproducible(cases: usize, course: Course, noise: Noise) -> Findings {
        let mut findings = Findings::nothing(cases, Evidence::Unexplained, course);
        findings.not_reproducible = Some(noise);
        findings
    }

    /// A Tick 1* program's run (`star_run.rs`): its images are judged by their options,
    /// nothing is diagnosed.
    pub fn of_star(course: Course) -> Findings {
        Findings::nothing(0, Evidence::Nothing, course)
    }

    /// A bump-mapped image's findings: option 1's judge's, nothing else diagnosed.
    pub fn of_bump(verdict: bump_judge::BumpVerdict, course: Course) -> Findings {
        let evidence = if verdict.passes() {
            Evidence::AllCorrect
        } else {
            Evidence::Unexplained
        };
        let mut findings = Findings::nothing(1, evidence, course);
        findings.bump = Some(verdict);
        findings
    }

    /// An image of another scene than the default one it was checked against: the note
    /// (`another_scene.rs`) and nothing diagnosed.
    pub fn of_another_scene(note: String, course: Course) -> Findings {
        let mut findings = Findings::nothing(1, Evidence::Nothing, course);
        findings.another_scene = Some(note);
        findings
    }

    /// Nothing found: no images, or every one identical.
    fn nothing(cases: usize, evidence: Evidence, course: Course) -> Findings {
        Findings {
            diagnosis: Vec::new(),
            per_case: vec![CaseFinding::default(); cases],
            terms: Vec::new(),
            parameters: Vec::new(),
            progress: Stages::of(&evidence, course),
            not_reproducible: None,
            missing_class: None,
            tick1_star: None,
            outside: None,
            bump: None,
            another_scene: None,
        }
    }
}

/// Diagnoses `cases` (each rendered under `course`) together; `all_pass` says whether every
/// case (of the suite, including those with no image) passed.
pub fn find(cases: &[Case], all_pass: bool, course: Course) -> Result<Findings> {
    if cases.is_empty() {
        return Ok(Findings::nothing(0, Evidence::Nothing, course));
    }
    if cases.iter().all(Case::identical) {
        let evidence = if all_pass {
            Evidence::AllCorrect
        } else {
            Evidence::Nothing
        };
        return Ok(Findings::nothing(cases.len(), evidence, course));
    }
    let mut search = Search::run(cases)?;
    // A number fit that settles the story (`SETTLED`) hides every weak candidate, so their
    // whole renders are skipped; it is tried first where the sample already says the
    // catalogue is weak. Otherwise the findings are what finalising first and fitting
    // after gives: the fit is kept only where the whole renders say weak too, and done
    // again if they change its bases.
    let mut fitted = None;
    if weak(&search.diagnosis(cases)) {
        let fit = Fitted::on(cases, &search.diagnosis(cases))?;
        if fit.settles(&search.diagnosis(cases)) {
            return Ok(fit.findings(cases, search.diagnosis(cases), all_pass, course));
        }
        fitted = Some(fit);
    }
    search.finalise(cases)?;
    let mut diagnosis = search.diagnosis(cases);
    // Where the catalogue is weak and what the best candidate leaves lies on one kind of
    // object, an entry of it that reproduces nothing but pixels of that kind is not needed:
    // the off-catalogue story claims them. The candidates holding one are set aside.
    if let Some(top) = diagnosis.first().filter(|_| weak(&diagnosis)) {
        let top = top.mistakes;
        if let Some(kind) = Outside::of(cases, top)?.as_ref().and_then(Outside::kind) {
            let absorbed = outside::absorbed(cases, top, kind)?;
            if !absorbed.is_empty() {
                search.absorb(absorbed);
                search.finalise(cases)?;
                diagnosis = search.diagnosis(cases);
            }
        }
    }
    if let Some(top) = diagnosis
        .first_mut()
        .filter(|d| d.explained >= GOOD_EXPLANATION)
    {
        top.image_identical_with = search.image_identical_with(cases, top.mistakes)?;
    }
    let per_case = (0..cases.len())
        .map(|i| match diagnosis.first() {
            Some(top) => search.in_case(cases, top.mistakes, i),
            None => CaseFinding::default(),
        })
        .collect();
    let mut findings = Findings {
        diagnosis,
        per_case,
        terms: Vec::new(),
        parameters: Vec::new(),
        progress: Stages::of(&Evidence::Nothing, course),
        not_reproducible: None,
        missing_class: None,
        tick1_star: None,
        outside: None,
        bump: None,
        another_scene: None,
    };
    if findings.weak() {
        let fit = match fitted {
            Some(fit) if fit.bases == Fitted::bases(&findings.diagnosis) => fit,
            _ => Fitted::on(cases, &findings.diagnosis)?,
        };
        fit.tell(&mut findings, cases);
        if !findings.settled_by_fit() {
            let top = findings
                .diagnosis
                .first()
                .map_or(Mistakes::NONE, |d| d.mistakes);
            findings.outside = Outside::of(cases, top)?;
        }
    }
    findings.progress = Stages::of(&evidence(&findings, all_pass), course);
    Ok(findings)
}

/// Whether no catalogued candidate in `diagnosis` explains `GOOD_EXPLANATION`.
fn weak(diagnosis: &[Diagnosis]) -> bool {
    diagnosis
        .first()
        .is_none_or(|d| d.explained < GOOD_EXPLANATION)
}

/// The best number fit, where it explains more than the best catalogued candidate.
fn by_number<'a>(diagnosis: &[Diagnosis], parameters: &'a [NumberFit]) -> Option<&'a NumberFit> {
    let top = diagnosis.first();
    parameters
        .first()
        .filter(|n| top.is_none_or(|d| n.explained > d.explained))
}

/// Whether the catalogue is weak and a number fit explains `SETTLED`.
fn settled(diagnosis: &[Diagnosis], parameters: &[NumberFit]) -> bool {
    weak(diagnosis) && by_number(diagnosis, parameters).is_some_and(|n| n.explained >= SETTLED)
}

/// What is fitted beyond the catalogue where it explains too little: the model's terms, and
/// its numbers alone and on top of the best entries.
struct Fitted {
    bases: Vec<Mistakes>,
    terms: Vec<TermFit>,
    parameters: Vec<NumberFit>,
}

impl Fitted {
    /// No entries, and the best entries where they explain a good part: a half-written
    /// program with one wrong number.
    fn bases(diagnosis: &[Diagnosis]) -> Vec<Mistakes> {
        let mut bases = vec![Mistakes::NONE];
        bases.extend(
            diagnosis
                .first()
                .filter(|d| d.explained >= PART_EXPLAINED)
                .map(|d| d.mistakes),
        );
        bases
    }

    fn on(cases: &[Case], diagnosis: &[Diagnosis]) -> Result<Fitted> {
        let bases = Fitted::bases(diagnosis);
        Ok(Fitted {
            terms: fit_terms(cases)?,
            parameters: numbers::fit(cases, &bases)?,
            bases,
        })
    }

    /// Whether the best number settles the story over `diagnosis`.
    fn settles(&self, diagnosis: &[Diagnosis]) -> bool {
        settled(diagnosis, &self.parameters)
    }

    /// Findings whose story is this fit (the candidates in `diagnosis` as the sample
    /// scored them: none of them is shown).
    fn findings(
        self,
        cases: &[Case],
        diagnosis: Vec<Diagnosis>,
        all_pass: bool,
        course: Course,
    ) -> Findings {
        let mut findings = Findings {
            diagnosis,
            per_case: vec![CaseFinding::default(); cases.len()],
            terms: Vec::new(),
            parameters: Vec::new(),
            progress: Stages::of(&Evidence::Nothing, course),
            not_reproducible: None,
            missing_class: None,
            tick1_star: None,
            outside: None,
            bump: None,
            another_scene: None,
        };
        self.tell(&mut findings, cases);
        findings.progress = Stages::of(&evidence(&findings, all_pass), course);
        findings
    }

    /// Puts the fits into `findings`; when a number explains the images best, each case
    /// tells its part of that story.
    fn tell(self, findings: &mut Findings, cases: &[Case]) {
        findings.terms = self.terms;
        findings.parameters = self.parameters;
        if let Some(fit) = findings.by_number() {
            let labels: Vec<Option<Diagnosis>> = fit
                .per_case
                .iter()
                .zip(cases)
                .map(|(d, case)| (!case.identical()).then(|| d.clone()))
                .collect();
            for (finding, label) in findings.per_case.iter_mut().zip(labels) {
                *finding = CaseFinding {
                    label,
                    exactly: false,
                };
            }
        }
    }
}

/// The best explanation found, for the progress.
fn evidence(findings: &Findings, all_pass: bool) -> Evidence {
    let top = findings.diagnosis.first();
    match (top, findings.by_number()) {
        (_, Some(n)) => Evidence::Explained {
            mistakes: n.with,
            number: Some(n.parameter),
            explained: n.explained,
        },
        // What lies outside the catalogue on one kind of object is a story of its own: the
        // stages are read from the catalogued rest.
        (Some(d), None) => Evidence::Explained {
            mistakes: d.mistakes,
            number: None,
            explained: match &findings.outside {
                Some(o) if o.located() => d.explained + o.share,
                _ => d.explained,
            },
        },
        (None, None) if all_pass => Evidence::AllCorrect,
        (None, None) => Evidence::Unexplained,
    }
}

/// The term fit over the sampled differing pixels of every case, a factor shared by all.
/// Its least squares read a byte as the linear value it clamps: not run for the years whose
/// PNG is tone-mapped.
fn fit_terms(cases: &[Case]) -> Result<Vec<TermFit>> {
    let linear = cases
        .first()
        .is_none_or(|c| c.renderer.course().tonemap() == ToneMap::Tick);
    if !linear {
        return Ok(Vec::new());
    }
    let term_cases: Vec<TermCase> = cases
        .iter()
        .filter(|c| !c.identical())
        .map(|c| {
            let pixels = &c.sample.positions[..c.sample.wrong];
            let samples = c.renderer.layers_at(pixels)?;
            Ok(TermCase::new(
                c.renderer.scene,
                c.renderer.bounces(),
                &samples,
                pixels,
                &c.student,
            ))
        })
        .collect::<Result<_>>()?;
    Ok(terms::fit(&term_cases))
}

/// A student's Tick 1* bump-mapped image of `scene` (its bumped spheres in `star`, the maps
/// of the student's own scene) judged by option 1's judge (`bump_judge.rs`), the one
/// `--star bump` and a program's run use, so `-i bump.xml` and no `-i` agree. The case is
/// judged by `rule` against the render the verdict is read against: the Tick 1 render for
/// option 1 not done, else the correct method in the parametrisation found (a draw's own).
pub fn check_bump_image(
    scene: &Scene,
    scene_name: &str,
    star: &whitted_core::star::Star,
    (bounces, rule): (u32, PassRule),
    student: Rgb8,
    course: Course,
) -> Result<(CaseReport, Findings)> {
    use bump_judge::BumpVerdict;
    use whitted_core::star::{bump::Parametrisation, BumpMethod, Star};
    let judged = bump_judge::judge(scene, star, &student, bounces, course)?;
    let size = (student.width, student.height);
    let reference = match (&judged.verdict, judged.correct) {
        (BumpVerdict::NotDone, _) | (_, None) => bump::render_bump(
            scene,
            &Star::default(),
            BumpMethod::default(),
            size,
            bounces,
            course,
        )?,
        (BumpVerdict::Drawn(draw), _) => {
            let method = BumpMethod {
                parametrisation: Parametrisation::named(draw.parametrisation).unwrap_or_default(),
                mistake: None,
            };
            bump::render_bump(scene, star, method, size, bounces, course)?
        }
        (BumpVerdict::Rendered(_), Some(correct)) => correct,
    };
    let report = bump_report(scene_name, (bounces, rule), student, reference);
    Ok((report, Findings::of_bump(judged.verdict, course)))
}

/// A bump image's case: judged by `rule` against `reference`, with no Tick 1 diagnosis (a
/// bump image's finding is the bump check's, never a Tick 1 mistake).
fn bump_report(
    scene_name: &str,
    (bounces, rule): (u32, PassRule),
    student: Rgb8,
    reference: Rgb8,
) -> CaseReport {
    CaseReport {
        scene_name: scene_name.to_string(),
        bounces,
        difference: difference(&student, &reference, rule),
        diagnosis: Vec::new(),
        hidden_mistakes: Mistakes::NONE,
        student,
        reference,
    }
}

/// Everything known about one student image of one scene.
#[derive(Debug, Clone)]
pub struct CaseReport {
    pub scene_name: String,
    pub bounces: u32,
    /// How it differs, and the verdict by the rule it was given (`difference.rule`).
    pub difference: Difference,
    /// The diagnosis as it concerns this case: the whole ranking for one image; in a suite,
    /// the part of the suite's explanation that shows here, if it explains this case.
    pub diagnosis: Vec<Diagnosis>,
    /// Entries this case passes with, yet renders exactly as they do: the same fix as the
    /// failing cases'.
    pub hidden_mistakes: Mistakes,
    pub student: Rgb8,
    pub reference: Rgb8,
}

/// One case ready to diagnose, and its report without a diagnosis yet. `shared` names the
/// scene for the cache of whole images (`image_cache.rs`), when it is one many checks share.
#[allow(clippy::too_many_arguments)]
pub fn prepare<'a>(
    scene: &'a Scene,
    scene_name: &str,
    bounces: u32,
    rule: PassRule,
    student: Rgb8,
    cases: usize,
    shared: Option<SharedScene>,
    course: Course,
) -> Result<(Case<'a>, CaseReport)> {
    let renderer = Renderer::new(scene, student.width, student.height, bounces)?
        .in_course(course)
        .remembered_as(shared);
    let case = Case::new(renderer, student, cases)?;
    let report = CaseReport {
        scene_name: scene_name.to_string(),
        bounces,
        difference: difference(&case.student, &case.reference, rule),
        diagnosis: Vec::new(),
        hidden_mistakes: Mistakes::NONE,
        student: case.student.clone(),
        reference: case.reference.clone(),
    };
    Ok((case, report))
}

/// Checks `student` against `scene` rendered at its size with `bounces` bounces under
/// `course`'s rules, passing it by `rule`.
pub fn check_image(
    scene: &Scene,
    scene_name: &str,
    bounces: u32,
    rule: PassRule,
    student: Rgb8,
    course: Course,
) -> Result<(CaseReport, Findings)> {
    // A cache of this check's own (one scene, so its name is empty): the search asks for
    // some whole images more than once (the top candidate's, to confirm the entries it
    // masks). Its samples are asked for once each, so they are not kept.
    let own = SharedScene {
        key: String::new(),
        bounce_family: Vec::new(),
        cache: ImageCache::new(),
        samples: false,
    };
    let (case, mut report) = prepare(
        scene,
        scene_name,
        bounces,
        rule,
        student,
        1,
        Some(own),
        course,
    )?;
    let passes = report.difference.verdict.passes();
    let findings = find(std::slice::from_ref(&case), passes, course)?;
    report.diagnosis = findings.diagnosis.clone();
    report.hidden_mistakes = findings.per_case[0].hidden(passes);
    Ok((report, findings))
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_courses;
