//! Naming the mistakes: candidate programs (sets of up to three catalogue entries) are
//! rendered as the course's model with those rules broken, and ranked by how well they
//! reproduce the student's images over every case at once, so that an entry that explains
//! every failing case ranks first and one that changes a case the student got right falls.
//!
//! Two stages keep a 640x480 check within a second on two cores. First every candidate
//! renders only each case's sample (`check::case`): every single entry and every pair, then
//! (unless the best of those reproduces every case exactly) a beam of the best pairs extended
//! by one more entry where that lowers the cost. Then the best `FINALISTS` render every case
//! whole, and their numbers are exact; after one that reproduces the student's images
//! exactly, only those that could be its twins. On a tie of cost, fewer entries rank first,
//! then catalogue order.

use std::collections::HashMap;

use rayon::prelude::*;

use crate::check::case::Case;
use crate::check::difference::pixel_difference;
use crate::check::score::{cost, explained_share, Scored};
use crate::check::student_png::Rgb8;
use crate::mistakes::{Bug, Mistakes, Number, Stage, Variant};
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::numbers::plain;

/// Candidates the second stage renders whole, at most: those whose sampled cost is within
/// `CLOSE` of the best (plus a margin for the sample's noise), where the ranking could turn.
pub const FINALISTS: usize = 4;
const CLOSE: f64 = 2.0;

/// Candidates that hinge on rounding scored every way it can go, per stage of the search.
const ROUNDED: usize = 3;

/// Pairs extended to triples.
const BEAM: usize = 6;

/// Entries an explanation masks, listed at most.
const MASKED_LISTED: usize = 3;

/// Diagnoses listed at most.
const LISTED: usize = 8;

/// One diagnosis: a candidate and how well it reproduces the student's images.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnosis {
    pub mistakes: Mistakes,
    /// Share of the differing pixels it reproduces within 1 LSB.
    pub explained: f64,
    pub unexplained_pixels: u64,
    pub wrongly_changed_pixels: u64,
    /// Candidates with as many entries that render every case identically.
    pub indistinguishable_from: Vec<Mistakes>,
    /// Whether the numbers were counted over whole images (else estimated from a sample).
    pub exact: bool,
    /// A fitted number of the model that is part of this explanation (a case's label when a
    /// number explains the images best).
    pub number: Option<Number>,
    /// Share of the differing pixels reproduced only as one way rounding can go (shadow
    /// acne and self-reflections: `whitted_core::model::rounding`).
    pub by_rounding: f64,
    /// Entries that, added to these, render every case byte for byte the same: the images
    /// cannot tell whether the program has them too. Most common first.
    pub image_identical_with: Vec<Bug>,
    /// The year it is a diagnosis of: its words are that year's (`Bug::advice`).
    pub course: Course,
}

impl Diagnosis {
    /// The explanation's name: its entries, and its number as `name=value`.
    pub fn name(&self) -> String {
        let number = self
            .number
            .map(|n| format!("{}={}", n.parameter.name(), plain(n.value)));
        let parts: Vec<String> = self
            .mistakes
            .ids()
            .into_iter()
            .map(str::to_string)
            .chain(number)
            .collect();
        parts.join("+")
    }
}

/// What the reference itself explains of `cases`: its cost, the cost of "no mistake".
pub fn null_cost(case: &Case) -> f64 {
    case.wrong
        .iter()
        .map(|&i| {
            cost(pixel_difference(
                &case.student.bytes,
                &case.reference.bytes,
                i,
            ))
        })
        .sum()
}

/// Every candidate scored on the samples, the finalists on whole images, in no set order.
pub struct Search {
    scored: Vec<Scored>,
    /// The candidates scored every way their rounding can go.
    rounded: Vec<Mistakes>,
    /// Entries the story outside the catalogue absorbs (`outside::absorbed`): no candidate
    /// holding one is worth ranking.
    absorbed: Mistakes,
}

/// Scores `list` on the samples, on every core.
fn score_all(cases: &[Case], list: &[Mistakes]) -> Result<Vec<Scored>> {
    list.par_iter()
        .map(|&m| Scored::on_samples(cases, Variant::from(m)))
        .collect()
}

