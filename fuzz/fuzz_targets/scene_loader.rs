//! Any bytes as a scene file: loading must return a scene or a located error, never panic;
//! a scene that loads must render (tiny, every AOV) without panicking, with finite layers.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whitted::frame::{Frame, FrameSpec};
use whitted::render::render;

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
    let spec = FrameSpec {
        width: 8,
        height: 6,
        ..FrameSpec::default()
    };
    let frame = Frame::new(&scene, &spec).expect("a loaded scene has a frame");
    let (film, _) = render(&scene, &frame, &|_| {}).expect("a loaded scene renders");
    assert!(film.data.iter().all(|v| v.is_finite()));
});
