//! `whitted explain --input SCENE --pixel X,Y [--json]`: one pixel's ray tree, readable next to
//! a student's own Java code, or as JSON whose `"beauty"` is what `render` stores there.

use glam::DVec3;
use serde_json::{json, Value};

use crate::aov;
use crate::cli::ExplainArgs;
use crate::error::Result;
use crate::explain::{explain, vector, Explanation};
use crate::mistakes::Mistakes;
use crate::model::Tick;
use crate::numbers::finite_or_null;
use crate::output::stdout;
use crate::scene::{self, Scene};

pub fn run(args: &ExplainArgs) -> Result<()> {
    let scene::Input { scene, name, .. } = scene::load_input(args.input.as_deref())?;
    let (x, y) = args.pixel;
    let mistakes = args.mistakes();
    let e = if mistakes.is_empty() {
        explain(&Tick, &scene, &args.frame(), x, y)?
    } else {
        explain(&mistakes, &scene, &args.frame(), x, y)?
    };
    let text = if args.json {
        // serde_json cannot fail to print a Value it built itself.
        serde_json::to_string_pretty(&to_json(&e, &scene, mistakes)).unwrap_or_default()
    } else {
        tree(&e, &scene, &name, mistakes)
    };
    stdout::print_line(&text)
}

fn kind(scene: &Scene, object: usize) -> &'static str {
    match scene.objects[object].shape {
        crate::geometry::Shape::Sphere { .. } => "sphere",
        crate::geometry::Shape::Plane { .. } => "plane",
    }
}

fn tree(e: &Explanation, scene: &Scene, name: &str, mistakes: Mistakes) -> String {
    let model = match mistakes.ids().join(", ") {
        ids if ids.is_empty() => String::new(),
        ids => format!(" as a program with the mistake {ids} traces it"),
    };
    let mut out = format!(
        "pixel ({}, {}) of {name}{model}\ncamera ray: origin {}, direction {}\n",
        e.pixel.0,
        e.pixel.1,
        vector(e.camera_ray.origin),
        vector(e.camera_ray.direction)
    );
    for vertex in &e.vertices {
        let v = &vertex.record;
        let m = &v.material;
        out += &format!(
            "\ndepth {}: hits object {} ({}) at s = {}\n  P = {}\n  N = {}\n  material: colour {}, kD {}, kS {}, n {}, reflectivity {}\n  weight w = {}{}\n  ambient I_a * C = {}\n",
            v.depth,
            v.object + 1,
            kind(scene, v.object),
            v.distance,
            vector(v.point),
            vector(v.normal),
            vector(m.colour),
            m.kd,
            m.ks,
            m.n,
            m.reflectivity,
            v.weight,
            if v.spawned.is_some() { " (a mirror: the chain goes on)" } else { "" },
            vector(v.ambient),
        );
        for light in &vertex.lights {
            let l = &light.record;
            let shadow = match (&l.shadow_ray, l.occluder) {
                (None, _) => "shadows off: lit".to_string(),
                (Some(ray), Some(hit)) => format!(
                    "shadow ray from {}: blocked by object {} ({}) at s = {}: in shadow, adds nothing",
                    vector(ray.origin),
                    hit.object + 1,
                    kind(scene, hit.object),
                    hit.distance
                ),
                (Some(ray), None) => format!(
                    "shadow ray from {}: reaches the light: lit",
                    vector(ray.origin)
                ),
            };
            out += &format!(
                "  light {}: d = {}, I = {}\n    L = {}, max(0, N.L) = {}, max(0, R.V) = {}\n    diffuse = {}, specular = {}\n    {shadow}\n",
                light.name,
                l.distance,
                vector(l.illumination),
                vector(l.to_light),
                l.n_dot_l,
                l.r_dot_v,
                vector(l.diffuse),
                vector(l.specular),
            );
        }
        out += &format!("  shaded colour = {}\n", vector(v.colour));
    }
    if let Some((depth, ray)) = e.miss {
        out += &format!(
            "\ndepth {depth}: the ray along {} leaves the scene: background\n",
            vector(ray.direction)
        );
    }
    out += "\nfold (far end first):\n";
    for line in e.fold() {
        out += &format!("  {line}\n");
    }
    let stored = e.stored.map(f64::from);
    out += &format!(
        "\nbeauty = {} (stored in the EXR as {}; the tick PNG byte is floor(255 * clamp))\n",
        vector(e.sample.beauty),
        vector(DVec3::from_array(stored))
    );
    out += "layers:\n";
    for (layer, value) in layers(e, scene) {
        out += &format!("  {layer:<16} {}\n", vector(value));
    }
    out.trim_end().to_string()
}

/// The per-layer totals of this sample, in file order.
/// The per-layer totals of this sample, in file order: every colour layer of the EXR but the
/// beauty, named and computed as the film names and computes them.
fn layers(e: &Explanation, scene: &Scene) -> Vec<(String, DVec3)> {
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

fn to_json(e: &Explanation, scene: &Scene, mistakes: Mistakes) -> Value {
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
                        "r_dot_v": l.r_dot_v,
                        "diffuse": array(l.diffuse),
                        "specular": array(l.specular),
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
        "beauty": e.stored.map(f64::from),
        "beauty_f64": array(e.sample.beauty),
        "layers": layers,
    })
}
