//! How well one candidate program reproduces the student's images: per case, a cost (how far
//! its bytes are from the student's), the differing pixels it reproduces and the right pixels
//! it changes, first estimated from the case's sample, then counted over the whole image.
//!
//! A pixel's cost is nothing when the bytes are equal, a little at 1 LSB (a student's own
//! `pow` or `sqrt` may round differently), a whole pixel beyond.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use crate::check::case::{position, Case};
use crate::check::difference::pixel_difference;
use crate::mistakes::{Rounding, Variant};
use whitted_core::error::Result;

/// What a pixel costs on top when a candidate reproduces it only as one of the ways its
/// rounding can go: a candidate that reproduces it for certain ranks first.
const ROUNDING_MATCH: f64 = 0.05;

/// A candidate's bytes at some pixels: what its own arithmetic renders, and, for a program
/// whose pixels hinge on rounding (`whitted_core::model::rounding`), per pixel the smallest
/// difference from the student's of any other way its rounding can go (`u8::MAX`: none
/// tried, or none closer).
#[derive(Clone, Copy)]
pub struct Rendered<'a> {
    pub exact: &'a [u8],
    pub ways: &'a [u8],
}

/// How a candidate's pixel compares with the student's.
struct PixelCall {
    cost: f64,
    /// Within 1 LSB of the student's, its own way or one way its rounding can go.
    reproduced: bool,
    /// Reproduced only as one way its rounding can go.
    by_rounding: bool,
}

impl Rendered<'_> {
    /// Pixel `i` of these bytes against pixel `i` of `student`.
    fn call(&self, student: &[u8], i: usize) -> PixelCall {
        let d = pixel_difference(self.exact, student, i);
        let either = self.ways.get(i).copied().unwrap_or(u8::MAX);
        if d <= 1 || either > 1 {
            return PixelCall {
                cost: cost(d),
                reproduced: d <= 1,
                by_rounding: false,
            };
        }
        PixelCall {
            cost: cost(either) + ROUNDING_MATCH,
            reproduced: true,
            by_rounding: true,
        }
    }
}

/// Per pixel of `exact` (rendered at `positions`), the smallest difference from `student` of
/// any other way `variant`'s rounding can go in a scene of `lights` lights, rendered by
/// `render_at` only at the pixels still not reproduced: first every root taken one way and the
/// other, then each light's shadow rays apart (`Variant::rounding_ways`). `u8::MAX` where
/// nothing was tried.
fn rounding_ways(
    variant: &Variant,
    lights: usize,
    (exact, student, positions): (&[u8], &[u8], &[(u32, u32)]),
    render_at: impl Fn(&Variant, &[(u32, u32)]) -> Result<Vec<u8>>,
) -> Result<Vec<u8>> {
    let n = exact.len() / 3;
    let mut best = vec![u8::MAX; n];
    if !variant.hinges_on_rounding() {
        return Ok(best);
    }
    let mut open: Vec<usize> = (0..n)
        .filter(|&i| pixel_difference(exact, student, i) > 1)
        .collect();
    let ways = variant.rounding_ways(lights);
    let render = |way: Rounding, open: &[usize]| -> Result<Vec<u8>> {
        let at: Vec<(u32, u32)> = open.iter().map(|&i| positions[i]).collect();
        render_at(&variant.rounded(way), &at)
    };
    // Channel difference of rendered pixel k (of `open`) and the student's pixel i.
    let apart = |bytes: &[u8], k: usize, i: usize| {
        (0..3)
            .map(|c| bytes[3 * k + c].abs_diff(student[3 * i + c]))
            .max()
            .unwrap_or(0)
    };
    // Every root one way, then the other.
    let (hit, miss) = (render(ways[0], &open)?, render(ways[1], &open)?);
    let mut uncertain = Vec::new();
    for (k, &i) in open.iter().enumerate() {
        best[i] = apart(&hit, k, i).min(apart(&miss, k, i));
        if best[i] > 1 && hit[3 * k..3 * k + 3] != miss[3 * k..3 * k + 3] {
            uncertain.push(i);
        }
    }
    // Each light apart, only where the two differ: a pixel both ways render alike does not
    // hinge on rounding at all.
    open = uncertain;
    for &way in &ways[2..] {
        if open.is_empty() {
            break;
        }
        let bytes = render(way, &open)?;
        for (k, &i) in open.iter().enumerate() {
            best[i] = best[i].min(apart(&bytes, k, i));
        }
        open.retain(|&i| best[i] > 1);
    }
    Ok(best)
}

