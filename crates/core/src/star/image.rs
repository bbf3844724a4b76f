//! Whole Tick 1* images: the course's seeded draw and the converged expectation with the
//! variance of one draw, pixel by pixel in parallel, with the layers Tick 1* adds.

use glam::DVec3;
use rayon::prelude::*;

use super::path::{trace_path, Path, ShadowQuery, Visibility};
use super::streams::{CourseStream, PixelPoints, MAX_SOBOL_POINTS};
use super::Star;
use crate::accel::Accelerator;
use crate::aov::Layer;
use crate::camera::Camera;
use crate::course::Course;
use crate::error::Result;
use crate::film::{Film, PixelAccumulator};
use crate::geometry::Ray;
use crate::interrupt;
use crate::model::Model;
use crate::sample::StarValues;
use crate::scene::Scene;
use crate::trace::TraceOptions;

/// Everything a Tick 1* image depends on.
#[derive(Debug, Clone, Copy)]
pub struct StarFrame<'a> {
    pub scene: &'a Scene,
    pub camera: Camera,
    /// The year whose shading rules (`Course::rules`) the tick model follows.
    pub course: Course,
    pub trace: TraceOptions,
    pub star: &'a Star,
}

/// When the converged estimate stops: once the standard error of every channel of a pixel's
/// expectation is at most `standard_error` (linear radiance), or at `max_paths` camera rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseFloor {
    pub standard_error: f64,
    pub max_paths: u32,
}

impl Default for NoiseFloor {
    /// A quarter of an 8-bit step: twice the standard error stays below half a step.
    fn default() -> Self {
        NoiseFloor {
            standard_error: 0.25 / 255.0,
            max_paths: 4096,
        }
    }
}

/// Shadow rays per light and vertex on each camera ray of the converged estimate: enough for
/// an unbiased `p (1 - p)`.
const SHADOW_POINTS: u32 = 4;

/// Camera rays per pixel in the converged estimate's first round: four per replicate, so
/// that the first standard error is not a lucky one.
const FIRST_ROUND: u32 = 32;

/// A Tick 1* image, linear radiance, row by row from the top-left pixel (of a `Grid`'s pixels
/// when estimated on one: `width` and `height` are then the grid's).
#[derive(Debug, Clone, PartialEq)]
pub struct StarImage {
    pub width: u32,
    pub height: u32,
    /// The draw (`course_draw`) or the expectation (`expectation`).
    pub beauty: Vec<DVec3>,
    /// The variance of one course draw of the pixel (`expectation` only; empty for a draw).
    pub variance: Vec<DVec3>,
    /// The standard error of `beauty` as an estimate of the expectation (`expectation` only).
    pub standard_error: Vec<DVec3>,
    /// Per light (scene order), per pixel: the visible share of the light at the camera's hit
    /// (0 where the ray misses), over the pixel's camera rays.
    pub visible: Vec<Vec<f32>>,
    /// The side, in pixels, of the square the pinhole hit is spread over by the aperture
    /// (empty without depth of field; 0 on a miss).
    pub circle_of_confusion: Vec<f32>,
    /// The shading normal at the pinhole ray's hit (perturbed on bumped spheres; 0 on a miss).
    pub normal: Vec<DVec3>,
    /// The bump map's height at the pinhole ray's hit (0 off bumped spheres; empty when the
    /// scene has none).
    pub bump_height: Vec<f32>,
    /// Camera rays traced per pixel (the converged estimate's count varies).
    pub paths: Vec<u32>,
}

/// What one pixel gives.
struct PixelResult {
    beauty: DVec3,
    variance: DVec3,
    standard_error: DVec3,
    visible: Vec<f32>,
    coc: f32,
    normal: DVec3,
    height: f32,
    paths: u32,
}

/// One draw of the course's process, seeded: pixel by pixel, the course's order of
/// `Math.random()` calls (per aperture ray its two coordinates, then per vertex and light its
/// shadow rays, each radius, polar angle, azimuth) from the pixel's own stream.
pub fn course_draw(frame: &StarFrame, seed: u64) -> Result<StarImage> {
    render(frame, Grid::EVERY, |model, accel, x, y| {
        draw_pixel(model, accel, frame, seed, (x, y), None)
    })
}

/// The expectation of the course's process and the variance of one draw, per pixel,
/// estimated with Sobol points seeded by `seed` to `floor`.
pub fn expectation(frame: &StarFrame, floor: NoiseFloor, seed: u64) -> Result<StarImage> {
    expectation_on(frame, floor, seed, Grid::EVERY)
}

