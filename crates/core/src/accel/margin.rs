//! The per-ray margin that makes the hierarchy return exactly what brute force returns, even
//! on rays where the course's sphere formula reports hits outside the sphere.

use glam::DVec3;

use super::aabb::{Aabb, REPRESENTATION_SLACK};
use crate::geometry::Ray;

/// 2^-23 (1.2e-7): how far outside a sphere, relative to `wmax` below, the brute-force formula
/// can report a hit. See [`RayMargin`].
pub(super) const CONDITIONING_BOUND: f64 = 1.0 / (1u64 << 23) as f64;

/// A ray prepared for box tests: `1 / direction`, and the margin every box is grown by for it.
///
/// Why a margin. For a sphere (C, r) and a ray (O, D), write w = O - C and e = 2^-53
/// (the unit roundoff). The formula of docs/rendering.md computes `disc = b^2 - 4ac` with
/// `b = 2 D.w`, `c = w.w - r^2`. Each of those dot products and products carries a rounding
/// error of at most a few e times the size of its terms (`|D.w| <= |D||w|`), so the computed
/// disc differs from the exact one by |err| <= 4 |D|^2 (|w|^2 + r^2) * k e with k < 16 (three
/// terms per dot product, the squares, the products and the final subtraction; the
/// subtraction `O - C` itself is exact to e of |w|). The exact disc is `4 a (r^2 - h^2)`, h the
/// distance from C to the ray's line, so a reported hit (disc >= 0) needs
/// `h^2 <= r^2 + E`, E = |err| / (4a) <= 16 e (|w|^2 + r^2) (the renderer's rays are unit,
/// a = 1 to within 3e). The reported root then lies sqrt(disc)/(2a) before the closest
/// approach (the far root of the later course years, `(-b + sqrt(disc)) / 2a`, as far after
/// it: the bound below holds for either), so the reported point Q = O + sD is at distance <= sqrt(r^2 + E) + (rounding of
/// s, a few e |w|) from C, and sqrt(r^2 + E) <= r + sqrt(E) <= r + 4 sqrt(e) (|w| + r). With
/// sqrt(e) = 1.05e-8, every reported point is within
/// r + 4.3e-8 (|w| + r) + (a few e |w|) < r + 2^-23 wmax
/// of C, where wmax is the distance from O to the farthest corner of the root box, which
/// contains every sphere, so wmax >= |w| + r for each of them. Growing every box by
/// `2^-23 wmax` therefore keeps every reported hit point inside the boxes that hold its
/// sphere (with room to spare for the slab test's own rounding, a few e of `wmax`), so:
/// - a box the ray misses holds no sphere the formula reports hit: skipping it is exact;
/// - a reported hit at s lies in the grown box, so the box's entry parameter is <= s: the
///   `entry > best` cut in `closest_hit` and the `entry < max_distance` test in `occluded`
///   never drop a hit brute force would keep.
///
/// The margin also carries 2^-40 of the origin's largest coordinate, so that storing
/// `origin +- margin` (rounded to 2^-53 of the origin) cannot eat into it.
///
/// For camera rays in a scene of size ~10 the margin is ~1e-6 and costs nothing; for a shadow
/// ray starting 1e7 away it is ~1.2, which is what exactness costs there. A ray with a NaN or
/// infinite origin or direction gets a non-finite margin, but the formula reports no hit at
/// all for such a ray (its disc or root is NaN), so whatever the box test does is exact; an
/// infinite margin from a finite ray (coordinates near f64::MAX) makes every box pass.
pub(super) struct RayMargin {
    pub(super) origin_plus_margin: DVec3,
    pub(super) origin_minus_margin: DVec3,
    pub(super) inverse: DVec3,
}

impl RayMargin {
    /// Parameter where the ray enters `bounds` grown by the ray's margin on every side, or
    /// `None` if it misses it or the box lies wholly behind the origin. Growing the box by m is
    /// moving the origin by -m towards `min` and +m towards `max`: the same three subtractions
    /// per slab as an ungrown test.
    pub(super) fn entry(&self, bounds: Aabb) -> Option<f64> {
        let t1 = (bounds.min - self.origin_plus_margin) * self.inverse;
        let t2 = (bounds.max - self.origin_minus_margin) * self.inverse;
        // f64::min/max ignore a NaN operand (0 * inf on a slab plane), keeping the test
        // conservative.
        let near = t1.x.min(t2.x).max(t1.y.min(t2.y)).max(t1.z.min(t2.z));
        let far = t1.x.max(t2.x).min(t1.y.max(t2.y)).min(t1.z.max(t2.z));
        (near <= far && far >= 0.0).then_some(near)
    }

    /// The ray with its own margin, or none when it starts in the near zone, whose margin the
    /// stored boxes already have.
    pub(super) fn new(ray: &Ray, root: Aabb, near_zone: Aabb) -> Self {
        let inverse = DVec3::ONE / ray.direction;
        if near_zone.contains(ray.origin) {
            return RayMargin {
                origin_plus_margin: ray.origin,
                origin_minus_margin: ray.origin,
                inverse,
            };
        }
        let far_corner = (ray.origin - root.min)
            .abs()
            .max((ray.origin - root.max).abs());
        // The L1 length bounds the Euclidean one from above and needs no square root.
        let margin = far_corner.element_sum() * CONDITIONING_BOUND
            + ray.origin.abs().max_element() * REPRESENTATION_SLACK;
        RayMargin {
            origin_plus_margin: ray.origin + DVec3::splat(margin),
            origin_minus_margin: ray.origin - DVec3::splat(margin),
            inverse,
        }
    }
}

/// The near zone of a root box and the margin that covers every ray starting in it. The zone
/// is the root box stretched to take in the camera at the origin, then grown by its longest
/// side S on every side: camera rays and rays from the scene's surfaces start in it. From
/// such an origin the far corner of the root is at most 2S away per axis, 6S in the L1
/// length, so the margin is 2^-23 * 6S, plus the representation slack of the zone's
/// coordinates (for storing the grown boxes and the origins). Rays from elsewhere add their
/// own margin on top, which only grows the boxes more.
pub(super) fn near_zone(root: Aabb) -> (Aabb, f64) {
    let root = root.grow_point(DVec3::ZERO);
    let side = (root.max - root.min).max_element();
    let zone = root.grown(side);
    let size = zone.min.abs().max(zone.max.abs()).max_element();
    let margin = 6.0 * side * CONDITIONING_BOUND + size * REPRESENTATION_SLACK;
    (zone, margin)
}
