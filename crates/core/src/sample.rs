//! What one primary ray brings back: the beauty, and the same radiance split by effect.
//!
//! The split follows docs/aovs.md. Along the mirror chain of a primary ray, vertex k = 0, 1, ...
//! has throughput `beta_k` (`beta_0 = 1`, `beta_{k+1} = beta_k * r_k`) and its shading counts
//! with weight `w_k = beta_k * (1 - r_k)` when the chain continues there, else `beta_k`.
//! Every field except `beauty` is a sum of weighted terms accumulated in f64; `beauty` is the
//! course's own nested evaluation, so the tick PNG is exact while the layers add up to it
//! within float rounding.

use glam::DVec3;

/// The radiance breakdown of one camera sample. Values only: the film decides what is stored.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// The colour the course's renderer computes, in its operation order.
    pub beauty: DVec3,
    /// `w_0 * shade(P_0)`, or the background on a primary miss.
    pub direct: DVec3,
    /// `reflected_by_bounce[k - 1]`: everything arriving after exactly k mirror reflections,
    /// including the background seen in a mirror. One entry per allowed bounce.
    pub reflected_by_bounce: Vec<DVec3>,
    /// `sum_k w_k * I_a * C_k`.
    pub ambient: DVec3,
    /// All lights' shadowed diffuse terms over all vertices.
    pub diffuse: DVec3,
    /// All lights' shadowed specular terms over all vertices.
    pub specular: DVec3,
    /// `beta_k * background` at the vertex where the chain leaves the scene.
    pub background: DVec3,
    /// One entry per point light, in file order.
    pub lights: Vec<LightSample>,
    /// Geometry of the first surface the camera sees, if any.
    pub primary: Option<PrimaryHit>,
    /// Rays cast for this sample: primary, shadow and reflected.
    pub rays: u64,
    /// What only a Tick 1* render measures (zero otherwise).
    pub star: StarValues,
}

/// The per-pixel values of a Tick 1* render's own layers (docs/tick1star.md), carried by each
/// of the pixel's samples.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StarValues {
    /// The variance of one course draw of the pixel (the converged estimate's; 0 in a draw).
    pub variance: DVec3,
    /// The side in pixels of the square the aperture spreads the pinhole hit over.
    pub circle_of_confusion: f64,
    /// The bump map's height at the pinhole hit (0 off bumped spheres).
    pub height: f64,
}

/// One light's share of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LightSample {
    /// Diffuse + specular where the light is visible, over all vertices, weighted by `w_k`.
    pub shadowed: DVec3,
    /// The same with visibility forced to 1.
    pub unshadowed: DVec3,
    /// The share of this light hidden at the primary hit: 0 or 1 for the tick's hard shadow
    /// ray, the occluded share of the shadow rays under Tick 1*'s soft shadows.
    pub shadowed_at_primary: f64,
}

/// The first surface along the camera ray: what the data layers (Z, N, P, albedo, objectid)
/// record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrimaryHit {
    pub position: DVec3,
    pub normal: DVec3,
    /// Diffuse colour C of the surface.
    pub albedo: DVec3,
    /// Index into `Scene::objects` (0-based; the EXR `objectid` adds 1).
    pub object: usize,
}

impl Sample {
    /// A sample with nothing in it yet, shaped for `lights` lights and `bounces` bounces.
    pub fn empty(lights: usize, bounces: u32) -> Self {
        Sample {
            beauty: DVec3::ZERO,
            direct: DVec3::ZERO,
            reflected_by_bounce: vec![DVec3::ZERO; bounces as usize],
            ambient: DVec3::ZERO,
            diffuse: DVec3::ZERO,
            specular: DVec3::ZERO,
            background: DVec3::ZERO,
            lights: vec![LightSample::default(); lights],
            primary: None,
            rays: 0,
            star: StarValues::default(),
        }
    }

    /// Empties the sample for reuse, keeping its buffers: the render loop traces millions of
    /// samples through one `Sample` instead of allocating each.
    pub fn reset(&mut self) {
        self.beauty = DVec3::ZERO;
        self.direct = DVec3::ZERO;
        self.reflected_by_bounce.fill(DVec3::ZERO);
        self.ambient = DVec3::ZERO;
        self.diffuse = DVec3::ZERO;
        self.specular = DVec3::ZERO;
        self.background = DVec3::ZERO;
        self.lights.fill(LightSample::default());
        self.primary = None;
        self.rays = 0;
        self.star = StarValues::default();
    }

    /// Everything that came through at least one mirror.
    pub fn reflected(&self) -> DVec3 {
        self.reflected_by_bounce.iter().copied().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reset_gives_an_empty_sample_of_the_same_shape() {
        let mut s = Sample::empty(2, 3);
        s.beauty = DVec3::ONE;
        s.reflected_by_bounce[1] = DVec3::ONE;
        s.lights[0].shadowed_at_primary = 1.0;
        s.rays = 9;
        s.primary = Some(PrimaryHit {
            position: DVec3::ONE,
            normal: DVec3::Y,
            albedo: DVec3::ONE,
            object: 1,
        });
        s.reset();
        assert_eq!(s, Sample::empty(2, 3));
    }
}
