//! Beyond the catalogue: when no listed mistake explains a student's image, say which terms
//! of the model the difference lives in. The reference's own layers (docs/aovs.md) split its
//! beauty into ambient, diffuse and specular, per light with and without shadows, and per
//! bounce; the student's image is fitted as the reference with one layer scaled
//! (`beauty + (f - 1) * layer`), or with a light's shadows left out (its `light_` layer
//! replaced by `f` times its `unshadowed_` layer), by least squares over the differing pixels.

use glam::DVec3;

use crate::check::student_png::Rgb8;
use whitted_core::aov::{self, Kind, PerLight, Quantity};
use whitted_core::sample::Sample;
use whitted_core::scene::Scene;
use whitted_io::output::png::tick_bytes;

/// Term fits reported at most.
const LISTED: usize = 3;

/// One fitted term.
#[derive(Debug, Clone, PartialEq)]
pub struct TermFit {
    /// The layer scaled, as the EXR names it.
    pub layer: String,
    /// The layer this one stands in for (a light's shadowed layer, for `unshadowed_`), if any.
    pub replaces: Option<String>,
    /// How strong the layer is in the student's image: 1 as in the reference, 0 missing, 2
    /// doubled.
    pub factor: f64,
    /// Share of the differing pixels this fit reproduces within 1 LSB.
    pub explained: f64,
}

impl TermFit {
    /// The fit in words, for the text report.
    pub fn sentence(&self) -> String {
        match (&self.replaces, self.factor) {
            (Some(shadowed), _) => format!(
                "`{shadowed}` looks unshadowed (`{}`, x{:.2}): that light's shadows are missing",
                self.layer, self.factor
            ),
            (None, f) if f.abs() < 0.05 => format!("`{}` is missing", self.layer),
            (None, f) => format!("`{}` is {f:.2}x as strong as the reference's", self.layer),
        }
    }
}

/// One candidate term: the image is `base + f * term`.
struct Term {
    layer: String,
    replaces: Option<String>,
    /// Per sampled pixel: (base, term).
    values: Vec<(DVec3, DVec3)>,
}

/// Factors outside this range are no finding: no plausible program scales a term so.
const PLAUSIBLE: std::ops::RangeInclusive<f64> = -0.05..=4.0;

fn layer_value(sample: &Sample, quantity: Quantity) -> DVec3 {
    let mut out = [0.0; 4];
    quantity.values(sample, &mut out);
    DVec3::new(out[0], out[1], out[2])
}

/// One case's candidate terms at its sampled differing pixels, and the student's bytes there.
pub struct TermCase {
    terms: Vec<Term>,
    beauty: Vec<DVec3>,
    targets: Vec<[u8; 3]>,
}

impl TermCase {
    /// The terms of `scene`'s render at `bounces`, from the reference `samples` of `pixels`.
    pub fn new(
        scene: &Scene,
        bounces: u32,
        samples: &[Sample],
        pixels: &[(u32, u32)],
        student: &Rgb8,
    ) -> Self {
        let names: Vec<String> = scene.lights.iter().map(|l| l.name.clone()).collect();
        let layers = aov::all_layers(&names, bounces);
        let colour = |q: Quantity| q.kind() == Kind::Colour && q != Quantity::Beauty;
        let mut terms: Vec<Term> = layers
            .iter()
            .filter(|l| colour(l.quantity))
            .map(|l| Term {
                layer: l.name.clone(),
                replaces: None,
                values: samples
                    .iter()
                    .map(|s| {
                        let v = layer_value(s, l.quantity);
                        (s.beauty - v, v)
                    })
                    .collect(),
            })
            .collect();
        for (i, name) in names.iter().enumerate() {
            terms.push(Term {
                layer: PerLight::Unshadowed.layer_name(name),
                replaces: Some(PerLight::Shadowed.layer_name(name)),
                values: samples
                    .iter()
                    .map(|s| (s.beauty - s.lights[i].shadowed, s.lights[i].unshadowed))
                    .collect(),
            });
        }
        TermCase {
            terms,
            beauty: samples.iter().map(|s| s.beauty).collect(),
            targets: pixels.iter().map(|&(x, y)| student.pixel(x, y)).collect(),
        }
    }

    fn term(&self, layer: &str, replaces: &Option<String>) -> Option<&Term> {
        self.terms
            .iter()
            .find(|t| t.layer == layer && &t.replaces == replaces)
    }
}

/// The fits that best reproduce the students' images over every case at once, best first: a
/// term's factor is shared by every case (the least-squares sums add across cases), and a
/// case without that layer keeps the reference's beauty.
pub fn fit(cases: &[TermCase]) -> Vec<TermFit> {
    let mut keys: Vec<(String, Option<String>)> = Vec::new();
    for t in cases.iter().flat_map(|c| &c.terms) {
        let key = (t.layer.clone(), t.replaces.clone());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let total: usize = cases.iter().map(|c| c.targets.len()).sum();
    let mut fits: Vec<TermFit> = keys
        .iter()
        .filter_map(|(layer, replaces)| {
            let (mut num, mut den) = (0.0, 0.0);
            for case in cases {
                if let Some(term) = case.term(layer, replaces) {
                    let (n, d) = sums(term, &case.targets);
                    num += n;
                    den += d;
                }
            }
            if den <= 1e-12 {
                return None;
            }
            let factor = num / den;
            let matched: usize = cases
                .iter()
                .map(|case| {
                    let predicted: Vec<DVec3> = match case.term(layer, replaces) {
                        Some(term) => term.values.iter().map(|&(b, x)| b + x * factor).collect(),
                        None => case.beauty.clone(),
                    };
                    matches(&predicted, &case.targets)
                })
                .sum();
            Some(TermFit {
                layer: layer.clone(),
                replaces: replaces.clone(),
                factor,
                explained: matched as f64 / total.max(1) as f64,
            })
        })
        .filter(|f| f.explained > 0.0 && (f.replaces.is_some() || (f.factor - 1.0).abs() > 1e-3))
        .filter(|f| PLAUSIBLE.contains(&f.factor))
        .collect();
    // On a tie the replacement reads better: "shadows missing", not "twice as strong".
    fits.sort_by(|a, b| {
        (b.explained, b.replaces.is_some())
            .partial_cmp(&(a.explained, a.replaces.is_some()))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    fits.truncate(LISTED);
    fits
}

/// The least-squares sums for `f` over the channels the student's bytes do not clip.
fn sums(term: &Term, targets: &[[u8; 3]]) -> (f64, f64) {
    let (mut num, mut den) = (0.0, 0.0);
    for (&(base, x), target) in term.values.iter().zip(targets) {
        for c in 0..3 {
            let byte = target[c];
            if byte == 0 || byte == 255 || !base[c].is_finite() || !x[c].is_finite() {
                continue;
            }
            // The middle of the byte's interval of values.
            let t = (f64::from(byte) + 0.5) / 255.0;
            num += x[c] * (t - base[c]);
            den += x[c] * x[c];
        }
    }
    (num, den)
}

/// How many `predicted` values give the target bytes within 1 LSB.
fn matches(predicted: &[DVec3], targets: &[[u8; 3]]) -> usize {
    let bytes = tick_bytes(predicted);
    targets
        .iter()
        .enumerate()
        .filter(|(i, t)| (0..3).all(|c| bytes[3 * i + c].abs_diff(t[c]) <= 1))
        .count()
}
