//! The pixels of a case that every candidate is scored on first: what `case.rs` draws and
//! `renderer.rs` renders, in a file of its own so that neither depends on the other.

use whitted_core::hits::tape::Tape;

/// The pixels of one case that every candidate renders first: up to a share of `SAMPLE` of
/// those the student got wrong, then as many of those they got right, each standing for its
/// share of the image.
#[derive(Debug, Clone)]
pub struct PixelSample {
    pub positions: Vec<(u32, u32)>,
    /// The first `wrong` positions are pixels the student got wrong.
    pub wrong: usize,
    /// How many image pixels one sampled wrong pixel stands for.
    pub wrong_weight: f64,
    /// How many image pixels one sampled right pixel stands for.
    pub right_weight: f64,
    /// The student's and the reference's bytes at `positions`, three a pixel.
    pub student: Vec<u8>,
    pub reference: Vec<u8>,
    /// The case's lattice, the same for every image of its size in a run of as many cases.
    pub lattice: Vec<(u32, u32)>,
    /// Where in `lattice` each sampled right pixel (`positions[wrong..]`) is.
    pub right_in_lattice: Vec<usize>,
    /// The hit searches of the course's trace of each of `positions`, which the candidates
    /// that intersect as the course does share (`Renderer::searches_at`).
    pub searches: Vec<Tape>,
    /// The same at each of `lattice`'s pixels where the renderer keeps lattices
    /// (`Renderer::keeps_lattices`), else empty.
    pub lattice_searches: Vec<Tape>,
}

impl PixelSample {
    /// The weight of sampled pixel `j` and whether the student got it wrong.
    pub fn kind(&self, j: usize) -> (f64, bool) {
        if j < self.wrong {
            (self.wrong_weight, true)
        } else {
            (self.right_weight, false)
        }
    }
}
