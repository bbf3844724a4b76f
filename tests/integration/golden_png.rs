//! Golden images: the course's reference renders reproduced with 0 differing pixels.

use crate::common::*;

/// Renders `scene` at `bounces` and compares with `reference` exactly. On failure the actual
/// image is kept under `target/golden-failures/` and named in the message.
fn assert_reproduces(scene_name: &str, bounces: u32, reference_name: &str) {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("actual.png");
    let run = whitted(
        dir.path(),
        &[
            "--input",
            scene(scene_name).to_str().expect("utf-8 path"),
            "--output",
            "actual.png",
            "--bounces",
            &bounces.to_string(),
        ],
    );
    assert!(run.status.success(), "render failed: {}", stderr(&run));
    let actual = read_png(&out);
    let expected = read_png(&reference(reference_name));
    assert_eq!(
        (actual.width, actual.height),
        (expected.width, expected.height)
    );
    assert_eq!(actual.color, png::ColorType::Rgb);
    assert_eq!(actual.depth, png::BitDepth::Eight);
    let expected_rgb = to_rgb(&expected);
    let differing = actual
        .data
        .chunks(3)
        .zip(expected_rgb.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    if differing > 0 {
        let keep = root().join("target/golden-failures");
        std::fs::create_dir_all(&keep).expect("mkdir");
        let kept = keep.join(format!("{scene_name}_b{bounces}.png"));
        std::fs::copy(&out, &kept).expect("keep the actual image");
        panic!(
            "{scene_name} at {bounces} bounces: {differing} pixels differ from {reference_name}; \
             actual image kept at {}",
            kept.display()
        );
    }
}

/// The reference PNGs may be RGB or RGBA; compare colour only.
fn to_rgb(png: &Png) -> Vec<u8> {
    match png.color {
        png::ColorType::Rgb => png.data.clone(),
        png::ColorType::Rgba => png.data.chunks(4).flat_map(|p| p[..3].to_vec()).collect(),
        other => panic!("unexpected reference colour type {other:?}"),
    }
}

#[test]
fn tick2_bounces_0() {
    assert_reproduces("tick2.xml", 0, "tick2_b0.png");
}

#[test]
fn tick2_bounces_1() {
    assert_reproduces("tick2.xml", 1, "tick2_b1.png");
}

#[test]
fn tick2_bounces_2() {
    assert_reproduces("tick2.xml", 2, "tick2_b2.png");
}

#[test]
fn tick2_bounces_2_is_the_course_expected_image() {
    assert_reproduces("tick2.xml", 2, "tick2_reference.png");
}

#[test]
fn tick2_bounces_3() {
    assert_reproduces("tick2.xml", 3, "tick2_b3.png");
}

#[test]
fn specular_test_bounces_2() {
    assert_reproduces("specular_test.xml", 2, "specular_test_b2.png");
}

#[test]
fn no_arguments_renders_the_embedded_tick2_to_output_png() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = whitted(dir.path(), &[]);
    assert!(run.status.success(), "{}", stderr(&run));
    let actual = read_png(&dir.path().join("output.png"));
    assert_eq!(actual.data, to_rgb(&read_png(&reference("tick2_b2.png"))));
    assert!(
        !actual.srgb,
        "the tick PNG carries no colour metadata, like the course's"
    );
}
