//! Whole images already rendered in one run, by scene, size, bounces and candidate program. A
//! class graded at once (`whitted grade`) checks every student against the same suite: the
//! references and the common mistakes' images are the same for all of them, so each is
//! rendered once per class, not once per student. The run that checks (`check --program`, a
//! class's grading) owns the cache and hands it to the renderers of its suite's scenes; a single
//! check has nothing to share and has none.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, MutexGuard};

use crate::check::student_png::Rgb8;
use crate::mistakes::{Mistakes, Parameter, Rounding, Variant};
use whitted_core::course::Course;
use whitted_core::error::Result;

/// What the cache may hold: about 400 images of 640x480. Past it, new images are not kept
/// (the first students' are, and the references come first).
const LIMIT_BYTES: usize = 384 << 20;

/// What an image is of: equal keys are equal programs rendering equal frames.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ImageKey {
    /// The scene's XML fingerprint.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub bounces: u32,
    pub mistakes: Mistakes,
    /// A changed number: which, and its value's bits (equal bits, equal arithmetic).
    pub number: Option<(Parameter, u64)>,
    /// `Some(n)`: the bytes at the case's lattice of `n` pixels, not the whole image.
    pub lattice: Option<usize>,
    /// How the program's rounding-dependent roots were taken.
    pub rounding: Rounding,
    /// The year whose rules rendered it.
    pub course: Course,
}

impl ImageKey {
    /// The whole image of `variant` (None: the course's model) of `scene` at this size.
    pub fn of(
        scene: &str,
        (width, height): (u32, u32),
        bounces: u32,
        variant: Option<&Variant>,
        course: Course,
    ) -> ImageKey {
        ImageKey {
            scene: scene.to_string(),
            width,
            height,
            bounces,
            mistakes: variant.map_or(Mistakes::NONE, |v| v.mistakes),
            number: variant
                .and_then(|v| v.number)
                .map(|n| (n.parameter, n.value.to_bits())),
            lattice: None,
            rounding: variant.map_or(Rounding::Exact, |v| v.rounding),
            course,
        }
    }
}

/// The images of one run, shared by its renderers (and their threads).
#[derive(Default)]
pub struct ImageCache {
    kept: Mutex<Kept>,
}

#[derive(Default)]
struct Kept {
    images: HashMap<ImageKey, Arc<Rgb8>>,
    bytes: usize,
}

impl ImageCache {
    /// An empty cache, to be shared.
    pub fn new() -> Arc<ImageCache> {
        Arc::new(ImageCache::default())
    }

    /// The image under `key`, rendered by `render` when it is not there yet. Two threads that
    /// ask for one key at once may both render it: the result is the same.
    pub fn get_or_render(
        &self,
        key: ImageKey,
        render: impl FnOnce() -> Result<Rgb8>,
    ) -> Result<Rgb8> {
        self.get_or_render_family(key, || Ok((render()?, Vec::new())))
    }

    /// The image under `key`; when it is not there yet, `render` makes it together with others
    /// that cost little more to make at once (the same scene's images at other bounce counts),
    /// and all are kept.
    pub fn get_or_render_family(
        &self,
        key: ImageKey,
        render: impl FnOnce() -> Result<(Rgb8, Vec<(ImageKey, Rgb8)>)>,
    ) -> Result<Rgb8> {
        if let Some(found) = self.lock().images.get(&key) {
            return Ok(Rgb8::clone(found));
        }
        let (image, others) = render()?;
        self.keep([(key, image.clone())].into_iter().chain(others));
        Ok(image)
    }

    /// The image under `key`, if it is kept.
    pub fn get(&self, key: &ImageKey) -> Option<Rgb8> {
        self.lock().images.get(key).map(|found| Rgb8::clone(found))
    }

    /// Keeps `images` as far as the limit allows (an image already kept stays as it is).
    pub fn keep(&self, images: impl IntoIterator<Item = (ImageKey, Rgb8)>) {
        let mut kept = self.lock();
        for (name, image) in images {
            if kept.bytes + image.bytes.len() <= LIMIT_BYTES && !kept.images.contains_key(&name) {
                kept.bytes += image.bytes.len();
                kept.images.insert(name, Arc::new(image));
            }
        }
    }

    /// Whether `bytes` more of images would be kept now.
    pub fn has_room(&self, bytes: usize) -> bool {
        self.lock().bytes.saturating_add(bytes) <= LIMIT_BYTES
    }

    /// The images, even if a thread panicked while holding them (they are finished images).
    fn lock(&self) -> MutexGuard<'_, Kept> {
        self.kept.lock().unwrap_or_else(|e| e.into_inner())
    }
}
