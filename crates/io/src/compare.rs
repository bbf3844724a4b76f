//! Layer-aware numeric comparison of two images (`whitted diff`, the golden tests).
//!
//! A value fails when `|a - b| > abs + rel * |b|` (b is the reference), or when exactly one of
//! the two is NaN; a pixel fails when any compared channel of the layer fails there. A layer
//! fails when more pixels fail than the criteria allow (`--allow-failures`, `--fail-percent`),
//! or when any pixel is off by more than `--hard-fail`. Pixels off by more than `--warn` but
//! within tolerance are counted as warnings, which do not fail. Images are first put on the
//! same pixel grid (`compare/align.rs`): different data windows are a difference, different
//! display windows cannot be compared.

mod align;
mod parts;

pub use align::{align, Alignment};
pub use parts::{compare_files, matching_part, PartReport};

use std::collections::HashMap;

use crate::input::{Channel, Image, Layer};

/// Layers in order, with an index from name to position.
fn by_name(layers: Vec<Layer>) -> (Vec<Layer>, HashMap<String, usize>) {
    let index = layers
        .iter()
        .enumerate()
        .map(|(i, l)| (l.name.clone(), i))
        .collect();
    (layers, index)
}

/// Tolerances: absolute and relative to the reference value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    pub abs: f64,
    pub rel: f64,
}

impl Tolerance {
    /// The tolerance docs/aovs.md states for sums of layers.
    pub const AOV: Tolerance = Tolerance {
        abs: 1e-6,
        rel: 1e-5,
    };

    /// How far past the tolerance `a` is from reference `b`: 0 when equal, <= 1 within.
    pub fn excess(self, a: f64, b: f64) -> f64 {
        match (a.is_nan(), b.is_nan()) {
            (true, true) => 0.0,
            (true, false) | (false, true) => f64::INFINITY,
            _ if a == b => 0.0,
            _ => (a - b).abs() / (self.abs + self.rel * b.abs()),
        }
    }
}

/// When a layer passes, in the spirit of OpenImageIO's `idiff`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criteria {
    pub tolerance: Tolerance,
    /// Failing pixels allowed, as a percentage of the layer's pixels.
    pub fail_percent: f64,
    /// Failing pixels allowed, as a count. The larger allowance of the two applies.
    pub allow_failures: usize,
    /// Any pixel off by more than this (absolute) fails the layer, whatever is allowed.
    pub hard_fail: Option<f64>,
    /// Pixels off by more than this (absolute) but within tolerance are warnings.
    pub warn: Option<f64>,
}

impl Criteria {
    /// Every pixel within `tolerance`, nothing else allowed.
    pub fn strict(tolerance: Tolerance) -> Self {
        Criteria {
            tolerance,
            fail_percent: 0.0,
            allow_failures: 0,
            hard_fail: None,
            warn: None,
        }
    }

    /// How many of `pixels` failing pixels are allowed.
    pub fn allowed(&self, pixels: usize) -> usize {
        let share = (self.fail_percent / 100.0 * pixels as f64).floor() as usize;
        share.max(self.allow_failures)
    }
}

/// How many failing pixels a layer report lists by position.
pub const FIRST_FAILING: usize = 10;

/// The comparison of one layer.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerReport {
    pub layer: String,
    pub channels: Vec<String>,
    pub max_abs: f64,
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB, peak = max(1, largest |reference|); infinite when
    /// the layers are identical.
    pub psnr: f64,
    /// Pixels compared.
    pub pixels: usize,
    /// Pixels beyond `--warn` but within tolerance.
    pub warnings: usize,
    /// Pixels beyond `--hard-fail`.
    pub hard_failures: usize,
    /// Whether the layer passes the criteria.
    pub passed: bool,
    /// Pixels where some channel fails.
    pub failing: usize,
    /// The first failing pixels in row order, as (x, y).
    pub first_failing: Vec<(usize, usize)>,
}

