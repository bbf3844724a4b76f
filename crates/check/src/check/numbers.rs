//! A mistake can be a wrong number rather than a wrong rule: a doubled specular exponent, a
//! linear falloff, a bigger EPSILON. Each of the model's numbers (`Parameter`) is fitted alone,
//! on top of a base set of catalogue entries: a grid over the values a student could
//! plausibly have written, scored on the cases' samples, then a golden-section search between
//! the best grid point's neighbours, then the plainest value (an integer exponent, a power of
//! ten) that does as well. The best fits render whole, so their figures are exact.

use rayon::prelude::*;

use crate::check::case::Case;
use crate::check::diagnose::Diagnosis;
use crate::check::score::{explained_share, Scored};
use crate::mistakes::{Mistakes, Number, Parameter, Variant};
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::numbers::plain;

/// Golden-section steps between two grid neighbours.
const REFINE_STEPS: usize = 8;

/// The share of the differing pixels a fit must reproduce (on the sample) to be reported.
const WORTH: f64 = 0.25;

/// Fits rendered whole and reported, at most.
const LISTED: usize = 2;

/// One fitted number.
#[derive(Debug, Clone, PartialEq)]
pub struct NumberFit {
    pub parameter: Parameter,
    pub fitted: f64,
    /// The catalogue entries it was fitted on top of (none: the course's rules).
    pub with: Mistakes,
    /// Share of the differing pixels it reproduces within 1 LSB.
    pub explained: f64,
    pub wrongly_changed_pixels: u64,
    /// Per case, counted whole: what the fit explains of it, as a case's label.
    pub per_case: Vec<Diagnosis>,
    /// The year it is fitted in: its words are that year's.
    pub course: Course,
}

impl NumberFit {
    /// The fit in words, for the text report.
    pub fn sentence(&self) -> String {
        let with: Vec<String> = self
            .with
            .bugs()
            .into_iter()
            .map(|b| {
                let course = self.course;
                format!(
                    "{} ({}; fix: {})",
                    b.id(),
                    b.description(course),
                    b.fix(course)
                )
            })
            .collect();
        let with = match with.is_empty() {
            true => String::new(),
            false => format!(", together with {}", with.join(" and ")),
        };
        format!(
            "{} looks like {} (the course's is {}){with}; look at {}",
            self.parameter.words(),
            plain(self.fitted),
            plain(self.parameter.course()),
            self.parameter.place()
        )
    }
}

fn variant(base: Mistakes, parameter: Parameter, value: f64) -> Variant {
    Variant {
        mistakes: base,
        number: Some(Number { parameter, value }),
        ..Variant::default()
    }
}

/// The sampled cost of `parameter` at `value` on top of `base`.
fn sampled(cases: &[Case], base: Mistakes, parameter: Parameter, value: f64) -> Result<Scored> {
    Scored::on_samples(cases, variant(base, parameter, value))
}

/// The best value of one parameter on the samples.
fn fit_one(cases: &[Case], base: Mistakes, parameter: Parameter) -> Result<Scored> {
    let grid = parameter.grid();
    let scores: Vec<Scored> = grid
        .par_iter()
        .map(|&v| sampled(cases, base, parameter, v))
        .collect::<Result<_>>()?;
    let best = (0..grid.len())
        .min_by(|&a, &b| scores[a].cost().total_cmp(&scores[b].cost()))
        .unwrap_or(0);
    let mut best_score = scores[best].clone();
    // Golden-section search between the neighbours, in log space for a geometric grid.
    let geometric = parameter.geometric();
    let to = |x: f64| if geometric { x.ln() } else { x };
    let from = |x: f64| if geometric { x.exp() } else { x };
    let mut lo = to(grid[best.saturating_sub(1)]);
    let mut hi = to(grid[(best + 1).min(grid.len() - 1)]);
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let mut inner = |x: f64| -> Result<(f64, f64)> {
        let s = sampled(cases, base, parameter, from(x))?;
        let cost = s.cost();
        if cost < best_score.cost() {
            best_score = s;
        }
        Ok((x, cost))
    };
    let mut a = inner(hi - ratio * (hi - lo))?;
    let mut b = inner(lo + ratio * (hi - lo))?;
    for _ in 0..REFINE_STEPS {
        if a.1 <= b.1 {
            hi = b.0;
            b = a;
            a = inner(hi - ratio * (hi - lo))?;
        } else {
            lo = a.0;
            a = b;
            b = inner(lo + ratio * (hi - lo))?;
        }
    }
    // The plainest value that does as well: what the student most likely wrote.
    let fitted = best_score.variant.number.map_or(0.0, |n| n.value);
    for value in plainer(parameter, fitted) {
        let s = sampled(cases, base, parameter, value)?;
        if s.cost() <= best_score.cost() {
            return Ok(s);
        }
    }
    Ok(best_score)
}

