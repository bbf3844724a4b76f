//! Rendering one scene at one size and bounce count under any candidate program ([`Variant`]):
//! the reference, a few pixels, every pixel, and the reference's layers where the term fit
//! needs them. Every whole image is checked against the memory budget before it is made: a
//! student's PNG sets the size, and a small file can claim a huge one.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use rayon::prelude::*;

use crate::check::image_cache::{ImageCache, ImageKey};
use crate::check::pixel_sample::PixelSample;
use crate::check::student_png::Rgb8;
use crate::mistakes::{Mistakes, Output, Variant};
use whitted_core::accel::Accelerator;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::frame::{Acceleration, Frame, FrameSpec};
use whitted_core::hits::tape::{bytes_per_pixel, Replay, Tape};
use whitted_core::interrupt;
use whitted_core::memory;
use whitted_core::model::Model;
use whitted_core::render::{
    record_pixels, trace_pixels, trace_pixels_at_bounces, trace_pixels_with,
};
use whitted_core::sample::Sample;
use whitted_core::scene::Scene;
use whitted_core::tonemap::ToneMap;
use whitted_io::output::png::bytes_with;

/// Rows rendered together on one core for a whole image.
const ROWS_PER_TASK: u32 = 4;

/// Bytes a check holds per pixel of the image at its peak: the student's image, the
/// reference, one candidate's whole image and its heat map (3 bytes each), the wrong-pixel
/// list (8), and a whole image's f64 beauty for the rows being traced, rounded up generously
/// for the allocator.
const BYTES_PER_PIXEL: u64 = 48;

/// The most bytes one list of recorded searches may take (`Renderer::searches_at`): a
/// check's sample and lattice at the course's sizes take a few MiB.
const TAPE_BUDGET: u64 = 64 << 20;

/// Whether a strip of rows (its first row, its bytes at each bounce count) differs from what
/// it was to be: rendering stops at the first that does.
type StripTest<'a> = dyn Fn(u32, &[Vec<u8>]) -> bool + Sync + 'a;

/// A scene many checks share (a class's suite), for the run's cache of whole images.
#[derive(Clone)]
pub struct SharedScene {
    /// The scene's XML fingerprint.
    pub key: String,
    /// The bounce counts of the suite's cases of this scene at the student's size.
    pub bounce_family: Vec<u32>,
    /// The run's images.
    pub cache: Arc<ImageCache>,
    /// Whether candidates' sample lattices are kept too: a class's students share them, a
    /// single check asks for each once and would only pay to keep it.
    pub samples: bool,
}

/// The cache a renderer keeps its images in, and under which scene.
struct Kept {
    /// The scene's name in the cache.
    scene: String,
    cache: Arc<ImageCache>,
    /// Whether sample lattices are kept too (`SharedScene::samples`).
    samples: bool,
}

/// Renders one scene at one size and bounce count under any candidate.
pub struct Renderer<'a> {
    pub scene: &'a Scene,
    /// Where this renderer's images are kept (`image_cache.rs`); None renders every time.
    shared: Option<Kept>,
    /// The bounce counts whose whole images are rendered together when one is asked for
    /// (this case's, and the suite's other cases of the scene at this size), ascending.
    bounce_family: Vec<u32>,
    spec: FrameSpec,
    bvh: Accelerator,
    brute: Accelerator,
}

/// The bytes a program writing `output` under `course` makes of linear `beauty`.
fn program_bytes(course: Course, output: Output, beauty: &[glam::DVec3]) -> Vec<u8> {
    let tonemap = course.tonemap();
    match output {
        Output::Course => bytes_with(tonemap, beauty),
        Output::Untonemapped => bytes_with(ToneMap::Tick, beauty),
        Output::Twice => {
            let once: Vec<glam::DVec3> = beauty.iter().map(|&v| tonemap.apply(v)).collect();
            bytes_with(tonemap, &once)
        }
    }
}

