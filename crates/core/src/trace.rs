//! The tick shading model (docs/rendering.md): Phong with several point lights, hard shadows and
//! mirror reflection, evaluated in the course's operation order so the beauty is bit-exact.

pub mod observe;

use glam::DVec3;
use smallvec::SmallVec;

use observe::{FoldStep, LightRecord, Observer, Silent, VertexRecord};

use crate::accel::Accelerator;
use crate::geometry::{Hit, Ray};
use crate::hits::Hits;
use crate::model::rounding::{SelfHit, TakingSelfHits};
use crate::model::{Model, Tick};
use crate::sample::{PrimaryHit, Sample};
use crate::scene::{Material, PointLight, Scene};

pub use crate::model::BACKGROUND;

/// What a trace may do, from the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TraceOptions {
    /// Mirror reflections followed after the primary hit.
    pub bounces: u32,
    /// `false` ignores occlusion: every light reaches every point (the handout's figure 2).
    pub shadows: bool,
}

/// Traces one camera ray through its mirror chain.
///
/// The chain is followed iteratively. Each vertex's weighted terms go straight into the
/// sample's layers; its unweighted shaded colour is kept so that the beauty can then be folded
/// from the far end exactly as the course's recursion evaluates it:
/// `direct * (1 - r) + reflected * r`.
pub fn trace(scene: &Scene, accel: &Accelerator, primary: Ray, options: TraceOptions) -> Sample {
    let mut sample = Sample::empty(scene.lights.len(), options.bounces);
    trace_into(scene, accel, primary, options, &mut sample);
    sample
}

/// `trace` into an existing sample (shaped for this scene and bounce count by
/// `Sample::empty`), which is reset first: the render loop reuses one per task.
pub fn trace_into(
    scene: &Scene,
    accel: &Accelerator,
    primary: Ray,
    options: TraceOptions,
    sample: &mut Sample,
) {
    trace_observed::<true>(&Tick, scene, accel, primary, options, sample, &mut Silent);
}

/// `trace_into` for the beauty alone: the same `sample.beauty` and ray count, bit for bit, and
/// none of the per-effect sums (a PNG-only render needs nothing else).
pub fn trace_beauty(
    scene: &Scene,
    accel: &Accelerator,
    primary: Ray,
    options: TraceOptions,
    sample: &mut Sample,
) {
    trace_observed::<false>(&Tick, scene, accel, primary, options, sample, &mut Silent);
}

/// The trace itself under `model`'s rules, telling `observer` every vertex and light term on
/// the way (`explain` watches; the render passes `Silent`). With `LAYERS` false the
/// per-effect sums are left out at compile time. `accel` must be a brute-force one for a
/// model the hierarchy is not exact for (`Model::hierarchy_exact`).
///
/// The trace, `shade` and `light_terms` are inlined into one loop body, as the compiler chose
/// before the model was a parameter: left to itself it now splits them, and the calls and the
/// light loop's set-up cost tick2 2-13% more instructions (bench/README.md).
#[inline(always)]
pub fn trace_observed<const LAYERS: bool>(
    model: &impl Model,
    scene: &Scene,
    accel: &impl Hits,
    primary: Ray,
    options: TraceOptions,
    sample: &mut Sample,
    observer: &mut impl Observer,
) {
    let mut chain = Chain::new();
    follow_chain::<LAYERS>(
        model, scene, accel, primary, options, sample, observer, &mut chain,
    );
    sample.beauty = chain.fold(model, options.bounces, observer);
}

/// The mirror chain of one camera ray traced to `options.bounces` reflections, for its
/// beauty at that count or any smaller one (`Chain::beauty`): with fewer bounces a program
/// follows the same chain and stops early, so one trace gives each count's image bit for bit.
/// How `whitted check` renders a scene's cases that differ only in `--bounces` at once.
#[inline(always)]
pub fn trace_chain(
    model: &impl Model,
    scene: &Scene,
    accel: &impl Hits,
    primary: Ray,
    options: TraceOptions,
    sample: &mut Sample,
) -> Chain {
    let mut chain = Chain::new();
    follow_chain::<false>(
        model,
        scene,
        accel,
        primary,
        options,
        sample,
        &mut Silent,
        &mut chain,
    );
    chain
}

/// A camera ray's mirror chain: each vertex's (unweighted) shaded colour and its
/// reflectivity where the chain continues there. A chain that ends by leaving the scene sees
/// the background there; one that ends at a vertex reflects nothing.
pub struct Chain {
    /// On the stack for the usual few bounces.
    vertices: SmallVec<[(DVec3, Option<f64>); 4]>,
}

