//! The course's sigmoid tone map straight to 8-bit codes, exactly and without its three
//! `pow`s on nearly every channel: an 800x600 PNG spent a third of its render time in them.
//!
//! Hand-written because exactness is owed (the byte must be the course's on every input) and
//! no crate does it. The byte `floor(255 g(v))` is a non-decreasing step function of `v`: it
//! changes only where the real curve `G(v) = (p / (p + C))^(1/2.2)`, `p = v^1.3`, crosses
//! `k/255`. The curve inverts in closed form (`t = y^2.2`, `p = C t / (1 - t)`,
//! `v = p^(1/1.3)`), so each crossing `V_k` is known to about 1e-14 relative. The computed `g`
//! is within about 1e-15 relative of `G` (two `pow`s, a division, a product, each within an
//! ulp or so; an error in `p` reaches `t` damped by `C/(p+C)` and `g` by 1/2.2), and near
//! `V_k` a relative change `dv/v` moves `G` by at least `0.005 dv/v` (the slowest crossing,
//! k = 254). So outside `V_k (1 +- 1e-9)` the computed byte is the side of `V_k` that `v` is
//! on, with a factor of 50 to spare; inside such a zone, and wherever the argument does not
//! hold (not finite, not positive, or so large that `g` rounds towards 1), the course's
//! arithmetic itself is evaluated. A value's byte is then one look-up in a table of buckets
//! by the value's top bits (128 a doubling), except in the few buckets a zone meets. `tests`
//! checks the two against each other on every zone's and bucket's edges and on millions of
//! values.

use std::sync::OnceLock;

/// Half the width of each crossing's zone, relative.
const ZONE: f64 = 1e-9;

/// Beyond this, `g` is within 1e-13 of 1 and the error argument does not hold: evaluated.
const LARGE: f64 = 1e8;

/// Below this every value is byte 0: the first crossing is near 2.1e-5.
const FLOOR: f64 = 1.0 / (1u64 << 20) as f64;

/// Buckets of values by their top bits (the exponent and 7 bits of mantissa: 128 a doubling)
/// from `FLOOR` to `LARGE`: each holds its byte, or `CROSSED` when a zone meets it.
const BUCKET_SHIFT: u32 = 45;
const CROSSED: u16 = 0x100;

fn bucket(v: f64) -> usize {
    ((v.to_bits() >> BUCKET_SHIFT) - (FLOOR.to_bits() >> BUCKET_SHIFT)) as usize
}

/// The buckets from `FLOOR` to `LARGE`: a value's byte in one look-up, except in the few
/// buckets a crossing's zone meets.
fn buckets() -> &'static [u16] {
    static BUCKETS: OnceLock<Vec<u16>> = OnceLock::new();
    BUCKETS.get_or_init(|| {
        let zones = zones();
        (0..=bucket(LARGE))
            .map(|b| {
                let first = (b as u64 + (FLOOR.to_bits() >> BUCKET_SHIFT)) << BUCKET_SHIFT;
                let (lo, hi) = (
                    f64::from_bits(first),
                    f64::from_bits(first + (1 << BUCKET_SHIFT) - 1),
                );
                let passed = zones.partition_point(|&(_, zone_hi)| zone_hi < lo);
                match zones.get(passed) {
                    Some(&(zone_lo, _)) if zone_lo <= hi => CROSSED,
                    _ => passed as u16,
                }
            })
            .collect()
    })
}

/// The crossings' zones, `(lo, hi)` for k = 1..=254 in order.
fn zones() -> &'static [(f64, f64); 254] {
    static ZONES: OnceLock<[(f64, f64); 254]> = OnceLock::new();
    ZONES.get_or_init(|| {
        let c = (0.5f64 / 2.0).powf(1.3);
        std::array::from_fn(|i| {
            let y = (i + 1) as f64 / 255.0;
            let t = y.powf(2.2);
            let v = (c * t / (1.0 - t)).powf(1.0 / 1.3);
            (v * (1.0 - ZONE), v * (1.0 + ZONE))
        })
    })
}

/// The course's byte for linear `v`: `(int)(255 * clamp(g, 0, 1))` with `g` the sigmoid of
/// `super::sigmoid_gamma`, bit for bit.
pub fn sigmoid_byte(v: f64) -> u8 {
    // NaN, infinities, negatives, zero and the near-white: the arithmetic itself.
    if !(v > 0.0 && v < LARGE) {
        return exact(v);
    }
    if v < FLOOR {
        return 0;
    }
    let entry = buckets()[bucket(v)];
    if entry != CROSSED {
        return entry as u8;
    }
    let zones = zones();
    // Crossings certainly passed: their zone lies wholly below v.
    let passed = zones.partition_point(|&(_, hi)| hi < v);
    match zones.get(passed) {
        Some(&(lo, _)) if v >= lo => exact(v),
        _ => passed as u8,
    }
}

fn exact(v: f64) -> u8 {
    (255.0 * super::sigmoid_gamma(v)) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_buckets_cover_the_range_and_few_are_crossed() {
        assert!(zones()[0].0 > FLOOR, "the first crossing lies above FLOOR");
        let crossed = buckets().iter().filter(|&&b| b == CROSSED).count();
        assert!(crossed <= 254 * 2, "{crossed}");
        assert!(buckets().len() > 5000);
        // Every bucket's edges: the byte it holds is the course's.
        for b in 0..buckets().len() {
            let first = (b as u64 + (FLOOR.to_bits() >> BUCKET_SHIFT)) << BUCKET_SHIFT;
            for v in [
                f64::from_bits(first),
                f64::from_bits(first + (1 << BUCKET_SHIFT) - 1),
            ] {
                if v < LARGE {
                    assert_eq!(sigmoid_byte(v), exact(v), "{v:e}");
                }
            }
        }
    }

    #[test]
    fn every_zone_edge_and_its_neighbours_give_the_course_s_byte() {
        let next =
            |v: f64, up: bool| f64::from_bits(if up { v.to_bits() + 1 } else { v.to_bits() - 1 });
        for &(lo, hi) in zones().iter() {
            for edge in [lo, hi] {
                let mut below = edge;
                let mut above = edge;
                for _ in 0..64 {
                    assert_eq!(sigmoid_byte(below), exact(below), "{below:e}");
                    assert_eq!(sigmoid_byte(above), exact(above), "{above:e}");
                    below = next(below, false);
                    above = next(above, true);
                }
            }
            // The crossing itself lies inside the zone: the byte changes there.
            assert!(exact(lo * (1.0 - 1e-8)) < exact(hi * (1.0 + 1e-8)));
        }
    }

    #[test]
    fn millions_of_values_give_the_course_s_byte() {
        // Log-spaced from 1e-12 to 1e12, with every value's neighbours, and the specials.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..2_000_000u64 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            let v = 10f64.powf(-12.0 + 24.0 * u) * if i % 97 == 0 { -1.0 } else { 1.0 };
            assert_eq!(sigmoid_byte(v), exact(v), "{v:e}");
        }
        for v in [
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            1e300,
            1.0,
            10.0,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            assert_eq!(sigmoid_byte(v), exact(v), "{v:e}");
        }
        // The course's own figures: 1.0 gives 237, 10 gives 254, NaN and +inf 0.
        assert_eq!(sigmoid_byte(1.0), 237);
        assert_eq!(sigmoid_byte(10.0), 254);
        assert_eq!(sigmoid_byte(f64::INFINITY), 0);
        assert_eq!(sigmoid_byte(0.001), 9);
    }
}
