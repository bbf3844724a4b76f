//! Tick 1* renders (docs/tick1star.md) through the command line: the bump method on
//! hand-computed pixels, distinct parametrisations, byte-identical output for any thread
//! count, the layers' sums with OpenImageIO, and hostile bump maps.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::*;

fn star_scene(name: &str) -> PathBuf {
    scene(&format!("courses/tick1star/{name}"))
}

/// `whitted` with `args` in `dir` on `threads` rayon threads.
fn whitted_on(threads: usize, dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .current_dir(dir)
        .env("RAYON_NUM_THREADS", threads.to_string())
        .output()
        .expect("the whitted binary runs")
}

fn normalise(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[test]
fn bump_xml_follows_the_handout_s_method_at_hand_computed_pixels() {
    let dir = tempfile::tempdir().expect("tempdir");
    let args = ["--course", "2020-21", "--width", "160", "--height", "120"];
    let exr = render_exr(dir.path(), &star_scene("bump.xml"), "bump.exr", &args);
    let image = read_exr(&exr);
    let map = read_png(&star_scene("bumpmap.png"));
    assert_eq!(
        (map.width, map.height, map.color),
        (1500, 1500, png::ColorType::Rgb)
    );
    let height = |row: usize, col: usize| {
        let blue = map.data[(row * 1500 + col) * 3 + 2];
        f64::from(5.0f32 * (f32::from(blue) / 255.0))
    };
    let mut checked = 0;
    for (x, y) in [(80, 60), (70, 50), (95, 72), (60, 66), (88, 45), (75, 80)] {
        assert_eq!(
            image.at("objectid.X", x, y),
            1.0,
            "({x}, {y}) is on the sphere"
        );
        let p = ["P.X", "P.Y", "P.Z"].map(|c| f64::from(image.at(c, x, y)));
        let n = normalise([p[0], p[1], p[2] - 3.5]);
        // The default parametrisation `y-zx`: u = 0.5 + atan2(n.z, n.x)/2pi, v = acos(n.y)/pi.
        let phi = n[2].atan2(n[0]);
        let theta = n[1].acos();
        let (u, v) = (0.5 + phi / (2.0 * PI), theta / PI);
        let (cu, cv) = (u * 1500.0, v * 1500.0);
        // P is stored as f32: skip a pixel whose texel that rounding could change.
        if (cu - cu.round()).abs() < 1e-3 || (cv - cv.round()).abs() < 1e-3 {
            continue;
        }
        let (col, row) = (cu.floor() as usize, cv.floor() as usize);
        let b_u = height(row, col + 1) - height(row, col);
        let b_v = height(row + 1, col) - height(row, col);
        let p_u = [-phi.sin(), 0.0, phi.cos()];
        let p_v = [
            theta.cos() * phi.cos(),
            -theta.sin(),
            theta.cos() * phi.sin(),
        ];
        let (a, b) = (cross(n, p_v), cross(n, p_u));
        let expected = normalise([0, 1, 2].map(|i| n[i] + b_u * a[i] + b_v * b[i]));
        let got = ["N.X", "N.Y", "N.Z"].map(|c| f64::from(image.at(c, x, y)));
        for i in 0..3 {
            assert!(
                (got[i] - expected[i]).abs() < 1e-4,
                "({x}, {y}): N {got:?} vs the method's {expected:?}"
            );
        }
        let h = f64::from(image.at("height.Y", x, y));
        assert!(
            (h - height(row, col)).abs() < 1e-6,
            "({x}, {y}): height {h}"
        );
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} pixels checked");
}

#[test]
fn each_parametrisation_lays_the_map_differently() {
    let dir = tempfile::tempdir().expect("tempdir");
    let names = [
        "y-zx",
        "y-zx-mirrored",
        "y-xz",
        "y-zx-from-x",
        "z-yx",
        "z-yx-from-x",
    ];
    let images: Vec<Vec<u8>> = names
        .iter()
        .map(|name| {
            let out = format!("{name}.png");
            let run = whitted(
                dir.path(),
                &[
                    "render",
                    "-q",
                    "--course",
                    "2020-21",
                    "--width",
                    "96",
                    "--height",
                    "72",
                    "-i",
                    s(&star_scene("bump.xml")),
                    "-o",
                    &out,
                    "--bump-param",
                    name,
                ],
            );
            assert!(run.status.success(), "{name}: {}", stderr(&run));
            read_png(&dir.path().join(out)).data
        })
        .collect();
    for i in 0..names.len() {
        for j in i + 1..names.len() {
            let differing = images[i]
                .chunks(3)
                .zip(images[j].chunks(3))
                .filter(|(a, b)| a != b)
                .count();
            // The sphere covers about 1400 of the 6912 pixels.
            assert!(
                differing > 300,
                "{} and {} differ at only {differing} pixels",
                names[i],
                names[j]
            );
        }
    }
}

#[test]
fn tick1star_renders_are_byte_identical_on_one_and_two_threads() {
    let dir = tempfile::tempdir().expect("tempdir");
    let cases: [(&str, &[&str]); 3] = [
        ("bump.xml", &[]),
        (
            "distributed.xml",
            &["--soft-shadows", "--dof", "--seed", "7"],
        ),
        (
            "distributed.xml",
            &[
                "--soft-shadows",
                "--dof=3.51805,0.2,8",
                "--sampling",
                "converged",
                "--noise-floor",
                "0.02",
            ],
        ),
    ];
    for (k, (scene_name, extra)) in cases.iter().enumerate() {
        let outputs: Vec<(Vec<u8>, Vec<u8>)> = [1, 2]
            .iter()
            .map(|&threads| {
                let (png, exr) = (format!("{k}_{threads}.png"), format!("{k}_{threads}.exr"));
                let input = star_scene(scene_name);
                let mut args = small_render(s(&input), &png);
                args.extend_from_slice(&["--exr", &exr]);
                args.extend_from_slice(extra);
                let run = whitted_on(threads, dir.path(), &args);
                assert!(run.status.success(), "{scene_name}: {}", stderr(&run));
                let read = |f: &str| std::fs::read(dir.path().join(f)).expect("written");
                (read(&png), read(&exr))
            })
            .collect();
        assert!(
            outputs[0] == outputs[1],
            "case {k} ({scene_name}) differs by thread count"
        );
    }
}

/// Writes the sum of the RGB of `layers` (bare `R G B` for "") to `out` with oiiotool.
fn oiio_sum(exr: &Path, layers: &[&str], out: &Path) {
    let mut args: Vec<String> = Vec::new();
    for (i, layer) in layers.iter().enumerate() {
        let channels = if layer.is_empty() {
            "R,G,B".to_string()
        } else {
            format!("R={layer}.R,G={layer}.G,B={layer}.B")
        };
        args.extend([s(exr).to_string(), "--ch".into(), channels]);
        if i > 0 {
            args.push("--add".into());
        }
    }
    args.extend(["-d".into(), "float".into(), "-o".into(), s(out).to_string()]);
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = run_tool("oiiotool", &argv, exr.parent().expect("dir"));
    assert!(run.status.success(), "oiiotool {argv:?}: {}", stderr(&run));
}

#[test]
fn soft_shadow_layers_sum_to_the_beauty_and_their_masks_are_fractions() {
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = render_exr(
        dir.path(),
        &star_scene("distributed.xml"),
        "soft.exr",
        &[
            "--course",
            "2020-21",
            "--width",
            "64",
            "--height",
            "48",
            "--soft-shadows",
            "--dof=3.51805,0.2,4",
            "--seed",
            "3",
        ],
    );
    for (label, parts) in [
        (
            "effects",
            &["ambient", "diffuse", "specular", "background"][..],
        ),
        ("bounces", &["direct", "reflected"][..]),
        ("lights", &["ambient", "light_0", "background"][..]),
    ] {
        let (lhs, rhs) = (
            dir.path().join(format!("{label}.exr")),
            dir.path().join("rgb.exr"),
        );
        oiio_sum(&exr, parts, &lhs);
        oiio_sum(&exr, &[""], &rhs);
        let run = idiff_aov(&lhs, &rhs);
        assert_eq!(
            run.status.code(),
            Some(0),
            "{label}: {}",
            String::from_utf8_lossy(&run.stdout)
        );
    }
    let image = read_exr(&exr);
    let names = image.names();
    assert!(names.contains(&"coc.Y".to_string()), "{names:?}");
    let masks: Vec<f32> = (0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .map(|(x, y)| image.at("shadow_0.Y", x, y))
        .collect();
    assert!(masks.iter().all(|m| (0.0..=1.0).contains(m)));
    let fractional = masks.iter().filter(|m| **m > 0.0 && **m < 1.0).count();
    assert!(fractional > 20, "only {fractional} penumbra pixels");
    // The circle of confusion is 0 on the focal plane's sphere and grows behind it.
    let coc = |x, y| image.at("coc.Y", x, y);
    assert!(coc(40, 30) < coc(20, 20), "{} {}", coc(40, 30), coc(20, 20));
}

#[test]
fn a_hostile_or_missing_bump_map_is_one_located_message_and_exit_2() {
    let dir = tempfile::tempdir().expect("tempdir");
    let bad = root().join("tests/bad_images");
    let mut maps: Vec<PathBuf> = [
        "png_huge.png",
        "png_truncated.png",
        "png_bad_crc.png",
        "not_an_image.txt",
    ]
    .iter()
    .map(|f| bad.join(f))
    .collect();
    maps.push(dir.path().join("missing.png"));
    for map in maps {
        let xml = format!(
            "<scene>\n  <point-light x=\"1\" y=\"3\" z=\"2\" colour=\"#B3DDFF\" intensity=\"100\"/>\n  \
             <bumpy-sphere x=\"0\" y=\"0\" z=\"3.5\" radius=\"0.7\" colour=\"#F45B00\" bump-map=\"{}\"/>\n</scene>\n",
            s(&map)
        );
        let scene_file = write_scene(dir.path(), "bad.xml", &xml);
        let run = whitted(
            dir.path(),
            &[
                "render",
                "-q",
                "--course",
                "2020-21",
                "-i",
                s(&scene_file),
                "-o",
                "out.png",
            ],
        );
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{}: {err}", map.display());
        assert_eq!(err.trim().lines().count(), 1, "{}: {err}", map.display());
        assert!(
            err.contains("bad.xml:3:3") && err.contains("bump map"),
            "{err}"
        );
        assert!(!dir.path().join("out.png").exists(), "no partial output");
    }
}

#[test]
fn light_sampling_surface_moves_only_the_light_s_points() {
    // `--light-sampling surface` (the course's point normalised) changes the soft shadows;
    // with a light of radius 0 every sampling is the same point and the same image.
    let dir = tempfile::tempdir().expect("tempdir");
    let input = star_scene("distributed.xml");
    let render = |sampling: &str, size: &str| -> Vec<u8> {
        let out = format!("{sampling}_{size}.png");
        let mut args = small_render(s(&input), &out);
        args.extend_from_slice(&[
            "--soft-shadows",
            "--light-size",
            size,
            "--light-sampling",
            sampling,
            "--seed",
            "3",
        ]);
        let run = whitted_on(2, dir.path(), &args);
        assert!(run.status.success(), "{sampling}: {}", stderr(&run));
        std::fs::read(dir.path().join(out)).expect("written")
    };
    assert!(render("surface", "0.4") != render("course", "0.4"));
    assert!(render("surface", "0") == render("course", "0"));
}

/// The arguments of a quiet 48×36 2020-21 render of `input` to `out`, which tests extend.
fn small_render<'a>(input: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "render", "-q", "--course", "2020-21", "--width", "48", "--height", "36", "-i", input,
        "-o", out,
    ]
}
