//! Statistics of image layers, for `info`, `diff` and `sheet` captions.

use crate::input::{Image, Layer};

/// Statistics over the finite values of a group of channels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    /// How many values were finite (min, max and mean are over these; 0 when there are none).
    pub finite: usize,
    pub nan: usize,
    pub inf: usize,
}

impl Stats {
    /// Over all `values` of all `channels`.
    pub fn of<'a>(channels: impl IntoIterator<Item = &'a [f32]>) -> Self {
        Self::of_values(channels.into_iter().flatten().copied())
    }

    /// Over `values`; min, max and mean are 0 when nothing is finite.
    pub fn of_values(values: impl IntoIterator<Item = f32>) -> Self {
        let (mut min, mut max, mut sum) = (f64::INFINITY, f64::NEG_INFINITY, 0.0);
        let (mut finite, mut nan, mut inf) = (0usize, 0usize, 0usize);
        for v in values {
            if v.is_nan() {
                nan += 1;
            } else if v.is_infinite() {
                inf += 1;
            } else {
                let v = f64::from(v);
                min = min.min(v);
                max = max.max(v);
                sum += v;
                finite += 1;
            }
        }
        if finite == 0 {
            (min, max) = (0.0, 0.0);
        }
        Stats {
            min,
            max,
            mean: if finite == 0 {
                0.0
            } else {
                sum / finite as f64
            },
            finite,
            nan,
            inf,
        }
    }

    /// NaNs and infinities.
    pub fn non_finite(&self) -> usize {
        self.nan + self.inf
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
        assert_eq!((s.min, s.max, s.mean, s.non_finite()), (-2.0, 4.0, 1.0, 2));
        assert_eq!((s.finite, s.nan, s.inf), (3, 1, 1));
        let empty = Stats::of([&[f32::NAN][..]]);
        assert_eq!((empty.min, empty.non_finite()), (0.0, 1));
    }
}
