//! The pre-pass of the Tick 1* statistic. Judging one random image can take many converged
//! expectations: option 2's course process and its variants, and a bump image's smooth and
//! bumped scenes under every parametrisation and mistake. Each costs a minute or more at the
//! course's 800x600, the first time. Most of them are far from the image, and a far process
//! shows as plainly on a sparse grid of pixels as on all of them. So each process is scored on
//! a grid of about [`PIXELS`] pixels first (its expectation at 1/stride^2 of the cost, each
//! pixel's value exactly the whole expectation's: `whitted_core::star::expectation_on`); of
//! the processes that could be the verdict together (the variants of option 2, the
//! parametrisations, the mistakes), only the best is scored on every pixel, and only when its
//! grid score is within [`PRUNE`], where a verdict could turn on it.
//!
//! Why it cannot change a verdict: a draw of the process scores about 1 (mean z^2) whatever
//! pixels are taken, and the grid's mean over thousands of random channels spreads by a few
//! hundredths; [`PRUNE`] is twice the threshold, so a process the image is a draw of is never
//! pruned. A pruned process's statistic (its `Fit::stride` above 1) is the grid's estimate.

use crate::check::star_draw::{score_star, Pass, Score, THRESHOLD};
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene::Scene;
use whitted_core::star::{Grid, NoiseFloor, Star};

/// About how many pixels the pre-pass scores.
const PIXELS: u32 = 5_000;

/// The grid's mean z^2 above which a process is not scored in full: twice the threshold.
pub const PRUNE: f64 = 2.0 * THRESHOLD;

/// The pre-pass's floor: twice the full pass's standard error (a quarter of its rays), and at
/// most 512 camera rays a pixel. Its larger error widens each pixel's spread in the statistic, which lowers
/// the score: a coarse pre-pass prunes less, never more. Bump-mapped spheres seen through the
/// aperture are what it saves most on: their pixels take thousands of rays to the full floor.
const FLOOR: NoiseFloor = NoiseFloor {
    standard_error: 0.008,
    max_paths: 512,
};

/// The pre-pass's grid for an image of `width` x `height`: the widest stride that leaves
/// about [`PIXELS`] pixels (every pixel, for images that small).
pub fn grid(width: u32, height: u32) -> Grid {
    let pixels = f64::from(width) * f64::from(height);
    let stride = (pixels / f64::from(PIXELS)).sqrt().floor().max(1.0) as u32;
    // No wider than the narrower side: a grid keeps a pixel of every row and column it spans.
    Grid {
        stride: stride.min(width.min(height)).max(1),
    }
}

/// `image` scored against the distribution of each of `processes` on `scene` (a star, and the
/// factor its expectation is scaled by), in order: each on the pre-pass's grid, and the one
/// that fits best, when within [`PRUNE`], on every pixel. Only the best can be the verdict:
/// the others' grid scores say how far they are.
pub(crate) fn scores(
    scene: &Scene,
    processes: &[(Star, f64)],
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Vec<Score>> {
    let sparse = grid(image.width, image.height);
    let (full, pre) = (
        Pass::full(),
        Pass {
            grid: sparse,
            floor: FLOOR,
        },
    );
    let first = match sparse == Grid::EVERY {
        true => full,
        false => pre,
    };
    let mut scores = processes
        .iter()
        .map(|(star, scale)| score_star(scene, star, (*scale, first), image, bounces, course))
        .collect::<Result<Vec<Score>>>()?;
    let best = scores
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| a.mean().total_cmp(&b.mean()))
        .map(|(i, s)| (i, s.mean()));
    if let Some((i, _)) = best.filter(|&(_, mean)| sparse != Grid::EVERY && mean <= PRUNE) {
        let (star, scale) = &processes[i];
        scores[i] = score_star(scene, star, (*scale, full), image, bounces, course)?;
    }
    Ok(scores)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_leaves_about_five_thousand_pixels() {
        assert_eq!(grid(160, 120), Grid::EVERY);
        assert_eq!(grid(40, 30), Grid::EVERY);
        // A strip keeps a pixel across.
        assert_eq!(grid(100_000, 1), Grid::EVERY);
        assert_eq!(grid(100_000, 3).count(3), 1);
        for (w, h, stride) in [(640, 480, 7), (800, 600, 9), (1920, 1080, 20)] {
            let g = grid(w, h);
            assert_eq!(g.stride, stride, "{w}x{h}");
            let n = g.count(w) * g.count(h);
            assert!((4_000..=7_000).contains(&n), "{w}x{h}: {n}");
        }
    }
}