impl Chain {
    fn new() -> Self {
        Chain {
            vertices: SmallVec::new(),
        }
    }

    /// The beauty with the chain cut at `bounces` reflections (at most the traced count).
    #[inline(always)]
    pub fn beauty(&self, model: &impl Model, bounces: u32) -> DVec3 {
        self.fold(model, bounces, &mut Silent)
    }

    /// The beauty as the course's recursion evaluates it, `direct * (1 - r) + reflected * r`
    /// from the far end, with the chain cut at `bounces` reflections: the vertex there
    /// reflects nothing, as it does when the trace itself stops there.
    #[inline(always)]
    fn fold(&self, model: &impl Model, bounces: u32, observer: &mut impl Observer) -> DVec3 {
        let kept = self.vertices.len().min(bounces as usize + 1);
        self.vertices[..kept].iter().enumerate().rev().fold(
            model.background(),
            |reflected, (depth, &(colour, r))| {
                let r = if depth == bounces as usize { None } else { r };
                let result = match r {
                    Some(r) => model.blend(colour, reflected, r),
                    None => colour,
                };
                observer.fold(FoldStep {
                    depth: depth as u32,
                    colour,
                    reflectivity: r,
                    reflected,
                    result,
                });
                result
            },
        )
    }
}

/// The chain of `primary` under `model`'s rules up to `options.bounces` reflections, into an
/// empty `chain` (the caller's, so the hot loop never moves it), its weighted terms added to
/// `sample` (with `LAYERS`) and told to `observer` on the way.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn follow_chain<const LAYERS: bool>(
    model: &impl Model,
    scene: &Scene,
    accel: &impl Hits,
    primary: Ray,
    options: TraceOptions,
    sample: &mut Sample,
    observer: &mut impl Observer,
    chain: &mut Chain,
) {
    if LAYERS {
        sample.reset();
    } else {
        sample.rays = 0;
    }
    let mut ray = primary;
    let mut throughput = 1.0;
    for k in 0..=options.bounces {
        sample.rays += 1;
        let Some(hit) = accel.closest_hit(model, &ray) else {
            observer.miss(k, ray);
            if LAYERS {
                let background = model.background() * throughput;
                sample.background += background;
                *bucket(sample, k) += background;
            }
            break;
        };
        let object = &scene.objects[hit.object];
        let material = &object.material;
        let point = ray.at(hit.distance);
        let normal = object.shape.normal_at(point);
        let reflectivity = model.reflectivity(material.reflectivity);
        let continues = k < options.bounces && reflectivity != 0.0;
        let weight = if continues {
            throughput * (1.0 - reflectivity)
        } else {
            throughput
        };
        let vertex = Vertex {
            ray_origin: ray.origin,
            point,
            normal,
            material,
            weight,
            depth: k,
        };
        let (ambient, colour) = shade::<LAYERS, _>(
            model,
            scene,
            accel,
            &vertex,
            options.shadows,
            sample,
            observer,
        );
        let spawned = continues.then(|| model.mirror_ray(point, ray.direction, normal));
        observer.vertex(VertexRecord {
            depth: k,
            ray,
            object: hit.object,
            distance: hit.distance,
            point,
            normal,
            material: *material,
            weight,
            spawned,
            ambient,
            colour,
        });
        if LAYERS {
            *bucket(sample, k) += colour * weight;
        }
        if LAYERS && k == 0 {
            sample.primary = Some(PrimaryHit {
                position: point,
                normal,
                albedo: material.colour,
                object: hit.object,
            });
        }
        chain
            .vertices
            .push((colour, continues.then_some(reflectivity)));
        let Some(next) = spawned else {
            break;
        };
        throughput *= reflectivity;
        ray = next;
    }
}

/// Where vertex k's radiance is filed: the direct layer for the primary hit, else the
/// reflected layer for k bounces.
fn bucket(sample: &mut Sample, k: u32) -> &mut DVec3 {
    match k {
        0 => &mut sample.direct,
        k => &mut sample.reflected_by_bounce[k as usize - 1],
    }
}

