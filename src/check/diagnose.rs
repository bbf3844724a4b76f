//! Naming the mistake: every catalogued mistake, and every pair of them, is rendered as the
//! course's model with those rules broken (`Mistakes`), and ranked by how well it reproduces
//! the student's image.
//!
//! Two stages keep a 640x480 check with pairs within a second on two cores. First every
//! candidate renders only a sample of the pixels: up to `SAMPLE` of those the student got
//! wrong and as many of those they got right, each standing for its share of the image. Then
//! the best `FINALISTS` render the whole image, and their numbers are exact.
//!
//! A pixel's cost is how far the candidate's bytes are from the student's: nothing when equal,
//! a little at 1 LSB (a student's own `pow` or `sqrt` may round differently), a whole pixel
//! beyond. The candidate with the lowest cost over the image ranks first; on a tie, fewer
//! mistakes, then catalogue order.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use rayon::prelude::*;

use crate::accel::Accelerator;
use crate::check::difference::pixel_difference;
use crate::check::student_png::Rgb8;
use crate::error::Result;
use crate::frame::{Acceleration, Frame, FrameSpec};
use crate::interrupt;
use crate::mistakes::{Bug, Mistakes};
use crate::model::{Model, Tick};
use crate::output::png::tick_bytes;
use crate::render::trace_pixels;
use crate::scene::Scene;

/// Pixels of each kind (wrong, right) the first stage renders at most.
pub(crate) const SAMPLE: usize = 2500;

/// Candidates the second stage renders whole, at most: those whose sampled cost is within
/// `CLOSE` of the best (plus a margin for the sample's noise), where the ranking could turn.
const FINALISTS: usize = 6;
const CLOSE: f64 = 2.0;

/// Diagnoses listed at most.
const LISTED: usize = 8;

/// A pixel's cost for a candidate `difference` LSB away from the student's pixel.
fn cost(difference: u8) -> f64 {
    match difference {
        0 => 0.0,
        1 => 0.25,
        _ => 1.0,
    }
}

/// Renders one scene at one size and bounce count under any set of mistakes.
pub struct Renderer<'a> {
    scene: &'a Scene,
    spec: FrameSpec,
    bvh: Accelerator,
    brute: Accelerator,
    every_pixel: Vec<(u32, u32)>,
}

impl<'a> Renderer<'a> {
    pub fn new(scene: &'a Scene, width: u32, height: u32, bounces: u32) -> Result<Self> {
        let spec = FrameSpec::tick(width, height, bounces, true);
        Frame::new(scene, &spec)?;
        let every_pixel = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .collect();
        Ok(Renderer {
            scene,
            spec,
            bvh: Accelerator::build(&scene.objects),
            brute: Accelerator::brute_force(&scene.objects),
            every_pixel,
        })
    }

    /// The frame a program with `mistakes` renders.
    pub fn frame(&self, mistakes: Mistakes) -> Result<Frame> {
        Frame::new(self.scene, &mistakes.frame_spec(&self.spec))
    }

    /// The tick bytes of `pixels` under `model` in `frame` (sequential); an error when the
    /// user stopped the run half-way.
    fn bytes_at(
        &self,
        model: &impl Model,
        frame: &Frame,
        pixels: &[(u32, u32)],
    ) -> Result<Vec<u8>> {
        // `Mistakes::frame_spec` asks for brute force where the model needs it.
        let accel = match frame.acceleration() {
            Acceleration::Bvh => &self.bvh,
            Acceleration::BruteForce => &self.brute,
        };
        let beauty =
            trace_pixels::<false, _>(model, self.scene, accel, frame, pixels, |s| s.beauty);
        interrupt::check()?;
        Ok(tick_bytes(&beauty))
    }

    /// The whole image under `model` in `frame`, on every core.
    fn image_with(&self, model: &impl Model, frame: &Frame) -> Result<Rgb8> {
        let chunks: Vec<Vec<u8>> = self
            .every_pixel
            .par_chunks(1024)
            .map(|chunk| self.bytes_at(model, frame, chunk))
            .collect::<Result<_>>()?;
        Ok(Rgb8 {
            width: self.spec.width,
            height: self.spec.height,
            bytes: chunks.concat(),
        })
    }

