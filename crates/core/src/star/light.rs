//! Tick 1* soft shadows: the course's sphere light (docs/tick1star.md, Option 2). Each shadow
//! ray aims at the light's position plus `LIGHT_SIZE` times a point drawn inside the unit
//! sphere; the light's diffuse and specular terms are scaled by the share not occluded.

use std::f64::consts::PI;

use glam::DVec3;

/// The course's `SHADOW_RAY_COUNT`.
pub const COURSE_SHADOW_RAYS: u32 = 10;

/// The course's `LIGHT_SIZE`.
pub const COURSE_LIGHT_SIZE: f64 = 0.4;

/// How a point inside the unit sphere is drawn from three uniform numbers in [0, 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LightSampling {
    /// The course's `randomInsideUnitSphere`: radius, polar angle in [0, pi) and azimuth in
    /// [0, 2 pi) each uniform and independent, so denser towards the centre.
    #[default]
    Course,
    /// Uniform in volume: radius `cbrt(u)`, `cos(theta)` uniform in [-1, 1].
    Uniform,
    /// On the sphere's surface: the course's point normalised (radius 1, its polar angle and
    /// azimuth as the course draws them), what a student writes as
    /// `Vector3.randomInsideUnitSphere().normalised()` times `LIGHT_SIZE`. Its polar angle is
    /// uniform, so the points crowd the poles; the radius is always the light's.
    Surface,
}

impl LightSampling {
    pub fn name(self) -> &'static str {
        match self {
            LightSampling::Course => "course",
            LightSampling::Uniform => "uniform",
            LightSampling::Surface => "surface",
        }
    }

    pub fn named(name: &str) -> Option<LightSampling> {
        [
            LightSampling::Course,
            LightSampling::Uniform,
            LightSampling::Surface,
        ]
        .into_iter()
        .find(|s| s.name() == name)
    }

    /// The point of the unit ball for uniform numbers (u1, u2, u3), in the course's order:
    /// radius, polar angle, azimuth.
    pub fn point(self, [u1, u2, u3]: [f64; 3]) -> DVec3 {
        let (radius, cos_theta) = match self {
            LightSampling::Course => (u1, (u2 * PI).cos()),
            LightSampling::Uniform => (u1.cbrt(), 1.0 - 2.0 * u2),
            // The radius's draw is still made (and ignored), as the student's call makes it.
            LightSampling::Surface => (1.0, (u2 * PI).cos()),
        };
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let (sin_phi, cos_phi) = (u3 * 2.0 * PI).sin_cos();
        DVec3::new(
            radius * sin_theta * cos_phi,
            radius * sin_theta * sin_phi,
            radius * cos_theta,
        )
    }
}

/// What the light's terms are scaled by, from the k of n shadow rays not occluded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShadowShare {
    /// The handout's fraction k / n.
    #[default]
    Averaged,
    /// The count k itself (the division by `SHADOW_RAY_COUNT` left out): n times the
    /// fraction, so n times the expectation and n^2 times the variance of the lit terms.
    Count,
}

impl ShadowShare {
    /// The factor on the fraction k / n for `rays` shadow rays.
    pub fn gain(self, rays: u32) -> f64 {
        match self {
            ShadowShare::Averaged => 1.0,
            ShadowShare::Count => f64::from(rays),
        }
    }
}

/// Which of a light's terms the visible share scales.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShadowedTerms {
    /// The handout's: diffuse and specular.
    #[default]
    Both,
    /// Diffuse only: the specular highlight is added whole, even in full shadow.
    DiffuseOnly,
}

/// The soft-shadow settings: shadow rays per light, the light's radius, how its points are
/// drawn, and how the visible share scales the light's terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftShadows {
    pub rays: u32,
    pub light_size: f64,
    pub sampling: LightSampling,
    pub share: ShadowShare,
    pub scaled: ShadowedTerms,
}

impl Default for SoftShadows {
    fn default() -> Self {
        SoftShadows {
            rays: COURSE_SHADOW_RAYS,
            light_size: COURSE_LIGHT_SIZE,
            sampling: LightSampling::Course,
            share: ShadowShare::Averaged,
            scaled: ShadowedTerms::Both,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn course_points_follow_radius_polar_azimuth() {
        let p = LightSampling::Course.point([0.5, 0.5, 0.25]);
        // r = 0.5, theta = pi/2, phi = pi/2: (0, 0.5, 0).
        assert!((p - DVec3::new(0.0, 0.5, 0.0)).length() < 1e-15, "{p}");
        let q = LightSampling::Uniform.point([0.125, 0.0, 0.0]);
        // r = cbrt(1/8) = 0.5, cos theta = 1: (0, 0, 0.5).
        assert!((q - DVec3::new(0.0, 0.0, 0.5)).length() < 1e-15, "{q}");
        // The surface keeps the course's angles at radius 1.
        let s = LightSampling::Surface.point([0.1, 0.5, 0.25]);
        assert!((s - DVec3::new(0.0, 1.0, 0.0)).length() < 1e-15, "{s}");
        for u in [[0.3, 0.2, 0.9], [0.01, 0.999, 0.5]] {
            let c = LightSampling::Course.point(u);
            let s = LightSampling::Surface.point(u);
            assert!((s.length() - 1.0).abs() < 1e-15);
            assert!((s - c / c.length()).length() < 1e-12, "{s} {c}");
        }
    }

    #[test]
    fn course_radius_is_uniform_so_the_mean_distance_is_half() {
        // E|p| = 1/2 for the course (radius uniform), 3/4 for uniform in volume.
        let n = 64;
        let mean = |s: LightSampling| {
            (0..n)
                .map(|i| {
                    s.point([(f64::from(i) + 0.5) / f64::from(n), 0.3, 0.7])
                        .length()
                })
                .sum::<f64>()
                / f64::from(n)
        };
        assert!((mean(LightSampling::Course) - 0.5).abs() < 1e-12);
        assert!((mean(LightSampling::Uniform) - 0.75).abs() < 1e-3);
    }
}
