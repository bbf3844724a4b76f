//! `whitted explain --input SCENE --pixel X,Y [--json]`: one pixel's ray tree, readable next to
//! a student's own Java code, or as JSON whose `"beauty"` is what `render` stores there.

use glam::DVec3;

use crate::cli::ExplainArgs;
use whitted_check::explain::compare;
use whitted_check::explain::json::{kind, layers, to_json};
use whitted_check::explain::{explain, vector, Explanation};
use whitted_check::mistakes::Mistakes;
use whitted_core::course::Course;
use whitted_core::error::Error;
use whitted_core::error::Result;
use whitted_core::scene::{self, Scene};
use whitted_core::tonemap::ToneMap;
use whitted_io::output::stdout;

pub fn run(args: &ExplainArgs) -> Result<()> {
    let course = args.frame.course.course();
    let mistakes = args.mistakes();
    if let Some(rule) = mistakes.bugs().into_iter().find(|b| !b.offered_in(course)) {
        return Err(Error::Usage(format!(
            "--bug {} is not a mistake of {course}'s catalogue (it is the year's own rule, or \
             its code is not in the year's skeleton; docs/courses.md)",
            rule.id()
        )));
    }
    let input = scene::input::load_input(args.input.as_deref(), course)?;
    input.report_warnings();
    let scene::input::Input { scene, name, .. } = input;
    let (x, y) = args.pixel;
    let e = if mistakes.is_empty() {
        explain(&course.rules(), &scene, &args.frame(), x, y)?
    } else {
        explain(
            &whitted_check::mistakes::Variant::from(mistakes).in_course(course),
            &scene,
            &args.frame(),
            x,
            y,
        )?
    };
    let text = if args.compare {
        let reference = explain(&course.rules(), &scene, &args.reference_frame(), x, y)?;
        compare::text(
            (x, y),
            &mistakes.name(),
            &to_json(&reference, &scene, Mistakes::NONE),
            &to_json(&e, &scene, mistakes),
        )
    } else if args.json {
        // serde_json cannot fail to print a Value it built itself.
        serde_json::to_string_pretty(&to_json(&e, &scene, mistakes)).unwrap_or_default()
    } else {
        tree(&e, &scene, &name, mistakes, course)
    };
    stdout::print_line(&text)
}

fn tree(e: &Explanation, scene: &Scene, name: &str, mistakes: Mistakes, course: Course) -> String {
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
                _ if !l.reaches => {
                    "N.L < 0: the light does not reach this side, adds nothing and casts no shadow ray"
                        .to_string()
                }
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
    let byte = match course.tonemap() {
        ToneMap::Sigmoid => "the PNG byte is the course's sigmoid tone map of it",
        _ => "the tick PNG byte is floor(255 * clamp)",
    };
    out += &format!(
        "\nbeauty = {} (stored in the EXR as {}; {byte})\n",
        vector(e.sample.beauty),
        vector(DVec3::from_array(stored))
    );
    out += "layers:\n";
    for (layer, value) in layers(e, scene) {
        out += &format!("  {layer:<16} {}\n", vector(value));
    }
    out.trim_end().to_string()
}
