//! The film: named layers declared up front, filled pixel by pixel from samples.
//!
//! The beauty is also kept in f64, because the tick PNG quantises the exact value the course
//! computes; rounding it to f32 first could move a pixel across a byte. Every layer is
//! accumulated in f64 and stored as f32, which is what the EXR holds.

use glam::DVec3;

use crate::aov::{Layer, Quantity, Reduction};
use crate::error::Result;
use crate::memory;
use crate::sample::Sample;

/// The rendered image and its AOV layers.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Where this film's top-left pixel sits in the full image (non-zero for a region).
    pub origin: (u32, u32),
    /// Size of the full image it is part of.
    pub display: (u32, u32),
    /// Row-major, y = 0 the top row; the exact mean beauty of each pixel.
    pub beauty: Vec<DVec3>,
    /// The layers stored, in file order.
    pub layers: Vec<Layer>,
    /// Full channel names of all layers, in storage order.
    pub channel_names: Vec<String>,
    /// Pixel-major: channel c of pixel i is `data[i * channel_count + c]`. Always finite.
    pub data: Vec<f32>,
}

impl Film {
    /// An empty film for `layers`; an error only when memory cannot be had.
    ///
    /// With no layers it holds the f64 beauty alone, which is all a PNG needs.
    ///
    /// # Panics
    /// With two layers declaring a channel of the same name (one would silently
    /// vanish from the file): the layer catalogue never does either, so that is a bug.
    pub fn new(width: u32, height: u32, layers: Vec<Layer>) -> Result<Self> {
        let channel_names: Vec<String> = layers.iter().flat_map(Layer::channel_names).collect();
        let mut sorted = channel_names.clone();
        sorted.sort_unstable();
        if let Some(pair) = sorted.windows(2).find(|pair| pair[0] == pair[1]) {
            panic!("two layers declare the channel `{}`", pair[0]);
        }
        let pixels = width as usize * height as usize;
        Ok(Film {
            width,
            height,
            origin: (0, 0),
            display: (width, height),
            beauty: memory::filled(pixels, DVec3::ZERO)?,
            data: memory::filled(pixels.saturating_mul(channel_names.len()), 0.0)?,
            layers,
            channel_names,
        })
    }

    /// Shortens this film to its first `rows` rows (a strip at the image's bottom edge),
    /// keeping its buffers' capacity. No-op for as many rows as it has or more.
    pub fn keep_rows(&mut self, rows: u32) {
        if rows < self.height {
            self.height = rows;
            let pixels = self.width as usize * rows as usize;
            self.beauty.truncate(pixels);
            self.data.truncate(pixels * self.channel_count());
        }
    }

    pub fn channel_count(&self) -> usize {
        self.channel_names.len()
    }

    /// The exact beauty of pixel (x, y).
    pub fn pixel(&self, x: u32, y: u32) -> DVec3 {
        self.beauty[y as usize * self.width as usize + x as usize]
    }

    /// One channel as a row-major plane, or `None` if the film does not hold it.
    pub fn channel(&self, name: &str) -> Option<Vec<f32>> {
        let c = self.channel_names.iter().position(|n| n == name)?;
        Some(
            self.data
                .chunks_exact(self.channel_count())
                .map(|pixel| pixel[c])
                .collect(),
        )
    }
}

/// Sums the samples of one pixel, then writes their reduction into the film's storage.
pub struct PixelAccumulator {
    /// Each layer's place in the sums, looked up once, not per sample.
    slots: Vec<Slot>,
    /// Per channel, whether it is averaged over the samples (the slots' flag, flattened).
    averaged: Vec<bool>,
    /// Per channel, the zero its sum starts from: +0.0 for a mean (so that a sum of -0.0
    /// values is +0.0), -0.0 for a kept value (adding -0.0 changes no value at all).
    zero: Vec<f64>,
    beauty: DVec3,
    sums: Vec<f64>,
    samples: u32,
}