/// Plainer values near `x`, plainest first.
fn plainer(parameter: Parameter, x: f64) -> Vec<f64> {
    match parameter {
        Parameter::SpecularExponent => vec![x.round()],
        Parameter::Epsilon => {
            let decade = 10f64.powf(x.log10().round());
            let five = 5.0 * 10f64.powf((x / 5.0).log10().round());
            vec![decade, five]
        }
        _ => vec![
            (x * 2.0).round() / 2.0,
            (x * 4.0).round() / 4.0,
            (x * 20.0).round() / 20.0,
        ],
    }
}

/// The best fit's number together with the one catalogue entry of its stage that lowers its
/// cost most, if one does by more than the sample's noise: `Math.pow(RdotV, 20)` is a doubled exponent
/// *and* an unclamped R.V, and the number alone leaves the second unsaid.
fn with_an_entry(cases: &[Case], best: Option<&Scored>) -> Result<Option<Scored>> {
    let Some((best, number)) = best.and_then(|b| Some((b, b.variant.number?))) else {
        return Ok(None);
    };
    // A fit that reproduces every sampled differing pixel leaves nothing for an entry to add.
    let differing: f64 = cases.iter().map(|c| c.wrong.len() as f64).sum();
    if best.explained() >= differing {
        return Ok(None);
    }
    let base = best.variant.mistakes;
    // An entry of the number's own stage: what a student wrote in the same lines.
    let candidates: Vec<Mistakes> = super::diagnose::catalogue(cases)
        .into_iter()
        .filter(|&b| base.admits(b) && !b.is_unfinished() && b.stage() == number.parameter.stage())
        .map(|b| base.with(b))
        .collect();
    let scored: Vec<Scored> = candidates
        .par_iter()
        .map(|&m| sampled(cases, m, number.parameter, number.value))
        .collect::<Result<_>>()?;
    let margin = PAIRED_GAIN * best.cost() + 1.0;
    Ok(scored
        .into_iter()
        .filter(|s| s.cost() + margin < best.cost())
        .min_by(|a, b| a.cost().total_cmp(&b.cost())))
}

/// The share of a fit's cost an added entry must remove to be named with it.
const PAIRED_GAIN: f64 = 0.1;

/// A fit (on the sample) must explain more than its entries alone:
/// - on its own: at least this share of the differing pixels more than they do;
const OWN_GAIN: f64 = 0.1;
/// - without changing, for each pixel it gains, more than this share of a pixel the student
///   had right (a wrong number is wrong everywhere the student wrote it, so a true one
///   changes next to nothing that is right);
const RIGHT_CHANGED_PER_GAIN: f64 = 0.1;
/// - in every case, costing at most this share of the case's differing pixels more than they
///   do (the sample's noise).
const CASE_SLACK: f64 = 0.01;

