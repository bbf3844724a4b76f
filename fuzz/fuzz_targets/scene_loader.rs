//! Any bytes as a scene file: loading must return a scene or a located error, never panic;
//! a scene that loads must render (tiny, every AOV) without panicking, with finite layers.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whitted::aov::all_layers;
use whitted::camera::Camera;
use whitted::render::{render, RenderSettings};
use whitted::trace::TraceOptions;

fuzz_target!(|data: &[u8]| {
    let scene = match whitted::scene::parse_bytes("fuzz.xml", data) {
        Ok(scene) => scene,
        Err(e) => {
            let message = e.to_string();
            assert!(
                message.starts_with("fuzz.xml:"),
                "unlocated error: {message}"
            );
            return;
        }
    };
    let names: Vec<String> = scene.lights.iter().map(|l| l.name.clone()).collect();
    let settings = RenderSettings {
        trace: TraceOptions {
            bounces: 2,
            shadows: true,
        },
        spp: 1, ..RenderSettings::default() };
    let film = render(
        &scene,
        &Camera::new(8, 6),
        settings,
        all_layers(&names, 2),
        &|_| {},
    )
    .expect("a loaded scene renders");
    assert!(film.data.iter().all(|v| v.is_finite()));
});
