//! Images no program renders twice alike (docs/courses.md, "Tick 1*"): soft shadows from ten
//! random shadow rays and depth of field from fifty random camera rays use `Math.random`, so a
//! student's Tick 1* image differs from any reference by noise. Diagnosing noise as mistakes
//! would name whatever happens to fit the speckle; instead the check says the image is not
//! reproducible and compares it with a tolerance meant for noise: blurred, both images must
//! agree.
//!
//! How noise is told from a mistake: a mistake changes pixels coherently (a highlight moves,
//! a shadow goes, acne darkens pixels), so a changed pixel's neighbours changed the same way or
//! not at all; noise scatters both ways, so many changed pixels have a neighbour changed the
//! other way.

use crate::check::student_png::Rgb8;

/// At least this many pixels must differ for a pattern to be called noise.
const MIN_PIXELS: usize = 500;

/// The share of differing pixels with a neighbour that differs the other way, above which
/// the difference is noise. Mistakes of the catalogue stay below 0.1 on the suites (pixels
/// along a moved edge); random sampling is above 0.4.
const OPPOSED: f64 = 0.3;

/// The share of rough differing pixels above which the difference is noise.
const ROUGH: f64 = 0.35;

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

/// How an image was found not reproducible.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Seen {
    /// The program, run twice on one case, wrote two different images.
    TwoRuns,
    /// The difference scatters as random sampling's does (one image, no program to rerun):
    /// the share of differing pixels with a neighbour differing the other way, in thousandths.
    Scattered { opposed_permille: u32 },
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
            Seen::TwoRuns => "run twice on one case, the program wrote two different images".into(),
            Seen::Scattered { opposed_permille } => format!(
                "{:.0}% of the differing pixels have a neighbour that differs the other way",
                f64::from(opposed_permille) / 10.0
            ),
        };
        format!(
            "not reproducible: the image is noisy as Tick 1*'s random sampling makes it (soft \
             shadows, depth of field: {seen}), so no program renders it pixel for pixel and no \
             mistake is diagnosed; compared blurred, it is {verdict}"
        )
    }
}

/// The signed difference of pixel `i`, summed over its channels.
fn signed(student: &Rgb8, reference: &Rgb8, i: usize) -> i32 {
    (0..3)
        .map(|c| i32::from(student.bytes[3 * i + c]) - i32::from(reference.bytes[3 * i + c]))
        .sum()
}

/// Whether `student` differs from `reference` (the same size) as random sampling makes it,
/// and if so how it compares blurred.
pub fn noise(student: &Rgb8, reference: &Rgb8) -> Option<Noise> {
    let (w, h) = (student.width as usize, student.height as usize);
    if student.bytes.len() != 3 * w * h || reference.bytes.len() != student.bytes.len() {
        return None;
    }
    let d: Vec<i32> = (0..w * h).map(|i| signed(student, reference, i)).collect();
    let mut differing = 0usize;
    let mut opposed = 0usize;
    for y in 0..h {
        for x in 0..w {
            let s = d[y * w + x];
            if s == 0 {
                continue;
            }
            differing += 1;
            let neighbours = [
                (x > 0).then(|| d[y * w + x - 1]),
                (x + 1 < w).then(|| d[y * w + x + 1]),
                (y > 0).then(|| d[(y - 1) * w + x]),
                (y + 1 < h).then(|| d[(y + 1) * w + x]),
            ];
            if neighbours
                .into_iter()
                .flatten()
                .any(|t| t.signum() == -s.signum())
            {
                opposed += 1;
            }
        }
    }
    let share = opposed as f64 / differing.max(1) as f64;
    let rough = roughness(&d, w, h);
    let scattered = share >= OPPOSED || (rough >= ROUGH && share >= OPPOSED / 3.0);
    if differing < MIN_PIXELS || !scattered {
        return None;
    }
    let opposed_permille = (share * 1000.0).round() as u32;
    Some(compared(
        Seen::Scattered { opposed_permille },
        student,
        reference,
    ))
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

/// Of the differing pixels whose four neighbours differ too, the share whose difference is
/// far from its neighbours' mean (by more than half its own size): a mistake's differences
/// vary smoothly across a surface, random sampling's jump from pixel to pixel.
fn roughness(d: &[i32], w: usize, h: usize) -> f64 {
    let (mut inner, mut rough) = (0usize, 0usize);
    for y in 1..h.saturating_sub(1) {
        for x in 1..w.saturating_sub(1) {
            let s = d[y * w + x];
            let nb = [
                d[y * w + x - 1],
                d[y * w + x + 1],
                d[(y - 1) * w + x],
                d[(y + 1) * w + x],
            ];
            if s == 0 || nb.contains(&0) {
                continue;
            }
            inner += 1;
            let mean = f64::from(nb.iter().sum::<i32>()) / 4.0;
            if (f64::from(s) - mean).abs() > 0.5 * f64::from(s.abs()).max(4.0) {
                rough += 1;
            }
        }
    }
    rough as f64 / inner.max(1) as f64
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
    fn speckle_both_ways_is_noise_and_a_coherent_change_is_not() {
        let reference = flat(64, 64, 100);
        let mut noisy = reference.clone();
        // A deterministic scramble: +-12 on a third of the pixels.
        let mut state = 12345u32;
        for px in noisy.bytes.chunks_exact_mut(3) {
            state = state.wrapping_mul(1_103_515_245).wrapping_add(12345);
            match (state >> 16) % 3 {
                0 => px.iter_mut().for_each(|b| *b += 12),
                1 => px.iter_mut().for_each(|b| *b -= 12),
                _ => {}
            }
        }
        let n = noise(&noisy, &reference).expect("noise");
        assert!(n.within_tolerance(), "{n:?}");
        assert!(n.sentence().contains("not reproducible"));
        let mut darker = reference.clone();
        for b in &mut darker.bytes[..3 * 64 * 20] {
            *b -= 30;
        }
        assert_eq!(noise(&darker, &reference), None);
        // Noise over an image that is also too dark: more than noise.
        for b in &mut noisy.bytes[..3 * 64 * 20] {
            *b -= 30;
        }
        let n = noise(&noisy, &reference).expect("noise");
        assert!(!n.within_tolerance());
    }
}
