//! Images no program renders twice alike (docs/courses.md, "Tick 1*"): soft shadows from ten
//! random shadow rays and depth of field from fifty random camera rays use `Math.random`, so a
//! student's Tick 1* image differs from any reference by noise. Diagnosing noise as mistakes
//! would name whatever happens to fit the speckle; instead the check says the image is not
//! reproducible and compares it with a tolerance meant for noise: blurred, both images must
//! agree.
//!
//! How noise is told from a mistake: the program, run twice on one failing case, writes two
//! different images (`--program` mode). One image alone cannot tell it: the scatter of a
//! reflected ray's self-hits (`no-reflection-bias`) looks like random sampling's, and a
//! mistake called noise would never be named, so image mode does not guess.

use crate::check::student_png::Rgb8;

/// Half the side of the box both images are blurred with for the noise tolerance.
const RADIUS: usize = 4;

/// The largest difference of a blurred channel, in LSB, that noise is allowed.
pub const NOISE_TOLERANCE: u8 = 6;

/// What the comparison meant for noise found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Noise {
    /// How the noise was found.
    pub seen: Seen,
    /// The largest difference of a channel after both images are box-blurred, in LSB.
    pub blurred_max: u8,
}

/// How an image was found not reproducible (a closed set: more ways may come).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Seen {
    /// The program, run twice on one case, wrote two different images.
    TwoRuns,
}

impl Noise {
    /// Whether the blurred images agree within the noise tolerance.
    pub fn within_tolerance(&self) -> bool {
        self.blurred_max <= NOISE_TOLERANCE
    }

    /// The report's line.
    pub fn sentence(&self) -> String {
        let verdict = if self.within_tolerance() {
            "within the tolerance meant for noise: only noise differs".to_string()
        } else {
            format!(
                "more than noise: blurred over {side}x{side} pixels, the images still differ by \
                 up to {} of 255 (noise is allowed {NOISE_TOLERANCE})",
                self.blurred_max,
                side = 2 * RADIUS + 1
            )
        };
        let seen = match self.seen {
            Seen::TwoRuns => "run twice on one case, the program wrote two different images",
        };
        format!(
            "not reproducible: the image is noisy as Tick 1*'s random sampling makes it (soft \
             shadows, depth of field: {seen}), so no program renders it pixel for pixel and no \
             mistake is diagnosed; compared blurred, it is {verdict}"
        )
    }
}

/// `student` against `reference` (the same size) blurred, for an image known to be noisy.
pub fn compared(seen: Seen, student: &Rgb8, reference: &Rgb8) -> Noise {
    let (a, b) = (blurred(student), blurred(reference));
    let blurred_max = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs().round().min(255.0) as u8)
        .max()
        .unwrap_or(0);
    Noise { seen, blurred_max }
}

/// Each channel averaged over the box of side `2 RADIUS + 1` around each pixel (clipped at the
/// edges): two separable passes.
fn blurred(image: &Rgb8) -> Vec<f64> {
    let (w, h) = (image.width as usize, image.height as usize);
    let pass = |src: &[f64], along_x: bool| -> Vec<f64> {
        let mut out = vec![0.0; src.len()];
        for y in 0..h {
            for x in 0..w {
                let (i, n) = if along_x { (x, w) } else { (y, h) };
                let (lo, hi) = (i.saturating_sub(RADIUS), (i + RADIUS).min(n - 1));
                for c in 0..3 {
                    let mut sum = 0.0;
                    for j in lo..=hi {
                        let (px, py) = if along_x { (j, y) } else { (x, j) };
                        sum += src[3 * (py * w + px) + c];
                    }
                    out[3 * (y * w + x) + c] = sum / (hi - lo + 1) as f64;
                }
            }
        }
        out
    };
    let bytes: Vec<f64> = image.bytes.iter().map(|&b| f64::from(b)).collect();
    pass(&pass(&bytes, true), false)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(width: u32, height: u32, value: u8) -> Rgb8 {
        Rgb8 {
            width,
            height,
            bytes: vec![value; (3 * width * height) as usize],
        }
    }

    #[test]
    fn blurred_noise_is_within_the_tolerance_and_a_darker_region_is_not() {
        let reference = flat(64, 64, 100);
        let mut noisy = reference.clone();
        // A deterministic scramble: +-12 on a third of the pixels each.
        let mut state = 12345u32;
        for px in noisy.bytes.chunks_exact_mut(3) {
            state = state.wrapping_mul(1_103_515_245).wrapping_add(12345);
            match (state >> 16) % 3 {
                0 => px.iter_mut().for_each(|b| *b += 12),
                1 => px.iter_mut().for_each(|b| *b -= 12),
                _ => {}
            }
        }
        let n = compared(Seen::TwoRuns, &noisy, &reference);
        assert!(n.within_tolerance(), "{n:?}");
        assert!(n.sentence().contains("not reproducible"));
        for b in &mut noisy.bytes[..3 * 64 * 20] {
            *b -= 30;
        }
        let n = compared(Seen::TwoRuns, &noisy, &reference);
        assert!(!n.within_tolerance());
        assert!(n.sentence().contains("more than noise"));
    }
}
