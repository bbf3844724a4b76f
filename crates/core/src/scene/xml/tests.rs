//! The loader against every element, default and error class.

use super::attributes::{needs_normalising, parse_colour, trimmed};
use super::*;
use crate::geometry::Shape;
use crate::scene::Material;
use glam::DVec3;

fn parse(text: &str) -> Result<Scene> {
    parse_str("test.xml", text)
}

fn error(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("expected an error for {text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn reads_every_element_with_defaults_and_overrides() {
    let scene = parse(
        r##"<?xml version="1.0"?>
<scene>
  <!-- a comment -->
  <ambient-light colour="#555555"/>
  <point-light x="2" y="2" z="4.5" colour="#FFB0B2" intensity="100" name="key"/>
  <point-light colour="#ffffff"/>
  <sphere x="-0.95" y=" -.21884 " z="3.63261" radius="0.35" colour="#FF1D25"/>
  <sphere colour="#000000" kD="0.5" kS="0" n="3" reflectivity="1"/>
  <plane y="-1" nx="0" ny="2" nz="0" colour="#222222"></plane>
</scene>"##,
    )
    .expect("valid");
    assert_eq!(scene.ambient, DVec3::splat(85.0 / 255.0));
    assert_eq!(scene.lights.len(), 2);
    assert_eq!(scene.lights[0].name, "key");
    assert_eq!(scene.lights[1].name, "1");
    assert_eq!(scene.lights[1].intensity, 100.0);
    assert_eq!(scene.lights[1].position, DVec3::ZERO);
    assert_eq!(
        scene.lights[0].colour,
        DVec3::new(1.0, 176.0 / 255.0, 178.0 / 255.0)
    );
    assert_eq!(
        scene.objects[0].shape,
        Shape::Sphere {
            centre: DVec3::new(-0.95, -0.21884, 3.63261),
            radius: 0.35
        }
    );
    assert_eq!(
        scene.objects[0].material,
        Material::sphere(DVec3::new(1.0, 29.0 / 255.0, 37.0 / 255.0))
    );
    assert_eq!(
        scene.objects[1].shape,
        Shape::Sphere {
            centre: DVec3::ZERO,
            radius: 1.0
        }
    );
    let m = scene.objects[1].material;
    assert_eq!((m.kd, m.ks, m.n, m.reflectivity), (0.5, 0.0, 3.0, 1.0));
    assert_eq!(
        scene.objects[2].shape,
        Shape::Plane {
            point: DVec3::new(0.0, -1.0, 0.0),
            normal: DVec3::Y
        }
    );
    assert_eq!(
        scene.objects[2].material,
        Material::plane(DVec3::splat(34.0 / 255.0))
    );
}

#[test]
fn missing_ambient_is_white_and_empty_scene_is_valid() {
    let scene = parse("<scene/>").expect("valid");
    assert_eq!(scene.ambient, DVec3::ONE);
    assert!(scene.objects.is_empty() && scene.lights.is_empty());
}

#[test]
fn errors_are_located_and_explain_what_was_expected() {
    let cases = [
        ("", "test.xml:1:1: the file is empty"),
        ("<world/>", "test.xml:1:1: the root element is <world>, expected <scene>"),
        ("<scene>\n  <sphear colour=\"#FF0000\"/>\n</scene>", "test.xml:2:3: unknown element <sphear> (did you mean <sphere>?"),
        ("<scene>\n <sphere color=\"#FF0000\"/>\n</scene>", "test.xml:2:10: unknown attribute `color` on <sphere> (did you mean `colour`?"),
        ("<scene>\n <sphere x=\"1\" x=\"2\" colour=\"#FF0000\"/></scene>", "test.xml:2:16: duplicate attribute `x` on <sphere> (first given at 2:10)"),
        ("<scene><sphere/></scene>", "test.xml:1:8: <sphere> needs a `colour` attribute"),
        ("<scene><sphere colour=\"#FFF\"/></scene>", "test.xml:1:16: `colour` must be #RRGGBB"),
        ("<scene><sphere colour=\"red\"/></scene>", "`colour` must be #RRGGBB"),
        ("<scene><sphere colour=\"#GGGGGG\"/></scene>", "`colour` must be #RRGGBB"),
        ("<scene><sphere y=\"abc\" colour=\"#FF0000\"/></scene>", "test.xml:1:16: `y` must be a number"),
        ("<scene><sphere x=\"NaN\" colour=\"#FF0000\"/></scene>", "`x` must be a finite number, got `NaN`"),
        ("<scene><sphere x=\"inf\" colour=\"#FF0000\"/></scene>", "`x` must be a finite number"),
        ("<scene><sphere radius=\"0\" colour=\"#FF0000\"/></scene>", "`radius` must be > 0"),
        ("<scene><sphere radius=\"-1\" colour=\"#FF0000\"/></scene>", "`radius` must be > 0"),
        ("<scene><plane colour=\"#FF0000\"/></scene>", "test.xml:1:8: <plane> normal (nx, ny, nz) = (0, 0, 0) has (near) zero length"),
        ("<scene><point-light intensity=\"-1\" colour=\"#FF0000\"/></scene>", "`intensity` must be >= 0"),
        ("<scene><sphere reflectivity=\"1.5\" colour=\"#FF0000\"/></scene>", "`reflectivity` must be between 0 and 1"),
        ("<scene><sphere kD=\"-1\" colour=\"#FF0000\"/></scene>", "`kD` must be >= 0"),
        ("<scene><sphere kS=\"-1\" colour=\"#FF0000\"/></scene>", "`kS` must be >= 0"),
        ("<scene><sphere n=\"-1\" colour=\"#FF0000\"/></scene>", "`n` must be >= 0"),
        ("<scene><ambient-light colour=\"#FF0000\"/>\n<ambient-light colour=\"#FF0000\"/></scene>", "test.xml:2:1: a second <ambient-light> (the first is at 1:8"),
        ("<scene><point-light colour=\"#FF0000\" name=\"a\"/>\n<point-light colour=\"#FF0000\" name=\"a\"/></scene>", "test.xml:2:31: duplicate light name `a` (first used at 1:38"),
        ("<scene><point-light colour=\"#FF0000\" name=\"1a\"/></scene>", "light name `1a` must be a letter"),
        ("<scene><point-light colour=\"#FF0000\" name=\"abcdefghijklmnopq\"/></scene>", "at most 16 characters"),
        ("<scene>\n<sphere colour=\"#FF0000\">\n<plane/></sphere></scene>", "test.xml:3:1: <plane> is nested inside <sphere>"),
        ("<scene>\n  <sphere colour=\"#FF0000\">\n</scene>\n", "test.xml:3:1: not well-formed XML"),
        ("<scene>\n  <sphere colour=\"#FF0000\"/>\n", "test.xml:1:1: <scene> is never closed"),
        ("<scene>hello</scene>", "test.xml:1:8: unexpected text `hello` inside <scene>"),
        ("<scene/><scene/>", "test.xml:1:9: a second root element <scene>"),
        ("<scene foo=\"1\"/>", "unknown attribute `foo` on <scene> (it takes no attributes)"),
        ("<!-- only a comment -->", "no <scene> element"),
    ];
    for (text, want) in cases {
        let got = error(text);
        assert!(
            got.starts_with(want) || got.contains(want),
            "for {text:?}\n got: {got}\nwant: {want}"
        );
    }
}

#[test]
fn not_utf8_is_located() {
    let err = parse_bytes("bad.xml", b"<scene>\n  <sphere colour=\"\xff\"/>").unwrap_err();
    assert_eq!(
        err.to_string(),
        "bad.xml:2:19: the file is not valid UTF-8 (save it as UTF-8)"
    );
}

#[test]
fn colours_parse_either_case() {
    assert_eq!(
        parse_colour("#ff0080"),
        Some(DVec3::new(1.0, 0.0, 128.0 / 255.0))
    );
    assert_eq!(parse_colour("#FF0080"), parse_colour("#ff0080"));
    assert_eq!(parse_colour("FF0080"), None);
    assert_eq!(parse_colour("#FF008"), None);
    assert_eq!(parse_colour("#+F0080"), None);
}

#[test]
fn objects_read_in_batches_keep_file_order_and_the_first_error() {
    // More objects than one batch, so that some are read in parallel with others.
    let spheres: String = (0..BATCH + 100)
        .map(|i| format!("<sphere x=\"{i}\" colour=\"#FFFFFF\"/>\n"))
        .collect();
    let scene = parse(&format!("<scene>\n{spheres}</scene>")).expect("valid");
    assert_eq!(scene.objects.len(), BATCH + 100);
    for (i, object) in scene.objects.iter().enumerate() {
        let Shape::Sphere { centre, .. } = object.shape else {
            panic!("a sphere")
        };
        assert_eq!(centre.x, i as f64);
    }
    // A bad object is reported before a later light error and a later malformed tag, and
    // the first of two bad objects is the one reported.
    let bad = |late: &str| {
        error(&format!(
            "<scene>\n{spheres}<sphere radius=\"-1\" colour=\"#FFFFFF\"/>\n\
             <sphere radius=\"oops\" colour=\"#FFFFFF\"/>\n{late}\n</scene>"
        ))
    };
    let line = BATCH + 102;
    for late in [
        "<point-light colour=\"#FFFFFF\" name=\"1bad\"/>",
        "<sphere colour=\"#FFFFFF\" <",
    ] {
        let err = bad(late);
        assert!(
            err.starts_with(&format!("test.xml:{line}:")) && err.contains("radius"),
            "{err}"
        );
    }
    // A bad object in the first batch is reported before a malformed tag that the scanner
    // meets in a later batch, while the first is still being read.
    let err = error(&format!(
        "<scene>\n<sphere radius=\"-1\" colour=\"#FFFFFF\"/>\n{spheres}{spheres}\
         <sphere colour=\"#FFFFFF\" <\n</scene>"
    ));
    assert!(
        err.starts_with("test.xml:2:") && err.contains("radius"),
        "{err}"
    );
    // Without it, the malformed tag is the error.
    let err = error(&format!(
        "<scene>\n{spheres}{spheres}<sphere colour=\"#FFFFFF\" <\n</scene>"
    ));
    assert!(err.contains("not well-formed"), "{err}");
}

#[test]
fn values_are_trimmed_and_normalised_as_the_library_does() {
    for text in [
        "",
        " ",
        "1.5",
        " 1.5",
        "1.5 ",
        "\u{a0}1.5",
        "1.5\u{2003}",
        "x",
        "\t-2\n",
        "é",
        " é ",
    ] {
        assert_eq!(trimmed(text), text.trim(), "{text:?}");
    }
    // Exactly the values that XML 1.0 normalisation would change need it.
    for (raw, needs) in [
        ("1.5", false),
        ("#FFFFFF", false),
        ("a b", false),
        ("1\t5", true),
        ("1\r\n", true),
        ("\n", true),
        ("&lt;", true),
        ("&#x31;", true),
    ] {
        assert_eq!(needs_normalising(raw), needs, "{raw:?}");
    }
    // Values with tabs, line ends and references read as the library normalises them.
    let scene =
        parse("<scene><sphere x=\"&#x31;\" y=\"\t2\n\" z=\"\r\n3\" colour=\"#FFFFFF\"/></scene>")
            .expect("valid");
    let Shape::Sphere { centre, .. } = scene.objects[0].shape else {
        panic!("a sphere")
    };
    assert_eq!(centre, DVec3::new(1.0, 2.0, 3.0));
}

#[test]
fn a_later_year_s_scene_is_pointed_to_its_course() {
    let msg = |xml: &str| parse_str("s.xml", xml).expect_err("an error").to_string();
    let ambient = msg(r##"<scene><ambient-light colour="#010101" intensity="2"/></scene>"##);
    assert!(ambient.contains("--course YEAR"), "{ambient}");
    let alpha = msg(r##"<scene><sphere colour="#010101" alphaS="20"/></scene>"##);
    assert!(alpha.contains("--course YEAR"), "{alpha}");
    let bumpy = msg(r##"<scene><bumpy-sphere colour="#010101"/></scene>"##);
    assert!(bumpy.contains("Tick 1*"), "{bumpy}");
    // Not for what no year has.
    let color = msg(r##"<scene><sphere color="#010101"/></scene>"##);
    assert!(!color.contains("--course"), "{color}");
}