/// The expectation at the pixels of `grid` only: the image is the grid's, each of its pixels
/// exactly the whole expectation's value there (a pixel's estimate depends on its own index
/// alone), at 1/stride^2 of the cost. A check scores a student's image on it first, so that
/// processes far from the image cost little (`whitted_check`'s pre-pass).
pub fn expectation_on(
    frame: &StarFrame,
    floor: NoiseFloor,
    seed: u64,
    grid: Grid,
) -> Result<StarImage> {
    expectation_counted(frame, (floor, seed), grid, &|| {})
}

/// [`expectation_on`], calling `row_done` as each of the grid's rows is finished (from any
/// thread): a whole expectation at the course's size can take a minute, and the person
/// waiting for it is shown how far it is (`whitted_check`'s reference cache draws the bar).
pub fn expectation_counted(
    frame: &StarFrame,
    (floor, seed): (NoiseFloor, u64),
    grid: Grid,
    row_done: &(dyn Fn() + Sync),
) -> Result<StarImage> {
    render_counted(
        frame,
        grid,
        |model, accel, x, y| expect_pixel(model, accel, frame, (floor, seed), (x, y), None),
        row_done,
    )
}

/// Every `stride`-th pixel of every `stride`-th row, starting half a stride in (the middle of
/// each block of stride x stride pixels): the pixels a sparse expectation is estimated at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Grid {
    pub stride: u32,
}

impl Grid {
    /// Every pixel.
    pub const EVERY: Grid = Grid { stride: 1 };

    /// The first pixel of each row and column.
    pub fn offset(self) -> u32 {
        self.stride.max(1) / 2
    }

    /// The grid's pixels along an image side of `side` pixels.
    pub fn count(self, side: u32) -> u32 {
        let stride = self.stride.max(1);
        side.saturating_sub(self.offset()).div_ceil(stride)
    }

    /// The image's coordinate of the grid's `i`-th pixel along a side.
    pub fn at(self, i: u32) -> u32 {
        self.offset() + i * self.stride.max(1)
    }
}

/// What a Tick 1* film took.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StarStats {
    /// Rays cast: camera, shadow and reflected.
    pub rays: u64,
    /// Camera rays (aperture rays with depth of field).
    pub camera_rays: u64,
    /// Layer values that were NaN or infinite and were stored as 0.
    pub non_finite: u64,
}

/// How a Tick 1* film is sampled (`--sampling`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sampling {
    /// One draw of the course's process (`course_draw`).
    Course { seed: u64 },
    /// The expectation to a noise floor (`expectation`).
    Converged { floor: NoiseFloor, seed: u64 },
}

/// A Tick 1* render as a film of `layers` (the tick's layers split each camera ray, plus
/// `aov::star_layers`), for the image writers: every camera ray of a pixel is one sample.
pub fn star_film(
    frame: &StarFrame,
    sampling: Sampling,
    layers: Vec<Layer>,
) -> Result<(Film, StarStats)> {
    let (width, height) = (frame.camera.width, frame.camera.height);
    let mut film = Film::new(width, height, layers)?;
    film.display = (width, height);
    let model = frame.course.rules();
    let accel = accelerator(&model, frame.scene);
    let channels = film.channel_count();
    let row_channels = width as usize * channels;
    let lights = frame.scene.lights.len();
    let layers = &film.layers;
    let data: Vec<&mut [f32]> = if channels == 0 {
        (0..height).map(|_| <&mut [f32]>::default()).collect()
    } else {
        film.data.chunks_mut(row_channels).collect()
    };
    let stats = film
        .beauty
        .par_chunks_mut(width as usize)
        .zip(data)
        .enumerate()
        .map(|(y, (beauty, data))| {
            let mut accumulator = PixelAccumulator::new(layers, channels);
            let mut paths = Vec::new();
            let mut stats = StarStats::default();
            for (x, pixel) in beauty.iter_mut().enumerate() {
                if interrupt::requested() {
                    break;
                }
                paths.clear();
                let at = (x as u32, y as u32);
                let result = match sampling {
                    Sampling::Course { seed } => {
                        draw_pixel(&model, &accel, frame, seed, at, Some(&mut paths))
                    }
                    Sampling::Converged { floor, seed } => {
                        expect_pixel(&model, &accel, frame, (floor, seed), at, Some(&mut paths))
                    }
                };
                let star = StarValues {
                    variance: result.variance,
                    circle_of_confusion: f64::from(result.coc),
                    height: f64::from(result.height),
                };
                // Z, P and objectid come from the ray nearest the pinhole (the first of ties).
                let nearest = (0..paths.len())
                    .min_by(|&a, &b| {
                        paths[a]
                            .aperture_offset
                            .total_cmp(&paths[b].aperture_offset)
                    })
                    .unwrap_or(0);
                for (i, path) in paths.iter().enumerate() {
                    let sample = path.sample(lights, frame.trace.bounces, star);
                    stats.rays += sample.rays;
                    accumulator.add(&sample, i == nearest);
                }
                stats.camera_rays += paths.len() as u64;
                let values = &mut data[x * channels..(x + 1) * channels];
                stats.non_finite += accumulator.finish(pixel, values);
            }
            stats
        })
        .reduce(StarStats::default, |a, b| StarStats {
            rays: a.rays + b.rays,
            camera_rays: a.camera_rays + b.camera_rays,
            non_finite: a.non_finite + b.non_finite,
        });
    interrupt::check()?;
    Ok((film, stats))
}

