//! Golden images: the course's reference renders reproduced with 0 differing pixels.

use crate::common::*;

/// Renders `scene` at `bounces` and compares with `reference` exactly. On failure the actual
/// image is kept under `target/golden-failures/` and named in the message.
fn assert_reproduces(scene_name: &str, bounces: u32, reference_name: &str) {
    assert_reproduces_with(
        scene_name,
        &["--bounces", &bounces.to_string()],
        reference_name,
    );
}

/// `assert_reproduces` with the render's options `args`: the course's own defaults for
/// everything they leave out.
fn assert_reproduces_with(scene_name: &str, args: &[&str], reference_name: &str) {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("actual.png");
    let input = scene(scene_name);
    let mut all = vec!["render", "--input", s(&input), "--output", "actual.png"];
    all.extend(args);
    let run = whitted(dir.path(), &all);
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
        let label = format!("{scene_name} {}", args.join(" "));
        let kept = keep.join(format!("{}.png", label.replace(['/', ' '], "_")));
        std::fs::copy(&out, &kept).expect("keep the actual image");
        panic!(
            "{label}: {differing} pixels differ from {reference_name}; actual image kept at {}",
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

/// Each later year's expected images, reproduced by `render --course YEAR` at the year's
/// default size, bounces and tone map (docs/courses.md; reference/courses/ holds the course's
/// PNGs, scenes/courses/ its scenes).
fn assert_course_reproduces(course: &str, folder: &str, test: &str) {
    assert_reproduces_with(
        &format!("courses/{folder}/{test}.xml"),
        &["--course", course],
        &format!("courses/{folder}/{test}_reference.png"),
    );
}

#[test]
fn course_2019_20_test1_and_test2() {
    assert_course_reproduces("2019-20", "2019-20", "test1");
    assert_course_reproduces("2019-20", "2019-20", "test2");
}

#[test]
fn course_2020_21_test1_and_test2() {
    assert_course_reproduces("2020-21", "2020-21", "test1");
    assert_course_reproduces("2020-21", "2020-21", "test2");
}

#[test]
fn course_2021_22_test1_and_test2() {
    assert_course_reproduces("2021-22", "2021-24", "test1");
    assert_course_reproduces("2021-22", "2021-24", "test2");
}

#[test]
fn course_2023_24_test1_and_test2() {
    assert_course_reproduces("2023-24", "2021-24", "test1");
    assert_course_reproduces("2023-24", "2021-24", "test2");
}

#[test]
fn the_years_differ_where_the_course_s_images_say() {
    // 2019-20's shadow rays start along L, 2020-21's along N: each year's renderer misses the
    // other's test1 (24 pixels), so the tests above can fail.
    let dir = tempfile::tempdir().expect("tempdir");
    let run = whitted(
        dir.path(),
        &[
            "render",
            "--course",
            "2020-21",
            "-i",
            s(&scene("courses/2019-20/test1.xml")),
            "-o",
            "a.png",
        ],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let actual = read_png(&dir.path().join("a.png"));
    let expected = to_rgb(&read_png(&reference("courses/2019-20/test1_reference.png")));
    let differing = actual
        .data
        .chunks(3)
        .zip(expected.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differing, 24);
    // And 2016-17 is still the default: the same image as asked for by name.
    for args in [
        &["render", "-o", "d.png"][..],
        &["render", "--course", "2016-17", "-o", "n.png"],
    ] {
        let run = whitted(dir.path(), args);
        assert!(run.status.success(), "{}", stderr(&run));
    }
    assert_eq!(
        read_png(&dir.path().join("d.png")).data,
        read_png(&dir.path().join("n.png")).data
    );
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