/// A pixel's cost for a candidate `difference` LSB away from the student's pixel.
pub fn cost(difference: u8) -> f64 {
    match difference {
        0 => 0.0,
        1 => 0.25,
        _ => 1.0,
    }
}

/// `explained` differing pixels as a share of `differing` (0 when nothing differs).
pub fn explained_share(explained: f64, differing: usize) -> f64 {
    if differing == 0 {
        0.0
    } else {
        (explained / differing as f64).min(1.0)
    }
}

/// A hash of rendered bytes: two candidates with the same one render alike.
fn fingerprint(bytes: &[u8]) -> u64 {
    let mut hasher = DefaultHasher::new();
    bytes.hash(&mut hasher);
    hasher.finish()
}

/// One candidate's showing on one case.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseScore {
    /// Summed pixel costs.
    pub cost: f64,
    /// Differing pixels it reproduces within 1 LSB.
    pub explained: f64,
    /// Pixels the student got right that it changes by more than 1 LSB.
    pub wrongly_changed: f64,
    /// Of `explained`, the pixels it reproduces only as one way its rounding can go.
    pub by_rounding: f64,
    /// Whether it renders the case differently from the reference anywhere it was looked at.
    pub changes_image: bool,
    /// The fingerprint of what it rendered on the sample.
    pub sample_fingerprint: u64,
    /// Whether it rendered a sampled pixel otherwise than the student (kept when the case
    /// is counted whole: the sample's pixels are the whole image's too).
    pub differs_on_sample: bool,
    /// The fingerprint of the whole image, once it was rendered whole (the numbers are then
    /// counts, not estimates).
    pub image_fingerprint: Option<u64>,
}

impl CaseScore {
    fn empty(sample_fingerprint: u64) -> Self {
        CaseScore {
            cost: 0.0,
            explained: 0.0,
            wrongly_changed: 0.0,
            by_rounding: 0.0,
            changes_image: false,
            sample_fingerprint,
            differs_on_sample: false,
            image_fingerprint: None,
        }
    }

    /// Counts one pixel standing for `weight` pixels, which the student got wrong or not, as
    /// `call` compares the candidate's with the student's.
    fn tally(&mut self, weight: f64, was_wrong: bool, call: PixelCall) {
        self.cost += weight * call.cost;
        match (was_wrong, call.reproduced) {
            (true, true) => {
                self.explained += weight;
                if call.by_rounding {
                    self.by_rounding += weight;
                }
            }
            (false, false) => self.wrongly_changed += weight,
            _ => {}
        }
    }

    /// The estimate from `bytes` rendered at `case`'s sample.
    pub fn on_sample(case: &Case, bytes: Rendered) -> Self {
        let sample = &case.sample;
        let mut s = CaseScore::empty(fingerprint(bytes.exact));
        s.changes_image = bytes.exact != sample.reference.as_slice();
        s.differs_on_sample = bytes.exact != sample.student.as_slice();
        for j in 0..sample.positions.len() {
            let (weight, was_wrong) = sample.kind(j);
            s.tally(weight, was_wrong, bytes.call(&sample.student, j));
        }
        s
    }

    /// The counts over the whole image `bytes`, keeping the sample's fingerprint of
    /// `estimate`.
    pub fn on_image(case: &Case, bytes: Rendered, estimate: &CaseScore) -> Self {
        let mut s = CaseScore::empty(estimate.sample_fingerprint);
        s.differs_on_sample = estimate.differs_on_sample;
        s.changes_image = bytes.exact != case.reference.bytes.as_slice();
        s.image_fingerprint = Some(fingerprint(bytes.exact));
        let mut wrong = case.wrong.iter().peekable();
        for i in 0..bytes.exact.len() / 3 {
            let was_wrong = wrong.next_if_eq(&&i).is_some();
            s.tally(1.0, was_wrong, bytes.call(&case.student.bytes, i));
        }
        s
    }

    pub fn is_whole(&self) -> bool {
        self.image_fingerprint.is_some()
    }

    /// Whether two candidates render this case alike, as far as both were looked at.
    pub fn renders_like(&self, other: &CaseScore) -> bool {
        match (self.image_fingerprint, other.image_fingerprint) {
            (Some(a), Some(b)) => a == b,
            _ => self.sample_fingerprint == other.sample_fingerprint,
        }
    }
}

/// One candidate's showing on every case.
#[derive(Debug, Clone, PartialEq)]
pub struct Scored {
    pub variant: Variant,
    /// In the order of the cases.
    pub cases: Vec<CaseScore>,
}