/// The entries the year of `cases` offers (every case of a check is of one year).
pub fn catalogue(cases: &[Case]) -> Vec<Bug> {
    Bug::offered(cases.first().map_or(Course::Y2016, |c| c.renderer.course()))
}

/// Every single entry of `catalogue` and every pair that a program can have.
fn singles_and_pairs(catalogue: &[Bug]) -> Vec<Mistakes> {
    let singles = catalogue.iter().map(|&b| Mistakes::of(&[b]));
    let pairs = catalogue.iter().enumerate().flat_map(|(i, &a)| {
        catalogue[i + 1..]
            .iter()
            .filter(move |&&b| !a.excludes(b))
            .map(move |&b| Mistakes::of(&[a, b]))
    });
    singles.chain(pairs).collect()
}

impl Search {
    /// Runs both stages over `cases` (at least one differs from its reference) on the
    /// sample; [`Search::finalise`] renders the best whole.
    pub fn run(cases: &[Case]) -> Result<Self> {
        let mut search = Search {
            scored: score_all(cases, &singles_and_pairs(&catalogue(cases)))?,
            rounded: Vec::new(),
            absorbed: Mistakes::NONE,
        };
        search.every_way(cases)?;
        if !search.exactly_explained(cases)? {
            let triples = search.triples(&catalogue(cases));
            search.scored.extend(score_all(cases, &triples)?);
            search.every_way(cases)?;
        }
        // Every story a candidate is held against (its stage not written yet) is scored too.
        let offered = catalogue(cases);
        let mut unwritten: Vec<Mistakes> = search
            .scored
            .iter()
            .flat_map(|s| {
                let set = s.variant.mistakes;
                let mut stories = stage_unwritten(set, &offered);
                stories.extend(certain_instead(set, &offered));
                stories
            })
            .filter(|m| search.get(*m).is_none())
            .collect();
        unwritten.sort();
        unwritten.dedup();
        search.scored.extend(score_all(cases, &unwritten)?);
        Ok(search)
    }

    /// Scores again, every way its rounding can go, the best `ROUNDED` candidates that hinge
    /// on rounding and were scored their own way only. Not only those near the top: a
    /// program's acne can be far from what the model's own arithmetic renders.
    fn every_way(&mut self, cases: &[Case]) -> Result<()> {
        let mut hinging: Vec<usize> = (0..self.scored.len())
            .filter(|&i| {
                let s = &self.scored[i];
                s.variant.hinges_on_rounding() && !self.rounded.contains(&s.variant.mistakes)
            })
            .collect();
        hinging.sort_by(|&a, &b| self.scored[a].cost().total_cmp(&self.scored[b].cost()));
        hinging.truncate(ROUNDED);
        let again: Vec<Scored> = hinging
            .par_iter()
            .map(|&i| Scored::on_samples_every_way(cases, self.scored[i].variant))
            .collect::<Result<_>>()?;
        for (i, s) in hinging.into_iter().zip(again) {
            self.rounded.push(s.variant.mistakes);
            self.scored[i] = s;
        }
        Ok(())
    }

    /// Whether the best candidate so far reproduces every case exactly (it is then made
    /// whole): no triple can do better, and on a tie the fewer entries rank first, so the
    /// triples need not be scored.
    fn exactly_explained(&mut self, cases: &[Case]) -> Result<bool> {
        let mut order: Vec<&Scored> = self.useful().collect();
        order.sort_by(ranking);
        let Some(best) = order.first().filter(|s| s.cost() == 0.0) else {
            return Ok(false);
        };
        let mistakes = best.variant.mistakes;
        let Some(s) = self.get_mut(mistakes) else {
            return Ok(false);
        };
        *s = s.made_whole(cases)?;
        Ok(s.cost() == 0.0)
    }

    /// Sets aside every candidate holding one of `entries`: what they gain, the story
    /// outside the catalogue already claims.
    pub fn absorb(&mut self, entries: Mistakes) {
        self.absorbed = Mistakes::of(
            &self
                .absorbed
                .bugs()
                .into_iter()
                .chain(entries.bugs())
                .collect::<Vec<_>>(),
        );
    }

