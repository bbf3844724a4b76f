//! Rays, the closed set of shapes, and ray-shape intersection, with the exact operation order of
//! docs/rendering.md (Intersections): the tick reference is matched bit for bit, so every formula
//! here is evaluated the way the course evaluates it.

use glam::DVec3;

/// How far secondary rays start off the surface they leave, so they do not re-hit it.
pub const EPSILON: f64 = 0.0001;

/// A half-line `origin + s * direction`, `s > 0`. `direction` is unit length for every ray the
/// renderer casts, but the intersection formulas do not assume it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

/// The shapes a scene can hold. A closed set, so a `match` rather than trait objects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Sphere {
        centre: DVec3,
        radius: f64,
    },
    /// `normal` is unit length (the loader normalises it) and is never flipped: a plane seen
    /// from behind is shaded with the normal facing away.
    Plane {
        point: DVec3,
        normal: DVec3,
    },
}

/// The nearest surface along a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Index into `Scene::objects`.
    pub object: usize,
    /// Ray parameter `s` of the hit point.
    pub distance: f64,
}

/// `v` divided by its length, component by component. The course divides; glam's `normalize`
/// multiplies by the reciprocal, which differs in the last bit and changes tick pixels.
#[inline]
pub fn normalise(v: DVec3) -> DVec3 {
    divide_by_length(v, v.length())
}

/// `normalise` for a vector whose length is already at hand (`length` must be `v.length()`):
/// the same divisions, without computing the square root twice.
#[inline]
pub fn divide_by_length(v: DVec3, length: f64) -> DVec3 {
    DVec3::new(v.x / length, v.y / length, v.z / length)
}

impl Ray {
    #[inline]
    pub fn new(origin: DVec3, direction: DVec3) -> Self {
        Ray { origin, direction }
    }

    /// The point at parameter `s`.
    #[inline]
    pub fn at(&self, s: f64) -> DVec3 {
        self.origin + self.direction * s
    }

    /// A ray leaving `point` along `direction`, started `EPSILON` along it so that it does not
    /// find the surface it leaves.
    #[inline]
    pub fn offset_from(point: DVec3, direction: DVec3) -> Self {
        Ray::offset_by(point, direction, EPSILON)
    }

    /// A ray leaving `point` along `direction`, started `epsilon` along it.
    #[inline]
    pub fn offset_by(point: DVec3, direction: DVec3, epsilon: f64) -> Self {
        Ray::new(point + direction * epsilon, direction)
    }
}

/// The terms of the sphere quadratic that depend on the ray alone, `2a` and `4a` with
/// `a = D.D`, computed once per ray when many spheres are tested (the same values, so the
/// same hits).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereTerms {
    two_a: f64,
    four_a: f64,
}

impl SphereTerms {
    #[inline]
    pub fn of(ray: &Ray) -> Self {
        let a = ray.direction.dot(ray.direction);
        SphereTerms {
            two_a: 2.0 * a,
            four_a: 4.0 * a,
        }
    }
}

/// `-b` and `sqrt(disc)` of the sphere quadratic `a s^2 + b s + c` in the course's operation
/// order (docs/rendering.md), or `None` when `disc < 0`. `radius_squared` is `radius * radius`.
#[inline(always)]
fn sphere_quadratic(
    ray: &Ray,
    terms: &SphereTerms,
    centre: DVec3,
    radius_squared: f64,
) -> Option<(f64, f64)> {
    let to_origin = ray.origin - centre;
    let b = 2.0 * ray.direction.dot(to_origin);
    let c = to_origin.dot(to_origin) - radius_squared;
    // `4 a c` is `(4 a) c`, as written left to right.
    let disc = b * b - terms.four_a * c;
    if disc < 0.0 {
        return None;
    }
    Some((-b, disc.sqrt()))
}

