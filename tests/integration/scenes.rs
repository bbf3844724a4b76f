//! Every scene shipped in `scenes/` loads and renders to a finite, non-blank image, and the
//! showcase scenes show the effect they are there for.

use crate::common::render_frame;
use glam::DVec3;
use whitted_core::film::Film;
use whitted_core::frame::FrameSpec;
use whitted_core::scene;

fn render_scene(name: &str, width: u32, height: u32, bounces: u32, shadows: bool) -> Film {
    let scene = scene::load(&crate::common::scene(name)).unwrap_or_else(|e| panic!("{e}"));
    let spec = FrameSpec::tick(width, height, bounces, shadows);
    render_frame(&scene, &spec).0
}

#[test]
fn every_scene_loads_and_renders_finite_non_blank_images() {
    let mut count = 0;
    for entry in std::fs::read_dir(crate::common::root().join("scenes")).expect("scenes/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "xml") {
            continue;
        }
        let name = path.file_name().and_then(|n| n.to_str()).expect("name");
        let film = render_scene(name, 64, 48, 2, true);
        assert!(film.beauty.iter().all(|v| v.is_finite()), "{name}");
        let first = film.beauty[0];
        assert!(film.beauty.iter().any(|&v| v != first), "{name} is blank");
        count += 1;
    }
    assert!(
        count >= 7,
        "expected the course scenes and three of our own, found {count}"
    );
}

#[test]
fn the_embedded_scene_is_the_shipped_tick2() {
    let shipped = std::fs::read_to_string(crate::common::scene("tick2.xml")).expect("read");
    assert_eq!(shipped, scene::EMBEDDED_TICK2);
}

#[test]
fn coloured_lights_tint_the_sphere_by_side() {
    // Left of the sphere's centre the red light dominates, right of it the green one.
    let film = render_scene("coloured_lights.xml", 160, 120, 0, true);
    let left = film.pixel(65, 55);
    let right = film.pixel(95, 55);
    assert!(left.x > 2.0 * left.y, "left {left}");
    assert!(right.y > 2.0 * right.x, "right {right}");
}

#[test]
fn cast_shadow_darkens_the_big_sphere_only_with_shadows_on() {
    let shadowed = render_scene("cast_shadow.xml", 160, 120, 0, true);
    let unshadowed = render_scene("cast_shadow.xml", 160, 120, 0, false);
    // A point on the big sphere inside the small sphere's shadow.
    let (x, y) = (80, 80);
    let dark = shadowed.pixel(x, y);
    let lit = unshadowed.pixel(x, y);
    assert!(
        lit.element_sum() > 2.0 * dark.element_sum(),
        "{dark} vs {lit}"
    );
}

#[test]
fn mirror_floor_reflects_only_with_bounces() {
    let flat = render_scene("mirror_floor.xml", 160, 120, 0, true);
    let mirror = render_scene("mirror_floor.xml", 160, 120, 1, true);
    // Below the red sphere, on the floor: its reflection adds red.
    let (x, y) = (33, 110);
    let gain: DVec3 = mirror.pixel(x, y) - flat.pixel(x, y) * 0.4;
    assert!(gain.x > 0.05 && gain.x > 2.0 * gain.z, "{gain}");
}