    /// The reference: the course's model.
    pub fn reference(&self) -> Result<Rgb8> {
        self.image_with(&Tick, &self.frame(Mistakes::NONE)?)
    }

    /// The whole image a program with `mistakes` renders.
    pub fn image(&self, mistakes: Mistakes) -> Result<Rgb8> {
        self.image_with(&mistakes, &self.frame(mistakes)?)
    }
}

/// Every candidate: each mistake alone, then every pair, in catalogue order.
pub fn candidates() -> Vec<Mistakes> {
    let singles = Bug::ALL.iter().map(|&b| Mistakes::of(&[b]));
    let pairs = Bug::ALL.iter().enumerate().flat_map(|(i, &a)| {
        Bug::ALL[i + 1..]
            .iter()
            .map(move |&b| Mistakes::of(&[a, b]))
    });
    singles.chain(pairs).collect()
}

/// One candidate's showing on one case.
#[derive(Debug, Clone, PartialEq)]
pub struct Scored {
    pub mistakes: Mistakes,
    /// Summed pixel costs (estimated from the sample unless `exact`).
    pub cost: f64,
    /// Differing pixels it reproduces within 1 LSB.
    pub explained: f64,
    /// Pixels the student got right that it changes by more than 1 LSB.
    pub wrongly_changed: f64,
    /// Whether it renders this case differently from the reference anywhere it was looked at.
    pub changes_image: bool,
    /// A pair that renders what one of its two mistakes alone renders.
    pub same_as_member: bool,
    /// A hash of the bytes it rendered on the sample, and on the whole image once `exact`.
    pub sample_print: u64,
    pub image_print: Option<u64>,
}

impl Scored {
    /// Counts one pixel standing for `weight` pixels, which the student got wrong or not, and
    /// which this candidate renders `d` LSB away from the student's.
    fn tally(&mut self, weight: f64, was_wrong: bool, d: u8) {
        self.cost += weight * cost(d);
        match (was_wrong, d <= 1) {
            (true, true) => self.explained += weight,
            (false, false) => self.wrongly_changed += weight,
            _ => {}
        }
    }

    pub fn exact(&self) -> bool {
        self.image_print.is_some()
    }

    /// Whether the two render this case identically, as far as was looked.
    fn twin(&self, other: &Scored) -> bool {
        match (self.image_print, other.image_print) {
            (Some(a), Some(b)) => a == b,
            _ => self.sample_print == other.sample_print,
        }
    }
}

/// Every candidate's showing on one case (a student's image of one scene).
#[derive(Debug, Clone, PartialEq)]
pub struct CaseAnalysis {
    /// Pixels where the student's image differs from the reference at all.
    pub differing: usize,
    /// The reference's own cost: what "no catalogued mistake" explains.
    pub null_cost: f64,
    /// In the order of `candidates()`.
    pub scored: Vec<Scored>,
}

fn print(bytes: &[u8]) -> u64 {
    let mut hasher = DefaultHasher::new();
    bytes.hash(&mut hasher);
    hasher.finish()
}

/// At most `n` of `items`, evenly spread.
pub(crate) fn spread<T: Copy>(items: &[T], n: usize) -> Vec<T> {
    let step = items.len().div_ceil(n.max(1)).max(1);
    items.iter().step_by(step).copied().collect()
}

