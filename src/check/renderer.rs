//! Rendering one scene at one size and bounce count under any candidate program ([`Variant`]):
//! the reference, a few pixels, every pixel, and the reference's layers where the term fit
//! needs them. Every whole image is checked against the memory budget before it is made: a
//! student's PNG sets the size, and a small file can claim a huge one.

use rayon::prelude::*;

use crate::accel::Accelerator;
use crate::check::case::PixelSample;
use crate::check::student_png::Rgb8;
use crate::error::Result;
use crate::frame::{Acceleration, Frame, FrameSpec};
use crate::interrupt;
use crate::memory;
use crate::mistakes::{Mistakes, Variant};
use crate::model::Model;
use crate::output::png::tick_bytes;
use crate::render::trace_pixels;
use crate::sample::Sample;
use crate::scene::Scene;

/// Rows rendered together on one core for a whole image.
const ROWS_PER_TASK: u32 = 4;

/// Bytes a check holds per pixel of the image at its peak: the student's image, the
/// reference, one candidate's whole image and its heat map (3 bytes each), the wrong-pixel
/// list (8), and a whole image's f64 beauty for the rows being traced, rounded up generously
/// for the allocator.
const BYTES_PER_PIXEL: u64 = 48;

/// Renders one scene at one size and bounce count under any candidate.
pub struct Renderer<'a> {
    pub scene: &'a Scene,
    /// Names the scene for the image cache (`image_cache.rs`); None renders every time.
    scene_key: Option<String>,
    spec: FrameSpec,
    bvh: Accelerator,
    brute: Accelerator,
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
            scene_key: None,
            spec,
            bvh: Accelerator::build(&scene.objects),
            brute: Accelerator::brute_force(&scene.objects),
        })
    }

    /// This renderer's whole images kept for any other renderer of the scene `key` names
    /// (its XML's fingerprint): a class's students share the suite's renders.
    pub fn remembered_as(mut self, key: Option<String>) -> Self {
        self.scene_key = key;
        self
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
        model: &impl Model,
        frame: &Frame,
        pixels: &[(u32, u32)],
    ) -> Result<Vec<u8>> {
        let accel = self.accelerator(frame);
        let beauty =
            trace_pixels::<false, _>(model, self.scene, accel, frame, pixels, |s| s.beauty);
        interrupt::check()?;
        Ok(tick_bytes(&beauty))
    }

    /// `variant`'s bytes at `sample`'s positions: the wrong pixels rendered, the right ones
    /// picked from its lattice's bytes.
    pub fn sample_bytes(
        &self,
        variant: &Variant,
        frame: &Frame,
        sample: &PixelSample,
    ) -> Result<Vec<u8>> {
        let Some(lattice) = self.lattice_bytes(variant, frame, &sample.lattice)? else {
            return self.bytes_at(variant, frame, &sample.positions);
        };
        let mut bytes = self.bytes_at(variant, frame, &sample.positions[..sample.wrong])?;
        for &k in &sample.right_in_lattice {
            bytes.extend_from_slice(&lattice.bytes[3 * k..3 * k + 3]);
        }
        Ok(bytes)
    }

    /// `variant`'s bytes on the whole `lattice`, rendered once per class and kept with the
    /// whole images; None where little would be shared: a single check, a fitted number, a
    /// triple (each student's beam extends their own best pairs).
    fn lattice_bytes(
        &self,
        variant: &Variant,
        frame: &Frame,
        lattice: &[(u32, u32)],
    ) -> Result<Option<Rgb8>> {
        let shared = variant.number.is_none() && variant.mistakes.len() <= 2;
        let Some(scene) = self.scene_key.as_ref().filter(|_| shared) else {
            return Ok(None);
        };
        let key = format!(
            "{scene} {:?} {variant:?} lattice of {}",
            self.spec,
            lattice.len()
        );
        let render = || {
            Ok(Rgb8 {
                width: lattice.len() as u32,
                height: 1,
                bytes: self.bytes_at(variant, frame, lattice)?,
            })
        };
        crate::check::image_cache::get_or_render(key, render).map(Some)
    }

    /// The whole image under `model` in `frame`, on every core.
    fn image_with(&self, model: &impl Model, frame: &Frame) -> Result<Rgb8> {
        let (width, height) = (self.spec.width, self.spec.height);
        let starts: Vec<u32> = (0..height).step_by(ROWS_PER_TASK as usize).collect();
        let strips: Vec<Vec<u8>> = starts
            .par_iter()
            .map(|&y0| {
                let rows = y0..(y0 + ROWS_PER_TASK).min(height);
                let pixels: Vec<(u32, u32)> =
                    rows.flat_map(|y| (0..width).map(move |x| (x, y))).collect();
                self.bytes_at(model, frame, &pixels)
            })
            .collect::<Result<_>>()?;
        Ok(Rgb8 {
            width,
            height,
            bytes: strips.concat(),
        })
    }

    /// The whole image of `variant` (None: the course's model), from the cache when this
    /// renderer's scene has a key.
    fn remembered(&self, variant: Option<&Variant>) -> Result<Rgb8> {
        let render = || match variant {
            None => self.image_with(&crate::model::Tick, &self.frame(Mistakes::NONE)?),
            Some(v) => self.image_with(v, &self.frame(v.mistakes)?),
        };
        match &self.scene_key {
            None => render(),
            Some(scene) => {
                // Debug prints a number's exact value: equal keys are equal programs.
                let key = format!("{scene} {:?} {variant:?}", self.spec);
                crate::check::image_cache::get_or_render(key, render)
            }
        }
    }

    /// The reference: the course's model.
    pub fn reference(&self) -> Result<Rgb8> {
        self.remembered(None)
    }

    /// The whole image a program with `mistakes` renders.
    pub fn image(&self, mistakes: Mistakes) -> Result<Rgb8> {
        self.variant_image(&Variant::from(mistakes))
    }

    /// The whole image `variant` renders.
    pub fn variant_image(&self, variant: &Variant) -> Result<Rgb8> {
        self.remembered(Some(variant))
    }

    /// The reference's every layer at `pixels` (for the term fit).
    pub fn layers_at(&self, pixels: &[(u32, u32)]) -> Result<Vec<Sample>> {
        let frame = self.frame(Mistakes::NONE)?;
        let accel = self.accelerator(&frame);
        let samples = trace_pixels::<true, _>(
            &crate::model::Tick,
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
