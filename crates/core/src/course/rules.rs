//! A profile's rules as plain data, and the one [`Model`] that reads them: every method not
//! overridden here is 2016-17's (the trait's default), so a year differs from the course's
//! first model exactly where docs/courses.md says it does.

use glam::DVec3;

use super::{ShadowBias, View};
use crate::geometry::{normalise, sphere_near_else_far_hit, Ray, SphereTerms};
use crate::model::{Model, Tick};
use crate::scene::PointLight;

/// The rules that differ between years (docs/courses.md, "Rules that differ from 2016-17").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rules {
    pub view: View,
    /// The specular term carries the light's colour (`C_light * I`, so the colour enters
    /// twice), rather than white `I`.
    pub light_coloured_specular: bool,
    /// A light adds nothing (no diffuse, no specular, no shadow ray) where `N.L < 0`.
    pub gate: bool,
    /// `R = 2 (N.L) N - L` from the raw `N.L`, rather than the clamped one.
    pub reflect_unclamped: bool,
    pub shadow_bias: ShadowBias,
    /// A sphere hit from inside counts: the near root, else the far one if positive.
    pub far_root: bool,
    /// The radiance of a ray that leaves the scene, on every channel.
    pub background: f64,
}

impl Model for Rules {
    #[inline]
    fn sphere_root(
        &self,
        ray: &Ray,
        terms: &SphereTerms,
        centre: DVec3,
        radius_squared: f64,
    ) -> Option<f64> {
        if self.far_root {
            sphere_near_else_far_hit(ray, terms, centre, radius_squared)
        } else {
            Tick.sphere_root(ray, terms, centre, radius_squared)
        }
    }

    #[inline]
    fn far_root(&self) -> bool {
        self.far_root
    }

    #[inline]
    fn background(&self) -> DVec3 {
        DVec3::splat(self.background)
    }

    #[inline]
    fn view(&self, p: DVec3, ray_origin: DVec3) -> DVec3 {
        match self.view {
            View::ToCamera => Tick.view(p, ray_origin),
            View::FromRayOrigin => normalise(ray_origin - p),
        }
    }

    #[inline]
    fn reaches(&self, n_dot_l: f64) -> bool {
        // NaN is not < 0: a NaN N.L lights, as the course's `if (N.L < 0)` lets it.
        !(self.gate && n_dot_l < 0.0)
    }

    #[inline]
    fn specular_mirror(&self, n: DVec3, l: DVec3, n_dot_l: f64) -> DVec3 {
        if self.reflect_unclamped {
            n * (2.0 * n.dot(l)) - l
        } else {
            Tick.specular_mirror(n, l, n_dot_l)
        }
    }

    #[inline]
    fn specular(
        &self,
        light: &PointLight,
        illumination: DVec3,
        ks: f64,
        phong: f64,
        colour: DVec3,
        n_dot_l: f64,
    ) -> DVec3 {
        if self.light_coloured_specular {
            ((light.colour * illumination) * ks) * phong
        } else {
            Tick.specular(light, illumination, ks, phong, colour, n_dot_l)
        }
    }

