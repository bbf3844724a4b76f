//! Tone maps: linear HDR -> display values (tonemap.md). Pure functions on linear RGB.

use glam::DVec3;

/// The course's output: `floor(255 * clamp(v, 0, 1))` per channel, no gamma, NaN -> 0.
pub fn tick_bytes(v: DVec3) -> [u8; 3] {
    [tick_byte(v.x), tick_byte(v.y), tick_byte(v.z)]
}

fn tick_byte(v: f64) -> u8 {
    // `as` saturates and maps NaN to 0, which is exactly the rule; the clamp keeps the
    // truncation within 0..=255 for finite values.
    (255.0 * v.clamp(0.0, 1.0)) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_truncates_clamps_and_zeroes_nan() {
        assert_eq!(tick_bytes(DVec3::new(0.0, 1.0, 0.5)), [0, 255, 127]);
        assert_eq!(tick_bytes(DVec3::new(-3.0, 7.0, f64::NAN)), [0, 255, 0]);
        assert_eq!(
            tick_bytes(DVec3::new(254.999 / 255.0, 1.0 / 255.0, 0.999 / 255.0)),
            [254, 1, 0]
        );
        assert_eq!(tick_bytes(DVec3::splat(f64::INFINITY)), [255, 255, 255]);
    }
}