impl<'a> Renderer<'a> {
    /// Refuses a size whose check would not fit in the memory this process may use.
    pub fn new(scene: &'a Scene, width: u32, height: u32, bounces: u32) -> Result<Self> {
        let pixels = u64::from(width) * u64::from(height);
        memory::check(
            pixels.saturating_mul(BYTES_PER_PIXEL),
            memory::available_bytes(),
            &format!("checking a {width}x{height} image"),
        )?;
        let spec = FrameSpec::tick(width, height, bounces, true);
        Frame::new(scene, &spec)?;
        Ok(Renderer {
            scene,
            shared: None,
            bounce_family: vec![spec.bounces],
            spec,
            bvh: Accelerator::build(&scene.objects),
            brute: Accelerator::brute_force(&scene.objects),
        })
    }

    /// This renderer's whole images kept for any other renderer of the same shared scene: a
    /// class's students share the suite's renders. A whole image at one of the scene's bounce
    /// counts is rendered with the others, from one trace per pixel, where memory allows.
    pub fn remembered_as(mut self, shared: Option<SharedScene>) -> Self {
        let Some(shared) = shared else {
            return self;
        };
        let mut family = shared.bounce_family;
        family.push(self.spec.bounces);
        family.sort_unstable();
        family.dedup();
        let pixels = u64::from(self.spec.width) * u64::from(self.spec.height);
        let extra = pixels.saturating_mul(3 * (family.len() as u64 - 1));
        let budget = pixels.saturating_mul(BYTES_PER_PIXEL).saturating_add(extra);
        if memory::check(budget, memory::available_bytes(), "").is_ok() {
            self.bounce_family = family;
        }
        self.shared = Some(Kept {
            scene: shared.key,
            cache: shared.cache,
            samples: shared.samples,
        });
        self
    }

    /// This renderer for `course`: its rules, camera and tone map (every candidate is
    /// rendered under them).
    pub fn in_course(mut self, course: Course) -> Self {
        self.spec.course = course;
        self
    }

    /// The year whose rules this renderer follows.
    pub fn course(&self) -> Course {
        self.spec.course
    }

    fn size(&self) -> (u32, u32) {
        (self.spec.width, self.spec.height)
    }

    /// The cache's name for `variant`'s (None: the course's model) whole image of `scene` at
    /// this size and `bounces`.
    fn image_key(&self, scene: &str, bounces: u32, variant: Option<&Variant>) -> ImageKey {
        ImageKey::of(scene, self.size(), bounces, variant, self.course())
    }

    pub fn width(&self) -> u32 {
        self.spec.width
    }

    pub fn height(&self) -> u32 {
        self.spec.height
    }

    pub fn bounces(&self) -> u32 {
        self.spec.bounces
    }

    /// The frame a program with `mistakes` renders (its bounce count and shadow switch).
    pub fn frame(&self, mistakes: Mistakes) -> Result<Frame> {
        Frame::new(self.scene, &mistakes.frame_spec(&self.spec))
    }

    /// The hierarchy where it is exact for `variant`'s rules, else brute force.
    fn accelerator(&self, frame: &Frame) -> &Accelerator {
        // `Mistakes::frame_spec` asks for brute force where the model needs it.
        match frame.acceleration() {
            Acceleration::Bvh => &self.bvh,
            Acceleration::BruteForce => &self.brute,
        }
    }

    /// The tick bytes of `pixels` under `model` in `frame` (sequential: callers run many
    /// candidates side by side); an error when the user stopped the run half-way.
    pub fn bytes_at(
        &self,
        variant: &Variant,
        frame: &Frame,
        pixels: &[(u32, u32)],
    ) -> Result<Vec<u8>> {
        self.bytes_replaying(variant, frame, pixels, None)
    }

    /// `bytes_at`, with the hit searches the course's trace of `pixels` recorded
    /// (`searches_at`, one tape per pixel) answering those of `variant`'s rays that are the
    /// same, where it intersects as the course does: most candidates differ from the course
    /// in their shading only, and searching is half a trace.
    pub(crate) fn bytes_replaying(
        &self,
        variant: &Variant,
        frame: &Frame,
        pixels: &[(u32, u32)],
        searches: Option<&[Tape]>,
    ) -> Result<Vec<u8>> {
        let accel = self.accelerator(frame);
        let model = variant.in_course(self.course());
        let keep = |s: &Sample| s.beauty;
        // A tape per pixel, or none used (a recording the user stopped half-way is shorter).
        let usable =
            |tapes: &&[Tape]| tapes.len() >= pixels.len() && variant.intersects_as_course();
        let beauty = match searches.filter(usable) {
            Some(tapes) => {
                let hits = |j: usize| Replay::new(accel, &tapes[j]);
                trace_pixels_with::<false, _, _>(&model, self.scene, frame, pixels, hits, keep)
            }
            None => trace_pixels::<false, _>(&model, self.scene, accel, frame, pixels, keep),
        };
        interrupt::check()?;
        Ok(program_bytes(self.course(), variant.output(), &beauty))
    }

