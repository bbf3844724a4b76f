//! Camera rays -> `trace` -> film, in parallel over rows. Each pixel depends only on its own
//! rays, so the image is the same for any number of threads.

use rayon::prelude::*;

use crate::camera::Camera;
use crate::film::Film;
use crate::scene::Scene;
use crate::trace::{trace, TraceOptions};

/// Renders `scene` at `camera`'s size. `row_done` is called once per finished row (from any
/// thread), for progress reporting.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    options: TraceOptions,
    row_done: &(dyn Fn() + Sync),
) -> Film {
    let mut film = Film::new(camera.width, camera.height);
    let width = camera.width as usize;
    film.rays = film
        .beauty
        .par_chunks_mut(width)
        .enumerate()
        .map(|(y, row)| {
            let mut rays = 0;
            for (x, pixel) in row.iter_mut().enumerate() {
                let ray = camera.pixel_centre_ray(x as u32, y as u32);
                let sample = trace(scene, ray, options);
                *pixel = sample.beauty;
                rays += sample.rays;
            }
            row_done();
            rays
        })
        .sum();
    film
}