/// One layer's channels in a pixel's sums.
#[derive(Debug, Clone, Copy)]
struct Slot {
    quantity: Quantity,
    /// Where its channels start, and how many there are.
    start: usize,
    len: usize,
    /// Averaged over the samples; else the sample nearest the pixel centre is kept.
    mean: bool,
}

impl PixelAccumulator {
    pub fn new(layers: &[Layer], channel_count: usize) -> Self {
        let mut start = 0;
        let slots = layers
            .iter()
            .map(|layer| {
                let quantity = layer.quantity;
                let slot = Slot {
                    quantity,
                    start,
                    len: quantity.channels().len(),
                    mean: quantity.reduction() == Reduction::Mean,
                };
                start += slot.len;
                slot
            })
            .collect::<Vec<_>>();
        let averaged: Vec<bool> = slots
            .iter()
            .flat_map(|slot| std::iter::repeat_n(slot.mean, slot.len))
            .collect();
        let zero = averaged
            .iter()
            .map(|&mean| if mean { 0.0 } else { -0.0 })
            .collect();
        PixelAccumulator {
            slots,
            averaged,
            zero,
            beauty: DVec3::ZERO,
            sums: vec![0.0; channel_count],
            samples: 0,
        }
    }

    /// Adds one sample; `nearest_centre` marks the sample whose depth, position and id the
    /// pixel keeps. Values are written straight into the sums wherever they replace them (a
    /// pixel's first sample, the nearest-centre sample): at one sample per pixel that is
    /// every value, with nothing added and nothing copied twice.
    ///
    /// Always inlined: the render loop is compiled once per course model, and a function
    /// called from two loops is otherwise left out of line (tick2 +1.4% instructions).
    #[inline(always)]
    pub fn add(&mut self, sample: &Sample, nearest_centre: bool) {
        self.beauty += sample.beauty;
        let first = self.samples == 0;
        self.samples += 1;
        for &Slot {
            quantity,
            start,
            len,
            mean,
        } in &self.slots
        {
            let sums = &mut self.sums[start..start + len];
            if first || (nearest_centre && !mean) {
                quantity.values(sample, sums);
            } else if mean {
                let mut values = [0.0; 4];
                quantity.values(sample, &mut values[..len]);
                for (s, v) in sums.iter_mut().zip(values) {
                    *s += v;
                }
            }
        }
    }

    /// Writes the pixel (means, and nearest-centre values) and starts the next one.
    /// Returns how many channel values were not finite and were stored as 0.
    ///
    /// A mean is `(0.0 + v1 + v2 + ...) / n`, the sum started at zero so that a sum of -0.0
    /// values is +0.0: `add` starts from `v1` instead, and adding the channel's `zero` here
    /// gives the same value (the two running sums differ at most in the sign of a zero, which
    /// adding +0.0 removes). Branch-free at one sample, so that it vectorises.
    #[inline(always)]
    pub fn finish(&mut self, beauty: &mut DVec3, out: &mut [f32]) -> u64 {
        let count = f64::from(self.samples.max(1));
        *beauty = self.beauty / count;
        let mut non_finite = 0;
        let values = out.iter_mut().zip(&self.sums).zip(&self.zero);
        if self.samples <= 1 {
            // Dividing by 1 would change no value.
            for ((o, &s), &zero) in values {
                non_finite += store(o, s + zero);
            }
        } else {
            for (((o, &s), &zero), &mean) in values.zip(&self.averaged) {
                non_finite += store(o, if mean { (s + zero) / count } else { s + zero });
            }
        }
        self.beauty = DVec3::ZERO;
        self.samples = 0;
        non_finite
    }
}

