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

/// Where a pixel's rays converge, given `focal_z` (`DOF_FOCAL_PLANE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Focus {
    /// The handout's: where the pinhole ray meets the plane z = `focal_z`.
    #[default]
    Plane,
    /// `focal_z` along the (unit) pinhole ray, `ray.evaluateAt(DOF_FOCAL_PLANE)`: a sphere of
    /// focus around the pinhole, which leaves the image's corners out of focus on the plane.
    Distance,
}

/// The depth-of-field settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthOfField {
    /// z of the plane in focus (or the distance in focus, for `Focus::Distance`).
    pub focal_z: f64,
    /// Side of the square aperture in the xy-plane at the camera.
    pub side: f64,
    /// Rays per pixel in the course's draw.
    pub rays: u32,
    pub focus: Focus,
}

impl Default for DepthOfField {
    fn default() -> Self {
        DepthOfField {
            focal_z: COURSE_FOCAL_PLANE,
            side: COURSE_APERTURE,
            rays: COURSE_DOF_RAYS,
            focus: Focus::Plane,
        }
    }
}

impl DepthOfField {
    /// The depth along the unit pinhole direction `d` of the point every aperture ray of
    /// the pixel passes through.
    pub fn focal_depth(&self, d: DVec3) -> f64 {
        match self.focus {
            Focus::Plane => self.focal_z,
            Focus::Distance => self.focal_z * d.z,
        }
    }

    /// The ray from the aperture point for uniform numbers (u1, u2) in [0, 1), each mapped to
    /// [-1, 1] and scaled by the half side, through the pixel's point in focus.
    pub fn ray(&self, pinhole: &Ray, [u1, u2]: [f64; 2]) -> Ray {
        let d = pinhole.direction;
        let focus = match self.focus {
            Focus::Plane => d * (self.focal_z / d.z),
            Focus::Distance => d * self.focal_z,
        };
        let half = self.side / 2.0;
        let origin = DVec3::new((2.0 * u1 - 1.0) * half, (2.0 * u2 - 1.0) * half, 0.0);
        Ray::new(origin, normalise(focus - origin))
    }

    /// The side, in pixels of `pixel_step` image-plane units, of the square a point at depth
    /// `z` seen along the unit pinhole direction `d` is spread over:
    /// `side * |1/z - 1/focal depth| / pixel_step` (0 in focus).
    pub fn circle_of_confusion(&self, z: f64, d: DVec3, pixel_step: f64) -> f64 {
        self.side * (1.0 / z - 1.0 / self.focal_depth(d)).abs() / pixel_step
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
        assert_eq!(
            dof.circle_of_confusion(dof.focal_z, pinhole.direction, 0.01),
            0.0
        );
        // 0.2 * |1/2 - 1/4| / 0.01 = 5 pixels.
        let wide = DepthOfField {
            focal_z: 4.0,
            ..dof
        };
        assert!((wide.circle_of_confusion(2.0, DVec3::Z, 0.01) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_focal_distance_puts_the_focus_that_far_along_the_pinhole_ray() {
        let dof = DepthOfField {
            focus: Focus::Distance,
            ..DepthOfField::default()
        };
        let pinhole = Ray::new(DVec3::ZERO, normalise(DVec3::new(0.3, -0.2, 1.0)));
        let focus = pinhole.at(dof.focal_z);
        for u in [[0.0, 0.0], [0.99, 0.3], [0.5, 0.7]] {
            let ray = dof.ray(&pinhole, u);
            let s = (focus.z - ray.origin.z) / ray.direction.z;
            assert!((ray.at(s) - focus).length() < 1e-12);
        }
        // Nearer than the plane off the axis, the same on it.
        assert!(focus.z < dof.focal_z - 0.1);
        assert_eq!(dof.focal_depth(DVec3::Z), dof.focal_z);
        assert_eq!(
            dof.circle_of_confusion(focus.z, pinhole.direction, 0.01),
            0.0
        );
    }
}
