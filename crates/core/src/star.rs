//! The course's Tick 1* (docs/tick1star.md): bump mapping, soft shadows from a sphere light
//! and depth of field, rendered two ways.
//!
//! - [`course_draw`]: one draw of the course's own random process (10 shadow rays per light
//!   from `randomInsideUnitSphere`, 50 aperture rays), seeded: what a correct student
//!   program's screenshot is a draw of.
//! - [`expectation`]: per pixel, the expectation of that process and the variance of one
//!   draw, estimated with low-discrepancy samples to a stated noise floor. A statistical
//!   check compares a student's image with these.
//!
//! Both give the same image for a seed whatever the number of threads: every pixel draws
//! from its own stream (`streams`). Bump mapping is deterministic and shared by both.
//!
//! # The statistic
//! Along a camera ray's mirror chain the radiance is linear in each light's visible share at
//! each vertex, `c = sum_k w_k (a_k + sum_i f_ki t_ki) + background`, and the course draws each
//! `f_ki` as k/n of n shadow rays, independently: `E[c] = c(p)` and
//! `Var[c] = sum_ki (w_k t_ki)^2 p_ki (1 - p_ki) / n`. Depth of field averages D such rays over
//! the aperture: `Var = (Var_aperture(E[c|a]) + E_aperture(Var[c|a])) / D`. All values are
//! linear radiance before the tone map (the course averages before its per-pixel tone map).

pub mod aperture;
pub mod bump;
pub mod image;
pub mod light;
pub mod path;
pub mod streams;

use std::sync::Arc;

pub use aperture::{DepthOfField, Focus};
pub use bump::{BumpMap, BumpMethod, BumpMistake, Parametrisation};
pub use image::{
    course_draw, expectation, expectation_counted, expectation_on, star_film, Grid, NoiseFloor,
    Sampling, StarFrame, StarImage, StarStats,
};
pub use light::{LightSampling, ShadowShare, ShadowedTerms, SoftShadows};

/// A sphere of the scene that carries a bump map.
#[derive(Debug, Clone, PartialEq)]
pub struct BumpedSphere {
    /// Index into `Scene::objects`.
    pub object: usize,
    pub map: Arc<BumpMap>,
}

/// What a Tick 1* render adds to the tick model. The default adds nothing: a render with it
/// is the tick render's radiance.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Star {
    /// Soft shadows; `None` is the tick's hard shadow ray.
    pub soft: Option<SoftShadows>,
    /// Depth of field; `None` is the pinhole.
    pub dof: Option<DepthOfField>,
    /// The scene's bumped spheres.
    pub bumps: Vec<BumpedSphere>,
    /// How their normals are perturbed.
    pub bump: BumpMethod,
}

impl Star {
    /// The bump map of object `object`, if it is a bumped sphere.
    pub fn bump_map(&self, object: usize) -> Option<&BumpMap> {
        self.bumps
            .iter()
            .find(|b| b.object == object)
            .map(|b| b.map.as_ref())
    }

    /// Whether a render differs from one pixel-centre sample per pixel of the tick model.
    pub fn is_random(&self) -> bool {
        self.soft.is_some() || self.dof.is_some()
    }
}

#[cfg(test)]
mod tests;
