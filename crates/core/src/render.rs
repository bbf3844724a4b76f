//! Camera rays -> `trace` -> film, a strip of rows at a time: the strip renders in runs of
//! pixels on every core while the previous strip is written out.

use std::time::{Duration, Instant};

use glam::DVec3;
use rayon::prelude::*;

use crate::accel::Accelerator;
use crate::aov::Layer;
use crate::course::Course;
use crate::error::Result;
use crate::film::{Film, PixelAccumulator};
use crate::frame::{Acceleration, Frame};
use crate::hits::tape::{Recording, Tape};
use crate::hits::Hits;
use crate::interrupt;
use crate::model::{Model, Tick};
use crate::sample::Sample;
use crate::scene::Scene;
use crate::trace::observe::Silent;
use crate::trace::{trace_chain, trace_observed};

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

/// Renders `scene` as `frame` says into one film holding the whole region: for tests and
/// library users. `whitted render` streams strips instead (`render_strips`).
pub fn render(
    scene: &Scene,
    frame: &Frame,
    rows_done: &(dyn Fn(u64) + Sync),
) -> Result<(Film, RenderStats)> {
    let region = frame.region();
    let mut film = Film::new(region.width(), region.height(), frame.layers().to_vec())?;
    film.origin = (region.x0, region.y0);
    film.display = (frame.camera().width, frame.camera().height);
    let channels = film.channel_count();
    let width = region.width() as usize;
    let rows = strip_rows(region.width(), channels, None);
    let stats = render_strips(scene, frame, rows, rows_done, &mut |strip: &Film| {
        let first = (strip.origin.1 - region.y0) as usize * width;
        let pixels = strip.beauty.len();
        film.beauty[first..first + pixels].copy_from_slice(&strip.beauty);
        film.data[first * channels..(first + pixels) * channels].copy_from_slice(&strip.data);
        Ok(())
    })?;
    Ok((film, stats))
}

/// Pixels per task: a few hundred microseconds of tracing at one sample per pixel.
const TASK_PIXELS: usize = 256;

/// Rows in a strip of a render without an EXR: the PNG encoder is cheap, and short strips
/// keep the last one, which nothing overlaps, short.
const PNG_STRIP_ROWS: u32 = 16;

/// Most rows in a strip of a render with an EXR: four ZIP blocks, so that a strip's blocks
/// compress on several cores while the next strip renders.
const EXR_STRIP_ROWS: u32 = 64;

/// Bytes of f32 channel values a strip with an EXR may hold: a 4K, 53-channel strip has its
/// 64 rows, a 16384-pixel-wide one 16.
const EXR_STRIP_BYTES: u64 = 64 << 20;

/// Rows per strip for `width`-pixel rows of `channels` channels, and an EXR of `block_lines`
/// lines per block if any: whole blocks, at least one.
pub fn strip_rows(width: u32, channels: usize, block_lines: Option<u32>) -> u32 {
    let Some(block) = block_lines.map(|b| b.max(1)) else {
        return PNG_STRIP_ROWS;
    };
    let row_bytes = (u64::from(width) * 4 * channels as u64).max(1);
    let fitting = (EXR_STRIP_BYTES / row_bytes).min(u64::from(EXR_STRIP_ROWS)) as u32;
    (fitting / block).max(1) * block
}

/// Renders `scene` as `frame` says, strip by strip of `strip_rows` whole rows top to bottom,
/// handing each finished strip to `sink` in order. Memory is two strips, whatever the image
/// size: `sink` writes strip k while strip k + 1 renders on the other cores.
///
/// Every pixel depends only on its own rays and is written by exactly one task, so the image
/// is the same for any number of threads and no lock is taken while tracing. `rows_done` is
/// told how many rows have finished (from any thread), for progress. Stops early with
/// `Error::Interrupted` when the user presses Ctrl-C, and with `sink`'s first error.
pub fn render_strips(
    scene: &Scene,
    frame: &Frame,
    strip_rows: u32,
    rows_done: &(dyn Fn(u64) + Sync),
    sink: &mut (dyn FnMut(&Film) -> Result<()> + Send),
) -> Result<RenderStats> {
    // The year is chosen once per render, and each model's strips are compiled on their own:
    // 2016-17 runs the very code it ran before there were years (dispatching per task instead,
    // with both models' loops in one closure, cost tick2 2% more instructions).
    match frame.course() {
        Course::Y2016 => strips_under(Tick, scene, frame, strip_rows, rows_done, sink),
        course => strips_under(course.rules(), scene, frame, strip_rows, rows_done, sink),
    }
}

