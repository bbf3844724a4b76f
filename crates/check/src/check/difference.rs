//! How a student's image differs from the reference, byte by byte: the numbers the verdict
//! and the text report rest on.

use crate::check::pass_rule::{PassRule, KEPT_TOLERANCES};
use crate::check::student_png::Rgb8;

/// The verdicts of docs/check.md.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Every byte equals the reference.
    Identical,
    /// No channel differs by more than the tolerance, but for at most the allowance's pixels
    /// (`pass_rule.rs`; none by default).
    WithinTolerance,
    /// More pixels than the allowance have a channel that differs by more.
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
    /// Per channel tolerance t from 0 to `KEPT_TOLERANCES - 1`, the pixels with a channel off
    /// by more than t: what the rule needs to be replayed at another tolerance without the
    /// images (`grade --calibrate`).
    pub beyond_at: [u64; KEPT_TOLERANCES],
    /// The rule the verdict was given by.
    pub rule: PassRule,
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

/// Compares `student` with `reference` (the same size) and gives the verdict by `rule`.
pub fn difference(student: &Rgb8, reference: &Rgb8, rule: PassRule) -> Difference {
    let width = student.width;
    let tolerance = rule.tolerance;
    let mut d = Difference {
        width,
        height: student.height,
        differing_pixels: 0,
        beyond_tolerance: 0,
        beyond_at: [0; KEPT_TOLERANCES],
        rule,
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
        for beyond in d.beyond_at.iter_mut().take(usize::from(diff)) {
            *beyond += 1;
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
    d.verdict = match (
        d.differing_pixels,
        rule.passes(d.beyond_tolerance as u64, d.pixels()),
    ) {
        (0, _) => Verdict::Identical,
        (_, true) => Verdict::WithinTolerance,
        (_, false) => Verdict::Differs,
    };
    d
}

impl Difference {
    /// The image's pixels.
    pub fn pixels(&self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }

    /// How a case passing with pixels beyond the tolerance passes ("5 pixels beyond ±2,
    /// allowed up to 10"); None when it fails or none is beyond.
    pub fn allowed_words(&self) -> Option<String> {
        match self.verdict {
            Verdict::WithinTolerance => self
                .rule
                .allowed_words(self.beyond_tolerance as u64, self.pixels()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::pass_rule::Allowance;

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
        let strict = PassRule::strict(2);
        assert_eq!(
            difference(&student, &reference, strict).verdict,
            Verdict::Identical
        );
        student.bytes[4] = 12; // pixel (1, 0), 2 LSB
        let d = difference(&student, &reference, strict);
        assert_eq!(
            (d.verdict, d.differing_pixels, d.beyond_tolerance),
            (Verdict::WithinTolerance, 1, 0)
        );
        assert_eq!(d.allowed_words(), None);
        student.bytes[9] = 0; // pixel (1, 1), 10 LSB
        let d = difference(&student, &reference, strict);
        assert_eq!(d.verdict, Verdict::Differs);
        assert_eq!(
            (d.max_difference, d.worst_pixel, d.bounds),
            (10, Some((1, 1)), Some((1, 0, 1, 1)))
        );
        assert_eq!(d.beyond_at, [2, 2, 1, 1, 1, 1, 1, 1, 1]);
    }

    #[test]
    fn the_allowance_passes_a_few_pixels_beyond_and_no_more() {
        let reference = image(vec![10; 12]);
        let mut student = reference.clone();
        student.bytes[0] = 20; // pixel (0, 0), 10 LSB
        student.bytes[5] = 15; // pixel (1, 0), 5 LSB
        let one = PassRule {
            tolerance: 2,
            allowance: Allowance::Pixels(1),
        };
        let two = PassRule {
            allowance: Allowance::Pixels(2),
            ..one
        };
        assert_eq!(
            difference(&student, &reference, one).verdict,
            Verdict::Differs
        );
        let d = difference(&student, &reference, two);
        assert_eq!(d.verdict, Verdict::WithinTolerance);
        assert_eq!(
            d.allowed_words().as_deref(),
            Some("2 pixels beyond ±2, allowed up to 2")
        );
        // Half the four pixels is two.
        let half = PassRule {
            allowance: Allowance::parse("50%").expect("50%"),
            ..one
        };
        assert_eq!(
            difference(&student, &reference, half).verdict,
            Verdict::WithinTolerance
        );
        // At a tolerance of 5 only one pixel is beyond: one is allowed.
        let five = PassRule {
            tolerance: 5,
            ..one
        };
        assert_eq!(
            difference(&student, &reference, five).verdict,
            Verdict::WithinTolerance
        );
    }
}
