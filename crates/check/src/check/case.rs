//! One student image of one scene, prepared for the diagnosis: its reference, the pixels it
//! gets wrong (computed once), and the sample of pixels every candidate is first scored on.

use crate::check::difference::pixel_difference;
pub use crate::check::pixel_sample::PixelSample;
use crate::check::renderer::Renderer;
use crate::check::student_png::Rgb8;
use whitted_core::error::Result;

/// Pixels of each kind (wrong, right) the first stage looks at, over all cases together.
pub const SAMPLE: usize = 2000;

/// Each case looks at no fewer pixels of a kind than this, however many cases there are.
const MIN_PER_CASE: usize = 300;

/// The right pixels sampled are drawn from a lattice this many times denser than the sample,
/// the same for every student of a case: a candidate's bytes on it are rendered once per
/// class (`Renderer::lattice_bytes`), and each student picks the lattice's pixels they got
/// right.
const LATTICE_DENSITY: usize = 4;

/// One student image of one scene.
pub struct Case<'a> {
    pub renderer: Renderer<'a>,
    pub student: Rgb8,
    pub reference: Rgb8,
    /// The indices of the pixels that differ from the reference at all.
    pub wrong: Vec<usize>,
    pub sample: PixelSample,
}

/// Pixel `i` of an image `width` wide, as `(x, y)`.
pub fn position(width: u32, i: usize) -> (u32, u32) {
    let width = width as usize;
    ((i % width) as u32, (i / width) as u32)
}

/// At most `n` of `items`, evenly spread.
pub fn spread<T: Copy>(items: &[T], n: usize) -> Vec<T> {
    let step = items.len().div_ceil(n.max(1)).max(1);
    items.iter().step_by(step).copied().collect()
}

impl<'a> Case<'a> {
    /// Prepares `student`'s image of `renderer`'s scene as one of `cases` cases.
    pub fn new(renderer: Renderer<'a>, student: Rgb8, cases: usize) -> Result<Case<'a>> {
        let reference = renderer.reference()?;
        let pixels = student.bytes.len() / 3;
        let (wrong, right): (Vec<usize>, Vec<usize>) =
            (0..pixels).partition(|&i| pixel_difference(&student.bytes, &reference.bytes, i) > 0);
        let per_kind = (SAMPLE / cases.max(1)).max(MIN_PER_CASE);
        let step = pixels.div_ceil(per_kind * LATTICE_DENSITY).max(1);
        let lattice: Vec<usize> = (0..pixels).step_by(step).collect();
        let right_on_lattice: Vec<usize> = (0..lattice.len())
            .filter(|&k| pixel_difference(&student.bytes, &reference.bytes, lattice[k]) == 0)
            .collect();
        let right_in_lattice = spread(&right_on_lattice, per_kind);
        let right_sample: Vec<usize> = right_in_lattice.iter().map(|&k| lattice[k]).collect();
        let wrong_sample = spread(&wrong, per_kind);
        let looked: Vec<usize> = wrong_sample.iter().chain(&right_sample).copied().collect();
        let pick = |image: &Rgb8| -> Vec<u8> {
            looked
                .iter()
                .flat_map(|&i| image.bytes[3 * i..3 * i + 3].iter().copied())
                .collect()
        };
        let positions: Vec<(u32, u32)> =
            looked.iter().map(|&i| position(student.width, i)).collect();
        let lattice: Vec<(u32, u32)> = lattice
            .iter()
            .map(|&i| position(student.width, i))
            .collect();
        let lattice_searches = match renderer.keeps_lattices() {
            true => renderer.searches_at(&lattice)?,
            false => Vec::new(),
        };
        let sample = PixelSample {
            searches: renderer.searches_at(&positions)?,
            positions,
            wrong: wrong_sample.len(),
            wrong_weight: wrong.len() as f64 / wrong_sample.len().max(1) as f64,
            right_weight: right.len() as f64 / right_sample.len().max(1) as f64,
            student: pick(&student),
            reference: pick(&reference),
            lattice,
            lattice_searches,
            right_in_lattice,
        };
        Ok(Case {
            renderer,
            student,
            reference,
            wrong,
            sample,
        })
    }

    /// Whether the student's image equals the reference byte for byte.
    pub fn identical(&self) -> bool {
        self.wrong.is_empty()
    }
}