/// The hierarchy where the model's hits allow it, else brute force.
fn accelerator(model: &impl Model, scene: &Scene) -> Accelerator {
    if model.hierarchy_exact() {
        Accelerator::build(&scene.objects)
    } else {
        Accelerator::brute_force(&scene.objects)
    }
}

/// The pixels of `grid` rendered by `pixel`, rows in parallel; the image is the grid's.
fn render(
    frame: &StarFrame,
    grid: Grid,
    pixel: impl Fn(&crate::course::Rules, &Accelerator, u32, u32) -> PixelResult + Sync,
) -> Result<StarImage> {
    render_counted(frame, grid, pixel, &|| {})
}

/// [`render`], calling `row_done` after each row.
fn render_counted(
    frame: &StarFrame,
    grid: Grid,
    pixel: impl Fn(&crate::course::Rules, &Accelerator, u32, u32) -> PixelResult + Sync,
    row_done: &(dyn Fn() + Sync),
) -> Result<StarImage> {
    let model = frame.course.rules();
    let accel = accelerator(&model, frame.scene);
    let (width, height) = (
        grid.count(frame.camera.width),
        grid.count(frame.camera.height),
    );
    let rows: Vec<Vec<PixelResult>> = (0..height)
        .into_par_iter()
        .map(|j| {
            if interrupt::requested() {
                return Vec::new();
            }
            let row = (0..width)
                .map(|i| pixel(&model, &accel, grid.at(i), grid.at(j)))
                .collect();
            row_done();
            row
        })
        .collect();
    interrupt::check()?;
    let lights = frame.scene.lights.len();
    let pixels = (width as usize) * (height as usize);
    let mut image = StarImage {
        width,
        height,
        beauty: Vec::with_capacity(pixels),
        variance: Vec::new(),
        standard_error: Vec::new(),
        visible: vec![Vec::with_capacity(pixels); lights],
        circle_of_confusion: Vec::new(),
        normal: Vec::with_capacity(pixels),
        bump_height: Vec::new(),
        paths: Vec::with_capacity(pixels),
    };
    let random = frame.star.is_random();
    for p in rows.into_iter().flatten() {
        image.beauty.push(p.beauty);
        if random {
            image.variance.push(p.variance);
            image.standard_error.push(p.standard_error);
        }
        for (layer, v) in image.visible.iter_mut().zip(&p.visible) {
            layer.push(*v);
        }
        if frame.star.dof.is_some() {
            image.circle_of_confusion.push(p.coc);
        }
        image.normal.push(p.normal);
        if !frame.star.bumps.is_empty() {
            image.bump_height.push(p.height);
        }
        image.paths.push(p.paths);
    }
    Ok(image)
}

/// The row-major index of pixel (x, y): what numbers its stream.
fn pixel_index(frame: &StarFrame, x: u32, y: u32) -> u64 {
    u64::from(y) * u64::from(frame.camera.width) + u64::from(x)
}

/// The pinhole ray's path with every light lit (no shadow ray cast): the geometry layers.
fn pinhole_layers(
    model: &impl Model,
    accel: &Accelerator,
    frame: &StarFrame,
    pinhole: Ray,
) -> (f32, DVec3, f32) {
    let path = trace_path(
        model,
        frame.scene,
        accel,
        frame.star,
        pinhole,
        TraceOptions {
            bounces: 0,
            shadows: false,
        },
        &mut |_| Visibility::LIT,
    );
    let Some(hit) = path.primary else {
        return (0.0, DVec3::ZERO, 0.0);
    };
    let step = frame.camera.plane_point(1, 0).0 - frame.camera.plane_point(0, 0).0;
    let coc = frame.star.dof.map_or(0.0, |dof| {
        dof.circle_of_confusion(hit.position.z, pinhole.direction, step)
    });
    (coc as f32, hit.normal, hit.height.unwrap_or(0.0) as f32)
}

