//! One camera ray of a Tick 1* render through its mirror chain, with each light's
//! visibility at each vertex left to a sampler (the course's seeded draw, or the converged
//! estimate), and bumped spheres' normals perturbed. The shading is the year's model
//! (`Model`) term by term; only the visibility is a share instead of a yes or no.

use glam::DVec3;
use smallvec::SmallVec;

use super::bump::perturb;
use super::light::ShadowedTerms;
use super::Star;
use crate::geometry::{normalise, Ray};
use crate::hits::Hits;
use crate::model::Model;
use crate::sample::{PrimaryHit, Sample, StarValues};
use crate::scene::Scene;
use crate::trace::{light_geometry, TraceOptions};

/// A light's visibility at a vertex as a sampler estimated it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Visibility {
    /// The share of shadow rays not occluded, in [0, 1].
    pub fraction: f64,
    /// An unbiased estimate of `p (1 - p)`, the variance of one shadow ray's indicator
    /// (0 when the answer is certain, as for a hard shadow).
    pub spread: f64,
    /// Shadow rays cast.
    pub rays: u32,
}

impl Visibility {
    pub const LIT: Visibility = Visibility {
        fraction: 1.0,
        spread: 0.0,
        rays: 0,
    };
}

/// What a sampler is asked: the light's visibility from a shaded point, where
/// `blocked(offset)` casts the year's shadow ray towards the light's position plus `offset`.
pub struct ShadowQuery<'q> {
    /// Mirror vertex: 0 for the camera's own hit.
    pub depth: u32,
    pub light: usize,
    pub blocked: &'q dyn Fn(DVec3) -> bool,
}

/// One light's terms at a vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightTerm {
    /// The diffuse and specular terms with the light unoccluded, as the model gives them.
    pub diffuse: DVec3,
    pub specular: DVec3,
    pub visibility: Visibility,
    /// The factor on the visible fraction (`ShadowShare::gain`): 1, or the shadow-ray count
    /// where the count is used unaveraged.
    pub gain: f64,
    /// Which terms the visible share scales.
    pub scaled: ShadowedTerms,
}

impl LightTerm {
    /// A term the sampler's share scales as the handout says.
    pub fn new(diffuse: DVec3, specular: DVec3, visibility: Visibility) -> LightTerm {
        LightTerm {
            diffuse,
            specular,
            visibility,
            gain: 1.0,
            scaled: ShadowedTerms::Both,
        }
    }

    /// The sum of the terms the visible fraction multiplies (times the gain): the radiance is
    /// linear in the fraction with this slope.
    pub fn varying(&self) -> DVec3 {
        match self.scaled {
            ShadowedTerms::Both => (self.diffuse + self.specular) * self.gain,
            ShadowedTerms::DiffuseOnly => self.diffuse * self.gain,
        }
    }

    /// The diffuse and specular terms at visible fraction `f`.
    pub fn lit_at(&self, f: f64) -> (DVec3, DVec3) {
        let share = self.gain * f;
        let specular = match self.scaled {
            ShadowedTerms::Both => self.specular * share,
            ShadowedTerms::DiffuseOnly => self.specular,
        };
        (self.diffuse * share, specular)
    }

    /// Diffuse + specular at the sampler's visible fraction.
    pub fn lit(&self) -> DVec3 {
        let (diffuse, specular) = self.lit_at(self.visibility.fraction);
        diffuse + specular
    }

    /// Diffuse + specular with the light unoccluded.
    pub fn unshadowed(&self) -> DVec3 {
        let (diffuse, specular) = self.lit_at(1.0);
        diffuse + specular
    }
}

/// A shaded vertex of the chain.
#[derive(Debug, Clone, PartialEq)]
pub struct PathVertex {
    /// `w_k` of docs/aovs.md.
    pub weight: f64,
    pub ambient: DVec3,
    pub lights: SmallVec<[LightTerm; 4]>,
}

/// The first surface along the camera ray, for the layers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPrimary {
    pub position: DVec3,
    /// The shading normal (perturbed on a bumped sphere).
    pub normal: DVec3,
    /// The bump map's height read at the hit, on a bumped sphere.
    pub height: Option<f64>,
    pub object: usize,
    pub albedo: DVec3,
}

/// A camera ray's chain, each vertex's terms kept apart so that expectation and variance
/// follow from the visibilities.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Path {
    pub vertices: SmallVec<[PathVertex; 4]>,
    /// `beta_k * background` where the chain leaves the scene, else 0.
    pub background: DVec3,
    pub primary: Option<PathPrimary>,
    /// How far from the pinhole the camera ray starts (its aperture point): the ray nearest
    /// the pinhole gives the layers that are never blended (Z, P, objectid).
    pub aperture_offset: f64,
}

impl Path {
    /// The radiance: `sum_k w_k (ambient_k + sum_i fraction_ki * terms_ki) + background`.
    pub fn radiance(&self) -> DVec3 {
        self.vertices
            .iter()
            .map(|v| {
                let lit: DVec3 = v.lights.iter().map(LightTerm::lit).sum();
                (v.ambient + lit) * v.weight
            })
            .sum::<DVec3>()
            + self.background
    }

