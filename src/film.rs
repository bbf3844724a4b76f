//! The film: where samples are accumulated into pixels.

use glam::DVec3;

/// The rendered image. The beauty is kept in f64 because the tick PNG quantises the exact
/// value the course computes; rounding it to f32 first could move a pixel across a byte.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Row-major, y = 0 the top row.
    pub beauty: Vec<DVec3>,
    /// Rays cast while rendering it (primary, shadow, reflected).
    pub rays: u64,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        Film {
            width,
            height,
            beauty: vec![DVec3::ZERO; width as usize * height as usize],
            rays: 0,
        }
    }

    pub fn pixel(&self, x: u32, y: u32) -> DVec3 {
        self.beauty[y as usize * self.width as usize + x as usize]
    }
}
