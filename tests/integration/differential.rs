//! The hierarchy is invisible: adversarial scenes rendered with the BVH and with brute force
//! give bit-identical films, every layer, at several bounce counts (docs/rendering.md, "Closest
//! hit": the brute-force loop defines the result on every ray).
//!
//! `cargo test` runs a few scenes of every class. `WHITTED_DIFFERENTIAL_SCENES=N` runs N
//! scenes per class instead (the longer run reported in issue notes).

use crate::common::{render_frame, Lcg};
use whitted_core::course::Course;
use whitted_core::film::Film;
use whitted_core::frame::{Acceleration, FrameSpec};
use whitted_core::render::RenderStats;
use whitted_core::scene::parse_str;

/// The kinds of scene that stress the rules at their edges.
#[derive(Debug, Clone, Copy)]
enum Class {
    CameraInsideSphere,
    LightsInsideSpheres,
    LightOnSurface,
    PlaneThroughEye,
    TiesAndDuplicates,
    FarAndTiny,
    MirrorHall,
    ManyLights,
    LongRays,
}

const CLASSES: [Class; 9] = [
    Class::CameraInsideSphere,
    Class::LightsInsideSpheres,
    Class::LightOnSurface,
    Class::PlaneThroughEye,
    Class::TiesAndDuplicates,
    Class::FarAndTiny,
    Class::MirrorHall,
    Class::ManyLights,
    Class::LongRays,
];

fn sphere(x: f64, y: f64, z: f64, r: f64, colour: &str, extra: &str) -> String {
    format!("<sphere x=\"{x:e}\" y=\"{y:e}\" z=\"{z:e}\" radius=\"{r:e}\" colour=\"{colour}\" {extra}/>\n")
}

fn plane(p: [f64; 3], n: [f64; 3], colour: &str, extra: &str) -> String {
    format!(
        "<plane x=\"{:e}\" y=\"{:e}\" z=\"{:e}\" nx=\"{:e}\" ny=\"{:e}\" nz=\"{:e}\" colour=\"{colour}\" {extra}/>\n",
        p[0], p[1], p[2], n[0], n[1], n[2]
    )
}

fn light(x: f64, y: f64, z: f64, colour: &str, intensity: f64) -> String {
    format!("<point-light x=\"{x:e}\" y=\"{y:e}\" z=\"{z:e}\" colour=\"{colour}\" intensity=\"{intensity:e}\"/>\n")
}

/// A handful of ordinary spheres in front of the camera, so every class has a real hierarchy.
fn crowd(rng: &mut Lcg, n: usize) -> String {
    (0..n)
        .map(|_| {
            let c = rng.colour();
            sphere(
                rng.range(-3.0, 3.0),
                rng.range(-2.0, 2.0),
                rng.range(3.0, 9.0),
                rng.range(0.05, 0.6),
                &c,
                "",
            )
        })
        .collect()
}