/// `Math.max(0, x)` as Java evaluates it, which the course's reference does for every clamp
/// in shading (docs/rendering.md): NaN stays NaN (Rust's `f64::max` would return 0 and shade a
/// pixel the reference leaves NaN), and -0.0 becomes +0.0.
pub fn java_max_zero(x: f64) -> f64 {
    // One comparison: NaN <= 0 is false, so NaN falls through unchanged.
    if x <= 0.0 {
        0.0
    } else {
        x
    }
}

/// `x^n` for the specular term. `pow(x, ±0)` is 1 for every `x`, NaN included, and
/// `pow(+0, n)` is +0 for every `n > 0` (IEEE 754 and C's `pow`), so the library call is
/// skipped for an exponent of 0 (the plane's default) and for a clamped `R.V` of +0 (a lit
/// point whose mirror direction turns away from the viewer) with the very same result.
pub(crate) fn phong_power(x: f64, n: f64) -> f64 {
    if n == 0.0 {
        1.0
    } else if x.to_bits() == 0 && n > 0.0 {
        0.0
    } else {
        x.powf(n)
    }
}

/// One light's unshadowed geometry at a point, in the course's order (docs/rendering.md,
/// Shading): the one computation of the per-light step, shared by the tick trace
/// (`light_terms`) and Tick 1*'s paths (`star::path`), so that both shade a point alike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightGeometry {
    /// `d`, `I = c * k / (4 pi d^2)`, `L`.
    pub distance: f64,
    pub illumination: DVec3,
    pub to_light: DVec3,
    /// Whether the light reaches the point at all (`Model::reaches` of the raw `N.L`).
    pub reaches: bool,
    /// `max(0, N.L)`, `R` (the mirror of `L` the specular term uses), `max(0, R.V)`.
    pub n_dot_l: f64,
    pub mirror: DVec3,
    pub r_dot_v: f64,
}

/// The geometry of `light` at `point` with normal `n`, seen along `v` (towards the viewer).
/// Inlined: the tick trace is bit-exact and its loop body is one function (`trace_observed`).
#[inline(always)]
pub fn light_geometry(
    model: &impl Model,
    light: &PointLight,
    point: DVec3,
    n: DVec3,
    v: DVec3,
) -> LightGeometry {
    let to_light = light.position - point;
    let distance = to_light.length();
    let illumination = model.illumination(light, distance);
    let l = model.to_light(to_light, distance);
    let raw_n_dot_l = n.dot(l);
    let reaches = model.reaches(raw_n_dot_l);
    let n_dot_l = java_max_zero(raw_n_dot_l);
    let mirror = model.specular_mirror(n, l, n_dot_l);
    let r_dot_v = model.clamp_r_dot_v(mirror.dot(v));
    LightGeometry {
        distance,
        illumination,
        to_light: l,
        reaches,
        n_dot_l,
        mirror,
        r_dot_v,
    }
}

impl LightGeometry {
    /// The light's diffuse and specular terms on material `m` with the light unoccluded: pure
    /// functions of the geometry, so a caller may compute them only where it adds them.
    #[inline(always)]
    pub fn terms(&self, model: &impl Model, light: &PointLight, m: &Material) -> (DVec3, DVec3) {
        let diffuse = model.diffuse(m.colour, self.illumination, m.kd, self.n_dot_l);
        let phong = phong_power(self.r_dot_v, model.specular_exponent(m.n));
        let specular = model.specular(
            light,
            self.illumination,
            m.ks,
            phong,
            m.colour,
            self.n_dot_l,
        );
        (diffuse, specular)
    }
}

/// A surface point being shaded and how much it counts towards the pixel.
struct Vertex<'a> {
    /// Where the ray that found the point started.
    ray_origin: DVec3,
    point: DVec3,
    normal: DVec3,
    material: &'a Material,
    /// `w_k` of docs/aovs.md: the share of the pixel this vertex's shading makes up.
    weight: f64,
    /// 0 for the camera's own hit (shadow masks record only that one).
    depth: u32,
}