/// Adds the primary vertex's visible shares of `path` to `sums`.
fn add_visible(path: &Path, sums: &mut [f64]) {
    if let Some(vertex) = path.vertices.first() {
        for (sum, light) in sums.iter_mut().zip(&vertex.lights) {
            *sum += light.visibility.fraction;
        }
    }
}

/// A camera ray's path under `frame`, the one call both samplers make: each light's
/// visibility from `rays` shadow rays towards the light's position plus a point of the light
/// drawn from `uniform(query, s)`, the uniform numbers of shadow ray s (one hard shadow ray,
/// drawing nothing, without soft shadows).
fn trace_camera_ray(
    model: &impl Model,
    accel: &Accelerator,
    frame: &StarFrame,
    ray: Ray,
    rays: u32,
    uniform: &mut dyn FnMut(&ShadowQuery, u32) -> [f64; 3],
) -> Path {
    let star = frame.star;
    let mut sample = |q: ShadowQuery| match star.soft {
        None => share(u32::from(!(q.blocked)(DVec3::ZERO)), 1),
        Some(soft) => {
            let lit = (0..rays)
                .filter(|&s| {
                    let u = uniform(&q, s);
                    !(q.blocked)(soft.sampling.point(u) * soft.light_size)
                })
                .count() as u32;
            share(lit, rays)
        }
    };
    trace_path(
        model,
        frame.scene,
        accel,
        star,
        ray,
        frame.trace,
        &mut sample,
    )
}

/// The visible share from `n` shadow rays of which `lit` were not blocked.
fn share(lit: u32, n: u32) -> Visibility {
    let p = f64::from(lit) / f64::from(n);
    let spread = if n > 1 {
        p * (1.0 - p) * f64::from(n) / f64::from(n - 1)
    } else {
        0.0
    };
    Visibility {
        fraction: p,
        spread,
        rays: n,
    }
}

fn draw_pixel(
    model: &impl Model,
    accel: &Accelerator,
    frame: &StarFrame,
    seed: u64,
    (x, y): (u32, u32),
    mut keep: Option<&mut Vec<Path>>,
) -> PixelResult {
    let star = frame.star;
    let mut stream = CourseStream::new(seed, pixel_index(frame, x, y));
    let pinhole = frame.camera.pixel_centre_ray(x, y);
    let mut visible = vec![0.0; frame.scene.lights.len()];
    let trace = |ray: Ray, stream: &mut CourseStream| {
        let rays = star.soft.map_or(1, |soft| soft.rays);
        trace_camera_ray(model, accel, frame, ray, rays, &mut |_, _| {
            [stream.random(), stream.random(), stream.random()]
        })
    };
    let (beauty, paths) = match star.dof {
        None => {
            let path = trace(pinhole, &mut stream);
            add_visible(&path, &mut visible);
            let radiance = path.radiance();
            if let Some(kept) = keep.as_mut() {
                kept.push(path);
            }
            (radiance, 1)
        }
        Some(dof) => {
            let mut sum = DVec3::ZERO;
            for _ in 0..dof.rays {
                let u = [stream.random(), stream.random()];
                let path = trace(dof.ray(&pinhole, u), &mut stream);
                add_visible(&path, &mut visible);
                sum += path.radiance();
                if let Some(kept) = keep.as_mut() {
                    kept.push(path);
                }
            }
            (sum / f64::from(dof.rays), dof.rays)
        }
    };
    let (coc, normal, height) = pinhole_layers(model, accel, frame, pinhole);
    PixelResult {
        beauty,
        variance: DVec3::ZERO,
        standard_error: DVec3::ZERO,
        visible: visible
            .iter()
            .map(|v| (v / f64::from(paths.max(1))) as f32)
            .collect(),
        coc,
        normal,
        height,
        paths,
    }
}

/// Independently scrambled Sobol sequences a pixel's camera rays are dealt out to, in turn:
/// the spread of their means is the estimate's standard error, which (unlike the spread of
/// single rays) credits low-discrepancy points with converging faster than random ones.
const REPLICATES: usize = 8;

/// Running sums over a pixel's camera rays.
#[derive(Default)]
struct Sums {
    n: u32,
    radiance: DVec3,
    squares: DVec3,
    spread: DVec3,
    /// Radiance summed per replicate.
    replicates: [DVec3; REPLICATES],
}

