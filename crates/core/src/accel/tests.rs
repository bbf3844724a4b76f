//! The hierarchy against brute force: random rays, ties, long badly conditioned rays.

use super::*;
use crate::geometry::normalise;
use crate::geometry::Shape;
use crate::model::Tick;
use crate::scene::{Material, Object};

/// Brute force over every object, the reference.
fn closest_hit(objects: &[Object], ray: &Ray) -> Option<Hit> {
    search::closest_hit(&Tick, objects.iter().map(|o| &o.shape).enumerate(), ray)
}

fn occluded(objects: &[Object], ray: &Ray, max_distance: f64) -> bool {
    search::occluded(
        &Tick,
        objects.iter().map(|o| &o.shape).enumerate(),
        ray,
        max_distance,
    )
}

/// A small deterministic generator, so the test needs no randomness crate.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

fn scene(n: usize, seed: u64) -> Vec<Object> {
    let mut rng = Lcg(seed);
    let mut objects: Vec<Object> = (0..n)
        .map(|_| Object {
            shape: Shape::Sphere {
                centre: DVec3::new(
                    rng.range(-5.0, 5.0),
                    rng.range(-5.0, 5.0),
                    rng.range(2.0, 12.0),
                ),
                radius: rng.range(0.05, 0.8),
            },
            material: Material::sphere(DVec3::ONE),
        })
        .collect();
    // Duplicates make exact ties; a plane makes the unbounded list non-empty.
    objects.push(objects[3].clone());
    objects.push(objects[0].clone());
    objects.insert(
        5,
        Object {
            shape: Shape::Plane {
                point: DVec3::new(0.0, -3.0, 0.0),
                normal: DVec3::Y,
            },
            material: Material::plane(DVec3::ONE),
        },
    );
    objects
}

#[test]
fn agrees_with_brute_force_on_random_rays_including_ties() {
    for (n, seed) in [(10, 1), (200, 2), (2000, 3)] {
        let objects = scene(n, seed);
        let accel = Accelerator::build(&objects);
        let brute = Accelerator::brute_force(&objects);
        let mut rng = Lcg(seed + 100);
        for _ in 0..3000 {
            let origin = DVec3::new(
                rng.range(-6.0, 6.0),
                rng.range(-6.0, 6.0),
                rng.range(-2.0, 14.0),
            );
            let direction = normalise(DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ));
            let ray = Ray::new(origin, direction);
            let expected = closest_hit(&objects, &ray);
            assert_eq!(accel.closest_hit(&Tick, &ray), expected);
            assert_eq!(brute.closest_hit(&Tick, &ray), expected);
            let d = rng.range(0.1, 20.0);
            assert_eq!(accel.occluded(&Tick, &ray, d), occluded(&objects, &ray, d));
        }
    }
}

/// Spheres with radii down to 1e-4 in a cluster, and rays from up to 1e7 away aimed at
/// points near them: the badly conditioned case where the formula reports hits outside the
/// sphere. The hierarchy must report exactly those hits too.
fn long_rays(seed: u64, rays: usize) -> (Vec<Object>, Vec<(Ray, f64)>) {
    let mut rng = Lcg(seed);
    let objects: Vec<Object> = (0..300)
        .map(|_| Object {
            shape: Shape::Sphere {
                centre: DVec3::new(
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                    rng.range(2.0, 8.0),
                ),
                radius: 10f64.powf(rng.range(-4.0, -1.0)),
            },
            material: Material::sphere(DVec3::ONE),
        })
        .collect();
    let cases = (0..rays)
        .map(|_| {
            let Shape::Sphere { centre, radius } =
                objects[(rng.next() * objects.len() as f64) as usize].shape
            else {
                unreachable!("only spheres")
            };
            let far = 10f64.powf(rng.range(0.0, 7.0));
            let origin = centre
                + far
                    * normalise(DVec3::new(
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                    ));
            // Aim within a few radii of the centre, and up to 0.3 away at long range.
            let spread = radius * 3.0 + far * 3e-8;
            let target = centre
                + DVec3::new(
                    rng.range(-spread, spread),
                    rng.range(-spread, spread),
                    rng.range(-spread, spread),
                );
            let ray = Ray::new(origin, normalise(target - origin));
            (ray, far * rng.range(0.5, 1.5))
        })
        .collect();
    (objects, cases)
}