impl Scored {
    /// Scores `variant` on every case's sample.
    pub fn on_samples(cases: &[Case], variant: Variant) -> Result<Self> {
        Self::sampled(cases, variant, false)
    }

    /// Scores `variant` on every case's sample, each way its rounding can go counted too
    /// (the search does so for its best candidates that hinge on rounding: the other ways
    /// cost renders, and only a candidate near the top can use them).
    pub fn on_samples_every_way(cases: &[Case], variant: Variant) -> Result<Self> {
        Self::sampled(cases, variant, true)
    }

    fn sampled(cases: &[Case], variant: Variant, every_way: bool) -> Result<Self> {
        let scores = cases
            .iter()
            .map(|case| {
                let frame = case.renderer.frame(variant.mistakes)?;
                let sample = |v: &Variant| case.renderer.sample_bytes(v, &frame, &case.sample);
                let exact = sample(&variant)?;
                let lights = case.renderer.scene.lights.len();
                let looked = (
                    exact.as_slice(),
                    case.sample.student.as_slice(),
                    &case.sample.positions[..],
                );
                let ways = match every_way {
                    true => rounding_ways(&variant, lights, looked, |v, at| {
                        case.renderer
                            .bytes_at(v, &case.renderer.frame(v.mistakes)?, at)
                    })?,
                    false => Vec::new(),
                };
                let bytes = Rendered {
                    exact: &exact,
                    ways: &ways,
                };
                Ok(CaseScore::on_sample(case, bytes))
            })
            .collect::<Result<_>>()?;
        Ok(Scored {
            variant,
            cases: scores,
        })
    }

    /// This candidate counted over every case's whole image.
    pub fn made_whole(&self, cases: &[Case]) -> Result<Self> {
        let scores = cases
            .iter()
            .zip(&self.cases)
            .map(|(case, estimate)| {
                let exact = case.renderer.variant_image(&self.variant)?.bytes;
                let lights = case.renderer.scene.lights.len();
                let width = case.student.width;
                let every: Vec<(u32, u32)> = if self.variant.hinges_on_rounding() {
                    (0..exact.len() / 3).map(|i| position(width, i)).collect()
                } else {
                    Vec::new()
                };
                let looked = (exact.as_slice(), case.student.bytes.as_slice(), &every[..]);
                let ways = rounding_ways(&self.variant, lights, looked, |v, at| {
                    case.renderer
                        .bytes_at(v, &case.renderer.frame(v.mistakes)?, at)
                })?;
                let bytes = Rendered {
                    exact: &exact,
                    ways: &ways,
                };
                Ok(CaseScore::on_image(case, bytes, estimate))
            })
            .collect::<Result<_>>()?;
        Ok(Scored {
            variant: self.variant,
            cases: scores,
        })
    }

    pub fn cost(&self) -> f64 {
        self.cases.iter().map(|c| c.cost).sum()
    }

    pub fn explained(&self) -> f64 {
        self.cases.iter().map(|c| c.explained).sum()
    }

    pub fn wrongly_changed(&self) -> f64 {
        self.cases.iter().map(|c| c.wrongly_changed).sum()
    }

    /// Of `explained`, the pixels reproduced only as one way rounding can go.
    pub fn by_rounding(&self) -> f64 {
        self.cases.iter().map(|c| c.by_rounding).sum()
    }

    pub fn changes_any(&self) -> bool {
        self.cases.iter().any(|c| c.changes_image)
    }

    /// Whether some sampled pixel of some case differs from the student's: then its whole
    /// images do too, and it cannot reproduce them exactly.
    pub fn differs_on_sample(&self) -> bool {
        self.cases.iter().any(|c| c.differs_on_sample)
    }

    /// Whether every case was counted over its whole image.
    pub fn is_whole(&self) -> bool {
        self.cases.iter().all(CaseScore::is_whole)
    }

    /// Whether the two render every case alike, as far as both were looked at.
    pub fn renders_like(&self, other: &Scored) -> bool {
        self.cases
            .iter()
            .zip(&other.cases)
            .all(|(a, b)| a.renders_like(b))
    }

    /// Whether the two were compared over a whole image at least once: a sample alone can
    /// agree by chance.
    pub fn compared_whole(&self, other: &Scored) -> bool {
        self.cases
            .iter()
            .zip(&other.cases)
            .any(|(a, b)| a.is_whole() && b.is_whole())
    }
}
