//! Camera rays -> `trace` -> film. Work is split into bands of 16x16 tiles rendered in
//! parallel; every pixel depends only on its own rays and is written by exactly one task, so
//! the image is the same for any number of threads and no lock is taken while tracing.

use rayon::prelude::*;

use crate::accel::Accelerator;
use crate::aov::Layer;
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::film::{Film, PixelAccumulator};
use crate::interrupt;
use crate::sample::Sample;
use crate::scene::Scene;
use crate::trace::{trace_into, TraceOptions};

/// Side of a tile in pixels: small enough to balance two or many cores, large enough that
/// neighbouring rays reuse the same hierarchy nodes from cache.
const TILE: usize = 16;

/// A rectangle of the full image, `[x0, x1) x [y0, y1)`: the part a farm node renders.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Region {
    pub fn full(camera: &Camera) -> Self {
        Region {
            x0: 0,
            y0: 0,
            x1: camera.width,
            y1: camera.height,
        }
    }

    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }
}

/// How nearest hits are found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Acceleration {
    /// The bounding volume hierarchy (the normal path).
    #[default]
    Bvh,
    /// Every object for every ray: the reference the hierarchy is tested against.
    BruteForce,
}

/// How to sample each pixel, and which pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderSettings {
    pub trace: TraceOptions,
    /// Samples per pixel, a square k*k: a fixed stratified grid, no randomness.
    pub spp: u32,
    /// The part of the image to render; `None` for all of it.
    pub region: Option<Region>,
    pub acceleration: Acceleration,
}

impl Default for RenderSettings {
    /// The course's render: 2 bounces, shadows, one sample at each pixel's centre.
    fn default() -> Self {
        RenderSettings {
            trace: TraceOptions {
                bounces: 2,
                shadows: true,
            },
            spp: 1,
            region: None,
            acceleration: Acceleration::Bvh,
        }
    }
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

/// Renders `scene` into a film holding `layers`: the whole of `camera`'s image, or the region
/// the settings name. `rows_done` is told how many rows have finished (from any thread), for
/// progress. Stops early with `Error::Interrupted` when the user presses Ctrl-C.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    settings: RenderSettings,
    layers: Vec<Layer>,
    rows_done: &(dyn Fn(u64) + Sync),
) -> Result<Film> {
    let region = settings.region.unwrap_or(Region::full(camera));
    if region.x0 >= region.x1
        || region.y0 >= region.y1
        || region.x1 > camera.width
        || region.y1 > camera.height
    {
        return Err(Error::Usage(format!(
            "the region {},{},{},{} is not a non-empty part of the {}x{} image",
            region.x0, region.y0, region.x1, region.y1, camera.width, camera.height
        )));
    }
    let started = std::time::Instant::now();
    let accel = match settings.acceleration {
        Acceleration::Bvh => Accelerator::build(&scene.objects),
        Acceleration::BruteForce => Accelerator::brute_force(&scene.objects),
    };
    let hierarchy_time = started.elapsed();
    let mut film = Film::new(region.width(), region.height(), settings.spp, layers)?;
    film.hierarchy_time = hierarchy_time;
    film.origin = (region.x0, region.y0);
    film.display = (camera.width, camera.height);
    let (grid, centre) = sample_grid(settings.spp);
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
            let mut sample = Sample::empty(scene.lights.len(), settings.trace.bounces);
            let (mut rays, mut non_finite) = (0, 0);
            for tile_x in (0..width).step_by(TILE) {
                for row in 0..rows {
                    let y = region.y0 + (band * TILE + row) as u32;
                    for column in tile_x..(tile_x + TILE).min(width) {
                        let x = region.x0 + column as u32;
                        for (i, &(u, v)) in grid.iter().enumerate() {
                            // The exact tick ray wherever the grid has a cell at the centre.
                            let ray = if (u, v) == (0.5, 0.5) {
                                camera.pixel_centre_ray(x, y)
                            } else {
                                camera.sub_pixel_ray(x, y, u, v)
                            };
                            trace_into(scene, &accel, ray, settings.trace, &mut sample);
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

    #[test]
    fn regions_must_lie_inside_the_image() {
        let scene = crate::scene::parse_str("t.xml", "<scene/>").expect("scene");
        let camera = Camera::new(10, 10);
        let layers = crate::aov::all_layers(&[], 0)[..1].to_vec();
        for (x0, y0, x1, y1) in [(0, 0, 11, 10), (5, 5, 5, 9), (3, 0, 2, 10)] {
            let settings = RenderSettings {
                region: Some(Region { x0, y0, x1, y1 }),
                ..RenderSettings::default()
            };
            assert!(render(&scene, &camera, settings, layers.clone(), &|_| {}).is_err());
        }
        let settings = RenderSettings {
            region: Some(Region {
                x0: 2,
                y0: 3,
                x1: 7,
                y1: 4,
            }),
            ..RenderSettings::default()
        };
        let film = render(&scene, &camera, settings, layers, &|_| {}).expect("render");
        assert_eq!(
            (film.width, film.height, film.origin, film.display),
            (5, 1, (2, 3), (10, 10))
        );
    }
}
