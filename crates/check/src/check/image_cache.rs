//! Whole images already rendered in this process, by scene, size, bounces and candidate
//! program. A class graded at once (`whitted grade`) checks every student against the same
//! suite: the references and the common mistakes' images are the same for all of them, so
//! each is rendered once per class, not once per student. Only renderers given a scene key
//! (the suite's scenes, by their XML) use it; a single check has nothing to share.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use crate::check::student_png::Rgb8;
use whitted_core::error::Result;

/// What the cache may hold: about 400 images of 640x480. Past it, new images are not kept
/// (the first students' are, and the references come first).
const LIMIT_BYTES: usize = 384 << 20;

#[derive(Default)]
struct Cache {
    images: HashMap<String, Arc<Rgb8>>,
    bytes: usize,
}

fn cache() -> &'static Mutex<Cache> {
    static CACHE: OnceLock<Mutex<Cache>> = OnceLock::new();
    CACHE.get_or_init(Mutex::default)
}

/// The image under `key`, rendered by `render` when it is not there yet. Two threads that
/// ask for one key at once may both render it: the result is the same.
pub fn get_or_render(key: String, render: impl FnOnce() -> Result<Rgb8>) -> Result<Rgb8> {
    get_or_render_family(key, || Ok((render()?, Vec::new())))
}

/// The image under `key`; when it is not there yet, `render` makes it together with others
/// that cost little more to make at once (the same scene's images at other bounce counts),
/// and all are kept.
pub fn get_or_render_family(
    key: String,
    render: impl FnOnce() -> Result<(Rgb8, Vec<(String, Rgb8)>)>,
) -> Result<Rgb8> {
    if let Some(found) = lock().images.get(&key) {
        return Ok(Rgb8::clone(found));
    }
    let (image, others) = render()?;
    let mut cache = lock();
    for (name, kept) in [(key, image.clone())].into_iter().chain(others) {
        if cache.bytes + kept.bytes.len() <= LIMIT_BYTES && !cache.images.contains_key(&name) {
            cache.bytes += kept.bytes.len();
            cache.images.insert(name, Arc::new(kept));
        }
    }
    Ok(image)
}

/// Whether `bytes` more of images would be kept now.
pub fn has_room(bytes: usize) -> bool {
    lock().bytes.saturating_add(bytes) <= LIMIT_BYTES
}

/// The cache, even if a thread panicked while holding it (it holds finished images only).
fn lock() -> std::sync::MutexGuard<'static, Cache> {
    cache().lock().unwrap_or_else(|e| e.into_inner())
}