    /// The hit searches of the course's trace (the program with no mistake) of each of
    /// `pixels`, for `sample_bytes` to share with the candidates; none where they could
    /// take more than `TAPE_BUDGET` (a scene of thousands of lights), and then every
    /// candidate searches for itself.
    pub fn searches_at(&self, pixels: &[(u32, u32)]) -> Result<Vec<Tape>> {
        let frame = self.frame(Mistakes::NONE)?;
        let most = bytes_per_pixel(self.scene.lights.len(), frame.trace().bounces)
            .saturating_mul(pixels.len() as u64);
        if most > TAPE_BUDGET {
            return Ok(Vec::new());
        }
        let model = Variant::from(Mistakes::NONE).in_course(self.course());
        let tapes = record_pixels(&model, self.scene, self.accelerator(&frame), &frame, pixels);
        interrupt::check()?;
        Ok(tapes)
    }

    /// `variant`'s bytes at `sample`'s positions: the wrong pixels rendered, the right ones
    /// picked from its lattice's bytes.
    pub fn sample_bytes(
        &self,
        variant: &Variant,
        frame: &Frame,
        sample: &PixelSample,
    ) -> Result<Vec<u8>> {
        let searches = Some(&sample.searches[..]);
        let Some(lattice) = self.lattice_bytes(variant, frame, sample)? else {
            return self.bytes_replaying(variant, frame, &sample.positions, searches);
        };
        let wrong = &sample.positions[..sample.wrong];
        let mut bytes = self.bytes_replaying(variant, frame, wrong, searches)?;
        for &k in &sample.right_in_lattice {
            bytes.extend_from_slice(&lattice.bytes[3 * k..3 * k + 3]);
        }
        Ok(bytes)
    }

    /// Whether this renderer keeps candidates' bytes on a sample's lattice
    /// (`SharedScene::samples`): only then are the course's searches there worth recording.
    pub fn keeps_lattices(&self) -> bool {
        self.shared.as_ref().is_some_and(|k| k.samples)
    }

    /// `variant`'s bytes on the whole of `sample`'s lattice, rendered once per class and kept
    /// with the whole images; None where little would be shared: a single check
    /// (`SharedScene::samples`), a fitted number, a triple (each student's beam extends their
    /// own best pairs).
    fn lattice_bytes(
        &self,
        variant: &Variant,
        frame: &Frame,
        sample: &PixelSample,
    ) -> Result<Option<Rgb8>> {
        let shared = variant.number.is_none() && variant.mistakes.len() <= 2;
        let Some(Kept { scene, cache, .. }) = self.shared.as_ref().filter(|k| shared && k.samples)
        else {
            return Ok(None);
        };
        let lattice = &sample.lattice;
        let key = ImageKey {
            lattice: Some(lattice.len()),
            ..self.image_key(scene, self.spec.bounces, Some(variant))
        };
        // Empty where this renderer does not keep lattices: then not used.
        let searches = Some(&sample.lattice_searches[..]);
        let render = || {
            Ok(Rgb8 {
                width: lattice.len() as u32,
                height: 1,
                bytes: self.bytes_replaying(variant, frame, lattice, searches)?,
            })
        };
        cache.get_or_render(key, render).map(Some)
    }

