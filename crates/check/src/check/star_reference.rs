//! The converged references of Tick 1* scenes (`whitted_core::star::expectation`: per pixel
//! the expectation of the course's process and the variance of one draw), kept beside the
//! whole-image cache (`image_cache.rs`) for a run that checks many students' images of the
//! same scene: a reference takes minutes, the statistic on a cached one milliseconds.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use whitted_core::error::Result;
use whitted_core::star::{expectation, NoiseFloor, StarFrame, StarImage};

/// What a reference is of: equal keys are equal frames and equal estimates. Floats are kept
/// as their bits (equal bits, equal arithmetic).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ReferenceKey {
    /// The scene's XML fingerprint (as `ImageKey::scene`), with its bump maps' if any.
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
        }
    }
}

/// References computed in this run, shared between threads.
#[derive(Default)]
pub struct ReferenceCache {
    kept: Mutex<HashMap<ReferenceKey, Arc<StarImage>>>,
}

impl ReferenceCache {
    pub fn new() -> Self {
        ReferenceCache::default()
    }

    /// The reference of `frame` under `key`, computed on the first ask only.
    pub fn get_or_compute(
        &self,
        key: ReferenceKey,
        frame: &StarFrame,
        floor: NoiseFloor,
        seed: u64,
    ) -> Result<Arc<StarImage>> {
        if let Some(found) = self.lock().get(&key) {
            return Ok(Arc::clone(found));
        }
        // Computed without the lock: other references may be computed meanwhile.
        let image = Arc::new(expectation(frame, floor, seed)?);
        Ok(Arc::clone(self.lock().entry(key).or_insert(image)))
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<ReferenceKey, Arc<StarImage>>> {
        // A panic while holding the lock left the map whole: keep using it.
        self.kept
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
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
        let cache = ReferenceCache::new();
        let key = ReferenceKey::of("distributed", &frame, floor, 1);
        let first = cache
            .get_or_compute(key.clone(), &frame, floor, 1)
            .expect("computes");
        let draw = whitted_core::star::course_draw(&frame, 9).expect("draws");
        let started = Instant::now();
        let again = cache.get_or_compute(key, &frame, floor, 1).expect("cached");
        assert!(Arc::ptr_eq(&first, &again));
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
        let other = ReferenceKey::of("distributed", &frame, floor, 2);
        assert_ne!(other, ReferenceKey::of("distributed", &frame, floor, 1));
    }
}
