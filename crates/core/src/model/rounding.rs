//! Roots that hinge on rounding. A ray that starts exactly at a surface point P (a shadow or
//! reflected ray without the EPSILON offset) meets that surface again at a root within a few
//! units in the last place of zero, and whether that root comes out as a small positive number
//! (a hit: shadow acne, a reflection of itself) or not depends on the last bits of P, L and the
//! root, which every program computes its own way (`O + D s` or `D s + O`, L divided by its
//! length or scaled by its reciprocal, the plane's root from `(Q - O).N` or from the plane's
//! constant, `s > 0` or `s >= 0`). No one image is *the* image of such a mistake.
//!
//! So a model can take such roots both ways: [`SelfHit::Hit`] counts every root within the
//! band below as a hit, [`SelfHit::Miss`] none of them. A pixel whose two renders differ can go
//! either way in some student's program; one whose renders agree is certain.
//!
//! The band. A surface point computed by any reasonable order of operations lies within a few
//! e (the unit roundoff, 2^-53) times `|O| + |C| + r` (a sphere) or `|O| + |Q|` (a plane) of the
//! surface, measured across it; along a ray that leaves at an angle whose cosine to the normal
//! is `cos`, that is `/ cos` in distance, `/ (|D| cos)` in the ray's parameter. The root's own
//! rounding (the cancellation in `-b - sqrt(disc)`, the dot products; see `accel/margin.rs`
//! for the same terms) adds a few e of the same sizes. [`SPREAD`] is 32 e: more than any of
//! those orders of operations moves a point, while a root of the course's offset ray lies at
//! `-EPSILON`, eleven orders of magnitude outside it in a scene of unit size.

use glam::DVec3;

use crate::geometry::{plane_parameter, sphere_roots, Ray, SphereTerms};
use crate::model::Model;

/// How many units of roundoff (2^-53 each) of the scene's coordinates a surface point and
/// its self-root may be off by, whichever way a program computes them.
pub const SPREAD: f64 = 32.0 * (f64::EPSILON / 2.0);

/// How a root within the band is taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub enum SelfHit {
    /// As the model's own arithmetic has it (what `render` draws).
    #[default]
    Exact,
    /// Every root within the band is a hit, at a tiny positive distance.
    Hit,
    /// No root within the band is a hit.
    Miss,
}

/// What a root `s` with `band` comes to under `how`: `None` when the model's own rule
/// decides (outside the band, or [`SelfHit::Exact`]), else the hit's distance or no hit.
pub fn decide(how: SelfHit, s: f64, band: f64) -> Option<Option<f64>> {
    let within = s.abs() <= band;
    if how == SelfHit::Exact || !within {
        return None;
    }
    Some((how == SelfHit::Hit).then(|| s.abs().max(TINY)))
}

/// The band around zero of a root of `ray` on the sphere (`centre`, `radius_squared`): how far
/// rounding can move the root of a ray that starts on the sphere.
pub fn sphere_band(ray: &Ray, centre: DVec3, radius_squared: f64) -> f64 {
    let w = ray.origin - centre;
    let scale = ray.origin.length() + centre.length() + radius_squared.sqrt();
    // |D| cos(angle to the normal) = |D.w| / |w|.
    let across = ray.direction.dot(w).abs() / w.length();
    band(scale, across)
}

/// The band around zero of a root of `ray` on the plane through `point` with `normal`.
pub fn plane_band(ray: &Ray, point: DVec3, normal: DVec3) -> f64 {
    let scale = ray.origin.length() + point.length();
    let across = ray.direction.dot(normal).abs() / normal.length();
    band(scale, across)
}

/// `SPREAD * scale / across`, infinite for a ray along the surface (any root can go either
/// way there) and 0 where the sizes are not finite.
fn band(scale: f64, across: f64) -> f64 {
    let b = SPREAD * scale / across;
    if b.is_nan() {
        0.0
    } else {
        b
    }
}

/// The one rule for a sphere's roots under `how`: each root within the band is taken `how`,
/// every other one as the course's test does (positive). The near root first, then, for a
/// model that lets a ray from inside hit (`far_root`), the far one.
pub fn sphere_root_taken(
    how: SelfHit,
    ray: &Ray,
    terms: &SphereTerms,
    centre: DVec3,
    radius_squared: f64,
    far_root: bool,
) -> Option<f64> {
    let (near, far) = sphere_roots(ray, terms, centre, radius_squared)?;
    let band = sphere_band(ray, centre, radius_squared);
    for s in std::iter::once(near).chain(far_root.then_some(far)) {
        match decide(how, s, band) {
            Some(Some(hit)) => return Some(hit),
            Some(None) => {}
            None if s > 0.0 => return Some(s),
            None => {}
        }
    }
    None
}