#[test]
fn agrees_with_brute_force_on_long_badly_conditioned_rays() {
    let (objects, cases) = long_rays(11, 20_000);
    let accel = Accelerator::build(&objects);
    let mut outside = 0;
    for (ray, max_distance) in &cases {
        let expected = closest_hit(&objects, ray);
        assert_eq!(accel.closest_hit(&Tick, ray), expected, "{ray:?}");
        assert_eq!(
            accel.occluded(&Tick, ray, *max_distance),
            occluded(&objects, ray, *max_distance),
            "{ray:?}"
        );
        if let Some(hit) = expected {
            let Shape::Sphere { centre, radius } = objects[hit.object].shape else {
                unreachable!("only spheres")
            };
            let miss_by = (ray.at(hit.distance) - centre).length() - radius;
            outside += usize::from(miss_by > radius * 1e-4 + 1e-9);
        }
    }
    // The case this guards: hits reported well outside their sphere, which a box padded
    // by a fixed fraction of the radius would cull.
    assert!(outside > 100, "only {outside} hits outside their sphere");
}

#[test]
fn reported_hits_stay_within_the_conditioning_bound() {
    // The margin's argument, checked: how far outside its sphere a reported hit lies,
    // relative to |O - C| + r, stays below CONDITIONING_BOUND with room to spare.
    let (objects, cases) = long_rays(12, 20_000);
    let mut worst: f64 = 0.0;
    for (ray, _) in &cases {
        for object in &objects {
            let Shape::Sphere { centre, radius } = object.shape else {
                unreachable!("only spheres")
            };
            if let Some(s) = search::intersect(&Tick, &object.shape, ray) {
                let outside = (ray.at(s) - centre).length() - radius;
                let scale = (ray.origin - centre).length() + radius;
                worst = worst.max(outside / scale);
            }
        }
    }
    assert!(worst > 1e-9, "no badly conditioned hit was generated");
    assert!(
        worst < margin::CONDITIONING_BOUND / 2.0,
        "worst ratio {worst:e}"
    );
}

#[test]
fn a_single_leaf_hierarchy_keeps_brute_force_ties() {
    // Six spheres (two duplicates) and a plane: the root is one leaf, tested without boxes.
    let objects = scene(4, 5);
    let accel = Accelerator::build(&objects);
    assert!(accel.nodes.len() == 1 && accel.nodes[0].count > 0);
    let Shape::Sphere { centre, .. } = objects[0].shape else {
        panic!("sphere")
    };
    let ray = Ray::new(DVec3::new(centre.x, centre.y, -20.0), DVec3::Z);
    assert_eq!(accel.closest_hit(&Tick, &ray), closest_hit(&objects, &ray));
    assert_eq!(accel.closest_hit(&Tick, &ray).expect("hits").object, 0);
    assert_eq!(
        accel.occluded(&Tick, &ray, 100.0),
        occluded(&objects, &ray, 100.0)
    );
}

#[test]
fn duplicate_spheres_tie_to_the_first_in_file_order() {
    let objects = scene(50, 7);
    let accel = Accelerator::build(&objects);
    let Shape::Sphere { centre, .. } = objects[0].shape else {
        panic!("sphere")
    };
    let ray = Ray::new(DVec3::new(centre.x, centre.y, -20.0), DVec3::Z);
    let hit = accel.closest_hit(&Tick, &ray).expect("hits");
    assert_eq!(hit, closest_hit(&objects, &ray).expect("hits"));
    assert!(
        hit.object < objects.len() - 1,
        "the later duplicate must not win"
    );
}

#[test]
fn builds_a_real_hierarchy() {
    let objects = scene(5000, 9);
    let accel = Accelerator::build(&objects);
    assert_eq!(accel.items.len(), objects.len() - 1);
    assert_eq!(accel.unbounded, [(5, objects[5].shape)]);
    let leaves: Vec<&Node> = accel.nodes.iter().filter(|n| n.count > 0).collect();
    assert!(leaves.len() > 5000 / 8, "{} leaves", leaves.len());
    assert!(leaves.iter().all(|n| n.count <= 16));
}

#[test]
fn the_hierarchy_is_the_same_for_any_thread_count() {
    // Large enough for the parallel paths (binning in chunks, subtrees and node writing on
    // several threads), with planes scattered through the file.
    let mut objects = scene(4 * build::PARALLEL_BIN_CHUNK + 5000, 11);
    let plane = objects[5].clone();
    for i in [0, 17, 40_000, objects.len() - 1] {
        objects.insert(i, plane.clone());
    }
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool")
            .install(|| Accelerator::build(&objects))
    };
    let one = on(1);
    assert_eq!(one, on(3));
    // Every sphere is in exactly one leaf, and only spheres are.
    let mut items: Vec<usize> = one.items.iter().map(|&i| i as usize).collect();
    items.sort_unstable();
    let spheres: Vec<usize> = (0..objects.len())
        .filter(|&i| matches!(objects[i].shape, Shape::Sphere { .. }))
        .collect();
    assert_eq!(items, spheres);
    assert_eq!(one.unbounded.len(), 5);
}