/// Compares layers `layers` (all layers of `reference` when empty) of `actual` against
/// `reference`. Errors (not failures) when the sizes differ or a layer or channel is missing
/// from either image.
pub fn compare(
    actual: &Image,
    reference: &Image,
    layers: &[String],
    criteria: Criteria,
) -> Result<Vec<LayerReport>, String> {
    if (actual.width, actual.height) != (reference.width, reference.height) {
        return Err(format!(
            "sizes differ: {}x{} vs {}x{}",
            actual.width, actual.height, reference.width, reference.height
        ));
    }
    // Looked up by name through maps, so that many channels take linear time.
    let reference_layers = by_name(reference.layers());
    let actual_layers = by_name(actual.layers());
    let actual_channels: HashMap<&str, &Channel> = actual
        .channels
        .iter()
        .map(|c| (c.name.as_str(), c))
        .collect();
    let names: Vec<String> = if layers.is_empty() {
        let mut all: Vec<String> = reference_layers.0.iter().map(|l| l.name.clone()).collect();
        all.extend(
            actual_layers
                .0
                .iter()
                .filter(|l| !reference_layers.1.contains_key(&l.name))
                .map(|l| l.name.clone()),
        );
        all
    } else {
        layers.to_vec()
    };
    let mut reports = Vec::new();
    for name in names {
        let find = |(list, index): &(Vec<Layer>, HashMap<String, usize>), which: &str| {
            index
                .get(&name)
                .map(|&i| list[i].clone())
                .ok_or_else(|| format!("layer `{name}` is missing from the {which} image"))
        };
        let r = find(&reference_layers, "second (reference)")?;
        let a = find(&actual_layers, "first")?;
        let mut channel_names = Vec::new();
        let mut pairs = Vec::new();
        for &i in &r.channels {
            let reference_channel = &reference.channels[i];
            let actual_channel = actual_channels
                .get(reference_channel.name.as_str())
                .ok_or_else(|| {
                    format!(
                        "channel `{}` is missing from the first image",
                        reference_channel.name
                    )
                })?;
            channel_names.push(reference_channel.name.clone());
            pairs.push((&actual_channel.values, &reference_channel.values));
        }
        if a.channels.len() != r.channels.len() {
            return Err(format!(
                "layer `{name}` has {} channels in the first image and {} in the second",
                a.channels.len(),
                r.channels.len()
            ));
        }
        reports.push(compare_layer(
            &name,
            channel_names,
            &pairs,
            actual.width,
            criteria,
        ));
    }
    Ok(reports)
}

fn compare_layer(
    name: &str,
    channels: Vec<String>,
    pairs: &[(&Vec<f32>, &Vec<f32>)],
    width: usize,
    criteria: Criteria,
) -> LayerReport {
    let pixels = pairs.first().map_or(0, |(a, _)| a.len());
    let (mut max_abs, mut sum_sq, mut peak) = (0.0f64, 0.0f64, 1.0f64);
    let (mut failing, mut warnings, mut hard_failures) = (0, 0, 0);
    let mut first_failing = Vec::new();
    for p in 0..pixels {
        let (mut pixel_fails, mut pixel_max) = (false, 0.0f64);
        for (a, b) in pairs {
            let (a, b) = (f64::from(a[p]), f64::from(b[p]));
            if criteria.tolerance.excess(a, b) > 1.0 {
                pixel_fails = true;
            }
            let d = (a - b).abs();
            pixel_max = if d.is_nan() && a.is_nan() != b.is_nan() {
                f64::INFINITY
            } else {
                pixel_max.max(d)
            };
            if d.is_finite() {
                max_abs = max_abs.max(d);
                sum_sq += d * d;
            } else if !(a.is_nan() && b.is_nan()) && a != b {
                max_abs = f64::INFINITY;
                sum_sq = f64::INFINITY;
            }
            if b.is_finite() {
                peak = peak.max(b.abs());
            }
        }
        if criteria.hard_fail.is_some_and(|t| pixel_max > t) {
            hard_failures += 1;
        }
        if pixel_fails {
            failing += 1;
            if first_failing.len() < FIRST_FAILING {
                first_failing.push((p % width.max(1), p / width.max(1)));
            }
        } else if criteria.warn.is_some_and(|t| pixel_max > t) {
            warnings += 1;
        }
    }
    let count = (pixels * pairs.len()).max(1) as f64;
    let rmse = (sum_sq / count).sqrt();
    let psnr = if rmse == 0.0 {
        f64::INFINITY
    } else {
        20.0 * (peak / rmse).log10()
    };
    LayerReport {
        layer: name.to_string(),
        channels,
        max_abs,
        rmse,
        psnr,
        pixels,
        warnings,
        hard_failures,
        passed: hard_failures == 0 && failing <= criteria.allowed(pixels),
        failing,
        first_failing,
    }
}

