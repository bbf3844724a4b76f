//! The converged references of Tick 1* scenes (`whitted_core::star::expectation`: per pixel
//! the expectation of the course's process and the variance of one draw), kept in memory for
//! a run that checks many students' images of the same scene, and on disk
//! (`star_reference_file.rs`) for the next run: a reference takes seconds to minutes, the
//! statistic on a kept one milliseconds.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use crate::check::star_reference_file as file;
use whitted_core::error::Result;
use whitted_core::progress::Bar;
use whitted_core::scene::Scene;
use whitted_core::star::{expectation_counted, Grid, NoiseFloor, Star, StarFrame, StarImage};

/// Whether a reference being computed shows a bar (`show_progress`).
static SHOW_PROGRESS: AtomicBool = AtomicBool::new(false);

/// Shows a progress bar on stderr while a reference is computed, from now on in this process:
/// `whitted check`, where one person waits up to a minute for a whole reference the first
/// time. The bar appears only after half a second and only on a terminal
/// (`whitted_core::progress::Bar`); grade and serve, which draw their own, never call this.
pub fn show_progress() {
    SHOW_PROGRESS.store(true, Ordering::Relaxed);
}

/// What the memory may hold, in bytes of references (a 640x480 one is about 35 MB); past it,
/// new references are not kept in memory (they still are on disk).
const MEMORY_BYTES: usize = 512 << 20;

/// What a reference is of: equal keys are equal frames and equal estimates. Floats are kept
/// as their bits (equal bits, equal arithmetic).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ReferenceKey {
    /// The scene's fingerprint (`fingerprint`), with its bump maps' if any.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub bounces: u32,
    pub shadows: bool,
    pub course: &'static str,
    /// Everything of the `Star` but its maps, as text (its floats printed exactly).
    pub star: String,
    pub floor_bits: u64,
    pub max_paths: u32,
    pub seed: u64,
    /// The pixels estimated (`Grid`): every one, or a pre-pass's sparse grid.
    pub grid: Grid,
}

impl ReferenceKey {
    /// The key of `frame`'s reference estimated to `floor` with `seed`; `scene` names the
    /// scene and its maps.
    pub fn of(scene: &str, frame: &StarFrame, floor: NoiseFloor, seed: u64) -> Self {
        let star = frame.star;
        ReferenceKey {
            scene: scene.to_string(),
            width: frame.camera.width,
            height: frame.camera.height,
            bounces: frame.trace.bounces,
            shadows: frame.trace.shadows,
            course: frame.course.name(),
            // Debug prints f64 exactly (shortest round-trip form).
            star: format!("{:?} {:?} {:?}", star.soft, star.dof, star.bump),
            floor_bits: floor.standard_error.to_bits(),
            max_paths: floor.max_paths,
            seed,
            grid: Grid::EVERY,
        }
    }

    /// The key of the same reference estimated at `grid`'s pixels only.
    pub fn on(self, grid: Grid) -> Self {
        ReferenceKey { grid, ..self }
    }

    /// The key of `frame`'s reference, its scene fingerprinted from the frame itself.
    pub fn of_frame(frame: &StarFrame, floor: NoiseFloor, seed: u64) -> Self {
        ReferenceKey::of(&fingerprint(frame.scene, frame.star), frame, floor, seed)
    }

    /// The key as the disk cache's text: every field, and the build of whitted that
    /// computes the reference (`star_reference_file::build`).
    pub fn text(&self) -> String {
        format!(
            "scene {} size {}x{} bounces {} shadows {} course {} star {} floor {:016x} \
             max-paths {} seed {} grid {} build {}",
            self.scene,
            self.width,
            self.height,
            self.bounces,
            self.shadows,
            self.course,
            self.star,
            self.floor_bits,
            self.max_paths,
            self.seed,
            self.grid.stride,
            build()
        )
    }
}

/// The scene as parsed (every object, light, colour and number, floats exactly) and its bump
/// maps, hashed: two scenes alike in it render alike, whatever their XML's spacing.
pub fn fingerprint(scene: &Scene, star: &Star) -> String {
    let text = format!("{scene:?} {:?}", star.bumps);
    format!("{:016x}-{}", file::fnv(text.as_bytes()), text.len())
}

/// This build, computed once (it reads the executable's metadata).
fn build() -> &'static str {
    static BUILD: OnceLock<String> = OnceLock::new();
    BUILD.get_or_init(file::build)
}

/// References computed or read in this run, shared between threads, and the folder they are
/// kept in between runs.
#[derive(Default)]
pub struct ReferenceCache {
    kept: Mutex<Kept>,
    folder: Option<PathBuf>,
}

#[derive(Default)]
struct Kept {
    images: HashMap<ReferenceKey, Arc<StarImage>>,
    bytes: usize,
}

impl ReferenceCache {
    /// A cache in memory only.
    pub fn new() -> Self {
        ReferenceCache::default()
    }

    /// A cache in memory and in `folder` (None: memory only).
    pub fn in_folder(folder: Option<PathBuf>) -> Self {
        ReferenceCache {
            folder,
            ..ReferenceCache::default()
        }
    }