    /// The candidate for exactly `mistakes` (no number), if it was scored.
    pub fn get(&self, mistakes: Mistakes) -> Option<&Scored> {
        self.scored.iter().find(|s| s.variant.mistakes == mistakes)
    }

    fn get_mut(&mut self, mistakes: Mistakes) -> Option<&mut Scored> {
        self.scored
            .iter_mut()
            .find(|s| s.variant.mistakes == mistakes)
    }

    /// The best pairs, each extended by every entry it admits, where no triple of the same
    /// entries is scored yet.
    fn triples(&self, catalogue: &[Bug]) -> Vec<Mistakes> {
        let mut pairs: Vec<&Scored> = self
            .useful()
            .filter(|s| s.variant.mistakes.len() == 2)
            .collect();
        pairs.sort_by(ranking);
        let mut triples: Vec<Mistakes> = pairs
            .iter()
            .take(BEAM)
            .flat_map(|pair| {
                let set = pair.variant.mistakes;
                catalogue
                    .iter()
                    .copied()
                    .filter(move |&b| set.admits(b))
                    .map(move |b| set.with(b))
            })
            .collect();
        triples.sort();
        triples.dedup();
        triples
    }

    /// The candidates worth ranking: they change something, and each of their entries is
    /// needed: the candidate renders differently from every scored set one entry smaller (a
    /// single entry: from the reference) and, with two entries or more, costs less than each
    /// (the beam extends while the cost falls). And none is possible only if a stage is
    /// written that the images say is not: where the same program with that stage not
    /// written yet (`stage_unwritten`) is as credible, the mistakes made in the stage's code
    /// are a story the rest of the program rules out (no reflected ray, no
    /// `no-reflection-bias`; a self-hit that rounding may or may not make imitates a missing
    /// reflection). Nor one holding an entry the story outside the catalogue absorbs.
    fn useful(&self) -> impl Iterator<Item = &Scored> {
        let by_set: HashMap<Mistakes, &Scored> = self
            .scored
            .iter()
            .map(|s| (s.variant.mistakes, s))
            .collect();
        let offered = Bug::offered(
            self.scored
                .first()
                .map_or(Course::Y2016, |s| s.variant.course),
        );
        // Per stage, the most credible story in which it is not written yet.
        let unwritten: Vec<(Stage, &Scored)> = Stage::TICK1
            .into_iter()
            .filter_map(|stage| {
                let best = self
                    .scored
                    .iter()
                    .filter(|s| {
                        let bugs = s.variant.mistakes.bugs();
                        bugs.iter().any(|b| b.is_unfinished() && b.stage() == stage)
                            && !bugs.iter().any(|b| b.implies(stage))
                    })
                    .max_by(|a, b| credible(a).total_cmp(&credible(b)))?;
                Some((stage, best))
            })
            .collect();
        self.scored.iter().filter(move |s| {
            let set = s.variant.mistakes;
            let needed = set.one_smaller().iter().all(|smaller| {
                by_set
                    .get(smaller)
                    .is_none_or(|t| !s.renders_like(t) && (set.len() < 2 || s.cost() < t.cost()))
            });
            let bugs = set.bugs();
            let ruled_out = unwritten.iter().any(|&(stage, best)| {
                bugs.iter().any(|b| b.implies(stage))
                    && !bugs.iter().any(|b| b.is_unfinished() && b.stage() == stage)
                    && outdoes(best, s)
            }) || stage_unwritten(set, &offered)
                .iter()
                .filter_map(|m| by_set.get(m))
                .any(|t| outdoes(t, s))
                || certain_instead(set, &offered)
                    .iter()
                    .filter_map(|m| by_set.get(m))
                    .any(|t| outdoes(t, s) && credible(t) >= ROUNDING_OUTDONE * s.explained());
            let absorbed = bugs.iter().any(|&b| self.absorbed.has(b));
            s.changes_any() && needed && !ruled_out && !absorbed
        })
    }