/// Stores a channel value as f32; returns 1 if it was not finite (then stored as 0). Both
/// outcomes are computed and one selected, so that the loops over a pixel's channels
/// vectorise.
fn store(out: &mut f32, v: f64) -> u64 {
    let finite = v.is_finite();
    // Finite f64 beyond the f32 range stays finite, at the largest f32.
    let converted = v.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32;
    *out = if finite { converted } else { 0.0 };
    u64::from(!finite)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aov::{all_layers, Quantity};
    use crate::sample::PrimaryHit;

    fn sample(beauty: f64, depth: f64) -> Sample {
        let mut s = Sample::empty(1, 0);
        s.beauty = DVec3::splat(beauty);
        s.direct = DVec3::splat(beauty);
        s.primary = Some(PrimaryHit {
            position: DVec3::new(0.0, 0.0, depth),
            normal: DVec3::Y,
            albedo: DVec3::ONE,
            object: 4,
        });
        s
    }

    #[test]
    #[should_panic(expected = "two layers declare the channel `direct.")]
    fn duplicate_channels_are_a_bug() {
        let layer = all_layers(&[], 0).remove(1);
        let _ = Film::new(2, 2, vec![layer.clone(), layer]);
    }

    #[test]
    fn colour_is_averaged_and_depth_comes_from_the_centre_sample() {
        let layers = all_layers(&["a".into()], 0);
        let film = Film::new(1, 1, layers.clone()).expect("film");
        let mut acc = PixelAccumulator::new(&layers, film.channel_count());
        acc.add(&sample(1.0, 3.0), false);
        acc.add(&sample(0.5, 7.0), true);
        let mut beauty = DVec3::ZERO;
        let mut out = vec![0.0; film.channel_count()];
        assert_eq!(acc.finish(&mut beauty, &mut out), 0);
        assert_eq!(beauty, DVec3::splat(0.75));
        let at = |name: &str| {
            out[film
                .channel_names
                .iter()
                .position(|n| n == name)
                .expect(name)]
        };
        assert_eq!(at("R"), 0.75);
        assert_eq!(at("A"), 1.0);
        assert_eq!(at("direct.G"), 0.75);
        assert_eq!(at("Z"), 7.0);
        assert_eq!(at("objectid.X"), 5.0);
        assert_eq!(at("N.Y"), 1.0);
    }

    #[test]
    fn sums_start_at_plus_zero_and_kept_values_keep_their_sign() {
        let layers = all_layers(&[], 0);
        let film = Film::new(1, 1, layers.clone()).expect("film");
        let at = |out: &[f32], name: &str| {
            out[film
                .channel_names
                .iter()
                .position(|n| n == name)
                .expect(name)]
        };
        for samples in [1, 3] {
            let mut acc = PixelAccumulator::new(&layers, film.channel_count());
            let mut s = sample(1.0, -0.0);
            s.direct = DVec3::splat(-0.0);
            for i in 0..samples {
                acc.add(&s, i == 0);
            }
            let mut out = vec![9.0; film.channel_count()];
            acc.finish(&mut DVec3::default(), &mut out);
            // A mean of -0.0 samples is +0.0, as a sum from zero gives; Z is the sample's own.
            assert_eq!(
                at(&out, "direct.R").to_bits(),
                0.0f32.to_bits(),
                "{samples}"
            );
            assert_eq!(at(&out, "Z").to_bits(), (-0.0f32).to_bits(), "{samples}");
        }
    }

    #[test]
    fn non_finite_values_are_stored_as_zero_and_counted() {
        let layers = vec![Layer {
            name: "direct".into(),
            quantity: Quantity::Direct,
        }];
        let mut acc = PixelAccumulator::new(&layers, 3);
        let mut s = sample(1.0, 1.0);
        s.direct = DVec3::new(f64::NAN, f64::INFINITY, 1e300);
        acc.add(&s, true);
        let mut out = vec![9.0; 3];
        let mut beauty = DVec3::ZERO;
        assert_eq!(acc.finish(&mut beauty, &mut out), 2);
        assert_eq!(out, [0.0, 0.0, f32::MAX]);
    }
}