/// One scene of `class`, as XML.
fn generate(class: Class, rng: &mut Lcg) -> String {
    let mut xml = String::from("<scene>\n<ambient-light colour=\"#303030\"/>\n");
    let c = rng.colour();
    match class {
        Class::CameraInsideSphere => {
            xml += &sphere(0.1, -0.05, 0.2, 1.5, &c, "reflectivity=\"0.5\"");
            xml += &crowd(rng, 30);
            xml += &light(0.2, 0.3, 0.1, "#FFFFFF", 50.0);
            xml += &light(2.0, 3.0, 4.0, "#FFA0A0", 200.0);
        }
        Class::LightsInsideSpheres => {
            xml += &crowd(rng, 30);
            for _ in 0..3 {
                let (x, y, z) = (
                    rng.range(-2.0, 2.0),
                    rng.range(-1.0, 1.0),
                    rng.range(4.0, 7.0),
                );
                xml += &sphere(x, y, z, rng.range(0.2, 0.8), &rng.colour(), "");
                xml += &light(x, y, z, "#FFFFFF", 80.0);
            }
        }
        Class::LightOnSurface => {
            // Lights exactly on a plane and at sphere poles (exact in binary).
            xml += &plane([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], &c, "");
            xml += &light(0.5, -1.0, 5.0, "#FFFFFF", 60.0);
            xml += &sphere(0.0, 0.0, 6.0, 1.0, &rng.colour(), "");
            xml += &light(0.0, 1.0, 6.0, "#A0FFA0", 60.0);
            xml += &crowd(rng, 25);
            xml += &light(-2.0, 3.0, 1.0, "#FFFFFF", 150.0);
        }
        Class::PlaneThroughEye => {
            // Through the origin with a specular term, so V = 0/0 reaches the colour.
            let n = [
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ];
            xml += &plane([0.0; 3], n, &c, "kS=\"0.5\" n=\"7\"");
            xml += &plane(
                [0.0; 3],
                [0.0, 1.0, 0.0],
                &rng.colour(),
                "kS=\"0.3\" n=\"3\"",
            );
            xml += &crowd(rng, 30);
            xml += &light(1.0, 2.0, 3.0, "#FFFFFF", 120.0);
        }
        Class::TiesAndDuplicates => {
            // Every sphere twice, in different colours (the first must win), and coincident
            // planes.
            let spheres: Vec<[f64; 4]> = (0..20)
                .map(|_| {
                    let (x, y) = (rng.range(-3.0, 3.0), rng.range(-2.0, 2.0));
                    [x, y, rng.range(3.0, 9.0), rng.range(0.05, 0.6)]
                })
                .collect();
            for copy in 0..2 {
                for [x, y, z, r] in &spheres {
                    let colour = if copy == 0 { "#FF0000" } else { "#00FF00" };
                    xml += &sphere(*x, *y, *z, *r, colour, "");
                }
            }
            xml += &plane([0.0, -1.5, 0.0], [0.0, 1.0, 0.0], &c, "");
            xml += &plane([0.0, -1.5, 0.0], [0.0, 2.0, 0.0], &rng.colour(), "");
            xml += &plane(
                [0.0, 0.0, 12.0],
                [0.0, 0.0, -1.0],
                &rng.colour(),
                "reflectivity=\"0.9\"",
            );
            xml += &light(0.0, 4.0, 2.0, "#FFFFFF", 300.0);
        }
        Class::FarAndTiny => {
            xml += &crowd(rng, 10);
            for _ in 0..40 {
                let far = 10f64.powf(rng.range(2.0, 7.0));
                let (x, y) = (rng.range(-0.4, 0.4) * far, rng.range(-0.3, 0.3) * far);
                xml += &sphere(x, y, far, far * rng.range(1e-4, 5e-2), &rng.colour(), "");
                xml += &sphere(
                    rng.range(-0.4, 0.4),
                    rng.range(-0.3, 0.3),
                    rng.range(1.0, 5.0),
                    10f64.powf(rng.range(-4.0, -2.0)),
                    &rng.colour(),
                    "",
                );
            }
            xml += &light(1e7, 1e7, -1e7, "#FFFFFF", 1e16);
            xml += &light(0.0, 0.5, 0.5, "#FFFFFF", 20.0);
        }
        Class::MirrorHall => {
            let mirror = "reflectivity=\"1\" kS=\"0.2\"";
            xml += &plane([-2.0, 0.0, 0.0], [1.0, 0.0, 0.0], &c, mirror);
            xml += &plane([2.0, 0.0, 0.0], [-1.0, 0.0, 0.0], &rng.colour(), mirror);
            xml += &plane(
                [0.0, -1.5, 0.0],
                [0.0, 1.0, 0.0],
                &rng.colour(),
                "reflectivity=\"0.7\"",
            );
            xml += &crowd(rng, 20);
            xml += &light(0.0, 1.0, 3.0, "#FFFFFF", 100.0);
        }
        Class::ManyLights => {
            xml += &crowd(rng, 30);
            xml += &plane([0.0, -2.0, 0.0], [0.0, 1.0, 0.0], &c, "");
            for _ in 0..24 {
                let c = rng.colour();
                xml += &light(
                    rng.range(-5.0, 5.0),
                    rng.range(-1.0, 5.0),
                    rng.range(0.0, 10.0),
                    &c,
                    30.0,
                );
            }
        }
        Class::LongRays => {
            // A small cluster seen from afar, lit from 1e7 away, with a far mirror behind the
            // camera: shadow and mirror rays start far from the spheres they test.
            let far = 10f64.powf(rng.range(3.0, 7.0));
            for _ in 0..60 {
                xml += &sphere(
                    rng.range(-0.5, 0.5),
                    rng.range(-0.4, 0.4),
                    rng.range(4.0, 6.0),
                    10f64.powf(rng.range(-4.0, -1.5)),
                    &rng.colour(),
                    "",
                );
            }
            xml += &plane(
                [0.0, 0.0, -far],
                [0.0, 0.0, 1.0],
                &c,
                "reflectivity=\"0.8\"",
            );
            xml += &plane(
                [0.0, 0.0, 5.0 + far],
                [0.0, 0.0, -1.0],
                &rng.colour(),
                "reflectivity=\"0.8\"",
            );
            xml += &light(
                rng.range(-1.0, 1.0) * far,
                rng.range(-1.0, 1.0) * far,
                -far,
                "#FFFFFF",
                far * far,
            );
            xml += &light(0.2, 0.3, 4.5, "#FFFFFF", 5.0);
        }
    }
    xml + "</scene>\n"
}

