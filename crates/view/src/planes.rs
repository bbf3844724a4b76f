//! The values of one layer as the page asks for them: the image's, the reference's, or an
//! error metric of the two, channel by channel. Everything the viewer sends (layers, tiles,
//! statistics) reads through this, so a metric is computed in one place.

use super::metric::Metric;
use whitted_io::input::Image;

/// Which values of a layer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Which {
    Main,
    Reference,
    /// The metric of the image against the reference.
    Metric(Metric),
}

impl Which {
    pub fn from_name(name: &str) -> Option<Which> {
        match name {
            "main" => Some(Which::Main),
            "reference" => Some(Which::Reference),
            other => Metric::from_name(other).map(Which::Metric),
        }
    }
}

/// One layer's channels, ready to be read pixel by pixel.
pub struct Planes<'a> {
    pub names: Vec<String>,
    channels: Vec<Channel<'a>>,
    pub width: usize,
    pub height: usize,
}

enum Channel<'a> {
    Plain(&'a [f32]),
    Compared(Metric, &'a [f32], &'a [f32]),
}

/// Why no planes: no such layer, or no reference to compare with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Missing {
    Layer,
    Reference,
}

impl<'a> Planes<'a> {
    /// The channels of layer `name`, in display order. The reference has the image's layers
    /// (the viewer refuses one that does not), matched by name.
    pub fn of(
        main: &'a Image,
        reference: Option<&'a Image>,
        which: Which,
        name: &str,
    ) -> Result<Planes<'a>, Missing> {
        let layer_of = |image: &'a Image| -> Result<Vec<(String, &'a [f32])>, Missing> {
            let layer = image
                .layers()
                .into_iter()
                .find(|l| l.name == name)
                .ok_or(Missing::Layer)?;
            Ok(layer
                .channels
                .iter()
                .map(|&i| {
                    let c = &image.channels[i];
                    (
                        whitted_io::input::suffix(&c.name).to_string(),
                        c.values.as_slice(),
                    )
                })
                .collect())
        };
        let ours = layer_of(main)?;
        let theirs = match which {
            Which::Main => None,
            _ => Some(layer_of(reference.ok_or(Missing::Reference)?)?),
        };
        let channels = match (which, &theirs) {
            (Which::Main, _) | (_, None) => ours.iter().map(|(_, v)| Channel::Plain(v)).collect(),
            (Which::Reference, Some(t)) => t.iter().map(|(_, v)| Channel::Plain(v)).collect(),
            (Which::Metric(m), Some(t)) => ours
                .iter()
                .zip(t)
                .map(|((_, a), (_, b))| Channel::Compared(m, a, b))
                .collect(),
        };
        Ok(Planes {
            names: ours.into_iter().map(|(n, _)| n).collect(),
            channels,
            width: main.width,
            height: main.height,
        })
    }

    pub fn count(&self) -> usize {
        self.channels.len()
    }

    /// Channel `c` at pixel index `p`.
    #[inline]
    pub fn value(&self, c: usize, p: usize) -> f32 {
        match self.channels[c] {
            Channel::Plain(v) => v[p],
            Channel::Compared(m, a, b) => m.apply(a[p], b[p]),
        }
    }
}

/// How many pixels of layer `name` differ between the image and the reference in any channel
/// (bit for bit, NaN equal to NaN), or `None` without a reference.
pub fn differing_pixels(main: &Image, reference: Option<&Image>, name: &str) -> Option<u64> {
    let ours = Planes::of(main, reference, Which::Main, name).ok()?;
    let theirs = Planes::of(main, reference, Which::Reference, name).ok()?;
    let pixels = ours.width * ours.height;
    let same = |a: f32, b: f32| a == b || (a.is_nan() && b.is_nan());
    Some(
        (0..pixels)
            .filter(|&p| (0..ours.count()).any(|c| !same(ours.value(c, p), theirs.value(c, p))))
            .count() as u64,
    )
}
