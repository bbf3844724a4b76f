//! A layer's statistics and histogram for the viewer's panel, over every pixel at full
//! resolution (the page only ever holds a reduced copy of a large image).

use serde_json::{json, Value};

use super::planes::Planes;
use whitted_core::numbers::finite_or_null;
use whitted_io::stats::Stats;

/// Bins of the histogram.
pub const BINS: usize = 64;

/// Values from this magnitude up are left out of the display range: a miss stores 1e10 in Z
/// (docs/aovs.md), which would otherwise squeeze every hit into one colour.
const SENTINEL: f64 = 1e10;

/// Min, max and mean of the finite values of each channel (`null` when there are none), NaN
/// and infinity counts, the display range (the finite values short of the Z miss value, over
/// every channel), and a histogram of every channel over that range.
pub fn statistics(planes: &Planes) -> Value {
    let pixels = planes.width * planes.height;
    let channel = |c: usize| (0..pixels).map(move |p| planes.value(c, p));
    let channels: Vec<Value> = (0..planes.count())
        .map(|c| {
            let s = Stats::of_values(channel(c));
            let finite = |v: f64| {
                if s.finite > 0 {
                    finite_or_null(v)
                } else {
                    Value::Null
                }
            };
            json!({
                "name": planes.names[c],
                "min": finite(s.min),
                "max": finite(s.max),
                "mean": finite(s.mean),
                "nan": s.nan,
                "inf": s.inf,
            })
        })
        .collect();
    let shown = (0..planes.count()).flat_map(channel).map(f64::from);
    let (lo, hi) = shown
        .filter(|v| v.abs() < SENTINEL)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
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
    use crate::planes::Which;
    use whitted_io::input::raster;

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
