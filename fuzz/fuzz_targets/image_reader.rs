//! Any bytes as an image file (OpenEXR, PNG, or neither): reading must return an image or an
//! error, never panic or abort, and what it returns must be consistent.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // libFuzzer's RSS limit (4 GiB in tools/fuzz) is invisible to the process: tell whitted.
    whitted::memory::limit_to(1 << 30);
    if let Ok(parts) = whitted::input::decode(Path::new("fuzz.img"), data.to_vec()) {
        for image in parts {
            let pixels = image.width * image.height;
            assert!(image.channels.iter().all(|c| c.values.len() == pixels));
            for layer in image.layers() {
                let _ = whitted::stats::Stats::of_layer(&image, &layer);
            }
        }
    }
});