impl Sums {
    /// The standard error of the mean from the replicates' means (n a multiple of
    /// `REPLICATES`, at least two rays each).
    fn standard_error(&self, mean: DVec3) -> DVec3 {
        let per = f64::from(self.n) / REPLICATES as f64;
        let r = REPLICATES as f64;
        let variance: DVec3 = self
            .replicates
            .iter()
            .map(|s| {
                let d = *s / per - mean;
                d * d
            })
            .sum::<DVec3>()
            / (r - 1.0);
        (variance / r).powf(0.5)
    }
}

fn expect_pixel(
    model: &impl Model,
    accel: &Accelerator,
    frame: &StarFrame,
    (floor, seed): (NoiseFloor, u64),
    (x, y): (u32, u32),
    mut keep: Option<&mut Vec<Path>>,
) -> PixelResult {
    let star = frame.star;
    let pixel = pixel_index(frame, x, y);
    let replicates: [PixelPoints; REPLICATES] = std::array::from_fn(|r| {
        PixelPoints::new(seed ^ (r as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15), pixel)
    });
    let pinhole = frame.camera.pixel_centre_ray(x, y);
    let lights = frame.scene.lights.len() as u32;
    let mut visible = vec![0.0; lights as usize];
    // Without depth of field every camera ray is the pinhole's; without soft shadows too,
    // one ray is the exact answer.
    let shadow_points = if star.soft.is_some() {
        SHADOW_POINTS
    } else {
        1
    };
    let max_paths = floor.max_paths.clamp(FIRST_ROUND, MAX_SOBOL_POINTS);
    let mut sums = Sums::default();
    let mut target = if star.is_random() {
        FIRST_ROUND.min(max_paths)
    } else {
        1
    };
    loop {
        while sums.n < target {
            let (points, j) = (
                &replicates[sums.n as usize % REPLICATES],
                sums.n / REPLICATES as u32,
            );
            let ray = match star.dof {
                Some(dof) => dof.ray(&pinhole, points.aperture(j)),
                None => pinhole,
            };
            // Each of a ray's shadow points is point j of its own sequence: the points of
            // one ray are independent (so the spread is unbiased), each sequence stratified
            // over the pixel's rays.
            let path = trace_camera_ray(model, accel, frame, ray, shadow_points, &mut |q, s| {
                let stream = (q.depth * lights + q.light as u32) * shadow_points;
                points.shadow(stream + s, j)
            });
            add_visible(&path, &mut visible);
            let c = path.radiance();
            sums.replicates[sums.n as usize % REPLICATES] += c;
            sums.n += 1;
            sums.radiance += c;
            sums.squares += c * c;
            sums.spread += path.spread();
            if let Some(kept) = keep.as_mut() {
                kept.push(path);
            }
        }
        let n = f64::from(sums.n);
        let mean = sums.radiance / n;
        let standard_error = if sums.n > 1 {
            // The replicates credit the Sobol points' faster convergence, but a share of few
            // stratified points can come out the same in all eight (a Bernoulli-like spread
            // the replicates then miss): never less than a quarter of the iid error.
            let iid = ((sums.squares - sums.radiance * mean) / (n - 1.0)).max(DVec3::ZERO) / n;
            sums.standard_error(mean).max(iid.powf(0.5) / 4.0)
        } else {
            DVec3::ZERO
        };
        let done = !star.is_random()
            || standard_error.max_element() <= floor.standard_error
            || sums.n >= max_paths;
        if done {
            let variance = draw_variance(star, &sums, mean, shadow_points);
            let (coc, normal, height) = pinhole_layers(model, accel, frame, pinhole);
            return PixelResult {
                beauty: mean,
                variance,
                standard_error,
                visible: visible.iter().map(|v| (v / n) as f32).collect(),
                coc,
                normal,
                height,
                paths: sums.n,
            };
        }
        target = (target * 2).min(max_paths);
    }
}

/// The variance of one course draw of a pixel from the sums of its camera rays
/// (module docs, The statistic).
fn draw_variance(star: &Star, sums: &Sums, mean: DVec3, shadow_points: u32) -> DVec3 {
    let n = f64::from(sums.n);
    let spread = sums.spread / n;
    let within = match star.soft {
        Some(soft) => spread / f64::from(soft.rays),
        None => DVec3::ZERO,
    };
    match star.dof {
        None => within,
        Some(dof) => {
            // E[y^2] over the aperture overstates E[c|a]^2 by the estimator's own variance.
            let noise = spread / f64::from(shadow_points);
            let between = (sums.squares / n - mean * mean - noise).max(DVec3::ZERO);
            (between + within) / f64::from(dof.rays)
        }
    }
}
