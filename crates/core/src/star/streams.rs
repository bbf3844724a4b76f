//! The random numbers of Tick 1* renders, one independent stream per pixel, so that a pixel's
//! value depends on the seed and the pixel alone, never on the thread that renders it.
//! The course's draw uses a PCG stream (`rand_pcg`), numbered by the pixel; the converged
//! estimate uses Owen-scrambled Sobol points (`sobol_burley`) seeded per pixel.

use rand_core::Rng;
use rand_pcg::Pcg64;

/// splitmix64's finaliser: spreads a seed and an index over all bits.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The course's `Math.random()` for one pixel (`random`): uniform doubles in [0, 1), 53 bits each.
pub struct CourseStream(Pcg64);

impl CourseStream {
    /// Pixel `pixel` (row-major index in the full image) of the draw seeded `seed`.
    pub fn new(seed: u64, pixel: u64) -> Self {
        CourseStream(Pcg64::new(u128::from(mix(seed)), u128::from(pixel)))
    }

    pub fn random(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Sobol dimension sets (of four) the converged estimate draws from; set 0 is the aperture.
const SETS: u32 = 63;

/// Most points of one Sobol sequence `sobol_burley` gives.
pub const MAX_SOBOL_POINTS: u32 = 1 << 16;

/// Low-discrepancy points for one pixel of the converged estimate.
#[derive(Debug, Clone, Copy)]
pub struct PixelPoints {
    seed: u64,
}

impl PixelPoints {
    pub fn new(seed: u64, pixel: u64) -> Self {
        PixelPoints {
            seed: mix(seed ^ mix(pixel)),
        }
    }

    fn scramble(&self, salt: u64) -> u32 {
        (mix(self.seed ^ salt) >> 32) as u32
    }

    /// Point `index` of the aperture's sequence.
    pub fn aperture(&self, index: u32) -> [f64; 2] {
        let p = sobol_burley::sample_4d(index, 0, self.scramble(0));
        [f64::from(p[0]), f64::from(p[1])]
    }

    /// Point `index` of the sequence of shadow ray offsets for stream `stream` (one per
    /// vertex and light).
    pub fn shadow(&self, stream: u32, index: u32) -> [f64; 3] {
        let set = 1 + stream % SETS;
        let salt = 1 + u64::from(stream / SETS);
        let p = sobol_burley::sample_4d(index, set, self.scramble(salt));
        [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct_per_pixel() {
        let a: Vec<f64> = {
            let mut s = CourseStream::new(7, 3);
            (0..4).map(|_| s.random()).collect()
        };
        let again: Vec<f64> = {
            let mut s = CourseStream::new(7, 3);
            (0..4).map(|_| s.random()).collect()
        };
        let other: Vec<f64> = {
            let mut s = CourseStream::new(7, 4);
            (0..4).map(|_| s.random()).collect()
        };
        assert_eq!(a, again);
        assert_ne!(a, other);
        assert!(a.iter().all(|&x| (0.0..1.0).contains(&x)));
    }

    #[test]
    fn sobol_points_are_stratified() {
        // The first 16 points of a (0, 2)-sequence put one point in each 4 x 4 cell.
        let points = PixelPoints::new(1, 2);
        let mut cells = [0; 16];
        for i in 0..16 {
            let [u, v] = points.aperture(i);
            cells[(u * 4.0) as usize * 4 + (v * 4.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
    }
}
