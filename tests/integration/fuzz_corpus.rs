//! Replays the fuzz corpora (tools/fuzz) through the same checks as the fuzz targets, so
//! `cargo test` keeps every input the fuzzer found interesting. Scenes (with the bad-scene
//! corpus and the shipped scenes): loading never panics and errors are located; what loads
//! renders finite layers. Images (with tests/bad_images): reading never panics, and what reads
//! is consistent.

use std::path::PathBuf;

use crate::common::render_frame;
use whitted_core::frame::FrameSpec;

fn inputs() -> Vec<PathBuf> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        "fuzz/corpus/scene_loader",
        "tests/bad_scenes",
        "scenes",
        "scenes/check",
    ] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap_or_else(|e| panic!("{dir}: {e}")) {
            let path = entry.expect("entry").path();
            if path.is_file() && path.extension().is_none_or(|e| e != "expected") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn every_corpus_input_loads_or_fails_cleanly() {
    let files = inputs();
    assert!(files.len() > 50, "corpus too small: {}", files.len());
    let (mut loaded, mut refused) = (0, 0);
    for path in &files {
        let bytes = std::fs::read(path).expect("read");
        match whitted_core::scene::parse_bytes("corpus.xml", &bytes) {
            Ok(scene) => {
                let spec = FrameSpec {
                    width: 8,
                    height: 6,
                    ..FrameSpec::default()
                };
                let (film, _) = render_frame(&scene, &spec);
                assert!(
                    film.data.iter().all(|v| v.is_finite()),
                    "{}",
                    path.display()
                );
                loaded += 1;
            }
            Err(e) => {
                let message = e.to_string();
                assert!(
                    message.starts_with("corpus.xml:"),
                    "{}: unlocated: {message}",
                    path.display()
                );
                refused += 1;
            }
        }
    }
    assert!(
        loaded >= 7 && refused >= 40,
        "loaded {loaded}, refused {refused}"
    );
}

#[test]
fn every_image_corpus_input_reads_or_fails_cleanly() {
    // As in the fuzz target: a budget the corpus's largest declared sizes exceed.
    whitted_core::memory::limit_to(1 << 30);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let (mut read, mut refused) = (0, 0);
    for dir in ["fuzz/corpus/image_reader", "tests/bad_images"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap_or_else(|e| panic!("{dir}: {e}")) {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "expected") {
                continue;
            }
            let bytes = std::fs::read(&path).expect("read");
            match whitted_io::input::decode(&path, bytes) {
                Ok(parts) => {
                    for image in parts {
                        let pixels = image.width * image.height;
                        assert!(
                            image.channels.iter().all(|c| c.values.len() == pixels),
                            "{}",
                            path.display()
                        );
                    }
                    read += 1;
                }
                Err(e) => {
                    assert!(!e.to_string().is_empty());
                    refused += 1;
                }
            }
        }
    }
    assert!(read >= 4 && refused >= 8, "{read} read, {refused} refused");
}
