//! A layer's statistics and histogram for the viewer's panel, over every pixel at full
//! resolution (the page only ever holds a reduced copy of a large image).

use serde_json::{json, Value};

use super::planes::Planes;
use crate::numbers::finite_or_null;

/// Bins of the histogram.
pub const BINS: usize = 64;

/// Values from this magnitude up are left out of the display range: a miss stores 1e10 in Z
/// (docs/aovs.md), which would otherwise squeeze every hit into one colour.
const SENTINEL: f64 = 1e10;

/// Min, max and mean of the finite values of each channel, NaN and infinity counts, the
/// display range (the finite values short of the Z miss value, over every channel), and a
/// histogram of every channel over that range.
pub fn statistics(planes: &Planes) -> Value {
    let pixels = planes.width * planes.height;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut channels = Vec::new();
    for c in 0..planes.count() {
        let (mut min, mut max, mut sum, mut finite) = (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0u64);
        let (mut nan, mut inf) = (0u64, 0u64);
        for p in 0..pixels {
            let v = f64::from(planes.value(c, p));
            if v.is_nan() {
                nan += 1;
            } else if v.is_infinite() {
                inf += 1;
            } else {
                min = min.min(v);
                max = max.max(v);
                sum += v;
                finite += 1;
                if v.abs() < SENTINEL {
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
        }
        let mean = if finite > 0 {
            sum / finite as f64
        } else {
            f64::NAN
        };
        channels.push(json!({
            "name": planes.names[c],
            "min": finite_or_null(min),
            "max": finite_or_null(max),
            "mean": finite_or_null(mean),
            "nan": nan,
            "inf": inf,
        }));
    }
    let bins: Vec<Vec<u64>> = (0..planes.count())
        .map(|c| histogram(planes, c, lo, hi))
        .collect();
    json!({
        "channels": channels,
        "range": [finite_or_null(lo), finite_or_null(hi)],
        "histogram": { "lo": finite_or_null(lo), "hi": finite_or_null(hi), "bins": bins },
    })
}

/// Counts of channel `c`'s values in [lo, hi] in `BINS` equal bins (all in the first when the
/// range is one value).
fn histogram(planes: &Planes, c: usize, lo: f64, hi: f64) -> Vec<u64> {
    let mut bins = vec![0u64; BINS];
    if !(lo.is_finite() && hi.is_finite()) {
        return bins;
    }
    let width = hi - lo;
    for p in 0..planes.width * planes.height {
        let v = f64::from(planes.value(c, p));
        if (lo..=hi).contains(&v) {
            let t = if width > 0.0 { (v - lo) / width } else { 0.0 };
            bins[((t * BINS as f64) as usize).min(BINS - 1)] += 1;
        }
    }
    bins
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::raster;
    use crate::view::planes::Which;

    #[test]
    fn statistics_count_what_is_there() {
        let mut image = raster::rgb8(2, 1, &[0, 51, 255, 255, 51, 0]);
        image.channels[2].values[1] = f32::NAN;
        image.channels[1].values[1] = f32::INFINITY;
        let planes = Planes::of(&image, None, Which::Main, "beauty").expect("beauty");
        let s = statistics(&planes);
        assert_eq!(s["channels"][0]["min"], 0.0);
        assert_eq!(s["channels"][0]["max"], 1.0);
        assert_eq!(s["channels"][0]["mean"], 0.5);
        assert_eq!(s["channels"][1]["inf"], 1);
        assert_eq!(s["channels"][2]["nan"], 1);
        let bins = &s["histogram"]["bins"];
        assert_eq!(bins[0][0], 1);
        assert_eq!(bins[0][BINS - 1], 1);
        // 51/255 = 0.2 of the range [0, 1]: bin floor(0.2 * 64) = 12.
        assert_eq!(bins[1][12], 1, "{bins}");
    }
}