/// Both roots of the sphere quadratic, near then far, unfiltered, in the course's operation
/// order (the same bits as [`sphere_hit`] and [`sphere_far_hit`]), or `None` when
/// `disc < 0`: for a model that decides itself which roots count.
#[inline]
pub fn sphere_roots(
    ray: &Ray,
    terms: &SphereTerms,
    centre: DVec3,
    radius_squared: f64,
) -> Option<(f64, f64)> {
    let (minus_b, root) = sphere_quadratic(ray, terms, centre, radius_squared)?;
    Some((
        (minus_b - root) / terms.two_a,
        (minus_b + root) / terms.two_a,
    ))
}

/// The course's ray-sphere test: the near root `(-b - sqrt(disc)) / 2a`, if positive.
#[inline]
pub fn sphere_hit(
    ray: &Ray,
    terms: &SphereTerms,
    centre: DVec3,
    radius_squared: f64,
) -> Option<f64> {
    let (minus_b, root) = sphere_quadratic(ray, terms, centre, radius_squared)?;
    let s = (minus_b - root) / terms.two_a;
    (s > 0.0).then_some(s)
}

/// The far root `(-b + sqrt(disc)) / 2a`, if positive: not the course's rule, but what the
/// handout's literal reading adds (the `sphere-far-root` mistake of docs/check.md).
#[inline]
pub fn sphere_far_hit(
    ray: &Ray,
    terms: &SphereTerms,
    centre: DVec3,
    radius_squared: f64,
) -> Option<f64> {
    let (minus_b, root) = sphere_quadratic(ray, terms, centre, radius_squared)?;
    let s = (minus_b + root) / terms.two_a;
    (s > 0.0).then_some(s)
}

/// The near root if positive, else the far one if positive: a sphere hit from inside counts
/// (the later course years' rule, and the `sphere-far-root` mistake of 2016-17).
#[inline]
pub fn sphere_near_else_far_hit(
    ray: &Ray,
    terms: &SphereTerms,
    centre: DVec3,
    radius_squared: f64,
) -> Option<f64> {
    sphere_hit(ray, terms, centre, radius_squared)
        .or_else(|| sphere_far_hit(ray, terms, centre, radius_squared))
}

/// The parameter `s = ((Q - O).N) / (D.N)` at which `ray` meets the plane through `point`
/// with `normal`, before any test: infinite or NaN for a ray parallel to it, negative
/// behind it (the model decides which hits count).
#[inline]
pub fn plane_parameter(point: DVec3, normal: DVec3, ray: &Ray) -> f64 {
    (point - ray.origin).dot(normal) / ray.direction.dot(normal)
}

