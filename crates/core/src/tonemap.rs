//! Tone maps (docs/tonemap.md): pure functions from linear, scene-referred Rec.709 RGB to display
//! values in [0, 1], and the sRGB transfer function that encodes them.

mod sigmoid_bytes;

pub use sigmoid_bytes::sigmoid_byte;

use glam::{DMat3, DVec3};
use palette::encoding::{FromLinear, Srgb};

/// The operators `--tonemap` offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ToneMap {
    /// The course's output: clamp to [0, 1], no transfer function, truncating quantisation.
    #[default]
    Tick,
    /// Clamp to [0, 1], then sRGB.
    Clamp,
    /// `v / (1 + v)` per channel, then sRGB.
    Reinhard,
    /// Narkowicz's fit of the ACES filmic curve, per channel, then sRGB.
    Aces,
    /// Blender 4's AgX base look (polynomial fit of three.js / Filament), then sRGB.
    Agx,
    /// Khronos PBR Neutral, then sRGB.
    Neutral,
    /// The course's own from 2018-19 (docs/courses.md): per channel a sigmoid of `v^1.3`,
    /// then a 1/2.2 gamma, quantised by truncation as the course's `(int)(255 * g)`.
    Sigmoid,
}

/// Inputs are bounded to this before an operator: every operator is saturated long before
/// it, and bounding keeps the rational curves away from inf/inf.
const MAX_INPUT: f64 = 1e9;

impl ToneMap {
    /// Display values in [0, 1] for linear `v` (exposure already applied). NaN counts as 0 and
    /// negative values as 0, so that no curve maps a negative input to a bright output.
    #[inline]
    pub fn apply(self, v: DVec3) -> DVec3 {
        let bounded = bounded(v);
        match self {
            ToneMap::Tick | ToneMap::Clamp => bounded.clamp(DVec3::ZERO, DVec3::ONE),
            ToneMap::Reinhard => bounded / (DVec3::ONE + bounded),
            ToneMap::Aces => bounded.to_array().map(aces).into(),
            ToneMap::Agx => agx(bounded),
            ToneMap::Neutral => neutral(bounded),
            // The course's arithmetic on the exact value: its own NaN and infinity handling is
            // part of the image.
            ToneMap::Sigmoid => v.to_array().map(sigmoid_gamma).into(),
        }
    }

    /// Whether the display values are then sRGB-encoded (all but the course's own, `tick`
    /// and `sigmoid`, which are quantised by truncation as the course does).
    pub fn srgb_encoded(self) -> bool {
        !matches!(self, ToneMap::Tick | ToneMap::Sigmoid)
    }
}

/// `v` with NaN as 0 and every channel within [0, `MAX_INPUT`]: what the display operators
/// take.
#[inline]
fn bounded(v: DVec3) -> DVec3 {
    DVec3::from_array(v.to_array().map(|c| {
        if c.is_nan() {
            0.0
        } else {
            c.clamp(0.0, MAX_INPUT)
        }
    }))
}

/// The factor `2^EV` an exposure of `ev` stops multiplies linear values by: computed once per
/// image, not once per pixel.
pub fn exposure_gain(ev: f64) -> f64 {
    2f64.powf(ev)
}

/// The sRGB OETF of IEC 61966-2-1 (piecewise: linear toe, then a 1/2.4 power), via palette.
#[inline]
pub fn srgb_oetf(t: f64) -> f64 {
    <Srgb as FromLinear<f64, f64>>::from_linear(t)
}

/// Linear `v` as display values in [0, 1], ready to quantise: exposure (`gain` from
/// `exposure_gain`), the tone map, then the sRGB curve for every operator but `tick`. The one
/// place the PNG writer and the contact sheet share.
#[inline]
pub fn to_display(v: DVec3, tone_map: ToneMap, gain: f64) -> [f64; 3] {
    let t = tone_map.apply(v * gain).to_array();
    if tone_map.srgb_encoded() {
        t.map(srgb_oetf)
    } else {
        t
    }
}

