//! Statistics of image layers, for `info`, `diff` and `sheet` captions.

use crate::input::{Image, Layer};

/// Statistics over the finite values of a group of channels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    pub non_finite: usize,
}

impl Stats {
    /// Over all `values` of all `channels`; min, max and mean are 0 when nothing is finite.
    pub fn of<'a>(channels: impl IntoIterator<Item = &'a [f32]>) -> Self {
        let (mut min, mut max, mut sum, mut finite, mut non_finite) =
            (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0usize, 0usize);
        for values in channels {
            for &v in values {
                if v.is_finite() {
                    let v = f64::from(v);
                    min = min.min(v);
                    max = max.max(v);
                    sum += v;
                    finite += 1;
                } else {
                    non_finite += 1;
                }
            }
        }
        if finite == 0 {
            return Stats {
                min: 0.0,
                max: 0.0,
                mean: 0.0,
                non_finite,
            };
        }
        Stats {
            min,
            max,
            mean: sum / finite as f64,
            non_finite,
        }
    }

    /// Over a layer's colour channels (R, G, B, not alpha), or all its channels when it is
    /// not a colour layer.
    pub fn of_layer(image: &Image, layer: &Layer) -> Self {
        Self::of(
            image
                .statistics_channels(layer)
                .into_iter()
                .map(|i| image.channels[i].values.as_slice()),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_skip_non_finite_values() {
        let values = [1.0f32, -2.0, f32::NAN, 4.0, f32::INFINITY];
        let s = Stats::of([&values[..]]);
        assert_eq!((s.min, s.max, s.mean, s.non_finite), (-2.0, 4.0, 1.0, 2));
        let empty = Stats::of([&[f32::NAN][..]]);
        assert_eq!((empty.min, empty.non_finite), (0.0, 1));
    }
}