    /// Renders whole the best candidates, where the ranking could turn (a few whole renders:
    /// skipped when a number fit settles the story and no candidate is shown).
    pub fn finalise(&mut self, cases: &[Case]) -> Result<()> {
        let differing: usize = cases.iter().map(|c| c.wrong.len()).sum();
        let mut order: Vec<&Scored> = self.useful().collect();
        order.sort_by(ranking);
        let best = order.first().map_or(0.0, |s| s.cost());
        let margin = 0.01 * differing as f64 + 1.0;
        let finalists: Vec<Mistakes> = order
            .iter()
            .take(FINALISTS)
            .take_while(|s| s.cost() <= best * CLOSE + margin)
            .map(|s| s.variant.mistakes)
            .collect();
        let mut exact: Option<Mistakes> = None;
        for mistakes in finalists {
            if let Some(s) = self.get_mut(mistakes) {
                // Once a finalist renders every case exactly as the student did, only its
                // twins are listed (`rank`): one that already differs from the student on
                // the sample is no twin, and its whole images would change nothing shown,
                // unless it is the exact one less an entry (`in_case` compares those).
                let needed = exact.is_none_or(|e| e.one_smaller().contains(&mistakes));
                if !needed && s.differs_on_sample() {
                    continue;
                }
                if !s.is_whole() {
                    *s = s.made_whole(cases)?;
                }
                if exact.is_none() && s.cost() == 0.0 {
                    exact = Some(mistakes);
                }
            }
        }
        Ok(())
    }

    /// The entries that, added to `top`, render every case byte for byte as `top` does (each
    /// confirmed on whole images), though each alone changes some case: `top` masks them.
    /// Most common first. Only whether the images are equal is asked, not how well they
    /// score: they are compared strip by strip as they render, and one that differs stops
    /// at its first differing strip.
    pub fn image_identical_with(&self, cases: &[Case], top: Mistakes) -> Result<Vec<Bug>> {
        let Some(base) = self.get(top) else {
            return Ok(Vec::new());
        };
        let mut found = Vec::new();
        // `top`'s image of each case, rendered once when a first candidate needs it.
        let mut base_images: Option<Vec<Rgb8>> = None;
        for bug in Bug::BY_COMMONNESS {
            // An entry that changes none of these images on its own is one the cases cannot
            // show at all (a reflection mistake at 0 bounces), not one `top` masks.
            let visible = self
                .get(Mistakes::of(&[bug]))
                .is_some_and(Scored::changes_any);
            if !top.admits(bug) || !visible || found.len() == MASKED_LISTED {
                continue;
            }
            let Some(s) = self.get(top.with(bug)) else {
                continue;
            };
            // Where both were counted whole this compares their images, else their samples.
            if !s.renders_like(base) {
                continue;
            }
            let whole = s.is_whole() && base.is_whole();
            if whole {
                found.push(bug);
                continue;
            }
            let images = match base_images.take() {
                Some(images) => images,
                None => cases
                    .iter()
                    .map(|case| case.renderer.variant_image(&base.variant))
                    .collect::<Result<_>>()?,
            };
            if renders_alike(cases, &s.variant, &base.variant, &images)? {
                found.push(bug);
            }
            base_images = Some(images);
        }
        Ok(found)
    }

    /// The ranked diagnosis over every case.
    pub fn diagnosis(&self, cases: &[Case]) -> Vec<Diagnosis> {
        let null: f64 = cases.iter().map(null_cost).sum();
        let differing: usize = cases.iter().map(|c| c.wrong.len()).sum();
        let mut order: Vec<&Scored> = self.useful().filter(|s| s.cost() < null).collect();
        order.sort_by(ranking);
        rank(order, differing, course_of(cases))
    }