/// Scores every candidate on the student's image of `renderer`'s scene.
pub fn analyse(renderer: &Renderer, student: &Rgb8, reference: &Rgb8) -> Result<CaseAnalysis> {
    let width = student.width as usize;
    let pixels = student.bytes.len() / 3;
    let (wrong, right): (Vec<usize>, Vec<usize>) =
        (0..pixels).partition(|&i| pixel_difference(&student.bytes, &reference.bytes, i) > 0);
    let null_cost = wrong
        .iter()
        .map(|&i| cost(pixel_difference(&student.bytes, &reference.bytes, i)))
        .sum();
    let (wrong_sample, right_sample) = (spread(&wrong, SAMPLE), spread(&right, SAMPLE));
    let weights = (
        wrong.len() as f64 / wrong_sample.len().max(1) as f64,
        right.len() as f64 / right_sample.len().max(1) as f64,
    );
    let looked: Vec<usize> = wrong_sample.iter().chain(&right_sample).copied().collect();
    let at = |i: usize| ((i % width) as u32, (i / width) as u32);
    let positions: Vec<(u32, u32)> = looked.iter().map(|&i| at(i)).collect();
    let pick = |image: &Rgb8| -> Vec<u8> {
        looked
            .iter()
            .flat_map(|&i| image.bytes[3 * i..3 * i + 3].iter().copied())
            .collect()
    };
    let (student_here, reference_here) = (pick(student), pick(reference));
    let list = candidates();
    let frames: Vec<Frame> = list
        .iter()
        .map(|&m| renderer.frame(m))
        .collect::<Result<_>>()?;
    let mut scored: Vec<Scored> = list
        .par_iter()
        .zip(&frames)
        .map(|(&mistakes, frame)| {
            let bytes = renderer.bytes_at(&mistakes, frame, &positions)?;
            let mut s = Scored {
                mistakes,
                cost: 0.0,
                explained: 0.0,
                wrongly_changed: 0.0,
                changes_image: bytes != reference_here,
                same_as_member: false,
                sample_print: print(&bytes),
                image_print: None,
            };
            for j in 0..looked.len() {
                let was_wrong = j < wrong_sample.len();
                let weight = if was_wrong { weights.0 } else { weights.1 };
                s.tally(
                    weight,
                    was_wrong,
                    pixel_difference(&bytes, &student_here, j),
                );
            }
            Ok(s)
        })
        .collect::<Result<_>>()?;
    mark_pairs_like_a_member(&mut scored);
    if !wrong.is_empty() {
        let mut order: Vec<usize> = (0..scored.len())
            .filter(|&i| scored[i].changes_image && !scored[i].same_as_member)
            .collect();
        order.sort_by(|&a, &b| ranking(&scored[a], &scored[b]));
        let best = order.first().map_or(0.0, |&i| scored[i].cost);
        let margin = 0.01 * wrong.len() as f64 + 1.0;
        let close = |i: &&usize| scored[**i].cost <= best * CLOSE + margin;
        let finalists: Vec<usize> = order
            .iter()
            .take(FINALISTS)
            .take_while(close)
            .copied()
            .collect();
        for i in finalists {
            let image = renderer.image_with(&scored[i].mistakes, &frames[i])?;
            scored[i] = exact(&scored[i], &image, student, reference);
        }
        mark_pairs_like_a_member(&mut scored);
    }
    Ok(CaseAnalysis {
        differing: wrong.len(),
        null_cost,
        scored,
    })
}

/// `scored` with its numbers counted over the whole `image` it renders.
fn exact(scored: &Scored, image: &Rgb8, student: &Rgb8, reference: &Rgb8) -> Scored {
    let mut s = Scored {
        cost: 0.0,
        explained: 0.0,
        wrongly_changed: 0.0,
        changes_image: image.bytes != reference.bytes,
        image_print: Some(print(&image.bytes)),
        ..scored.clone()
    };
    for i in 0..image.bytes.len() / 3 {
        let was_wrong = pixel_difference(&student.bytes, &reference.bytes, i) > 0;
        s.tally(
            1.0,
            was_wrong,
            pixel_difference(&image.bytes, &student.bytes, i),
        );
    }
    s
}

/// Marks the pairs that render what one of their mistakes renders alone (singles come first
/// in `candidates()`, at the bug's catalogue index).
fn mark_pairs_like_a_member(scored: &mut [Scored]) {
    for i in Bug::ALL.len()..scored.len() {
        let members = scored[i].mistakes.bugs();
        let like = members.iter().any(|&b| scored[i].twin(&scored[b as usize]));
        scored[i].same_as_member = like;
    }
}