    /// The whole images under `model` in `frame` at each of `bounces` (each at most the
    /// frame's), from one trace per pixel, on every core. None as soon as `differs` says of a
    /// strip (its first row, its bytes at each of `bounces`) that it is not what it was to
    /// be: the strips not yet begun are then skipped.
    fn images_with(
        &self,
        model: &impl Model,
        output: Output,
        frame: &Frame,
        bounces: &[u32],
        differs: &StripTest<'_>,
    ) -> Result<Option<Vec<Rgb8>>> {
        let (width, height) = (self.spec.width, self.spec.height);
        let accel = self.accelerator(frame);
        let starts: Vec<u32> = (0..height).step_by(ROWS_PER_TASK as usize).collect();
        let stopped = AtomicBool::new(false);
        // Per strip, each bounce count's bytes.
        let strips: Vec<Vec<Vec<u8>>> = starts
            .par_iter()
            .map(|&y0| {
                if stopped.load(Ordering::Relaxed) {
                    return Ok(Vec::new());
                }
                let rows = y0..(y0 + ROWS_PER_TASK).min(height);
                let pixels: Vec<(u32, u32)> =
                    rows.flat_map(|y| (0..width).map(move |x| (x, y))).collect();
                let beauty =
                    trace_pixels_at_bounces(model, self.scene, accel, frame, &pixels, bounces);
                interrupt::check()?;
                let n = pixels.len();
                let bytes: Vec<Vec<u8>> = (0..bounces.len())
                    .map(|i| program_bytes(self.course(), output, &beauty[i * n..(i + 1) * n]))
                    .collect();
                if differs(y0, &bytes) {
                    stopped.store(true, Ordering::Relaxed);
                }
                Ok(bytes)
            })
            .collect::<Result<_>>()?;
        if stopped.into_inner() {
            return Ok(None);
        }
        Ok(Some(
            (0..bounces.len())
                .map(|i| Rgb8 {
                    width,
                    height,
                    bytes: strips.iter().flat_map(|s| s[i].iter().copied()).collect(),
                })
                .collect(),
        ))
    }

    /// The whole images of `variant` (None: the course's model) at each of `bounces` (as
    /// asked of the program, ascending), from one trace per pixel; None where `differs`
    /// stopped them (`images_with`).
    fn images_until(
        &self,
        variant: Option<&Variant>,
        bounces: &[u32],
        differs: &StripTest<'_>,
    ) -> Result<Option<Vec<Rgb8>>> {
        let mistakes = variant.map_or(Mistakes::NONE, |v| v.mistakes);
        // What a program with `mistakes` traces when asked for `bounces`.
        let asked = |bounces| {
            mistakes.frame_spec(&FrameSpec {
                bounces,
                ..self.spec.clone()
            })
        };
        let deepest = bounces.last().copied().unwrap_or(self.spec.bounces);
        let frame = Frame::new(self.scene, &asked(deepest))?;
        let traced: Vec<u32> = bounces.iter().map(|&b| asked(b).bounces).collect();
        let course = self.course();
        match variant {
            None if course.is_default() => self.images_with(
                &whitted_core::model::Tick,
                Output::Course,
                &frame,
                &traced,
                differs,
            ),
            None => self.images_with(&course.rules(), Output::Course, &frame, &traced, differs),
            Some(v) => self.images_with(&v.in_course(course), v.output(), &frame, &traced, differs),
        }
    }

    /// The whole images of `variant` (None: the course's model) at each of `bounces` (as
    /// asked of the program, ascending), from one trace per pixel.
    fn images_at(&self, variant: Option<&Variant>, bounces: &[u32]) -> Result<Vec<Rgb8>> {
        // Nothing stops them: always whole.
        let whole = self.images_until(variant, bounces, &|_, _| false)?;
        Ok(whole.unwrap_or_default())
    }

    /// The whole image of `variant` (None: the course's model), from the cache when this
    /// renderer's scene has a key, rendered with the rest of its bounce family.
    fn remembered(&self, variant: Option<&Variant>) -> Result<Rgb8> {
        let own = self
            .bounce_family
            .iter()
            .position(|&b| b == self.spec.bounces);
        let (Some(Kept { scene, cache, .. }), Some(own)) = (&self.shared, own) else {
            let mut images = self.images_at(variant, &[self.spec.bounces])?;
            return Ok(images.swap_remove(0));
        };
        let key = |bounces| self.image_key(scene, bounces, variant);
        cache.get_or_render_family(key(self.spec.bounces), || {
            // The others are worth their deeper trace only if the cache can keep them.
            let family_bytes = (3 * self.bounce_family.len())
                .saturating_mul(self.spec.width as usize)
                .saturating_mul(self.spec.height as usize);
            if !cache.has_room(family_bytes) {
                let mut images = self.images_at(variant, &[self.spec.bounces])?;
                return Ok((images.swap_remove(0), Vec::new()));
            }
            let mut images = self.images_at(variant, &self.bounce_family)?;
            let image = images.remove(own);
            let mut others = self.bounce_family.clone();
            others.remove(own);
            Ok((image, others.into_iter().map(key).zip(images).collect()))
        })
    }