    /// What the suite's best explanation `top` says of case `i`: the part of it that shows
    /// there (an entry shows where leaving it out renders the case otherwise), with its
    /// numbers on that case, and whether it renders the case exactly as the student did.
    pub fn in_case(&self, cases: &[Case], top: Mistakes, i: usize) -> CaseFinding {
        let Some(scored) = self.get(top) else {
            return CaseFinding::default();
        };
        let here = &scored.cases[i];
        let shows = Mistakes::of(
            &top.bugs()
                .into_iter()
                .filter(|&m| {
                    let without = top.one_smaller().into_iter().find(|s| !s.has(m));
                    match without.filter(|w| !w.is_empty()).and_then(|w| self.get(w)) {
                        Some(smaller) => !here.renders_like(&smaller.cases[i]),
                        None => here.changes_image,
                    }
                })
                .collect::<Vec<_>>(),
        );
        let wrong = cases[i].wrong.len();
        let label = Diagnosis {
            mistakes: shows,
            explained: explained_share(here.explained, wrong),
            unexplained_pixels: (wrong as f64 - here.explained).max(0.0).round() as u64,
            wrongly_changed_pixels: here.wrongly_changed.round() as u64,
            indistinguishable_from: Vec::new(),
            exact: here.is_whole(),
            number: None,
            by_rounding: explained_share(here.by_rounding, wrong),
            course: course_of(cases),
            image_identical_with: Vec::new(),
        };
        CaseFinding {
            exactly: here.is_whole() && here.changes_image && here.cost == 0.0 && !shows.is_empty(),
            label: (!shows.is_empty() && wrong > 0 && label.explained >= LABELLED).then_some(label),
        }
    }
}

/// The same program as `set` told with a stage not written yet instead of `set`'s mistakes
/// that need that stage (`Bug::implies`): for each stage some entry implies and none of `set`
/// leaves unwritten, those entries replaced by each of the stage's unfinished entries that
/// `offered` holds and the rest admits.
fn stage_unwritten(set: Mistakes, offered: &[Bug]) -> Vec<Mistakes> {
    let mut stories = Vec::new();
    for stage in Stage::TICK1 {
        let needing: Vec<Bug> = set
            .bugs()
            .into_iter()
            .filter(|b| b.implies(stage))
            .collect();
        let unwritten_already = set
            .bugs()
            .iter()
            .any(|b| b.is_unfinished() && b.stage() == stage);
        if needing.is_empty() || unwritten_already {
            continue;
        }
        let rest = Mistakes::of(
            &set.bugs()
                .into_iter()
                .filter(|b| !needing.contains(b))
                .collect::<Vec<_>>(),
        );
        stories.extend(
            stage
                .missing_entries()
                .iter()
                .filter(|m| offered.contains(m) && rest.admits(**m))
                .map(|&m| rest.with(m)),
        );
    }
    stories
}

/// The same program as `set` with each of its entries that hinge on rounding (a ray that
/// starts on its own surface: `no-shadow-bias`, `no-reflection-bias`) left out, or replaced by
/// another written entry of its stage that `offered` holds and the rest admits. Such an entry
/// reproduces a pixel either way its rounding goes, so it can imitate a mistake of its stage
/// made for certain (every pixel `shadow-any-hit` darkens is one a self-shadow could).
fn certain_instead(set: Mistakes, offered: &[Bug]) -> Vec<Mistakes> {
    let mut stories = Vec::new();
    for e in set.bugs() {
        if !matches!(e, Bug::NoShadowBias | Bug::NoReflectionBias) {
            continue;
        }
        let rest = Mistakes::of(
            &set.bugs()
                .into_iter()
                .filter(|&b| b != e)
                .collect::<Vec<_>>(),
        );
        if rest.bugs().iter().any(|b| b.implies(e.stage())) {
            stories.push(rest);
        }
        stories.extend(
            offered
                .iter()
                .filter(|f| f.implies(e.stage()) && **f != e && rest.admits(**f))
                .map(|&f| rest.with(f)),
        );
    }
    stories
}

/// A candidate whose rounding entry a certain one could replace is ruled out only where that
/// one reproduces, for certain, at least this share of what the candidate explains: then the
/// rounding did not find pixels of its own.
const ROUNDING_OUTDONE: f64 = 0.5;