impl Shape {
    /// Unit surface normal at a point `p` on the shape.
    #[inline]
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        match *self {
            Shape::Sphere { centre, .. } => normalise(p - centre),
            Shape::Plane { normal, .. } => normal,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::search::{closest_hit, intersect};
    use crate::model::Tick;

    fn sphere(centre: DVec3, radius: f64) -> Shape {
        Shape::Sphere { centre, radius }
    }

    fn plane(point: DVec3, normal: DVec3) -> Shape {
        Shape::Plane { point, normal }
    }

    #[test]
    fn sphere_hit_distance_and_normal_match_the_analytic_answer() {
        let s = sphere(DVec3::new(0.0, 0.0, 5.0), 1.0);
        let ray = Ray::new(DVec3::ZERO, DVec3::Z);
        assert_eq!(intersect(&Tick, &s, &ray), Some(4.0));
        assert_eq!(s.normal_at(ray.at(4.0)), DVec3::new(0.0, 0.0, -1.0));

        // Off-axis: the ray y = 0.6 meets the unit sphere at z = 5 - 0.8.
        let ray = Ray::new(DVec3::new(0.0, 0.6, 0.0), DVec3::Z);
        let hit = intersect(&Tick, &s, &ray).expect("hits");
        assert!((hit - 4.2).abs() < 1e-12, "{hit}");
        let n = s.normal_at(ray.at(hit));
        assert!((n - DVec3::new(0.0, 0.6, -0.8)).length() < 1e-12, "{n}");
    }

    #[test]
    fn sphere_missed_and_behind_gives_no_hit() {
        let s = sphere(DVec3::new(0.0, 0.0, 5.0), 1.0);
        assert_eq!(
            intersect(&Tick, &s, &Ray::new(DVec3::new(0.0, 1.5, 0.0), DVec3::Z)),
            None
        );
        assert_eq!(
            intersect(&Tick, &s, &Ray::new(DVec3::ZERO, -DVec3::Z)),
            None
        );
    }

    #[test]
    fn ray_starting_inside_a_sphere_does_not_hit_it() {
        let s = sphere(DVec3::new(0.0, 0.0, 5.0), 1.0);
        for dir in [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(0.3, -0.4, 0.5).normalize(),
        ] {
            assert_eq!(
                intersect(&Tick, &s, &Ray::new(DVec3::new(0.0, 0.0, 5.2), dir)),
                None,
                "{dir}"
            );
        }
    }

    #[test]
    fn plane_in_front_behind_parallel_and_from_behind() {
        let floor = plane(DVec3::new(0.0, -1.0, 0.0), DVec3::Y);
        // In front, seen from above.
        let down = Ray::new(DVec3::ZERO, DVec3::new(0.0, -1.0, 0.0));
        assert_eq!(intersect(&Tick, &floor, &down), Some(1.0));
        // Behind the ray.
        assert_eq!(
            intersect(&Tick, &floor, &Ray::new(DVec3::ZERO, DVec3::Y)),
            None
        );
        // Parallel: D.N = 0 gives an infinite or NaN parameter, never a hit.
        assert_eq!(
            intersect(&Tick, &floor, &Ray::new(DVec3::ZERO, DVec3::X)),
            None
        );
        assert_eq!(
            intersect(
                &Tick,
                &floor,
                &Ray::new(DVec3::new(0.0, -1.0, 0.0), DVec3::X)
            ),
            None
        );
        // Seen from behind: still hit, and the normal is not flipped.
        let up = Ray::new(DVec3::new(0.0, -3.0, 0.0), DVec3::Y);
        assert_eq!(intersect(&Tick, &floor, &up), Some(2.0));
        assert_eq!(floor.normal_at(up.at(2.0)), DVec3::Y);
    }

    #[test]
    fn ties_go_to_the_earlier_object() {
        let shapes = [
            plane(DVec3::new(0.0, 0.0, 4.0), -DVec3::Z),
            sphere(DVec3::new(0.0, 0.0, 5.0), 1.0),
            plane(DVec3::new(0.0, 0.0, 4.0), DVec3::Z),
        ];
        let hit = closest_hit(
            &Tick,
            shapes.iter().enumerate(),
            &Ray::new(DVec3::ZERO, DVec3::Z),
        )
        .expect("hits");
        assert_eq!(
            hit,
            Hit {
                object: 0,
                distance: 4.0
            }
        );
    }

    #[test]
    fn a_ray_spawned_off_a_sphere_does_not_rehit_it() {
        let s = sphere(DVec3::new(0.2, -0.1, 4.0), 0.7);
        let shapes = [s];
        for i in 0..100 {
            let t = i as f64 * 0.173;
            let dir = normalise(DVec3::new(t.sin(), (2.0 * t).cos(), -0.5 - t.cos().abs()));
            let hit = intersect(&Tick, &s, &Ray::new(DVec3::ZERO, dir));
            let Some(d) = hit else { continue };
            let p = dir * d;
            let n = s.normal_at(p);
            let out = normalise(n + DVec3::new(0.1 * t.cos(), 0.1 * t.sin(), 0.0));
            assert!(
                closest_hit(&Tick, shapes.iter().enumerate(), &Ray::offset_from(p, out)).is_none(),
                "ray {i}"
            );
        }
    }

    #[test]
    fn normalise_divides_each_component() {
        let v = DVec3::new(0.1, 0.7, 1.0);
        let l = (0.1f64 * 0.1 + 0.7 * 0.7 + 1.0).sqrt();
        assert_eq!(normalise(v), DVec3::new(0.1 / l, 0.7 / l, 1.0 / l));
    }
}