/// One light's terms at a vertex, in the course's order (docs/rendering.md, Shading), and its
/// shadow test: a pure function of the vertex, the light and `V`. The occluder is found only
/// for an observer that records it; otherwise the search stops at the first blocker. With
/// `all_terms` false a shadowed light's terms are left at zero (see `Observer`).
/// Inlined (see `trace_observed`), so the record's fields nobody reads are never computed.
#[inline(always)]
fn light_terms<O: Observer>(
    model: &impl Model,
    accel: &impl Hits,
    vertex: &Vertex,
    (index, light): (usize, &PointLight),
    v: DVec3,
    shadows: bool,
    all_terms: bool,
) -> LightRecord {
    let Vertex {
        point: p,
        normal: n,
        material: m,
        ..
    } = *vertex;
    let geometry = light_geometry(model, light, p, n, v);
    let LightGeometry {
        distance: d,
        illumination,
        to_light: l,
        reaches,
        n_dot_l,
        mirror: r,
        r_dot_v,
    } = geometry;
    let shadow_ray = model.shadow_ray(p, l, n);
    let reach = model.shadow_reach(d);
    let cast = shadows && reaches;
    let (in_shadow, occluder) = match model.self_hits_toward(index) {
        SelfHit::Exact => shadow_test::<O>(model, accel, &shadow_ray, reach, cast),
        how => shadow_test::<O>(
            &TakingSelfHits { model, how },
            accel,
            &shadow_ray,
            reach,
            cast,
        ),
    };
    // A light that does not reach the point adds exact zeros: no term is computed for it. Nor
    // for one in shadow when nobody reads its terms (`all_terms` false): the terms are pure
    // functions of the vertex and the light, so computing them after the shadow test, or not
    // at all where the pixel never adds them, changes no value it gets.
    let (diffuse, specular) = if reaches && (all_terms || !in_shadow) {
        geometry.terms(model, light, m)
    } else {
        (DVec3::ZERO, DVec3::ZERO)
    };
    LightRecord {
        depth: vertex.depth,
        light: index,
        distance: d,
        illumination,
        to_light: l,
        n_dot_l,
        mirror: r,
        view: v,
        r_dot_v,
        diffuse,
        specular,
        reaches,
        shadow_ray: (shadows && reaches).then_some(shadow_ray),
        in_shadow,
        occluder,
    }
}

/// Whether `shadow_ray` is blocked before `reach` (when it is `cast` at all), and by what
/// when the observer records it.
#[inline(always)]
fn shadow_test<O: Observer>(
    model: &impl Model,
    accel: &impl Hits,
    shadow_ray: &Ray,
    reach: f64,
    cast: bool,
) -> (bool, Option<Hit>) {
    match (cast, O::RECORDS_OCCLUDERS) {
        (false, _) => (false, None),
        (true, true) => {
            // The nearest hit is before `reach` exactly when something blocks the ray.
            let hit = accel
                .closest_hit(model, shadow_ray)
                .filter(|hit| hit.distance < reach);
            (hit.is_some(), hit)
        }
        (true, false) => (accel.occluded(model, shadow_ray, reach), None),
    }
}

