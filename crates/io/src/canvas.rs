//! An 8-bit RGB picture to compose contact sheets and figure strips on, with text from the
//! embedded public-domain 8x8 bitmap font of the `font8x8` crate.

use font8x8::{UnicodeFonts, BASIC_FONTS};

use crate::output::png::{PngImage, PngPixels};

/// Height of one line of text at scale 1, in pixels.
pub const LINE_HEIGHT: usize = 10;

/// Width of one character at scale 1.
pub const CHAR_WIDTH: usize = 8;

#[derive(Debug, Clone, PartialEq)]
pub struct Canvas {
    pub width: usize,
    pub height: usize,
    /// Row-major RGB.
    pub pixels: Vec<[u8; 3]>,
}

impl Canvas {
    pub fn new(width: usize, height: usize, background: [u8; 3]) -> Self {
        Canvas {
            width,
            height,
            pixels: vec![background; width * height],
        }
    }

    /// Copies `tile` with its top-left corner at (x, y), clipped to the canvas.
    pub fn blit(&mut self, x: usize, y: usize, tile: &Canvas) {
        for ty in 0..tile.height.min(self.height.saturating_sub(y)) {
            let row = (y + ty) * self.width;
            for tx in 0..tile.width.min(self.width.saturating_sub(x)) {
                self.pixels[row + x + tx] = tile.pixels[ty * tile.width + tx];
            }
        }
    }

    /// Draws `text` with its top-left corner at (x, y); characters the font lacks show as `?`,
    /// and text past the right edge is cut off.
    pub fn text(&mut self, x: usize, y: usize, text: &str, colour: [u8; 3]) {
        for (i, c) in text.chars().enumerate() {
            let glyph = BASIC_FONTS
                .get(c)
                .or_else(|| BASIC_FONTS.get('?'))
                .unwrap_or([0; 8]);
            let left = x + i * CHAR_WIDTH;
            for (gy, bits) in glyph.iter().enumerate() {
                for gx in 0..8 {
                    let (px, py) = (left + gx, y + gy);
                    if bits >> gx & 1 == 1 && px < self.width && py < self.height {
                        self.pixels[py * self.width + px] = colour;
                    }
                }
            }
        }
    }

    /// As a display-encoded 8-bit PNG.
    pub fn into_png(self) -> PngImage {
        PngImage {
            width: u32::try_from(self.width).unwrap_or(u32::MAX),
            height: u32::try_from(self.height).unwrap_or(u32::MAX),
            pixels: PngPixels::Eight(self.pixels.into_iter().flatten().collect()),
            srgb: true,
        }
    }
}

/// `text` shortened with `~` to fit `width` pixels.
pub fn fit(text: &str, width: usize) -> String {
    let max = width / CHAR_WIDTH;
    if text.chars().count() <= max {
        text.to_string()
    } else {
        let mut short: String = text.chars().take(max.saturating_sub(1)).collect();
        short.push('~');
        short
    }
}

/// `text` broken into lines that fit `width` pixels: at spaces where it can be, inside a word
/// only where one word alone is wider. Nothing is cut.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let max = (width / CHAR_WIDTH).max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let mut word: Vec<char> = word.chars().collect();
        let used = line.chars().count();
        if used > 0 && used + 1 + word.len() > max {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        while line.chars().count() + word.len() > max {
            let room = max - line.chars().count();
            line.extend(word.drain(..room));
            lines.push(std::mem::take(&mut line));
        }
        line.extend(word);
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapping_keeps_every_character_and_fits_the_width() {
        let text = "look at the exponent n in Renderer.illuminate's Math.pow(Math.max(0, R.dot(V)), n): object.getPhong_n()";
        let width = 20 * CHAR_WIDTH;
        let lines = wrap(text, width);
        assert!(lines.len() > 1);
        assert!(lines.iter().all(|l| l.chars().count() <= 20), "{lines:?}");
        assert_eq!(lines.join(" ").replace(' ', ""), text.replace(' ', ""));
        assert_eq!(wrap("", width), vec![String::new()]);
        assert_eq!(wrap(&"x".repeat(45), width).len(), 3);
    }

    #[test]
    fn text_sets_pixels_inside_its_box_only() {
        let mut c = Canvas::new(40, 12, [0; 3]);
        c.text(2, 2, "Hi", [255; 3]);
        let lit: Vec<(usize, usize)> = (0..c.pixels.len())
            .filter(|&i| c.pixels[i] == [255; 3])
            .map(|i| (i % 40, i / 40))
            .collect();
        assert!(!lit.is_empty());
        assert!(lit
            .iter()
            .all(|&(x, y)| (2..18).contains(&x) && (2..10).contains(&y)));
    }

    #[test]
    fn blit_clips_and_fit_shortens() {
        let mut c = Canvas::new(4, 4, [0; 3]);
        c.blit(2, 2, &Canvas::new(5, 5, [9; 3]));
        assert_eq!(c.pixels.iter().filter(|p| **p == [9; 3]).count(), 4);
        assert_eq!(fit("abcdef", 32), "abc~");
        assert_eq!(fit("abc", 32), "abc");
    }
}
