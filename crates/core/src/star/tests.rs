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

/// `P(z > t)` for the course's point normalised (its polar angle uniform): `acos(t) / pi`.
fn surface_tail(t: f64) -> f64 {
    t.acos() / std::f64::consts::PI
}

/// The penumbra scene with a glossy floor, so that a light's specular term is not zero.
fn glossy_penumbra_scene() -> Scene {
    let mut scene = penumbra_scene();
    scene.objects[0].material.ks = 0.6;
    scene.objects[0].material.n = 1.0;
    scene
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
        (LightSampling::Surface, 1.0 - surface_tail(t)),
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
    // The distributions differ here by far more than the tolerance.
    assert!((course_tail(t) - uniform_tail(t)).abs() > 0.05);
    assert!((course_tail(t) - surface_tail(t)).abs() > 0.05);
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

/// The expectation of `scene` with `star` and shadows as given, to a tight floor.
fn converged(scene: &Scene, star: &Star, shadows: bool) -> StarImage {
    let floor = NoiseFloor {
        standard_error: 1e-4,
        max_paths: 4096,
    };
    let f = StarFrame {
        trace: TraceOptions {
            bounces: 0,
            shadows,
        },
        ..frame(scene, star)
    };
    expectation(&f, floor, 5).expect("renders")
}

#[test]
fn the_reported_variance_is_the_binomial_one_of_the_light_s_terms() {
    // On a glossy floor, for the handout's share and the two ways students misuse it: the
    // radiance is ambient + g p (terms scaled) + (terms not scaled), its variance
    // (g terms scaled)^2 p (1 - p) / 10, with g = 10 for the count unaveraged.
    let scene = glossy_penumbra_scene();
    let mut matte = scene.clone();
    matte.objects[0].material.ks = 0.0;
    // The light's unoccluded terms at a pixel: the render without shadows minus the ambient
    // term, which is the converged one with visibility 1; the diffuse alone from the floor
    // without its gloss.
    let lit = Star::default();
    let unshadowed = converged(&scene, &lit, false);
    let diffuse_only = converged(&matte, &lit, false);
    let p = 1.0 - course_tail(H / RADIUS);
    for (share, scaled, gain) in [
        (ShadowShare::Averaged, ShadowedTerms::Both, 1.0),
        (ShadowShare::Count, ShadowedTerms::Both, 10.0),
        (ShadowShare::Averaged, ShadowedTerms::DiffuseOnly, 1.0),
    ] {
        let star = Star {
            soft: Some(SoftShadows {
                share,
                scaled,
                ..SoftShadows::default()
            }),
            ..Star::default()
        };
        let image = converged(&scene, &star, true);
        let mut glossy = 0;
        for i in floor_pixels(&image) {
            let ambient = DVec3::splat(0.05) * 0.8;
            let terms = unshadowed.beauty[i] - ambient;
            let diffuse = diffuse_only.beauty[i] - ambient;
            let specular = terms - diffuse;
            glossy += usize::from(specular.min_element() > 0.05 * terms.max_element());
            let (scaled_terms, fixed) = match scaled {
                ShadowedTerms::Both => (terms, DVec3::ZERO),
                ShadowedTerms::DiffuseOnly => (diffuse, specular),
            };
            let slope = scaled_terms * gain;
            let expected = slope * slope * (p * (1.0 - p) / 10.0);
            let got = image.variance[i];
            assert!(
                ((got - expected) / expected).abs().max_element() < 0.03,
                "{share:?} {scaled:?} pixel {i}: {got} vs {expected}"
            );
            let mean = ambient + slope * p + fixed;
            assert!(
                (image.beauty[i] - mean).abs().max_element() < 3e-3 * slope.max_element(),
                "{share:?} {scaled:?} pixel {i}: {} vs {mean}",
                image.beauty[i]
            );
            // The visible share is the light's, whatever scales the terms.
            assert!((f64::from(image.visible[0][i]) - p).abs() < 3e-3);
        }
        // The specular term is a real share of the light's at most floor pixels.
        let pixels = floor_pixels(&image).len();
        assert!(glossy * 2 > pixels, "{glossy} of {pixels} glossy");
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
    // Soft shadows and depth of field together, at 32 x 24, on the glossy floor: the mean of
    // K course draws of a pixel is normal around the expectation with variance
    // `variance / K`, for the handout's process and each variant a check names.
    let scene = glossy_penumbra_scene();
    let soft = SoftShadows::default();
    let dof = DepthOfField {
        focal_z: 3.0,
        side: 0.4,
        rays: 6,
        ..DepthOfField::default()
    };
    let variants = [
        (soft, dof),
        (
            SoftShadows {
                sampling: LightSampling::Surface,
                ..soft
            },
            dof,
        ),
        (
            SoftShadows {
                share: ShadowShare::Count,
                ..soft
            },
            dof,
        ),
        (
            SoftShadows {
                scaled: ShadowedTerms::DiffuseOnly,
                ..soft
            },
            dof,
        ),
        (
            soft,
            DepthOfField {
                focus: aperture::Focus::Distance,
                ..dof
            },
        ),
    ];
    for (soft, dof) in variants {
        let star = Star {
            soft: Some(soft),
            dof: Some(dof),
            ..Star::default()
        };
        draws_scatter_around_the_expectation(&scene, &star);
    }
}

fn draws_scatter_around_the_expectation(scene: &Scene, star: &Star) {
    let frame = StarFrame {
        camera: Camera::new(32, 24),
        ..frame(scene, star)
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
                assert!(
                    (mean[c] - expected.beauty[i][c]).abs() < 1e-9,
                    "{star:?} pixel {i}"
                );
                continue;
            }
            tested += 1;
            if ((mean[c] - expected.beauty[i][c]) / sd[c]).abs() > 4.0 {
                outliers += 1;
            }
        }
    }
    assert!(tested > 300, "{star:?}: {tested} random channels");
    // |z| > 4 has probability 6e-5 for a normal; allow a few for the heavier tails of small K.
    assert!(
        outliers <= tested / 200,
        "{star:?}: {outliers} of {tested} channels beyond 4 sigma"
    );
}