/// Phong shading at a vertex: the ambient term, then each light's terms added where it is not
/// in shadow. Returns the (unweighted) ambient term and shaded colour, and adds the weighted
/// per-effect terms to `sample`. Inlined: see `trace_observed`.
#[inline(always)]
fn shade<const LAYERS: bool, O: Observer>(
    model: &impl Model,
    scene: &Scene,
    accel: &impl Hits,
    vertex: &Vertex,
    shadows: bool,
    sample: &mut Sample,
    observer: &mut O,
) -> (DVec3, DVec3) {
    let weight = vertex.weight;
    let ambient = model.ambient(scene.ambient, vertex.material.colour);
    if LAYERS {
        sample.ambient += ambient * weight;
    }
    let mut colour = ambient;
    let v = model.view(vertex.point, vertex.ray_origin);
    let lights = model.lights(&scene.lights).iter();
    // Known at compile time: whether a shadowed light's terms are read at all.
    let all_terms = LAYERS || O::READS_SHADOWED_TERMS;
    for (index, (light, out)) in lights.zip(sample.lights.iter_mut()).enumerate() {
        let record = light_terms::<O>(model, accel, vertex, (index, light), v, shadows, all_terms);
        sample.rays += u64::from(shadows && record.reaches);
        let (diffuse, specular) = (record.diffuse, record.specular);
        if LAYERS {
            out.unshadowed += (diffuse + specular) * weight;
            if vertex.depth == 0 {
                out.shadowed_at_primary = f64::from(u8::from(record.in_shadow));
            }
        }
        if record.reaches && !record.in_shadow {
            colour = model.add_light(colour, ambient, diffuse, specular);
            if LAYERS {
                out.shadowed += (diffuse + specular) * weight;
                sample.diffuse += diffuse * weight;
                sample.specular += specular * weight;
            }
        }
        observer.light(record);
    }
    (ambient, colour)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{normalise, Shape};
    use crate::model::mirror_direction;
    use crate::scene::{Object, PointLight};
    use std::f64::consts::PI;

    /// Traces with the hierarchy, after checking brute force gives the very same sample.
    fn trace(scene: &Scene, ray: Ray, options: TraceOptions) -> Sample {
        let fast = super::trace(scene, &Accelerator::build(&scene.objects), ray, options);
        let slow = super::trace(
            scene,
            &Accelerator::brute_force(&scene.objects),
            ray,
            options,
        );
        // Compared as text: NaN samples are legitimate and NaN != NaN.
        assert_eq!(format!("{fast:?}"), format!("{slow:?}"));
        fast
    }

    const NO_BOUNCES: TraceOptions = TraceOptions {
        bounces: 0,
        shadows: true,
    };

    fn light(position: DVec3, intensity: f64) -> PointLight {
        PointLight {
            position,
            colour: DVec3::ONE,
            intensity,
            name: "0".into(),
        }
    }

    /// A plane facing the camera at z = 4, lit head-on from z = 2.
    fn wall_scene() -> Scene {
        Scene {
            objects: vec![Object {
                shape: Shape::Plane {
                    point: DVec3::new(0.0, 0.0, 4.0),
                    normal: DVec3::new(0.0, 0.0, -1.0),
                },
                material: Material::plane(DVec3::new(1.0, 0.5, 0.25)),
            }],
            lights: vec![light(DVec3::new(0.0, 0.0, 2.0), 100.0)],
            ambient: DVec3::splat(0.2),
        }
    }

    #[test]
    fn lambertian_plane_at_normal_incidence_is_ambient_plus_diffuse() {
        let scene = wall_scene();
        let c = DVec3::new(1.0, 0.5, 0.25);
        let s = trace(&scene, Ray::new(DVec3::ZERO, DVec3::Z), NO_BOUNCES);
        // I = 100 / (4 pi 2^2); kD = 0.9; N.L = 1; kS = 0.
        let expected = 0.2 * c + c * 0.9 * (100.0 / (16.0 * PI));
        assert!(
            (s.beauty - expected).length() < 1e-15,
            "{} vs {expected}",
            s.beauty
        );
        assert_eq!(s.direct, s.beauty);
        assert_eq!(s.specular, DVec3::ZERO);
        assert_eq!(s.rays, 2);
        let hit = s.primary.expect("hit");
        assert_eq!(hit.position, DVec3::new(0.0, 0.0, 4.0));
        assert_eq!(s.lights[0].shadowed_at_primary, 0.0);
    }

    #[test]
    fn shadowed_point_receives_ambient_only() {
        let mut scene = wall_scene();
        scene.lights = vec![light(DVec3::new(0.0, 2.0, 3.0), 100.0)];
        // A small sphere on the segment from the hit point (0,0,4) to the light, off the
        // camera ray.
        scene.objects.push(Object {
            shape: Shape::Sphere {
                centre: DVec3::new(0.0, 1.0, 3.5),
                radius: 0.3,
            },
            material: Material::sphere(DVec3::ONE),
        });
        let s = trace(&scene, Ray::new(DVec3::ZERO, DVec3::Z), NO_BOUNCES);
        assert_eq!(s.beauty, DVec3::new(0.2, 0.1, 0.05));
        assert_eq!(s.lights[0].shadowed_at_primary, 1.0);
        assert_eq!(s.lights[0].shadowed, DVec3::ZERO);
        assert!(s.lights[0].unshadowed.min_element() > 0.0);

        let lit = trace(
            &scene,
            Ray::new(DVec3::ZERO, DVec3::Z),
            TraceOptions {
                shadows: false,
                ..NO_BOUNCES
            },
        );
        assert!(lit.beauty.min_element() > 0.2 * 0.25);
        assert_eq!(lit.lights[0].shadowed, lit.lights[0].unshadowed);
        assert_eq!(lit.lights[0].shadowed_at_primary, 0.0);
    }

    #[test]
    fn miss_gives_the_background_in_direct() {
        let scene = wall_scene();
        let s = trace(
            &scene,
            Ray::new(DVec3::ZERO, -DVec3::Z),
            TraceOptions {
                bounces: 3,
                shadows: true,
            },
        );
        assert_eq!(s.beauty, BACKGROUND);
        assert_eq!(s.direct, BACKGROUND);
        assert_eq!(s.background, BACKGROUND);
        assert_eq!(s.reflected(), DVec3::ZERO);
        assert!(s.primary.is_none());
    }

    #[test]
    fn mirror_chain_layers_add_up_to_the_beauty() {
        // Two facing mirrors with a light between them: the chain uses every bounce.
        let mirror = |z: f64, nz: f64, colour: DVec3| Object {
            shape: Shape::Plane {
                point: DVec3::new(0.0, 0.0, z),
                normal: DVec3::new(0.0, 0.0, nz),
            },
            material: Material {
                reflectivity: 0.5,
                ..Material::sphere(colour)
            },
        };
        let scene = Scene {
            objects: vec![
                mirror(4.0, -1.0, DVec3::new(1.0, 0.2, 0.2)),
                mirror(-1.0, 1.0, DVec3::new(0.2, 0.2, 1.0)),
            ],
            lights: vec![light(DVec3::new(0.5, 0.5, 1.5), 50.0)],
            ambient: DVec3::splat(0.3),
        };
        let ray = Ray::new(DVec3::ZERO, normalise(DVec3::new(0.05, 0.02, 1.0)));
        for bounces in 0..5 {
            let s = trace(
                &scene,
                ray,
                TraceOptions {
                    bounces,
                    shadows: true,
                },
            );
            let sum_effects = s.ambient + s.diffuse + s.specular + s.background;
            let sum_lights = s.ambient + s.lights[0].shadowed + s.background;
            for total in [s.direct + s.reflected(), sum_effects, sum_lights] {
                assert!(
                    (total - s.beauty).abs().max_element() < 1e-12,
                    "bounces {bounces}"
                );
            }
            assert_eq!(s.reflected_by_bounce.len(), bounces as usize);
            assert!(s.reflected_by_bounce.iter().all(|r| r.min_element() > 0.0));
            assert_eq!(s.rays, 2 * (u64::from(bounces) + 1));
        }
    }

    #[test]
    fn phong_power_is_pow_including_a_zero_exponent_and_a_zero_base() {
        let xs = [
            0.0,
            -0.0,
            5e-324,
            0.5,
            1.0,
            1.5,
            f64::NAN,
            f64::INFINITY,
            -1.0,
        ];
        let ns = [
            0.0,
            -0.0,
            5e-324,
            0.5,
            1.0,
            3.0,
            10.0,
            1e300,
            -1.0,
            -3.0,
            f64::NAN,
        ];
        for x in xs {
            for n in ns {
                assert_eq!(
                    phong_power(x, n).to_bits(),
                    x.powf(n).to_bits(),
                    "pow({x}, {n})"
                );
            }
        }
    }

    #[test]
    fn clamps_follow_java_math_max() {
        assert!(java_max_zero(f64::NAN).is_nan());
        assert_eq!(java_max_zero(-2.0), 0.0);
        assert_eq!(java_max_zero(-0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(java_max_zero(0.25), 0.25);
        assert_eq!(java_max_zero(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn a_hit_at_the_eye_is_nan_as_in_the_reference() {
        // A plane through the camera with a specular term: V = (-P) normalised is 0/0 at
        // P = 0, and Math.max(0, NaN) keeps it NaN, so the pixel is NaN (0 in the PNG).
        let mut scene = wall_scene();
        scene.objects[0] = Object {
            shape: Shape::Plane {
                point: DVec3::ZERO,
                normal: DVec3::new(0.0, 0.0, -1.0),
            },
            material: Material::sphere(DVec3::ONE),
        };
        let s = trace(&scene, Ray::new(DVec3::ZERO, DVec3::Z), NO_BOUNCES);
        assert_eq!(s.primary.expect("hit").position, DVec3::ZERO);
        assert!(s.beauty.is_nan(), "{}", s.beauty);
    }

    #[test]
    fn a_light_on_the_surface_makes_the_point_nan() {
        // L = 0/0 at a light exactly on the hit point: every term of that light is NaN.
        let mut scene = wall_scene();
        scene.lights = vec![light(DVec3::new(0.0, 0.0, 4.0), 100.0)];
        let s = trace(&scene, Ray::new(DVec3::ZERO, DVec3::Z), NO_BOUNCES);
        assert!(s.beauty.is_nan(), "{}", s.beauty);
    }

    #[test]
    fn mirror_direction_reflects_about_the_normal() {
        let d = normalise(DVec3::new(1.0, -1.0, 0.0));
        let r = mirror_direction(d, DVec3::Y);
        assert!((r - normalise(DVec3::new(1.0, 1.0, 0.0))).length() < 1e-15);
    }
}