/// `render_strips` under `model`'s rules.
#[inline(never)]
fn strips_under<M: Model>(
    model: M,
    scene: &Scene,
    frame: &Frame,
    strip_rows: u32,
    rows_done: &(dyn Fn(u64) + Sync),
    sink: &mut (dyn FnMut(&Film) -> Result<()> + Send),
) -> Result<RenderStats> {
    let started = Instant::now();
    let accel = match frame.acceleration() {
        Acceleration::Bvh => Accelerator::build(&scene.objects),
        Acceleration::BruteForce => Accelerator::brute_force(&scene.objects),
    };
    let hierarchy_time = started.elapsed();
    let region = frame.region();
    let strip_rows = strip_rows.clamp(1, region.height());
    let new_strip = || -> Result<Film> {
        let mut strip = Film::new(region.width(), strip_rows, frame.layers().to_vec())?;
        strip.display = (frame.camera().width, frame.camera().height);
        Ok(strip)
    };
    let (mut rendering, mut finished) = (new_strip()?, new_strip()?);
    let mut have_finished = false;
    let pixels = PixelRenderer::new(model, scene, &accel, frame);
    let mut stats = RenderStats {
        hierarchy_time,
        ..RenderStats::default()
    };
    for top in (region.y0..region.y1).step_by(strip_rows as usize) {
        rendering.origin = (region.x0, top);
        rendering.keep_rows(strip_rows.min(region.y1 - top));
        let (counts, written) = rayon::join(
            || pixels.render_strip(&mut rendering, rows_done),
            || {
                if have_finished {
                    sink(&finished)
                } else {
                    Ok(())
                }
            },
        );
        written?;
        interrupt::check()?;
        stats.rays += counts.0;
        stats.non_finite += counts.1;
        std::mem::swap(&mut rendering, &mut finished);
        have_finished = true;
    }
    sink(&finished)?;
    Ok(stats)
}

/// What every pixel of a frame needs: the model, the scene, its hierarchy, the camera and
/// the sample grid.
struct PixelRenderer<'a, M> {
    model: M,
    scene: &'a Scene,
    accel: &'a Accelerator,
    frame: &'a Frame,
    grid: Vec<(f64, f64)>,
    centre: usize,
}

impl<'a, M: Model> PixelRenderer<'a, M> {
    fn new(model: M, scene: &'a Scene, accel: &'a Accelerator, frame: &'a Frame) -> Self {
        let (grid, centre) = sample_grid(frame.spp());
        PixelRenderer {
            model,
            scene,
            accel,
            frame,
            grid,
            centre,
        }
    }

    /// Fills `strip` (placed by its origin), a run of `TASK_PIXELS` pixels per task: small
    /// enough that the cores finish a strip together. Returns (rays, non-finite values).
    fn render_strip(&self, strip: &mut Film, rows_done: &(dyn Fn(u64) + Sync)) -> (u64, u64) {
        let channels = strip.channel_count();
        let layers = &strip.layers;
        let place = (strip.width as usize, strip.origin);
        // A film without layers has no channel values: every task gets an empty slice.
        let tasks = strip.beauty.len().div_ceil(TASK_PIXELS);
        let data: Vec<&mut [f32]> = if channels == 0 {
            (0..tasks).map(|_| <&mut [f32]>::default()).collect()
        } else {
            strip.data.chunks_mut(TASK_PIXELS * channels).collect()
        };
        let counts = strip
            .beauty
            .par_chunks_mut(TASK_PIXELS)
            .zip(data)
            .enumerate()
            .map(|(task, (beauty, data))| {
                self.render_pixels(place, task * TASK_PIXELS, layers, beauty, data)
            })
            .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
        rows_done(u64::from(strip.height));
        counts
    }

    /// The pixels of a strip from index `first` on, the strip being `width` pixels wide with
    /// its top-left pixel at `origin` in the image.
    fn render_pixels(
        &self,
        (width, origin): (usize, (u32, u32)),
        first: usize,
        layers: &[Layer],
        beauty: &mut [DVec3],
        data: &mut [f32],
    ) -> (u64, u64) {
        let (camera, trace) = (self.frame.camera(), self.frame.trace());
        let channels = data.len() / beauty.len().max(1);
        let mut accumulator = PixelAccumulator::new(layers, channels);
        let mut sample = Sample::empty(self.scene.lights.len(), trace.bounces);
        let (mut rays, mut non_finite) = (0, 0);
        for (offset, pixel) in beauty.iter_mut().enumerate() {
            let values = &mut data[offset * channels..(offset + 1) * channels];
            // At every pixel: a stop is seen within one pixel's samples.
            if interrupt::requested() {
                break;
            }
            let index = first + offset;
            let x = origin.0 + (index % width) as u32;
            let y = origin.1 + (index / width) as u32;
            for (i, &(u, v)) in self.grid.iter().enumerate() {
                // The exact tick ray wherever the grid has a cell at the centre.
                let ray = if (u, v) == (0.5, 0.5) {
                    camera.pixel_centre_ray(x, y)
                } else {
                    camera.sub_pixel_ray(x, y, u, v)
                };
                let (model, scene, accel) = (&self.model, self.scene, self.accel);
                if layers.is_empty() {
                    trace_observed::<false>(
                        model,
                        scene,
                        accel,
                        ray,
                        trace,
                        &mut sample,
                        &mut Silent,
                    );
                } else {
                    trace_observed::<true>(
                        model,
                        scene,
                        accel,
                        ray,
                        trace,
                        &mut sample,
                        &mut Silent,
                    );
                }
                rays += sample.rays;
                accumulator.add(&sample, i == self.centre);
            }
            non_finite += accumulator.finish(pixel, values);
        }
        (rays, non_finite)
    }
}

