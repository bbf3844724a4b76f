//! `whitted relight`: light groups recombined from the EXR's layers, checked against the layer
//! arithmetic done here independently.

use crate::common::*;

/// A layer and its gain.
type Term<'a> = (&'a str, [f64; 3]);

/// `sum_k gain_k * layer_k` at pixel (x, y), channel c, from the EXR's f32 layers.
fn arithmetic(exr: &Exr, terms: &[Term], x: usize, y: usize, c: usize) -> f64 {
    let channel = ["R", "G", "B"][c];
    terms
        .iter()
        .map(|(layer, gain)| gain[c] * f64::from(exr.at(&format!("{layer}.{channel}"), x, y)))
        .sum()
}

#[test]
fn relighting_is_the_layer_arithmetic() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr_path = render_exr(
        d,
        &scene("tick2.xml"),
        "in.exr",
        &["--width", "64", "--height", "48"],
    );
    let exr = read_exr(&exr_path);
    let one = [1.0; 3];
    let cases: Vec<(Vec<&str>, Vec<Term>)> = vec![
        (
            vec![],
            vec![
                ("ambient", one),
                ("light_0", one),
                ("light_1", one),
                ("background", one),
            ],
        ),
        (
            vec!["--light", "0=0"],
            vec![("ambient", one), ("light_1", one), ("background", one)],
        ),
        (
            vec!["--light", "1=2,0.5,0", "--ambient", "0.5"],
            vec![
                ("ambient", [0.5; 3]),
                ("light_0", one),
                ("light_1", [2.0, 0.5, 0.0]),
                ("background", one),
            ],
        ),
        (
            vec!["--no-shadow", "0", "--background", "0"],
            vec![("ambient", one), ("unshadowed_0", one), ("light_1", one)],
        ),
    ];
    for (options, terms) in cases {
        let mut args = vec!["relight", s(&exr_path), "-o", "out.exr"];
        args.extend_from_slice(&options);
        let run = whitted(d, &args);
        assert!(run.status.success(), "{options:?}: {}", stderr(&run));
        let out = read_exr(&d.join("out.exr"));
        assert_eq!(out.names(), ["A", "B", "G", "R"]);
        for (x, y) in [(0, 0), (20, 30), (40, 20), (63, 47), (10, 40)] {
            for c in 0..3 {
                let want = arithmetic(&exr, &terms, x, y, c);
                let got = f64::from(out.at(["R", "G", "B"][c], x, y));
                assert!(
                    (got - want).abs() <= 1e-6 + 1e-5 * want.abs(),
                    "{options:?} ({x}, {y}) channel {c}: {got} vs {want}"
                );
            }
        }
    }
    // With no options it is the beauty, to float rounding.
    let run = whitted(d, &["relight", s(&exr_path), "-o", "same.exr"]);
    assert!(run.status.success());
    let diff = whitted(d, &["diff", "same.exr", s(&exr_path), "--layers", "beauty"]);
    assert_eq!(
        diff.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&diff.stdout)
    );
}

#[test]
fn relight_writes_pngs_and_refuses_unknown_lights() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = render_exr(
        d,
        &scene("tick2.xml"),
        "in.exr",
        &["--width", "32", "--height", "24"],
    );
    let run = whitted(d, &["relight", s(&exr), "-o", "dark.png", "--light", "0=0"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let png = read_png(&d.join("dark.png"));
    assert_eq!((png.width, png.height), (32, 24));
    let run = whitted(d, &["relight", s(&exr), "-o", "x.png", "--light", "key=2"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("no light `key` in the file (its lights: 0, 1)"));
    assert!(!d.join("x.png").exists());
    let run = whitted(d, &["relight", s(&exr), "-o", "in.exr"]);
    assert_eq!(run.status.code(), Some(2), "its own input");
}

#[test]
fn relight_refuses_png_options_for_an_exr_overflow_and_incomplete_light_layers() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let exr = render_exr(
        d,
        &scene("tick2.xml"),
        "in.exr",
        &["--width", "16", "--height", "12"],
    );
    for option in [
        &["--exposure", "1"][..],
        &["--tonemap", "aces"],
        &["--png-depth", "16"],
        &["--dither", "--tonemap", "clamp"],
    ] {
        let mut args = vec!["relight", s(&exr), "-o", "out.exr"];
        args.extend_from_slice(option);
        let run = whitted(d, &args);
        assert_eq!(run.status.code(), Some(2), "{option:?}");
        assert!(stderr(&run).contains("shapes a PNG"), "{}", stderr(&run));
        assert!(!d.join("out.exr").exists());
    }
    // A finite gain whose product overflows float32: refused, no file with infinities.
    let run = whitted(
        d,
        &["relight", s(&exr), "-o", "out.exr", "--light", "0=1e300"],
    );
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(stderr(&run).contains("cannot hold"), "{}", stderr(&run));
    assert!(!d.join("out.exr").exists());

    // A light layer without its B channel: an error, not a light left out of the sum.
    use exr::prelude::*;
    let plane = |name: &str| AnyChannel::new(name, FlatSamples::F32(vec![0.25; 16]));
    let mut channels = vec![plane("light_0.R"), plane("light_0.G")];
    for layer in ["ambient", "background", "light_1"] {
        channels.extend(["R", "G", "B"].map(|c| plane(&format!("{layer}.{c}"))));
    }
    let layer = Layer::new(
        (4, 4),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    Image::from_layer(layer)
        .write()
        .to_file(d.join("partial.exr"))
        .expect("exr");
    let run = whitted(d, &["relight", "partial.exr", "-o", "p.png"]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(stderr(&run).contains("light_0"), "{}", stderr(&run));
}

#[test]
fn a_light_layer_without_a_light_name_is_refused_not_left_out() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    use exr::prelude::*;
    let plane = |name: &str| AnyChannel::new(name, FlatSamples::F32(vec![0.25; 16]));
    let mut channels = Vec::new();
    for layer in ["ambient", "background", "light_0", "light_1", "light_"] {
        channels.extend(["R", "G", "B"].map(|c| plane(&format!("{layer}.{c}"))));
    }
    let layer = Layer::new(
        (4, 4),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    Image::from_layer(layer)
        .write()
        .to_file(d.join("nameless.exr"))
        .expect("exr");
    for extra in [&[][..], &["--light", "=2"]] {
        let mut args = vec!["relight", "nameless.exr", "-o", "out.exr"];
        args.extend_from_slice(extra);
        let run = whitted(d, &args);
        assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
        assert!(stderr(&run).contains("`light_`"), "{}", stderr(&run));
        assert!(!d.join("out.exr").exists());
    }
}