    /// The process's cache, in the user's cache folder (`star_reference_file::default_folder`).
    pub fn shared() -> &'static ReferenceCache {
        static SHARED: OnceLock<ReferenceCache> = OnceLock::new();
        SHARED.get_or_init(|| ReferenceCache::in_folder(file::default_folder()))
    }

    /// The reference of `frame` under `key`: from memory, else from disk, else computed (and
    /// then kept in both).
    pub fn get_or_compute(
        &self,
        key: ReferenceKey,
        frame: &StarFrame,
        floor: NoiseFloor,
        seed: u64,
    ) -> Result<Arc<StarImage>> {
        if let Some(found) = self.lock().images.get(&key) {
            return Ok(Arc::clone(found));
        }
        let text = key.text();
        let from_disk = self
            .folder
            .as_deref()
            .and_then(|folder| file::load(folder, &text));
        // Computed without the lock: other references may be computed meanwhile.
        let image = match from_disk {
            Some(image) => Arc::new(image),
            None => {
                let image = Arc::new(compute(&key, frame, floor, seed)?);
                if let Some(folder) = &self.folder {
                    file::store(folder, &text, &image);
                }
                image
            }
        };
        let mut kept = self.lock();
        if let Some(found) = kept.images.get(&key) {
            return Ok(Arc::clone(found));
        }
        let bytes = size_of(&image);
        if kept.bytes + bytes <= MEMORY_BYTES {
            kept.bytes += bytes;
            kept.images.insert(key, Arc::clone(&image));
        }
        Ok(image)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Kept> {
        // A panic while holding the lock left the map whole: keep using it.
        self.kept
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// The reference of `key`, computed; with a bar when `show_progress` was called.
fn compute(
    key: &ReferenceKey,
    frame: &StarFrame,
    floor: NoiseFloor,
    seed: u64,
) -> Result<StarImage> {
    let shown = SHOW_PROGRESS.load(Ordering::Relaxed);
    let rows = key.grid.count(key.height);
    let what = match key.grid == Grid::EVERY {
        true => format!(
            "reference {}x{} (kept for next time)",
            key.width, key.height
        ),
        false => format!(
            "reference {}x{}, 1 px in {}x{} (kept for next time)",
            key.width, key.height, key.grid.stride, key.grid.stride
        ),
    };
    let bar = Bar::counting(u64::from(rows), !shown, &what, "rows");
    let image = expectation_counted(frame, (floor, seed), key.grid, &|| bar.advance(1))?;
    bar.finish();
    Ok(image)
}

/// The bytes `image` holds, about.
fn size_of(image: &StarImage) -> usize {
    let pixels = image.beauty.len();
    pixels * (4 * 24 + 4 * (3 + image.visible.len()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use std::time::Instant;
    use whitted_core::camera::Camera;
    use whitted_core::course::Course;
    use whitted_core::scene::input::parse_with_bumps;
    use whitted_core::star::{DepthOfField, SoftShadows, Star};
    use whitted_core::trace::TraceOptions;

    #[test]
    fn a_reference_is_computed_once_and_the_statistic_on_it_is_quick() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes/courses/tick1star/distributed.xml");
        let xml = std::fs::read(root).expect("distributed.xml");
        let (scene, _, _) =
            parse_with_bumps("distributed.xml", &xml, Course::Y2020).expect("reads");
        let star = Star {
            soft: Some(SoftShadows::default()),
            dof: Some(DepthOfField::default()),
            ..Star::default()
        };
        let frame = StarFrame {
            scene: &scene,
            camera: Camera::with_rows(40, 30, Course::Y2020.row_step()),
            course: Course::Y2020,
            trace: TraceOptions {
                bounces: 2,
                shadows: true,
            },
            star: &star,
        };
        let floor = NoiseFloor {
            standard_error: 2.0 / 255.0,
            max_paths: 256,
        };
        let folder = tempfile::tempdir().expect("tempdir");
        let cache = ReferenceCache::in_folder(Some(folder.path().to_path_buf()));
        let key = ReferenceKey::of_frame(&frame, floor, 1);
        let first = cache
            .get_or_compute(key.clone(), &frame, floor, 1)
            .expect("computes");
        let draw = whitted_core::star::course_draw(&frame, 9).expect("draws");
        let started = Instant::now();
        let again = cache
            .get_or_compute(key.clone(), &frame, floor, 1)
            .expect("cached");
        assert!(Arc::ptr_eq(&first, &again));
        // Another run (a new cache on the same folder) reads it back bit for bit.
        let next_run = ReferenceCache::in_folder(Some(folder.path().to_path_buf()));
        let read = next_run
            .get_or_compute(key, &frame, floor, 1)
            .expect("read");
        assert_eq!(*read, *first);
        // The statistic over a whole image: a z-score per channel of a course draw.
        let sum_z2: f64 = draw
            .beauty
            .iter()
            .zip(first.beauty.iter().zip(&first.variance))
            .map(|(d, (m, v))| {
                let var = *v + DVec3::splat(1e-12);
                ((*d - *m) * (*d - *m) / var).element_sum()
            })
            .sum();
        assert!(started.elapsed().as_secs_f64() < 2.0, "statistic too slow");
        assert!(sum_z2.is_finite());
        let other = ReferenceKey::of_frame(&frame, floor, 2);
        assert_ne!(other, ReferenceKey::of_frame(&frame, floor, 1));
        // Another scene (the light moved) is another key.
        let mut moved = scene.clone();
        moved.lights[0].position.x += 1e-9;
        let frame2 = StarFrame {
            scene: &moved,
            ..frame
        };
        assert_ne!(
            ReferenceKey::of_frame(&frame2, floor, 1).text(),
            ReferenceKey::of_frame(&frame, floor, 1).text()
        );
    }
}