/// What `keep` takes from each listed pixel's sample (`(x, y)` of the frame's image), one
/// sample at each pixel's centre, traced under `model`'s rules (with every layer if
/// `LAYERS`): how `whitted check` renders a student's mistakes only where it needs to look.
/// `accel` must suit the model (`Model::hierarchy_exact`). Sequential: callers run many such
/// lists side by side. Stops early (a shorter list) when the user presses Ctrl-C.
pub fn trace_pixels<const LAYERS: bool, T>(
    model: &impl Model,
    scene: &Scene,
    accel: &Accelerator,
    frame: &Frame,
    pixels: &[(u32, u32)],
    keep: impl Fn(&Sample) -> T,
) -> Vec<T> {
    assert_suits(model, accel);
    trace_pixels_with::<LAYERS, _, _>(model, scene, frame, pixels, |_| accel, keep)
}

/// `trace_pixels` with the hit searches of pixel `j` answered by `hits(j)`: a replay of
/// the searches a trace of the same pixels recorded (`record_pixels`), where `model`
/// intersects by the recording model's rules (`hits::tape`).
pub fn trace_pixels_with<const LAYERS: bool, T, H: Hits>(
    model: &impl Model,
    scene: &Scene,
    frame: &Frame,
    pixels: &[(u32, u32)],
    hits: impl Fn(usize) -> H,
    keep: impl Fn(&Sample) -> T,
) -> Vec<T> {
    let mut sample = Sample::empty(scene.lights.len(), frame.trace().bounces);
    pixels
        .iter()
        .enumerate()
        .take_while(|_| !interrupt::requested())
        .map(|(j, &(x, y))| {
            let ray = frame.camera().pixel_centre_ray(x, y);
            trace_observed::<LAYERS>(
                model,
                scene,
                &hits(j),
                ray,
                frame.trace(),
                &mut sample,
                &mut Silent,
            );
            keep(&sample)
        })
        .collect()
}

/// The hit searches of each listed pixel's trace under `model` (as `trace_pixels` traces it),
/// for tracing the same pixels again under models that intersect by its rules
/// (`trace_pixels_with` and `hits::tape::Replay`). Stops early (a shorter list) when the user
/// presses Ctrl-C.
pub fn record_pixels(
    model: &impl Model,
    scene: &Scene,
    accel: &Accelerator,
    frame: &Frame,
    pixels: &[(u32, u32)],
) -> Vec<Tape> {
    assert_suits(model, accel);
    let recording = Recording::new(accel);
    trace_pixels_with::<false, _, _>(
        model,
        scene,
        frame,
        pixels,
        |_| &recording,
        |_| recording.take(),
    )
}

/// `trace_pixels` for the beauty at several bounce counts at once, each at most the frame's:
/// one trace per pixel at the frame's count (`trace::trace_chain`). The beauty at
/// `bounces[i]` of pixel `j` is element `i * pixels.len() + j`. Stops early (an empty list)
/// when the user presses Ctrl-C.
pub fn trace_pixels_at_bounces(
    model: &impl Model,
    scene: &Scene,
    accel: &Accelerator,
    frame: &Frame,
    pixels: &[(u32, u32)],
    bounces: &[u32],
) -> Vec<DVec3> {
    assert_suits(model, accel);
    let mut sample = Sample::empty(scene.lights.len(), frame.trace().bounces);
    let mut beauty = vec![DVec3::ZERO; bounces.len() * pixels.len()];
    for (j, &(x, y)) in pixels.iter().enumerate() {
        if interrupt::requested() {
            return Vec::new();
        }
        let ray = frame.camera().pixel_centre_ray(x, y);
        let chain = trace_chain(model, scene, accel, ray, frame.trace(), &mut sample);
        for (i, &limit) in bounces.iter().enumerate() {
            beauty[i * pixels.len() + j] = chain.beauty(model, limit);
        }
    }
    beauty
}

/// A model the hierarchy is not exact for would get wrong hits, silently: a bug in the
/// caller, never an input's fault.
fn assert_suits(model: &impl Model, accel: &Accelerator) {
    assert!(
        model.hierarchy_exact() || accel.is_exhaustive(),
        "a model the hierarchy is not exact for was traced with the hierarchy"
    );
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
