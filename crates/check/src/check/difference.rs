//! How a student's image differs from the reference, byte by byte: the numbers the verdict
//! and the text report rest on.

use crate::check::student_png::Rgb8;

/// The verdicts of docs/check.md.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Every byte equals the reference.
    Identical,
    /// No channel differs by more than the tolerance.
    WithinTolerance,
    /// Some channel differs by more.
    Differs,
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Identical => "identical",
            Verdict::WithinTolerance => "within-tolerance",
            Verdict::Differs => "differs",
        }
    }

    pub fn passes(self) -> bool {
        self != Verdict::Differs
    }
}

/// Where and by how much two images of one size differ.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Difference {
    pub width: u32,
    pub height: u32,
    /// Pixels with any channel different.
    pub differing_pixels: usize,
    /// Pixels with a channel off by more than the tolerance.
    pub beyond_tolerance: usize,
    /// The largest difference of one channel, in LSB.
    pub max_difference: u8,
    /// The first pixel (in scan order) with the largest difference.
    pub worst_pixel: Option<(u32, u32)>,
    /// The differing pixels' bounding box, corners inclusive: (x0, y0, x1, y1).
    pub bounds: Option<(u32, u32, u32, u32)>,
    pub verdict: Verdict,
}

/// The largest channel difference of pixel `i` (three bytes a pixel).
pub fn pixel_difference(a: &[u8], b: &[u8], i: usize) -> u8 {
    (0..3)
        .map(|c| a[3 * i + c].abs_diff(b[3 * i + c]))
        .max()
        .unwrap_or(0)
}

/// Compares `student` with `reference` (the same size) at `tolerance` LSB.
pub fn difference(student: &Rgb8, reference: &Rgb8, tolerance: u8) -> Difference {
    let width = student.width;
    let mut d = Difference {
        width,
        height: student.height,
        differing_pixels: 0,
        beyond_tolerance: 0,
        max_difference: 0,
        worst_pixel: None,
        bounds: None,
        verdict: Verdict::Identical,
    };
    for i in 0..student.bytes.len() / 3 {
        let diff = pixel_difference(&student.bytes, &reference.bytes, i);
        if diff == 0 {
            continue;
        }
        let (x, y) = ((i % width as usize) as u32, (i / width as usize) as u32);
        d.differing_pixels += 1;
        if diff > tolerance {
            d.beyond_tolerance += 1;
        }
        if diff > d.max_difference {
            d.max_difference = diff;
            d.worst_pixel = Some((x, y));
        }
        d.bounds = Some(match d.bounds {
            None => (x, y, x, y),
            Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(x), y1.max(y)),
        });
    }
    d.verdict = match (d.differing_pixels, d.max_difference <= tolerance) {
        (0, _) => Verdict::Identical,
        (_, true) => Verdict::WithinTolerance,
        (_, false) => Verdict::Differs,
    };
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(bytes: Vec<u8>) -> Rgb8 {
        Rgb8 {
            width: 2,
            height: 2,
            bytes,
        }
    }

    #[test]
    fn counts_where_and_by_how_much() {
        let reference = image(vec![10; 12]);
        let mut student = reference.clone();
        assert_eq!(
            difference(&student, &reference, 2).verdict,
            Verdict::Identical
        );
        student.bytes[4] = 12; // pixel (1, 0), 2 LSB
        let d = difference(&student, &reference, 2);
        assert_eq!(
            (d.verdict, d.differing_pixels, d.beyond_tolerance),
            (Verdict::WithinTolerance, 1, 0)
        );
        student.bytes[9] = 0; // pixel (1, 1), 10 LSB
        let d = difference(&student, &reference, 2);
        assert_eq!(d.verdict, Verdict::Differs);
        assert_eq!(
            (d.max_difference, d.worst_pixel, d.bounds),
            (10, Some((1, 1)), Some((1, 0, 1, 1)))
        );
    }
}