fn film(
    xml: &str,
    bounces: u32,
    acceleration: Acceleration,
    course: Course,
) -> (Film, RenderStats) {
    let scene = parse_str("differential.xml", xml).unwrap_or_else(|e| panic!("{e}\n{xml}"));
    let spec = FrameSpec {
        width: 40,
        height: 30,
        bounces,
        acceleration,
        course,
        ..FrameSpec::default()
    };
    render_frame(&scene, &spec)
}

/// Every bit of the beauty (f64, NaN included) and of every stored layer.
fn bits(film: &Film) -> (Vec<[u64; 3]>, Vec<u32>) {
    (
        film.beauty
            .iter()
            .map(|v| v.to_array().map(f64::to_bits))
            .collect(),
        film.data.iter().map(|v| v.to_bits()).collect(),
    )
}

#[test]
fn hierarchy_renders_bit_identical_films_on_adversarial_scenes() {
    let per_class: u64 = std::env::var("WHITTED_DIFFERENTIAL_SCENES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(3);
    let mut nan_pixels = 0;
    for (c, class) in CLASSES.iter().enumerate() {
        for seed in 0..per_class {
            let mut rng = Lcg(1000 * c as u64 + seed);
            let xml = generate(*class, &mut rng);
            // Every distinct set of rules: the far root, the N.L gate and the shadow ray's
            // bias along N change which rays are cast and which hits count.
            for course in [Course::Y2016, Course::Y2017, Course::Y2019, Course::Y2020] {
                for bounces in [0, 2, 5] {
                    let (fast, fast_stats) = film(&xml, bounces, Acceleration::Bvh, course);
                    let (slow, slow_stats) = film(&xml, bounces, Acceleration::BruteForce, course);
                    assert!(
                        bits(&fast) == bits(&slow),
                        "{class:?} seed {seed} bounces {bounces} course {course}: the hierarchy differs from brute force\n{xml}"
                    );
                    assert_eq!(fast_stats.rays, slow_stats.rays);
                    nan_pixels += fast.beauty.iter().filter(|v| v.is_nan()).count();
                }
            }
        }
    }
    // The NaN rule is exercised, not just tolerated.
    assert!(nan_pixels > 0, "no scene produced a NaN pixel");
}