/// Whether the story `t` is at least as credible as `s` without being its twin: where both
/// render the images alike, the images cannot choose, and both are listed as twins.
fn outdoes(t: &Scored, s: &Scored) -> bool {
    let (a, b) = (credible(t), credible(s));
    a > b || (a == b && !t.renders_like(s))
}

/// How much of the images a candidate reproduces that it could not have reproduced by
/// chance: the differing pixels it renders for certain (not only as one way rounding can go,
/// where a self-hit may land either way and so imitates much), less the right pixels it
/// changes.
fn credible(s: &Scored) -> f64 {
    s.explained() - s.by_rounding() - s.wrongly_changed()
}

/// Whether `variant` renders every case byte for byte as `base` does.
fn renders_alike(
    cases: &[Case],
    variant: &Variant,
    base: &Variant,
    base_images: &[Rgb8],
) -> Result<bool> {
    for (case, base_image) in cases.iter().zip(base_images) {
        if !case.renderer.renders_as(variant, base, base_image)? {
            return Ok(false);
        }
    }
    Ok(true)
}

/// What the suite's explanation says of one case.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CaseFinding {
    /// The part of the suite's explanation that shows in this case, where it explains at
    /// least `LABELLED` of the case's differing pixels.
    pub label: Option<Diagnosis>,
    /// Whether the suite's explanation renders this case byte for byte as the student did.
    pub exactly: bool,
}

impl CaseFinding {
    /// The entries a case that `passes` hides: it renders exactly what they render.
    pub fn hidden(&self, passes: bool) -> Mistakes {
        match (&self.label, passes && self.exactly) {
            (Some(label), true) => label.mistakes,
            _ => Mistakes::NONE,
        }
    }
}

/// A case is labelled with the suite's explanation only where that explains this share of
/// its differing pixels: below, the label would say little.
const LABELLED: f64 = 0.5;

/// Lower cost first; then fewer entries, then catalogue order.
/// The year the cases are of (their renderers'; 2016-17 for none).
pub fn course_of(cases: &[Case]) -> Course {
    cases.first().map_or(Course::Y2016, |c| c.renderer.course())
}

fn ranking(a: &&Scored, b: &&Scored) -> std::cmp::Ordering {
    a.cost()
        .total_cmp(&b.cost())
        .then_with(|| simpler(a.variant.mistakes, b.variant.mistakes))
}

/// Fewer entries first, then catalogue order.
fn simpler(a: Mistakes, b: Mistakes) -> std::cmp::Ordering {
    let (a, b) = (a.bugs(), b.bugs());
    a.len().cmp(&b.len()).then(a.cmp(&b))
}

/// The listed diagnoses from candidates in ranking order: twins fold into the first of them,
/// and after an exact explanation of everything only its twins remain.
fn rank(order: Vec<&Scored>, differing: usize, course: Course) -> Vec<Diagnosis> {
    let mut listed: Vec<(&Scored, Diagnosis)> = Vec::new();
    for s in order {
        let mistakes = s.variant.mistakes;
        if let Some((_, entry)) = listed
            .iter_mut()
            .find(|(r, _)| r.renders_like(s) && r.compared_whole(s))
        {
            // A twin with more entries adds nothing: the simpler explanation stands.
            if entry.mistakes.len() == mistakes.len() {
                entry.indistinguishable_from.push(mistakes);
            }
            continue;
        }
        let complete = listed.first().is_some_and(|(_, d)| {
            d.exact && d.unexplained_pixels == 0 && d.wrongly_changed_pixels == 0
        });
        if listed.len() == LISTED || complete {
            continue;
        }
        let explained = s.explained();
        let diagnosis = Diagnosis {
            mistakes,
            explained: explained_share(explained, differing),
            unexplained_pixels: (differing as f64 - explained).max(0.0).round() as u64,
            wrongly_changed_pixels: s.wrongly_changed().round() as u64,
            indistinguishable_from: Vec::new(),
            exact: s.is_whole(),
            number: None,
            by_rounding: explained_share(s.by_rounding(), differing),
            image_identical_with: Vec::new(),
            course,
        };
        listed.push((s, diagnosis));
    }
    listed.into_iter().map(|(_, d)| d).collect()
}