    /// The reference: the course's model.
    pub fn reference(&self) -> Result<Rgb8> {
        self.remembered(None)
    }

    /// Whether `variant` renders this case byte for byte as `base` does, and the suite's other
    /// cases of this scene at this size too where `base`'s are kept (all from one trace per
    /// pixel). Strip by strip, stopping at the first strip that differs: a candidate that
    /// renders otherwise costs a fraction of a whole render. Images found equal are kept for
    /// the class. `base_image` is `base`'s image of this case (the caller renders it once for
    /// every candidate it asks about).
    pub fn renders_as(&self, variant: &Variant, base: &Variant, base_image: &Rgb8) -> Result<bool> {
        let own = self.spec.bounces;
        let kept = self.shared.as_ref();
        let get = |v, b| kept.and_then(|k| k.cache.get(&self.image_key(&k.scene, b, Some(v))));
        // `base`'s images at the family's other bounce counts, where they are kept.
        let others: Vec<(u32, Rgb8)> = self
            .bounce_family
            .iter()
            .filter(|&&b| b != own)
            .filter_map(|&b| get(base, b).map(|image| (b, image)))
            .collect();
        let mut family: Vec<(u32, &Rgb8)> = others.iter().map(|(b, image)| (*b, image)).collect();
        family.push((own, base_image));
        family.sort_by_key(|&(b, _)| b);
        // Rendered before: compared as kept, over the same bounce counts.
        let found: Option<Vec<Rgb8>> = family.iter().map(|&(b, _)| get(variant, b)).collect();
        if let Some(found) = found {
            return Ok(found
                .iter()
                .zip(&family)
                .all(|(v, (_, b))| v.bytes == b.bytes));
        }
        let width = self.spec.width as usize;
        let differs = |y0: u32, strips: &[Vec<u8>]| {
            let at = 3 * width * y0 as usize;
            strips.iter().zip(&family).any(|(strip, (_, image))| {
                image.bytes.get(at..at + strip.len()) != Some(strip.as_slice())
            })
        };
        let bounces: Vec<u32> = family.iter().map(|&(b, _)| b).collect();
        let Some(images) = self.images_until(Some(variant), &bounces, &differs)? else {
            return Ok(false);
        };
        if let Some(k) = kept {
            let keys = bounces
                .iter()
                .map(|&b| self.image_key(&k.scene, b, Some(variant)));
            k.cache.keep(keys.zip(images));
        }
        Ok(true)
    }

    /// The whole image a program with `mistakes` renders.
    pub fn image(&self, mistakes: Mistakes) -> Result<Rgb8> {
        self.variant_image(&Variant::from(mistakes))
    }

    /// The whole image `variant` renders.
    pub fn variant_image(&self, variant: &Variant) -> Result<Rgb8> {
        self.remembered(Some(variant))
    }

    /// The object (its index in the scene) each of `pixels` shows in the reference, None for
    /// the background: where a difference lies.
    pub fn objects_at(&self, pixels: &[(u32, u32)]) -> Result<Vec<Option<usize>>> {
        let frame = self.frame(Mistakes::NONE)?;
        let accel = self.accelerator(&frame);
        let rules = self.course().rules();
        Ok(pixels
            .iter()
            .map(|&(x, y)| {
                let ray = frame.camera().pixel_centre_ray(x, y);
                accel.closest_hit(&rules, &ray).map(|hit| hit.object)
            })
            .collect())
    }

    /// The reference's every layer at `pixels` (for the term fit).
    pub fn layers_at(&self, pixels: &[(u32, u32)]) -> Result<Vec<Sample>> {
        let frame = self.frame(Mistakes::NONE)?;
        let accel = self.accelerator(&frame);
        let samples = trace_pixels::<true, _>(
            &self.course().rules(),
            self.scene,
            accel,
            &frame,
            pixels,
            Sample::clone,
        );
        interrupt::check()?;
        Ok(samples)
    }
}
