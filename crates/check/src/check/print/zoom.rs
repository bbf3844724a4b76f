//! The worst region of a failing image, enlarged: a student cannot see a few pixels of acne
//! or a 3-of-255 edge in a whole 800x600 image scaled to a third of a page. The report pages
//! show the square where the differences add up most, cut from the student's image, the
//! reference and the difference alike, each pixel enlarged to a block (nearest neighbour:
//! every pixel stays a pixel, nothing is smoothed).

use crate::check::difference::pixel_difference;
use crate::check::student_png::Rgb8;

/// The zoom is shown about this wide, in page pixels.
const SHOWN: u32 = 256;

/// A square of an image, in its pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    pub x: u32,
    pub y: u32,
    pub size: u32,
}

impl Region {
    /// Its place and enlargement, in words: "x 10..25, y 40..55, each pixel shown 12x12".
    pub fn described(&self) -> String {
        format!(
            "x {}..{}, y {}..{}, each pixel shown {}x{}",
            self.x,
            self.x + self.size - 1,
            self.y,
            self.y + self.size - 1,
            self.scale(),
            self.scale()
        )
    }

    /// How many times each pixel is enlarged to be shown about `SHOWN` wide.
    pub fn scale(&self) -> u32 {
        (SHOWN / self.size.max(1)).max(1)
    }

    /// The square cut from `rgb` (`width` wide, three bytes a pixel), each pixel a block of
    /// `scale` x `scale`.
    pub fn enlarged(&self, rgb: &[u8], width: u32) -> Vec<u8> {
        let k = self.scale() as usize;
        let side = self.size as usize * k;
        let mut out = Vec::with_capacity(side * side * 3);
        for row in 0..side {
            let y = self.y as usize + row / k;
            for column in 0..side {
                let x = self.x as usize + column / k;
                let i = 3 * (y * width as usize + x);
                out.extend_from_slice(&rgb[i..i + 3]);
            }
        }
        out
    }

    /// The side of the enlarged square, in pixels.
    pub fn shown_side(&self) -> u32 {
        self.size * self.scale()
    }
}

/// The side of the square looked at: an eighth of the image's smaller side, from 8 to 64
/// pixels (never more than the image).
fn side(width: u32, height: u32) -> u32 {
    (width.min(height) / 8).clamp(8, 64).min(width.min(height))
}

/// The square where the student's image differs from the reference most (the sum of every
/// pixel's largest channel difference), the first in reading order among equals; None when
/// the images are equal.
pub fn worst_region(student: &Rgb8, reference: &Rgb8) -> Option<Region> {
    let (w, h) = (student.width as usize, student.height as usize);
    if w == 0 || h == 0 || student.bytes.len() != reference.bytes.len() {
        return None;
    }
    let s = side(student.width, student.height) as usize;
    // A summed-area table of the differences: any square's sum in four look-ups.
    let mut table = vec![0u64; (w + 1) * (h + 1)];
    for y in 0..h {
        let mut row = 0u64;
        for x in 0..w {
            row += u64::from(pixel_difference(
                &student.bytes,
                &reference.bytes,
                y * w + x,
            ));
            table[(y + 1) * (w + 1) + x + 1] = table[y * (w + 1) + x + 1] + row;
        }
    }
    let sum = |x: usize, y: usize| {
        let at = |x: usize, y: usize| table[y * (w + 1) + x];
        at(x + s, y + s) + at(x, y) - at(x + s, y) - at(x, y + s)
    };
    let mut best = (0u64, 0, 0);
    for y in 0..=h - s {
        for x in 0..=w - s {
            let total = sum(x, y);
            if total > best.0 {
                best = (total, x, y);
            }
        }
    }
    (best.0 > 0).then_some(Region {
        x: best.1 as u32,
        y: best.2 as u32,
        size: s as u32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(width: u32, height: u32) -> Rgb8 {
        Rgb8 {
            width,
            height,
            bytes: vec![100; (width * height * 3) as usize],
        }
    }

    #[test]
    fn the_zoom_finds_the_cluster_not_the_lone_worst_pixel() {
        let reference = grey(200, 160);
        let mut student = reference.clone();
        let mut set = |x: u32, y: u32, v: u8| {
            let i = 3 * (y * 200 + x) as usize;
            student.bytes[i] = v;
        };
        // One pixel far off, and a cluster of many a little off.
        set(5, 5, 255);
        for y in 120..140 {
            for x in 150..170 {
                set(x, y, 110);
            }
        }
        let region = worst_region(&student, &reference).expect("a region");
        assert_eq!(region.size, 20);
        assert_eq!((region.x, region.y), (150, 120));
        assert_eq!(worst_region(&reference, &reference), None);
    }

    #[test]
    fn each_pixel_becomes_a_block() {
        let mut image = grey(16, 16);
        image.bytes[3 * (9 * 16 + 8)] = 7;
        let region = Region {
            x: 8,
            y: 8,
            size: 8,
        };
        assert_eq!(region.scale(), 32);
        let zoom = region.enlarged(&image.bytes, 16);
        assert_eq!(zoom.len(), 256 * 256 * 3);
        // Source pixel (8, 9) is the block of rows 32..64, columns 0..32.
        for (x, y, v) in [(0, 32, 7), (31, 63, 7), (32, 32, 100), (0, 31, 100)] {
            assert_eq!(zoom[3 * (y * 256 + x)], v, "({x}, {y})");
        }
    }
}
