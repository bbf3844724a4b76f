//! The Tick 1* renders against closed forms: a penumbra whose visible share is known exactly
//! for both light distributions, the course draw's binomial spread, and the variance the
//! expectation reports.

use glam::DVec3;

use super::*;
use crate::camera::Camera;
use crate::course::Course;
use crate::geometry::Shape;
use crate::scene::{Material, Object, PointLight, Scene};
use crate::trace::TraceOptions;

/// The light's centre; an occluding wall faces the camera at z = `LIGHT_Z + H`.
const LIGHT_Z: f64 = 6.0;
const H: f64 = 0.1;
const RADIUS: f64 = 0.4;

/// A floor at y = -1 lit by a light at (0, 1, 6) behind which a wall z = 6 + H stands: a
/// shadow ray from a floor point nearer than the wall reaches its target on the light exactly
/// when the target's z is below the wall, so the visible share is `P(R s_z < H)` for every
/// such floor point, whatever its position.
fn penumbra_scene() -> Scene {
    Scene {
        objects: vec![
            Object {
                shape: Shape::Plane {
                    point: DVec3::new(0.0, -1.0, 0.0),
                    normal: DVec3::Y,
                },
                material: Material::plane(DVec3::splat(0.8)),
            },
            Object {
                shape: Shape::Plane {
                    point: DVec3::new(0.0, 0.0, LIGHT_Z + H),
                    normal: -DVec3::Z,
                },
                material: Material::plane(DVec3::splat(0.2)),
            },
        ],
        lights: vec![PointLight {
            position: DVec3::new(0.0, 1.0, LIGHT_Z),
            colour: DVec3::ONE,
            intensity: 50.0,
            name: "key".into(),
        }],
        ambient: DVec3::splat(0.05),
    }
}

/// `P(z > t)` for z the third coordinate of the course's point (radius and polar angle
/// uniform): `(acos t - t ln((1 + sqrt(1 - t^2)) / t)) / pi` for t in (0, 1].
fn course_tail(t: f64) -> f64 {
    (t.acos() - t * ((1.0 + (1.0 - t * t).sqrt()) / t).ln()) / std::f64::consts::PI
}

/// `P(z > t)` for a point uniform in the unit ball: the cap's share `(1 - t)^2 (2 + t) / 4`.
fn uniform_tail(t: f64) -> f64 {
    (1.0 - t) * (1.0 - t) * (2.0 + t) / 4.0
}

fn frame<'a>(scene: &'a Scene, star: &'a Star) -> StarFrame<'a> {
    StarFrame {
        scene,
        camera: Camera::new(16, 12),
        course: Course::Y2016,
        trace: TraceOptions {
            bounces: 0,
            shadows: true,
        },
        star,
    }
}

/// The floor pixels nearer than the wall: the bottom sixth of the rows.
fn floor_pixels(image: &StarImage) -> Vec<usize> {
    let (w, h) = (image.width as usize, image.height as usize);
    (h * 5 / 6 * w..h * w).collect()
}

#[test]
fn the_expected_visible_share_matches_the_closed_form_for_both_distributions() {
    let scene = penumbra_scene();
    let t = H / RADIUS;
    for (sampling, visible) in [
        (LightSampling::Course, 1.0 - course_tail(t)),
        (LightSampling::Uniform, 1.0 - uniform_tail(t)),
    ] {
        let star = Star {
            soft: Some(SoftShadows {
                sampling,
                ..SoftShadows::default()
            }),
            ..Star::default()
        };
        let floor = NoiseFloor {
            standard_error: 1e-5,
            max_paths: 65536,
        };
        let image = expectation(&frame(&scene, &star), floor, 3).expect("renders");
        for i in floor_pixels(&image) {
            let got = f64::from(image.visible[0][i]);
            // Sobol points converge far faster than the iid bound; 4096 rays of 4 points.
            assert!(
                (got - visible).abs() < 3e-3,
                "{sampling:?} pixel {i}: {got} vs {visible}"
            );
        }
    }
    // The two distributions differ here by far more than the tolerance.
    assert!((course_tail(t) - uniform_tail(t)).abs() > 0.05);
}

#[test]
fn the_course_draw_is_binomial_around_the_closed_form() {
    let scene = penumbra_scene();
    let star = Star {
        soft: Some(SoftShadows::default()),
        ..Star::default()
    };
    let p = 1.0 - course_tail(H / RADIUS);
    // Many floor pixels, so that the spread of their shares is a sure estimate.
    let wide = StarFrame {
        camera: Camera::new(64, 48),
        ..frame(&scene, &star)
    };
    let image = course_draw(&wide, 11).expect("renders");
    let pixels = floor_pixels(&image);
    let shares: Vec<f64> = pixels
        .iter()
        .map(|&i| f64::from(image.visible[0][i]))
        .collect();
    // Each share is k/10: whole tenths.
    assert!(shares
        .iter()
        .all(|s| ((s * 10.0).round() - s * 10.0).abs() < 1e-6));
    let n = shares.len() as f64;
    let mean = shares.iter().sum::<f64>() / n;
    let sigma = (p * (1.0 - p) / 10.0 / n).sqrt();
    assert!(
        (mean - p).abs() < 4.0 * sigma,
        "{mean} vs {p} (sigma {sigma})"
    );
    let variance = shares.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let expected = p * (1.0 - p) / 10.0;
    assert!(
        (variance / expected - 1.0).abs() < 0.25,
        "{variance} vs {expected}"
    );
    // Another seed is another draw.
    let other = course_draw(&wide, 12).expect("renders");
    assert_ne!(image.visible, other.visible);
}

