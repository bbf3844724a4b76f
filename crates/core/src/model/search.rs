//! The brute-force hit search: the *definition* of the closest hit and of a shadow test
//! (docs/rendering.md, Intersections) under a model's rules. The hierarchy must agree with it
//! on every ray; the tests and the unbounded shapes use it directly.

use crate::geometry::{Hit, Ray, Shape, SphereTerms};
use crate::model::Model;

/// The parameter at which `ray` hits `shape` under `model`'s rules, or `None`.
pub fn intersect(model: &impl Model, shape: &Shape, ray: &Ray) -> Option<f64> {
    match *shape {
        Shape::Sphere { centre, radius } => {
            model.sphere_root(ray, &SphereTerms::of(ray), centre, radius * radius)
        }
        Shape::Plane { point, normal } => model.plane_root(ray, point, normal),
    }
}

/// The nearest hit along `ray` over `(file index, shape)` pairs given in file order. A later
/// shape wins only when strictly nearer, so ties go to the earlier one (`min_by` keeps the
/// first minimum).
pub fn closest_hit<'a>(
    model: &impl Model,
    shapes: impl IntoIterator<Item = (usize, &'a Shape)>,
    ray: &Ray,
) -> Option<Hit> {
    shapes
        .into_iter()
        .filter_map(|(object, shape)| {
            intersect(model, shape, ray).map(|distance| Hit { object, distance })
        })
        .min_by(|a, b| a.distance.total_cmp(&b.distance))
}

/// Whether any of `shapes` lies along `ray` strictly nearer than `max_distance`: the shadow
/// test. The same answer as `closest_hit(..).distance < max_distance`, but stops at the first
/// blocker.
pub fn occluded<'a>(
    model: &impl Model,
    shapes: impl IntoIterator<Item = (usize, &'a Shape)>,
    ray: &Ray,
    max_distance: f64,
) -> bool {
    shapes
        .into_iter()
        .any(|(_, shape)| intersect(model, shape, ray).is_some_and(|s| s < max_distance))
}