/// Per pixel, the largest `excess` over all compared channels of `layers`: the heat map.
pub fn excess_map(
    actual: &Image,
    reference: &Image,
    layers: &[String],
    tolerance: Tolerance,
) -> Vec<f64> {
    let mut map = vec![0.0f64; reference.width * reference.height];
    for layer in reference
        .layers()
        .iter()
        .filter(|l| layers.is_empty() || layers.contains(&l.name))
    {
        for &i in &layer.channels {
            let b = &reference.channels[i];
            let Some(a) = actual.channel(&b.name) else {
                continue;
            };
            for (m, (&x, &y)) in map.iter_mut().zip(a.values.iter().zip(&b.values)) {
                *m = m.max(tolerance.excess(f64::from(x), f64::from(y)));
            }
        }
    }
    map
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::image::{Channel, Format, Window};

    fn image(width: usize, values: &[(&str, Vec<f32>)]) -> Image {
        let height = values[0].1.len() / width;
        Image {
            format: Format::Exr,
            part: None,
            width,
            height,
            data_window: Window::at([0, 0], width, height),
            display_window: Window::at([0, 0], width, height),
            channels: values
                .iter()
                .map(|(n, v)| Channel {
                    name: (*n).into(),
                    pixel_type: "float",
                    values: v.clone(),
                })
                .collect(),
            attributes: vec![],
        }
    }

    #[test]
    fn tolerance_is_absolute_plus_relative() {
        let t = Tolerance {
            abs: 0.1,
            rel: 0.01,
        };
        assert!(t.excess(1.1, 1.0) <= 1.0);
        assert!(t.excess(1.2, 1.0) > 1.0);
        assert!(t.excess(105.0, 100.0) > 1.0);
        assert!(t.excess(100.9, 100.0) <= 1.0);
        assert_eq!(t.excess(f64::NAN, f64::NAN), 0.0);
        assert!(t.excess(f64::NAN, 0.0) > 1.0);
    }

    #[test]
    fn reports_the_failing_layer_its_count_and_positions() {
        let reference = image(3, &[("R", vec![0.0; 6]), ("Z", vec![1.0; 6])]);
        let mut z = vec![1.0; 6];
        z[4] = 1.5;
        z[5] = 0.5;
        let actual = image(3, &[("R", vec![0.0; 6]), ("Z", z)]);
        let reports = compare(&actual, &reference, &[], Criteria::strict(Tolerance::AOV))
            .expect("comparable");
        let r = reports
            .iter()
            .find(|r| r.layer == "beauty")
            .expect("beauty");
        assert!(r.passed && r.psnr.is_infinite());
        let z = reports.iter().find(|r| r.layer == "Z").expect("Z");
        assert_eq!(
            (z.failing, z.first_failing.clone()),
            (2, vec![(1, 1), (2, 1)])
        );
        assert_eq!(z.max_abs, 0.5);
        assert!((z.rmse - (0.5f64 / 6.0).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn mismatches_are_errors_not_failures() {
        let a = image(2, &[("R", vec![0.0; 4])]);
        let b = image(4, &[("R", vec![0.0; 4])]);
        assert!(compare(&a, &b, &[], Criteria::strict(Tolerance::AOV))
            .unwrap_err()
            .contains("sizes differ"));
        let c = image(2, &[("Z", vec![0.0; 4])]);
        assert!(compare(&a, &c, &[], Criteria::strict(Tolerance::AOV))
            .unwrap_err()
            .contains("missing"));
        assert!(
            compare(&a, &a, &["nope".into()], Criteria::strict(Tolerance::AOV))
                .unwrap_err()
                .contains("`nope`")
        );
    }
}