    #[inline]
    fn shadow_ray(&self, p: DVec3, l: DVec3, n: DVec3) -> Ray {
        match self.shadow_bias {
            ShadowBias::AlongL => Tick.shadow_ray(p, l, n),
            ShadowBias::AlongN => Ray::new(p + n * self.epsilon(), l),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::course::Course;

    #[test]
    fn the_2016_17_rules_are_the_course_s_model() {
        let rules = Course::Y2016.rules();
        let (p, o) = (DVec3::new(0.3, -0.2, 4.0), DVec3::new(1.0, 1.0, 1.0));
        assert_eq!(rules.view(p, o), Tick.view(p, o));
        assert_eq!(rules.background(), Tick.background());
        let (n, l) = (DVec3::Y, normalise(DVec3::new(1.0, -1.0, 0.0)));
        assert_eq!(
            rules.specular_mirror(n, l, 0.0),
            Tick.specular_mirror(n, l, 0.0)
        );
        assert_eq!(rules.shadow_ray(p, l, n), Tick.shadow_ray(p, l, n));
        assert!(rules.reaches(-1.0));
    }

    use crate::accel::Accelerator;
    use crate::frame::{Frame, FrameSpec};
    use crate::render::trace_pixels;
    use crate::scene::Scene;

    /// The course's tick2 scene at 64x48 and 3 bounces, with every pixel.
    struct Tick2 {
        scene: Scene,
        frame: Frame,
        accel: Accelerator,
        pixels: Vec<(u32, u32)>,
    }

    impl Tick2 {
        fn at_64x48() -> Tick2 {
            let scene =
                crate::scene::parse_str("tick2.xml", crate::scene::EMBEDDED_TICK2).expect("tick2");
            let frame = Frame::new(&scene, &FrameSpec::tick(64, 48, 3, true)).expect("frame");
            let accel = Accelerator::build(&scene.objects);
            let pixels = (0..48).flat_map(|y| (0..64).map(move |x| (x, y))).collect();
            Tick2 {
                scene,
                frame,
                accel,
                pixels,
            }
        }

        /// What `keep` keeps of every pixel's sample under `model`.
        fn trace<const LAYERS: bool, T>(
            &self,
            model: &impl crate::model::Model,
            keep: impl Fn(&crate::sample::Sample) -> T,
        ) -> Vec<T> {
            let Tick2 {
                scene,
                frame,
                accel,
                pixels,
            } = self;
            trace_pixels::<LAYERS, _>(model, scene, accel, frame, pixels, keep)
        }
    }

    #[test]
    fn every_year_s_beauty_is_the_same_without_the_layers_where_lights_are_shadowed() {
        // Without the layers (a PNG or a check's bytes) a shadowed light's terms are never
        // computed (`Observer::READS_SHADOWED_TERMS`); the beauty must not notice.
        let tick2 = Tick2::at_64x48();
        for course in Course::ALL {
            let rules = course.rules();
            let layered = tick2.trace::<true, _>(&rules, |s| {
                let shadowed = s.lights.iter().any(|l| l.shadowed_at_primary > 0.0);
                (s.beauty.to_array().map(f64::to_bits), shadowed)
            });
            let bare = tick2.trace::<false, _>(&rules, |s| s.beauty.to_array().map(f64::to_bits));
            let shadowed = layered.iter().filter(|(_, shadowed)| *shadowed).count();
            assert!(shadowed > 50, "{course}: {shadowed} pixels in some shadow");
            let layered: Vec<[u64; 3]> = layered.into_iter().map(|(b, _)| b).collect();
            assert_eq!(layered, bare, "{course}");
        }
    }

    #[test]
    fn the_2016_17_rules_render_what_tick_renders_on_every_pixel() {
        // `render` runs `Tick` for 2016-17 (the same code as before there were years); the
        // data-driven rules, which `explain` and the viewer trace, must agree with it.
        let tick2 = Tick2::at_64x48();
        let tick = tick2.trace::<true, _>(&Tick, |s| format!("{s:?}"));
        let rules = tick2.trace::<true, _>(&Course::Y2016.rules(), |s| format!("{s:?}"));
        assert_eq!(tick.len(), 64 * 48);
        assert_eq!(tick, rules);
    }

    #[test]
    fn later_years_gate_on_n_dot_l_and_move_the_shadow_ray_along_n() {
        let rules = Course::Y2020.rules();
        assert!(!rules.reaches(-1e-300));
        assert!(rules.reaches(0.0) && rules.reaches(-0.0) && rules.reaches(f64::NAN));
        let (p, l, n) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        assert_eq!(rules.shadow_ray(p, l, n).origin, DVec3::new(0.0, 1e-4, 0.0));
        assert_eq!(
            Course::Y2019.rules().shadow_ray(p, l, n).origin,
            DVec3::new(1e-4, 0.0, 0.0)
        );
        let o = DVec3::new(0.0, 0.0, 2.0);
        assert_eq!(rules.view(DVec3::new(0.0, 0.0, 4.0), o), DVec3::NEG_Z);
    }

    #[test]
    fn the_light_s_colour_enters_the_specular_twice() {
        let light = PointLight {
            position: DVec3::ZERO,
            colour: DVec3::new(1.0, 0.5, 0.25),
            intensity: 100.0,
            name: String::new(),
        };
        let i = light.colour * 2.0;
        let s = Course::Y2019
            .rules()
            .specular(&light, i, 1.0, 1.0, DVec3::ONE, 1.0);
        assert_eq!(s, DVec3::new(2.0, 0.5, 0.125));
    }
}
