//! Axis-aligned boxes: the hierarchy's bounding volumes, and the box around a shape.

use glam::DVec3;

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    pub(super) const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    pub(super) fn grow(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    pub(super) fn grow_point(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The box moved out by `by` on every side.
    pub(super) fn grown(self, by: f64) -> Aabb {
        Aabb {
            min: self.min - DVec3::splat(by),
            max: self.max + DVec3::splat(by),
        }
    }

    pub(super) fn contains(self, p: DVec3) -> bool {
        (self.min.x <= p.x && p.x <= self.max.x)
            && (self.min.y <= p.y && p.y <= self.max.y)
            && (self.min.z <= p.z && p.z <= self.max.z)
    }

    pub(super) fn area(self) -> f64 {
        let d = (self.max - self.min).max(DVec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }
}

/// The half side of the box stored around a sphere. It exceeds the radius by 2^-40 of the
/// coordinates' size, far more than the rounding of `centre +- half side` (2^-53 of it), so the
/// stored box contains the exact sphere. Hits the formula reports *outside* the sphere are the
/// per-ray margin's job ([`RayMargin`]), not the box's.
pub(super) fn sphere_half_side(centre: DVec3, radius: f64) -> f64 {
    radius + (centre.abs().max_element() + radius) * REPRESENTATION_SLACK
}

/// The box of half side `half_side` around `centre`.
pub(super) fn cube(centre: DVec3, half_side: f64) -> Aabb {
    Aabb {
        min: centre,
        max: centre,
    }
    .grown(half_side)
}

/// 2^-40: relative slack for storing a box's corners in f64 (whose rounding is 2^-53).
pub(super) const REPRESENTATION_SLACK: f64 = 1.0 / (1u64 << 40) as f64;
