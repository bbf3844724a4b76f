//! Camera rays -> `trace` -> film. Work is split into bands of 16x16 tiles rendered in
//! parallel; every pixel depends only on its own rays and is written by exactly one task, so
//! the image is the same for any number of threads and no lock is taken while tracing.

use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::accel::Accelerator;
use crate::error::Result;
use crate::film::{Film, PixelAccumulator};
use crate::frame::{Acceleration, Frame};
use crate::interrupt;
use crate::sample::Sample;
use crate::scene::Scene;
use crate::trace::trace_into;

/// Side of a tile in pixels: small enough to balance two or many cores, large enough that
/// neighbouring rays reuse the same hierarchy nodes from cache.
const TILE: usize = 16;

/// How a render went: what the summary line and the warnings report. Not part of the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RenderStats {
    /// Rays cast (primary, shadow, reflected).
    pub rays: u64,
    /// Channel values that were NaN or infinite and were stored as 0.
    pub non_finite: u64,
    /// Time spent building the acceleration hierarchy before tracing.
    pub hierarchy_time: Duration,
}

/// The sub-pixel positions of a k*k grid: cell centres, row by row, and the index of the one
/// nearest the pixel centre (the first of them when k is even).
fn sample_grid(spp: u32) -> (Vec<(f64, f64)>, usize) {
    let k = spp.isqrt().max(1);
    let cell = |i: u32| (f64::from(i) + 0.5) / f64::from(k);
    let grid: Vec<(f64, f64)> = (0..k)
        .flat_map(|j| (0..k).map(move |i| (cell(i), cell(j))))
        .collect();
    let distance = |&(u, v): &(f64, f64)| (u - 0.5).powi(2) + (v - 0.5).powi(2);
    let centre = (0..grid.len())
        .min_by(|&a, &b| distance(&grid[a]).total_cmp(&distance(&grid[b])))
        .unwrap_or(0);
    (grid, centre)
}

/// Renders `scene` as `frame` says: the frame's region of its camera's image, into a film
/// holding the frame's layers. `rows_done` is told how many rows have finished (from any thread), for
/// progress. Stops early with `Error::Interrupted` when the user presses Ctrl-C.
pub fn render(
    scene: &Scene,
    frame: &Frame,
    rows_done: &(dyn Fn(u64) + Sync),
) -> Result<(Film, RenderStats)> {
    let (camera, region, trace) = (&frame.camera, frame.region, frame.trace);
    let started = Instant::now();
    let accel = match frame.acceleration {
        Acceleration::Bvh => Accelerator::build(&scene.objects),
        Acceleration::BruteForce => Accelerator::brute_force(&scene.objects),
    };
    let hierarchy_time = started.elapsed();
    let mut film = Film::new(region.width(), region.height(), frame.layers.clone())?;
    film.origin = (region.x0, region.y0);
    film.display = (camera.width, camera.height);
    let (grid, centre) = sample_grid(frame.spp);
    let width = region.width() as usize;
    let channels = film.channel_count();
    let layers = &film.layers;
    let (rays, non_finite) = film
        .beauty
        .par_chunks_mut(width * TILE)
        .zip(film.data.par_chunks_mut(width * TILE * channels))
        .enumerate()
        .map(|(band, (beauty, data))| {
            if interrupt::requested() {
                return (0, 0);
            }
            let rows = beauty.len() / width;
            let mut accumulator = PixelAccumulator::new(layers, channels);
            let mut sample = Sample::empty(scene.lights.len(), trace.bounces);
            let (mut rays, mut non_finite) = (0, 0);
            for tile_x in (0..width).step_by(TILE) {
                for row in 0..rows {
                    let y = region.y0 + (band * TILE + row) as u32;
                    for column in tile_x..(tile_x + TILE).min(width) {
                        // At every pixel: a stop is seen within one pixel's samples.
                        if interrupt::requested() {
                            return (rays, non_finite);
                        }
                        let x = region.x0 + column as u32;
                        for (i, &(u, v)) in grid.iter().enumerate() {
                            // The exact tick ray wherever the grid has a cell at the centre.
                            let ray = if (u, v) == (0.5, 0.5) {
                                camera.pixel_centre_ray(x, y)
                            } else {
                                camera.sub_pixel_ray(x, y, u, v)
                            };
                            trace_into(scene, &accel, ray, trace, &mut sample);
                            rays += sample.rays;
                            accumulator.add(&sample, i == centre);
                        }
                        let pixel = row * width + column;
                        non_finite += accumulator.finish(
                            &mut beauty[pixel],
                            &mut data[pixel * channels..(pixel + 1) * channels],
                        );
                    }
                }
            }
            rows_done(rows as u64);
            (rays, non_finite)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    interrupt::check()?;
    let stats = RenderStats {
        rays,
        non_finite,
        hierarchy_time,
    };
    Ok((film, stats))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_are_stratified_and_know_their_centre() {
        let (g1, c1) = sample_grid(1);
        assert_eq!((g1, c1), (vec![(0.5, 0.5)], 0));
        let (g9, c9) = sample_grid(9);
        assert_eq!(g9.len(), 9);
        assert_eq!(g9[c9], (0.5, 0.5));
        assert_eq!(g9[0], (1.0 / 6.0, 1.0 / 6.0));
        let (g4, c4) = sample_grid(4);
        assert_eq!((g4[c4], c4), ((0.25, 0.25), 0));
    }
}