/// A sparse expectation is the whole one's values at the grid's pixels, bit for bit.
#[test]
fn an_expectation_on_a_grid_is_the_whole_one_at_its_pixels() {
    let scene = penumbra_scene();
    let star = Star {
        soft: Some(SoftShadows::default()),
        dof: Some(DepthOfField::default()),
        ..Star::default()
    };
    let f = frame(&scene, &star);
    let floor = NoiseFloor {
        standard_error: 4.0 / 255.0,
        max_paths: 128,
    };
    let whole = expectation(&f, floor, 7).expect("renders");
    let grid = Grid { stride: 3 };
    let sparse = expectation_on(&f, floor, 7, grid).expect("renders");
    assert_eq!(sparse.width, grid.count(whole.width));
    assert_eq!(sparse.height, grid.count(whole.height));
    assert!(sparse.width >= 2 && sparse.height >= 2);
    for j in 0..sparse.height {
        for i in 0..sparse.width {
            let s = (j * sparse.width + i) as usize;
            let w = (grid.at(j) * whole.width + grid.at(i)) as usize;
            assert_eq!(sparse.beauty[s], whole.beauty[w], "({i}, {j})");
            assert_eq!(sparse.variance[s], whole.variance[w], "({i}, {j})");
        }
    }
    // Counted (the check's progress bar), the same image, one call per row of the grid.
    let rows = std::sync::atomic::AtomicU32::new(0);
    let counted = expectation_counted(&f, (floor, 7), grid, &|| {
        rows.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    })
    .expect("renders");
    assert_eq!(counted, sparse);
    assert_eq!(rows.into_inner(), sparse.height);
}
