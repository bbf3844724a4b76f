//! One explanation as JSON: what `whitted explain --json` prints and what the viewer's ray tree
//! shows, built once so the two cannot disagree.

use glam::DVec3;
use serde_json::{json, Value};

use super::Explanation;
use crate::mistakes::Mistakes;
use whitted_core::aov;
use whitted_core::numbers::finite_or_null;
use whitted_core::scene::Scene;

pub fn kind(scene: &Scene, object: usize) -> &'static str {
    match scene.objects[object].shape {
        whitted_core::geometry::Shape::Sphere { .. } => "sphere",
        whitted_core::geometry::Shape::Plane { .. } => "plane",
    }
}

/// The per-layer totals of this sample, in file order: every colour layer of the EXR but the
/// beauty, named and computed as the film names and computes them.
pub fn layers(e: &Explanation, scene: &Scene) -> Vec<(String, DVec3)> {
    let names: Vec<String> = scene.lights.iter().map(|l| l.name.clone()).collect();
    let bounces = e.sample.reflected_by_bounce.len() as u32;
    aov::all_layers(&names, bounces)
        .into_iter()
        .filter(|l| l.quantity.kind() == aov::Kind::Colour && l.quantity != aov::Quantity::Beauty)
        .map(|l| {
            let mut values = [0.0; 4];
            l.quantity.values(&e.sample, &mut values);
            (l.name, DVec3::new(values[0], values[1], values[2]))
        })
        .collect()
}

fn array(v: DVec3) -> Value {
    json!(v.to_array().map(finite_or_null))
}

pub fn to_json(e: &Explanation, scene: &Scene, mistakes: Mistakes) -> Value {
    let vertices: Vec<Value> = e
        .vertices
        .iter()
        .map(|vertex| {
            let v = &vertex.record;
            let lights: Vec<Value> = vertex
                .lights
                .iter()
                .map(|light| {
                    let l = &light.record;
                    json!({
                        "light": light.name,
                        "d": l.distance,
                        "I": array(l.illumination),
                        "L": array(l.to_light),
                        "n_dot_l": l.n_dot_l,
                        "R": array(l.mirror),
                        "V": array(l.view),
                        "r_dot_v": l.r_dot_v,
                        "diffuse": array(l.diffuse),
                        "specular": array(l.specular),
                        "reaches": l.reaches,
                        "shadow_tested": l.shadow_ray.is_some(),
                        "in_shadow": l.in_shadow,
                        "shadow_origin": l.shadow_ray.map(|r| array(r.origin)),
                        "occluder": l.occluder.map(|h| json!({"object": h.object + 1, "kind": kind(scene, h.object), "distance": h.distance})),
                    })
                })
                .collect();
            json!({
                "depth": v.depth,
                "object": v.object + 1,
                "kind": kind(scene, v.object),
                "distance": v.distance,
                "P": array(v.point),
                "N": array(v.normal),
                "material": {
                    "colour": array(v.material.colour),
                    "kD": v.material.kd,
                    "kS": v.material.ks,
                    "n": v.material.n,
                    "reflectivity": v.material.reflectivity,
                },
                "weight": v.weight,
                "continues": v.spawned.is_some(),
                "reflected_ray": v.spawned.map(|r| json!({"origin": array(r.origin), "direction": array(r.direction)})),
                "ambient": array(v.ambient),
                "lights": lights,
                "colour": array(v.colour),
            })
        })
        .collect();
    let layers: serde_json::Map<String, Value> = layers(e, scene)
        .into_iter()
        .map(|(k, v)| (k, array(v)))
        .collect();
    json!({
        "pixel": [e.pixel.0, e.pixel.1],
        "bugs": mistakes.ids(),
        "camera_ray": {"origin": array(e.camera_ray.origin), "direction": array(e.camera_ray.direction)},
        "vertices": vertices,
        "miss": e.miss.map(|(depth, ray)| json!({"depth": depth, "direction": array(ray.direction)})),
        "fold": e.fold(),
        "fold_steps": e.fold.iter().map(|step| json!({
            "depth": step.depth,
            "colour": array(step.colour),
            "reflectivity": step.reflectivity,
            "reflected": array(step.reflected),
            "result": array(step.result),
        })).collect::<Vec<_>>(),
        "beauty": e.stored.map(f64::from),
        "beauty_f64": array(e.sample.beauty),
        "layers": layers,
    })
}
