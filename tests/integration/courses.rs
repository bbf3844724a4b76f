//! Every course year, exact against a program of that year: `tests/java/.../tick1/Tick1.java`,
//! a correct Tick 1 written from docs/courses.md (its year a parameter, `-Dcourse=YEAR`),
//! renders random scenes in the year's own scene format, and `whitted render --course YEAR`
//! must give the very same bytes. Scenes are built to reach every rule that differs between
//! years: the camera and lights inside spheres (the far root), lights behind surfaces (the
//! N.L gate), mirrors (the reflected ray), planes with materials of their own, coloured lights
//! (the specular colour) and an ambient intensity.

use std::path::Path;
use std::process::Command;

use crate::common::*;

/// Whether the year's loader reads material attributes and an ambient intensity.
fn reads_materials(course: &str) -> bool {
    course >= "2019-20"
}

/// Material attributes for one object, as the year's scenes may give them (none before
/// 2019-20, and not always after: the defaults are part of what is tested).
fn materials(rng: &mut Lcg, course: &str) -> String {
    if !reads_materials(course) || rng.chance(0.3) {
        return String::new();
    }
    let mut attributes = String::new();
    for (name, lo, hi) in [
        ("kD", 0.0, 1.0),
        ("kS", 0.0, 2.0),
        ("alphaS", 1.0, 60.0),
        ("reflectivity", 0.0, 1.0),
    ] {
        if rng.chance(0.6) {
            attributes += &format!(" {name}=\"{}\"", rng.range(lo, hi));
        }
    }
    attributes
}

/// One random scene in the year's format.
fn scene_for(course: &str, rng: &mut Lcg) -> String {
    let mut xml = String::from("<scene>\n");
    let intensity = if reads_materials(course) {
        format!(" intensity=\"{}\"", rng.range(0.05, 3.0))
    } else {
        String::new()
    };
    xml += &format!("<ambient-light colour=\"{}\"{intensity}/>\n", rng.colour());
    if rng.chance(0.5) {
        // The camera inside a sphere: every camera ray takes the far root.
        let m = materials(rng, course);
        xml += &format!(
            "<sphere x=\"0.1\" y=\"-0.1\" z=\"0.3\" radius=\"{}\" colour=\"{}\"{m}/>\n",
            rng.range(6.0, 9.0),
            rng.colour()
        );
    }
    for _ in 0..8 {
        let m = materials(rng, course);
        xml += &format!(
            "<sphere x=\"{}\" y=\"{}\" z=\"{}\" radius=\"{}\" colour=\"{}\"{m}/>\n",
            rng.range(-2.0, 2.0),
            rng.range(-1.5, 1.5),
            rng.range(2.5, 7.0),
            rng.range(0.2, 0.9),
            rng.colour()
        );
    }
    for _ in 0..2 {
        let m = materials(rng, course);
        xml += &format!(
            "<plane x=\"0\" y=\"{}\" z=\"{}\" nx=\"{}\" ny=\"{}\" nz=\"{}\" colour=\"{}\"{m}/>\n",
            rng.range(-2.0, -0.5),
            rng.range(5.0, 9.0),
            rng.range(-0.5, 0.5),
            rng.range(0.2, 1.0),
            rng.range(-1.0, 0.0),
            rng.colour()
        );
    }
    for _ in 0..3 {
        xml += &format!(
            "<point-light x=\"{}\" y=\"{}\" z=\"{}\" colour=\"{}\" intensity=\"{}\"/>\n",
            rng.range(-3.0, 3.0),
            rng.range(-1.0, 3.0),
            rng.range(0.0, 8.0),
            rng.colour(),
            rng.range(20.0, 200.0)
        );
    }
    xml + "</scene>\n"
}

/// The RGB bytes of a PNG.
fn rgb(path: &Path) -> Vec<u8> {
    let png = read_png(path);
    match png.color {
        png::ColorType::Rgb => png.data,
        png::ColorType::Rgba => png.data.chunks(4).flat_map(|p| p[..3].to_vec()).collect(),
        other => panic!("unexpected colour type {other:?}"),
    }
}

#[test]
fn every_year_renders_what_a_correct_program_of_that_year_renders() {
    let years = [
        "2016-17", "2017-18", "2018-19", "2019-20", "2020-21", "2021-22", "2023-24",
    ];
    let dir = tempfile::tempdir().expect("tempdir");
    let mut lit = 0;
    for (y, course) in years.iter().enumerate() {
        for seed in 0..3u64 {
            let mut rng = Lcg(100 * y as u64 + seed);
            let xml = scene_for(course, &mut rng);
            let file = write_scene(dir.path(), &format!("{course}_{seed}.xml"), &xml);
            let bounces = (seed + y as u64) % 4;
            let java = Command::new("java")
                .arg(format!("-Dcourse={course}"))
                .arg("-cp")
                .arg(tick1_classes())
                .arg("uk.ac.cam.cl.gfxintro.whitted.tick1.Tick1")
                .args(["-i", s(&file), "-o", "java.png", "-r", "96x72"])
                .args(["-b", &bounces.to_string()])
                .current_dir(dir.path())
                .output()
                .expect("java runs");
            assert!(java.status.success(), "{}", stderr(&java));
            let ours = whitted(
                dir.path(),
                &[
                    "render",
                    "--course",
                    course,
                    "-i",
                    s(&file),
                    "-o",
                    "whitted.png",
                    "--width",
                    "96",
                    "--height",
                    "72",
                    "-b",
                    &bounces.to_string(),
                ],
            );
            assert!(ours.status.success(), "{}", stderr(&ours));
            let (expected, actual) = (
                rgb(&dir.path().join("java.png")),
                rgb(&dir.path().join("whitted.png")),
            );
            let differing = expected
                .chunks(3)
                .zip(actual.chunks(3))
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(
                differing, 0,
                "{course} seed {seed} at {bounces} bounces: {differing} pixels differ\n{xml}"
            );
            lit += expected.iter().filter(|&&b| b > 40).count();
        }
    }
    // The scenes are lit, not black: the comparison sees the shading.
    assert!(lit > 10_000, "{lit}");
}

#[test]
fn the_years_are_not_one_image() {
    // The same scene under 2019-20 and 2020-21 rules (they differ only in the shadow ray's
    // bias) and under 2016-17 and 2017-18: the test above could tell the years apart.
    let dir = tempfile::tempdir().expect("tempdir");
    let mut rng = Lcg(7);
    let file = write_scene(dir.path(), "s.xml", &scene_for("2016-17", &mut rng));
    let render = |course: &str| {
        let out = format!("{course}.png");
        let run = whitted(
            dir.path(),
            &["render", "--course", course, "-i", s(&file), "-o", &out],
        );
        assert!(run.status.success(), "{}", stderr(&run));
        rgb(&dir.path().join(out))
    };
    assert_ne!(render("2016-17"), render("2017-18"));
    assert_ne!(render("2018-19"), render("2017-18"));
}
