//! Tick 1* depth of field (docs/tick1star.md, Option 2): per pixel, rays from points of a
//! square aperture at the camera through the point where the pinhole ray meets the focal
//! plane z = `focal_z`; their colours are averaged before the tone map.

use glam::DVec3;

use crate::geometry::{normalise, Ray};

/// The course's `DOF_FOCAL_PLANE`.
pub const COURSE_FOCAL_PLANE: f64 = 3.51805;

/// The course's `DOF_AMOUNT`: the aperture's side.
pub const COURSE_APERTURE: f64 = 0.2;

/// The course's `DOF_RAY_COUNT`.
pub const COURSE_DOF_RAYS: u32 = 50;

/// The depth-of-field settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthOfField {
    /// z of the plane in focus.
    pub focal_z: f64,
    /// Side of the square aperture in the xy-plane at the camera.
    pub side: f64,
    /// Rays per pixel in the course's draw.
    pub rays: u32,
}

impl Default for DepthOfField {
    fn default() -> Self {
        DepthOfField {
            focal_z: COURSE_FOCAL_PLANE,
            side: COURSE_APERTURE,
            rays: COURSE_DOF_RAYS,
        }
    }
}

impl DepthOfField {
    /// The ray from the aperture point for uniform numbers (u1, u2) in [0, 1), each mapped to
    /// [-1, 1] and scaled by the half side, through where `pinhole` meets the focal plane.
    pub fn ray(&self, pinhole: &Ray, [u1, u2]: [f64; 2]) -> Ray {
        let d = pinhole.direction;
        let focus = d * (self.focal_z / d.z);
        let half = self.side / 2.0;
        let origin = DVec3::new((2.0 * u1 - 1.0) * half, (2.0 * u2 - 1.0) * half, 0.0);
        Ray::new(origin, normalise(focus - origin))
    }

    /// The side, in pixels of `pixel_step` image-plane units, of the square a point at depth
    /// `z` is spread over: `side * |1/z - 1/focal_z| / pixel_step` (0 on the focal plane).
    pub fn circle_of_confusion(&self, z: f64, pixel_step: f64) -> f64 {
        self.side * (1.0 / z - 1.0 / self.focal_z).abs() / pixel_step
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_aperture_ray_meets_the_pinhole_ray_on_the_focal_plane() {
        let dof = DepthOfField::default();
        let pinhole = Ray::new(DVec3::ZERO, normalise(DVec3::new(0.1, -0.2, 1.0)));
        let focus = pinhole.direction * (dof.focal_z / pinhole.direction.z);
        for u in [[0.0, 0.0], [0.99, 0.3], [0.5, 0.5]] {
            let ray = dof.ray(&pinhole, u);
            let s = (dof.focal_z - ray.origin.z) / ray.direction.z;
            assert!((ray.at(s) - focus).length() < 1e-12);
            assert!(ray.origin.x.abs() <= 0.1 && ray.origin.y.abs() <= 0.1);
        }
        assert_eq!(dof.circle_of_confusion(dof.focal_z, 0.01), 0.0);
        // 0.2 * |1/2 - 1/4| / 0.01 = 5 pixels.
        let wide = DepthOfField {
            focal_z: 4.0,
            ..dof
        };
        assert!((wide.circle_of_confusion(2.0, 0.01) - 5.0).abs() < 1e-12);
    }
}