    /// The path as the tick's layers split it (docs/aovs.md), with `star` for its pixel's
    /// Tick 1* layers: each visibility scales its light's terms, and a shadow mask is the
    /// occluded share at the camera's hit.
    pub fn sample(&self, lights: usize, bounces: u32, star: StarValues) -> Sample {
        let mut s = Sample::empty(lights, bounces);
        s.rays = 1;
        for (k, v) in self.vertices.iter().enumerate() {
            let mut shaded = v.ambient;
            s.ambient += v.ambient * v.weight;
            for (out, l) in s.lights.iter_mut().zip(&v.lights) {
                let f = l.visibility.fraction;
                let (diffuse, specular) = l.lit_at(f);
                shaded += diffuse + specular;
                out.shadowed += (diffuse + specular) * v.weight;
                out.unshadowed += l.unshadowed() * v.weight;
                s.diffuse += diffuse * v.weight;
                s.specular += specular * v.weight;
                if k == 0 {
                    out.shadowed_at_primary = 1.0 - f;
                }
                s.rays += u64::from(l.visibility.rays);
            }
            *bucket(&mut s, k) += shaded * v.weight;
            s.rays += u64::from(k > 0);
        }
        s.background = self.background;
        if self.vertices.len() <= bounces as usize {
            *bucket(&mut s, self.vertices.len()) += self.background;
        }
        s.beauty = self.radiance();
        s.primary = self.primary.map(|p| PrimaryHit {
            position: p.position,
            normal: p.normal,
            albedo: p.albedo,
            object: p.object,
        });
        s.star = star;
        s
    }

    /// `sum_k sum_i (w_k varying_ki)^2 spread_ki`: divided by a shadow-ray count n, the
    /// variance of the radiance when each visibility is a mean of n independent rays (the
    /// terms the fraction scales, times its gain: n^2 times for the count unaveraged).
    pub fn spread(&self) -> DVec3 {
        self.vertices
            .iter()
            .flat_map(|v| {
                v.lights.iter().map(move |l| {
                    let t = l.varying() * v.weight;
                    t * t * l.visibility.spread
                })
            })
            .sum()
    }
}

/// Traces `ray` through its chain under `model`, asking `visibility` for each light at each
/// vertex (not asked where shadows are off or the light does not reach the point: lit).
pub fn trace_path<M: Model>(
    model: &M,
    scene: &Scene,
    accel: &impl Hits,
    star: &Star,
    mut ray: Ray,
    options: TraceOptions,
    visibility: &mut dyn FnMut(ShadowQuery) -> Visibility,
) -> Path {
    let mut path = Path {
        aperture_offset: ray.origin.length(),
        ..Path::default()
    };
    let mut throughput = 1.0;
    for k in 0..=options.bounces {
        let Some(hit) = accel.closest_hit(model, &ray) else {
            path.background = model.background() * throughput;
            break;
        };
        let object = &scene.objects[hit.object];
        let material = &object.material;
        let point = ray.at(hit.distance);
        let mut normal = object.shape.normal_at(point);
        let mut height = None;
        if let (Some(map), crate::geometry::Shape::Sphere { radius, .. }) =
            (star.bump_map(hit.object), object.shape)
        {
            let (bumped, h) = perturb(&star.bump, map, point, normal, radius);
            normal = bumped;
            height = Some(h);
        }
        let reflectivity = model.reflectivity(material.reflectivity);
        let continues = k < options.bounces && reflectivity != 0.0;
        let weight = if continues {
            throughput * (1.0 - reflectivity)
        } else {
            throughput
        };
        let ambient = model.ambient(scene.ambient, material.colour);
        let v = model.view(point, ray.origin);
        let mut lights = SmallVec::new();
        for (index, light) in model.lights(&scene.lights).iter().enumerate() {
            let geometry = light_geometry(model, light, point, normal, v);
            if !geometry.reaches {
                lights.push(LightTerm::new(DVec3::ZERO, DVec3::ZERO, Visibility::LIT));
                continue;
            }
            let (diffuse, specular) = geometry.terms(model, light, material);
            let seen = if options.shadows {
                let blocked = |offset: DVec3| {
                    let target = light.position + offset;
                    let towards = target - point;
                    let reach = towards.length();
                    let shadow = model.shadow_ray(point, normalise(towards), normal);
                    accel.occluded(model, &shadow, model.shadow_reach(reach))
                };
                visibility(ShadowQuery {
                    depth: k,
                    light: index,
                    blocked: &blocked,
                })
            } else {
                Visibility::LIT
            };
            let mut term = LightTerm::new(diffuse, specular, seen);
            if let (Some(soft), true) = (star.soft, options.shadows) {
                term.gain = soft.share.gain(soft.rays);
                term.scaled = soft.scaled;
            }
            lights.push(term);
        }
        if k == 0 {
            path.primary = Some(PathPrimary {
                position: point,
                normal,
                height,
                object: hit.object,
                albedo: material.colour,
            });
        }
        path.vertices.push(PathVertex {
            weight,
            ambient,
            lights,
        });
        if !continues {
            break;
        }
        throughput *= reflectivity;
        ray = model.mirror_ray(point, ray.direction, normal);
    }
    path
}

/// Where vertex k's radiance is filed: `direct` for the camera's hit, else the bounce's
/// reflected layer (a chain that leaves the scene files its background at the next vertex).
fn bucket(sample: &mut Sample, k: usize) -> &mut DVec3 {
    match k {
        0 => &mut sample.direct,
        k => &mut sample.reflected_by_bounce[k - 1],
    }
}
