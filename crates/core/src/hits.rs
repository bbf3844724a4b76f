//! The two questions a trace asks of a scene's geometry: the nearest hit along a ray, and
//! whether anything blocks a shadow ray before a reach. [`Accelerator`] answers them by
//! searching; [`tape`] answers them from a recording of an earlier trace, so that `check`'s
//! many candidate programs that intersect as the course does share the reference's searches
//! on the pixels every candidate renders.

pub mod tape;

use crate::accel::Accelerator;
use crate::geometry::{Hit, Ray};
use crate::model::Model;

/// Answers a trace's hit searches under a model's intersection rules
/// (`Model::sphere_root`, `Model::plane_root` and what they call).
pub trait Hits {
    /// The nearest hit along `ray`.
    fn closest_hit(&self, model: &impl Model, ray: &Ray) -> Option<Hit>;

    /// Whether anything lies along `ray` strictly nearer than `reach`.
    fn occluded(&self, model: &impl Model, ray: &Ray, reach: f64) -> bool;
}

impl Hits for Accelerator {
    #[inline(always)]
    fn closest_hit(&self, model: &impl Model, ray: &Ray) -> Option<Hit> {
        Accelerator::closest_hit(self, model, ray)
    }

    #[inline(always)]
    fn occluded(&self, model: &impl Model, ray: &Ray, reach: f64) -> bool {
        Accelerator::occluded(self, model, ray, reach)
    }
}

impl<H: Hits + ?Sized> Hits for &H {
    #[inline(always)]
    fn closest_hit(&self, model: &impl Model, ray: &Ray) -> Option<Hit> {
        (**self).closest_hit(model, ray)
    }

    #[inline(always)]
    fn occluded(&self, model: &impl Model, ray: &Ray, reach: f64) -> bool {
        (**self).occluded(model, ray, reach)
    }
}