#[test]
fn the_reported_variance_is_the_binomial_one_of_the_light_s_terms() {
    let scene = penumbra_scene();
    let star = Star {
        soft: Some(SoftShadows::default()),
        ..Star::default()
    };
    let floor = NoiseFloor {
        standard_error: 1e-4,
        max_paths: 4096,
    };
    let f = frame(&scene, &star);
    let image = expectation(&f, floor, 5).expect("renders");
    // The light's unoccluded terms at a pixel: the render without shadows minus the ambient
    // term, which is the converged one with visibility 1.
    let lit = Star::default();
    let unshadowed = expectation(
        &StarFrame {
            trace: TraceOptions {
                bounces: 0,
                shadows: false,
            },
            ..frame(&scene, &lit)
        },
        floor,
        5,
    )
    .expect("renders");
    let p = 1.0 - course_tail(H / RADIUS);
    for i in floor_pixels(&image) {
        let ambient = DVec3::splat(0.05) * 0.8;
        let terms = unshadowed.beauty[i] - ambient;
        let expected = terms * terms * (p * (1.0 - p) / 10.0);
        let got = image.variance[i];
        assert!(
            ((got - expected) / expected).abs().max_element() < 0.03,
            "pixel {i}: {got} vs {expected}"
        );
        let mean = ambient + terms * p;
        assert!((image.beauty[i] - mean).abs().max_element() < 3e-3 * terms.max_element());
    }
}

#[test]
fn without_effects_the_star_render_is_the_tick_render() {
    let scene = penumbra_scene();
    let star = Star::default();
    let f = frame(&scene, &star);
    let image = course_draw(&f, 0).expect("renders");
    let accel = crate::accel::Accelerator::build(&scene.objects);
    for (i, b) in image.beauty.iter().enumerate() {
        let (x, y) = (i as u32 % 16, i as u32 / 16);
        let tick = crate::trace::trace(&scene, &accel, f.camera.pixel_centre_ray(x, y), f.trace);
        assert!((tick.beauty - *b).abs().max_element() < 1e-12, "pixel {i}");
    }
}

#[test]
fn course_draws_scatter_around_the_expectation_by_the_reported_variance() {
    // Soft shadows and depth of field together, at 32 x 24: the mean of K course draws of a
    // pixel is normal around the expectation with variance `variance / K`.
    let scene = penumbra_scene();
    let star = Star {
        soft: Some(SoftShadows::default()),
        dof: Some(DepthOfField {
            focal_z: 3.0,
            side: 0.4,
            rays: 6,
        }),
        ..Star::default()
    };
    let frame = StarFrame {
        camera: Camera::new(32, 24),
        ..frame(&scene, &star)
    };
    let expected = expectation(&frame, NoiseFloor::default(), 1).expect("renders");
    let k = 40;
    let mut sums = vec![DVec3::ZERO; expected.beauty.len()];
    for seed in 0..k {
        let draw = course_draw(&frame, 100 + seed).expect("renders");
        for (s, b) in sums.iter_mut().zip(&draw.beauty) {
            *s += *b;
        }
    }
    let (mut tested, mut outliers) = (0, 0);
    for (i, s) in sums.iter().enumerate() {
        let mean = *s / k as f64;
        // The expectation is promised to the noise floor (its standard error estimate, from
        // eight replicates, is itself noisy).
        let floor = NoiseFloor::default().standard_error;
        let error = expected.standard_error[i].max(DVec3::splat(floor));
        let sd = (expected.variance[i] / k as f64 + error * error).powf(0.5);
        for c in 0..3 {
            if sd[c] < 1e-9 {
                assert!((mean[c] - expected.beauty[i][c]).abs() < 1e-9, "pixel {i}");
                continue;
            }
            tested += 1;
            if ((mean[c] - expected.beauty[i][c]) / sd[c]).abs() > 4.0 {
                outliers += 1;
            }
        }
    }
    assert!(tested > 300, "{tested} random channels");
    // |z| > 4 has probability 6e-5 for a normal; allow a few for the heavier tails of small K.
    assert!(
        outliers <= tested / 200,
        "{outliers} of {tested} channels beyond 4 sigma"
    );
}