/// Whether the fit `s` tells a story of its own that holds across the cases: it gains
/// `OWN_GAIN` over its entries alone, changes next to nothing the student had right, costs no
/// case more than they do, and its number's stage is written: a number of a stage the entries
/// leave unwritten shows nothing, and one that renders no better than that stage unwritten
/// (a reflectivity factor of 0 is the reflection not written) is that story, told already.
fn holds(cases: &[Case], s: &Scored) -> Result<bool> {
    let Some(number) = s.variant.number else {
        return Ok(false);
    };
    let base = s.variant.mistakes;
    let stage = number.parameter.stage();
    if base
        .bugs()
        .iter()
        .any(|b| b.is_unfinished() && b.stage() == stage)
    {
        return Ok(false);
    }
    let without = Scored::on_samples(cases, Variant::from(base))?;
    let differing: f64 = cases.iter().map(|c| c.wrong.len() as f64).sum();
    let gain = s.explained() - without.explained();
    let changed = s.wrongly_changed() - without.wrongly_changed();
    let every_case =
        cases
            .iter()
            .zip(s.cases.iter().zip(&without.cases))
            .all(|(case, (fit, alone))| {
                fit.cost <= alone.cost + CASE_SLACK * case.wrong.len() as f64 + 1.0
            });
    if s.cost() >= without.cost()
        || gain < OWN_GAIN * differing
        || changed > RIGHT_CHANGED_PER_GAIN * gain
        || !every_case
    {
        return Ok(false);
    }
    let offered = super::diagnose::catalogue(cases);
    for &missing in stage.missing_entries() {
        if offered.contains(&missing) && base.admits(missing) {
            let unwritten = Scored::on_samples(cases, Variant::from(base.with(missing)))?;
            if unwritten.cost() <= s.cost() {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// Every parameter fitted on top of each of `bases`; the best `LISTED` that explain the
/// images better than `bases` do without a number, counted whole, best first.
pub fn fit(cases: &[Case], bases: &[Mistakes]) -> Result<Vec<NumberFit>> {
    let differing: usize = cases.iter().map(|c| c.wrong.len()).sum();
    let jobs: Vec<(Mistakes, Parameter)> = bases
        .iter()
        .flat_map(|&b| Parameter::ALL.into_iter().map(move |p| (b, p)))
        .collect();
    let mut fits: Vec<Scored> = jobs
        .par_iter()
        .map(|&(base, parameter)| fit_one(cases, base, parameter))
        .collect::<Result<_>>()?;
    fits.retain(|s| {
        let number = s.variant.number.map(|n| (n.parameter, n.value));
        !number.is_some_and(|(p, v)| v == p.course())
    });
    fits.sort_by(|a, b| a.cost().total_cmp(&b.cost()));
    if let Some(paired) = with_an_entry(cases, fits.first())? {
        fits.insert(0, paired);
    }
    let mut kept = Vec::new();
    for s in fits {
        if holds(cases, &s)? {
            kept.push(s);
        }
    }
    let mut fits = kept;
    // A number on top of entries is worth saying only where it beats every number alone.
    let best_alone = fits
        .iter()
        .find(|s| s.variant.mistakes.is_empty())
        .map_or(f64::INFINITY, Scored::cost);
    fits.retain(|s| s.variant.mistakes.is_empty() || s.cost() < best_alone);
    // Only a fit that explains a fair part is worth its whole render.
    fits.retain(|s| s.explained() >= WORTH * differing as f64);
    fits.truncate(LISTED);
    let mut listed = Vec::new();
    for s in &fits {
        let whole = s.made_whole(cases)?;
        if let Some(number) = whole.variant.number {
            listed.push(NumberFit {
                parameter: number.parameter,
                fitted: number.value,
                with: whole.variant.mistakes,
                course: crate::check::diagnose::course_of(cases),
                explained: explained_share(whole.explained(), differing),
                wrongly_changed_pixels: whole.wrongly_changed().round() as u64,
                per_case: cases
                    .iter()
                    .zip(&whole.cases)
                    .map(|(case, here)| {
                        let wrong = case.wrong.len();
                        Diagnosis {
                            mistakes: whole.variant.mistakes,
                            explained: explained_share(here.explained, wrong),
                            unexplained_pixels: (wrong as f64 - here.explained).max(0.0).round()
                                as u64,
                            wrongly_changed_pixels: here.wrongly_changed.round() as u64,
                            indistinguishable_from: Vec::new(),
                            exact: true,
                            number: Some(number),
                            by_rounding: explained_share(here.by_rounding, wrong),
                            image_identical_with: Vec::new(),
                            course: crate::check::diagnose::course_of(cases),
                        }
                    })
                    .collect(),
            });
        }
    }
    Ok(listed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plainer_values_are_near() {
        assert_eq!(plainer(Parameter::SpecularExponent, 19.7), vec![20.0]);
        assert_eq!(plainer(Parameter::Epsilon, 0.0011)[0], 0.001);
        assert_eq!(plainer(Parameter::FalloffPower, 1.04)[0], 1.0);
    }
}