/// The one rule for a plane's root under `how`: within the band taken `how` (unless the model
/// hits no plane at all: one not written yet does not start to), else as `accepts` says.
/// The band costs two square roots, so it is computed only when `how` is not `Exact`.
pub fn plane_root_taken(
    how: SelfHit,
    ray: &Ray,
    point: DVec3,
    normal: DVec3,
    accepts: impl Fn(f64) -> bool,
) -> Option<f64> {
    let s = plane_parameter(point, normal, ray);
    if how != SelfHit::Exact && accepts(TINY) {
        if let Some(taken) = decide(how, s, plane_band(ray, point, normal)) {
            return taken;
        }
    }
    accepts(s).then_some(s)
}

/// `model` with the roots within the band taken `how` (for one light's shadow rays: a pixel
/// lit by two lights can self-shadow towards one and not the other). Only the hit search is
/// changed; the search asks nothing else of a model.
pub struct TakingSelfHits<'a, M> {
    pub model: &'a M,
    pub how: SelfHit,
}

/// The distance of a self-hit taken as a hit: tiny, positive, nearer than anything else.
const TINY: f64 = f64::MIN_POSITIVE;

impl<M: Model> Model for TakingSelfHits<'_, M> {
    fn hierarchy_exact(&self) -> bool {
        self.model.hierarchy_exact()
    }

    fn sphere_root(
        &self,
        ray: &Ray,
        terms: &SphereTerms,
        centre: DVec3,
        radius_squared: f64,
    ) -> Option<f64> {
        match self.how {
            SelfHit::Exact => self.model.sphere_root(ray, terms, centre, radius_squared),
            how => sphere_root_taken(
                how,
                ray,
                terms,
                centre,
                radius_squared,
                self.model.far_root(),
            ),
        }
    }

    fn far_root(&self) -> bool {
        self.model.far_root()
    }

    fn plane_accepts(&self, s: f64) -> bool {
        self.model.plane_accepts(s)
    }

    fn plane_root(&self, ray: &Ray, point: DVec3, normal: DVec3) -> Option<f64> {
        match self.how {
            SelfHit::Exact => self.model.plane_root(ray, point, normal),
            how => plane_root_taken(how, ray, point, normal, |s| self.model.plane_accepts(s)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{plane_parameter, sphere_roots, SphereTerms, EPSILON};

    #[test]
    fn a_self_root_lies_in_the_band_and_an_offset_one_does_not() {
        let centre = DVec3::new(0.3, -0.2, 7.0);
        let radius = 1.7_f64;
        let mut inside = 0;
        for i in 0..2000 {
            let t = f64::from(i) * 0.001_3;
            let n = DVec3::new(t.sin() * t.cos(), t.cos(), (t * 3.0).sin()).normalize();
            let p = centre + n * radius;
            let l = (DVec3::new(-4.0, 5.0, 1.0) - p).normalize();
            let ray = Ray::new(p, l);
            let (near, far) = sphere_roots(&ray, &SphereTerms::of(&ray), centre, radius * radius)
                .expect("a ray from the surface meets the sphere");
            let band = sphere_band(&ray, centre, radius * radius);
            // One root is the point itself: within the band.
            let self_root = if near.abs() < far.abs() { near } else { far };
            assert!(self_root.abs() <= band, "{self_root} outside {band}");
            inside += 1;
            let offset = Ray::offset_by(p, l, EPSILON);
            let (near, far) =
                sphere_roots(&offset, &SphereTerms::of(&offset), centre, radius * radius)
                    .expect("still meets it");
            let band = sphere_band(&offset, centre, radius * radius);
            assert!(near.abs() > band && far.abs() > band);
        }
        assert_eq!(inside, 2000);
    }

    #[test]
    fn a_plane_point_s_own_root_is_in_the_band() {
        let point = DVec3::new(0.0, -1.0, 0.0);
        let normal = DVec3::Y;
        for i in 1..500 {
            let d = DVec3::new(f64::from(i) * 0.01 - 2.5, -1.0, 3.0).normalize();
            let eye = Ray::new(DVec3::ZERO, d);
            let s = plane_parameter(point, normal, &eye);
            let p = eye.at(s);
            let to_light = (DVec3::new(1.0, 4.0, 2.0) - p).normalize();
            let shadow = Ray::new(p, to_light);
            let root = plane_parameter(point, normal, &shadow);
            assert!(root.abs() <= plane_band(&shadow, point, normal));
            assert_eq!(
                decide(SelfHit::Miss, root, plane_band(&shadow, point, normal)),
                Some(None)
            );
            assert!(matches!(
                decide(SelfHit::Hit, root, plane_band(&shadow, point, normal)),
                Some(Some(s)) if s > 0.0
            ));
            assert_eq!(decide(SelfHit::Exact, root, 1.0), None);
        }
    }
}