/// The course's tone map of one linear channel, in its operation order (docs/courses.md):
/// `p = v^1.3`, `t = p * (1 / (p + (0.5/2)^1.3))`, `g = t^(1/2.2)`, clamped to [0, 1]. A NaN
/// (from a NaN or infinite `v`, or a negative one) gives 0, as the course's `(int)` cast of
/// NaN does.
fn sigmoid_gamma(v: f64) -> f64 {
    let p = v.powf(1.3);
    let reciprocal = 1.0 / (p + (0.5f64 / 2.0).powf(1.3));
    let t = p * reciprocal;
    let g = t.powf(1.0 / 2.2);
    if g.is_nan() {
        0.0
    } else {
        g.clamp(0.0, 1.0)
    }
}

fn aces(v: f64) -> f64 {
    (v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// Builds a matrix from rows as docs/tonemap.md lists them (glam stores columns).
fn rows(r: [[f64; 3]; 3]) -> DMat3 {
    DMat3::from_cols_array_2d(&r).transpose()
}

fn agx(v: DVec3) -> DVec3 {
    const MIN_EV: f64 = -12.47393;
    const MAX_EV: f64 = 4.026069;
    let rec709_to_rec2020 = rows([
        [0.6274, 0.3293, 0.0433],
        [0.0691, 0.9195, 0.0113],
        [0.0164, 0.0880, 0.8956],
    ]);
    let inset = rows([
        [0.856627153315983, 0.0951212405381588, 0.0482516061458583],
        [0.137318972929847, 0.761241990602591, 0.101439036467562],
        [0.11189821299995, 0.0767994186031903, 0.811302368396859],
    ]);
    let outset = rows([
        [1.1271005818144368, -0.1106066430966032, -0.0164939387178346],
        [-0.1413297634984383, 1.157823702216272, -0.0164939387178343],
        [-0.1413297634984383, -0.1106066430966029, 1.2519364065950405],
    ]);
    let rec2020_to_rec709 = rows([
        [1.6605, -0.5876, -0.0728],
        [-0.1246, 1.1329, -0.0083],
        [-0.0182, -0.1006, 1.1187],
    ]);

    let c = inset * (rec709_to_rec2020 * v);
    let log = c
        .to_array()
        .map(|x| ((x.max(1e-10).log2() - MIN_EV) / (MAX_EV - MIN_EV)).clamp(0.0, 1.0));
    let curve = log.map(|x| {
        let (x2, x4) = (x * x, x * x * x * x);
        15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x
            - 0.00232
    });
    let c = outset * DVec3::from_array(curve);
    let linear = c.to_array().map(|x| x.max(0.0).powf(2.2));
    (rec2020_to_rec709 * DVec3::from_array(linear)).clamp(DVec3::ZERO, DVec3::ONE)
}

fn neutral(v: DVec3) -> DVec3 {
    const START_COMPRESSION: f64 = 0.8 - 0.04;
    const DESATURATION: f64 = 0.15;
    let x = v.min_element();
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = v - DVec3::splat(offset);
    let peak = c.max_element();
    if peak < START_COMPRESSION {
        return c;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let c = c * (new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    c * (1.0 - g) + DVec3::splat(new_peak * g)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The operator's value for a grey input `v`, red channel.
    fn grey(op: ToneMap, v: f64) -> f64 {
        op.apply(DVec3::splat(v)).x
    }

    fn close(a: f64, b: f64) {
        assert!((a - b).abs() < 1e-6, "{a} vs {b}");
    }

    #[test]
    fn clamp_and_reinhard_at_hand_computed_points() {
        for (v, want) in [
            (0.0, 0.0),
            (0.18, 0.18),
            (1.0, 1.0),
            (4.0, 1.0),
            (100.0, 1.0),
            (-1.0, 0.0),
            (f64::NAN, 0.0),
        ] {
            close(grey(ToneMap::Clamp, v), want);
        }
        for (v, want) in [
            (0.0, 0.0),
            (0.18, 0.18 / 1.18),
            (1.0, 0.5),
            (4.0, 0.8),
            (100.0, 100.0 / 101.0),
            (-1.0, 0.0),
            (f64::NAN, 0.0),
        ] {
            close(grey(ToneMap::Reinhard, v), want);
        }
    }

    #[test]
    fn aces_at_hand_computed_points() {
        // 0.18: 0.18 * 0.4818 / (0.18 * 1.0274 + 0.14) = 0.086724 / 0.324932
        for (v, want) in [
            (0.0, 0.0),
            (0.18, 0.086724 / 0.324932),
            (1.0, 2.54 / 3.16),
            (4.0, 40.28 / 41.38),
            (100.0, 1.0),
            (-1.0, 0.0),
            (f64::NAN, 0.0),
        ] {
            close(grey(ToneMap::Aces, v), want);
        }
    }

    #[test]
    fn neutral_at_hand_computed_points() {
        // Below the compression start, grey only loses the 0.04 offset.
        close(grey(ToneMap::Neutral, 0.18), 0.14);
        close(grey(ToneMap::Neutral, 0.0), 0.0);
        // 1.0: c = 0.96, new peak = 1 - 0.0576 / 0.44; grey stays grey at the new peak.
        close(grey(ToneMap::Neutral, 1.0), 1.0 - 0.0576 / 0.44);
        close(grey(ToneMap::Neutral, -1.0), 0.0);
        close(grey(ToneMap::Neutral, f64::NAN), 0.0);
        // Highlights approach 1 from below.
        assert!(grey(ToneMap::Neutral, 4.0) > 0.95 && grey(ToneMap::Neutral, 100.0) < 1.0);
    }

    #[test]
    fn agx_at_hand_computed_points() {
        // Black maps below the log range, so the curve gives ~0 and the result clamps to 0.
        close(grey(ToneMap::Agx, 0.0), 0.0);
        close(grey(ToneMap::Agx, -1.0), 0.0);
        close(grey(ToneMap::Agx, f64::NAN), 0.0);
        // Mid grey through the curve: log2(0.18) normalised = (-2.473931 + 12.47393) / 16.499999.
        let x: f64 = (0.18f64.log2() + 12.47393) / (4.026069 + 12.47393);
        let curve = 15.5 * x.powi(6) - 40.14 * x.powi(5) + 31.96 * x.powi(4) - 6.868 * x.powi(3)
            + 0.4298 * x * x
            + 0.1191 * x
            - 0.00232;
        // For grey the inset/outset rows sum to ~1, so the result is ~curve^2.2.
        let t = grey(ToneMap::Agx, 0.18);
        assert!(
            (t - curve.powf(2.2)).abs() < 2e-3,
            "{t} vs {}",
            curve.powf(2.2)
        );
        let bright = grey(ToneMap::Agx, 100.0);
        assert!(bright > 0.95 && bright <= 1.0, "{bright}");
        // Monotonic on greys.
        let values: Vec<f64> = [0.01, 0.1, 0.18, 0.5, 1.0, 4.0, 16.0]
            .iter()
            .map(|&v| grey(ToneMap::Agx, v))
            .collect();
        assert!(values.windows(2).all(|w| w[0] < w[1]), "{values:?}");
    }

    #[test]
    fn srgb_oetf_is_the_piecewise_iec_curve() {
        close(srgb_oetf(0.0), 0.0);
        close(srgb_oetf(0.002), 12.92 * 0.002);
        close(srgb_oetf(0.18), 1.055 * 0.18f64.powf(1.0 / 2.4) - 0.055);
        close(srgb_oetf(1.0), 1.0);
        // Not a 2.2 gamma.
        assert!((srgb_oetf(0.01) - 0.01f64.powf(1.0 / 2.2)).abs() > 0.01);
    }

    #[test]
    fn exposure_doubles_per_stop() {
        assert_eq!(exposure_gain(1.0), 2.0);
        assert_eq!(exposure_gain(-2.0), 0.25);
        assert_eq!(exposure_gain(0.0), 1.0);
    }
}