/// Lower cost first; then `simpler`.
fn ranking(a: &Scored, b: &Scored) -> std::cmp::Ordering {
    a.cost
        .total_cmp(&b.cost)
        .then_with(|| simpler(a.mistakes, b.mistakes))
}

/// Fewer mistakes first, then catalogue order.
fn simpler(a: Mistakes, b: Mistakes) -> std::cmp::Ordering {
    let (a, b) = (a.bugs(), b.bugs());
    a.len().cmp(&b.len()).then(a.cmp(&b))
}

/// One diagnosis: a candidate and how well it reproduces the student's images.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnosis {
    pub mistakes: Mistakes,
    /// Share of the differing pixels it reproduces within 1 LSB.
    pub explained: f64,
    pub unexplained_pixels: u64,
    pub wrongly_changed_pixels: u64,
    /// Candidates with as many mistakes that render every case identically.
    pub indistinguishable_from: Vec<Mistakes>,
    /// Whether the numbers were counted over whole images (else estimated from a sample).
    pub exact: bool,
}

/// The ranked diagnosis over one or more cases: a candidate's cost is its sum over them, so a
/// mistake that explains every failing case ranks first. Lists only candidates that explain
/// the images better than the reference itself does.
pub fn rank(cases: &[&CaseAnalysis]) -> Vec<Diagnosis> {
    let Some(first) = cases.first() else {
        return Vec::new();
    };
    let total = |i: usize, f: &dyn Fn(&Scored) -> f64| -> f64 {
        cases.iter().map(|c| f(&c.scored[i])).sum()
    };
    let null: f64 = cases.iter().map(|c| c.null_cost).sum();
    let differing: usize = cases.iter().map(|c| c.differing).sum();
    let costs: Vec<f64> = (0..first.scored.len())
        .map(|i| total(i, &|s| s.cost))
        .collect();
    let mut order: Vec<usize> = (0..first.scored.len())
        .filter(|&i| {
            cases.iter().any(|c| c.scored[i].changes_image)
                && !cases.iter().all(|c| c.scored[i].same_as_member)
                && costs[i] < null
        })
        .collect();
    order.sort_by(|&a, &b| {
        let mistakes = |i: usize| first.scored[i].mistakes;
        costs[a]
            .total_cmp(&costs[b])
            .then_with(|| simpler(mistakes(a), mistakes(b)))
    });
    // Twins only where whole images were compared at least once: a sample alone can agree by
    // chance.
    let twins = |a: usize, b: usize| {
        cases.iter().all(|c| c.scored[a].twin(&c.scored[b]))
            && cases
                .iter()
                .any(|c| c.scored[a].exact() && c.scored[b].exact())
    };
    let mut listed: Vec<(usize, Diagnosis)> = Vec::new();
    for i in order {
        let mistakes = first.scored[i].mistakes;
        let size = mistakes.bugs().len();
        if let Some((_, entry)) = listed.iter_mut().find(|(r, _)| twins(*r, i)) {
            // A twin with more mistakes adds nothing: the simpler explanation stands.
            if entry.mistakes.bugs().len() == size {
                entry.indistinguishable_from.push(mistakes);
            }
            continue;
        }
        if listed.len() == LISTED {
            continue;
        }
        let explained = total(i, &|s| s.explained);
        listed.push((
            i,
            Diagnosis {
                mistakes,
                explained: if differing == 0 {
                    0.0
                } else {
                    (explained / differing as f64).min(1.0)
                },
                unexplained_pixels: (differing as f64 - explained).max(0.0).round() as u64,
                wrongly_changed_pixels: total(i, &|s| s.wrongly_changed).round() as u64,
                indistinguishable_from: Vec::new(),
                exact: cases
                    .iter()
                    .all(|c| c.scored[i].exact() || c.differing == 0),
            },
        ));
    }
    listed.into_iter().map(|(_, d)| d).collect()
}
