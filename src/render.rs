//! Camera rays -> `trace` -> film, in parallel over rows. Each pixel depends only on its own
//! rays, so the image is the same for any number of threads.

use rayon::prelude::*;

use crate::aov::Layer;
use crate::camera::Camera;
use crate::error::Result;
use crate::film::{Film, PixelAccumulator};
use crate::interrupt;
use crate::scene::Scene;
use crate::trace::{trace, TraceOptions};

/// How to sample each pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderSettings {
    pub trace: TraceOptions,
    /// Samples per pixel, a square k*k: a fixed stratified grid, no randomness.
    pub spp: u32,
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

/// Renders `scene` at `camera`'s size into a film holding `layers`. `row_done` is called once
/// per finished row (from any thread), for progress reporting. Stops early with
/// `Error::Interrupted` when the user presses Ctrl-C.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    settings: RenderSettings,
    layers: Vec<Layer>,
    row_done: &(dyn Fn() + Sync),
) -> Result<Film> {
    let mut film = Film::new(camera.width, camera.height, settings.spp, layers)?;
    let (grid, centre) = sample_grid(settings.spp);
    let width = camera.width as usize;
    let channels = film.channel_count();
    let layers = &film.layers;
    let (rays, non_finite) = film
        .beauty
        .par_chunks_mut(width)
        .zip(film.data.par_chunks_mut(width * channels))
        .enumerate()
        .map(|(y, (beauty_row, data_row))| {
            if interrupt::requested() {
                return (0, 0);
            }
            let y = y as u32;
            let mut accumulator = PixelAccumulator::new(layers, channels);
            let (mut rays, mut non_finite) = (0, 0);
            let data_pixels = data_row.chunks_exact_mut(channels.max(1));
            for (x, (beauty, data)) in beauty_row.iter_mut().zip(data_pixels).enumerate() {
                let x = x as u32;
                for (i, &(u, v)) in grid.iter().enumerate() {
                    // The exact tick ray wherever the grid has a cell at the pixel centre.
                    let ray = if (u, v) == (0.5, 0.5) {
                        camera.pixel_centre_ray(x, y)
                    } else {
                        camera.sub_pixel_ray(x, y, u, v)
                    };
                    let sample = trace(scene, ray, settings.trace);
                    rays += sample.rays;
                    accumulator.add(&sample, i == centre);
                }
                non_finite += accumulator.finish(beauty, data);
            }
            row_done();
            (rays, non_finite)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    interrupt::check()?;
    film.rays = rays;
    film.non_finite = non_finite;
    Ok(film)
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
