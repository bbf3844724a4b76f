//! Property tests: random valid scenes load to exactly what they say and render finite layers
//! that add up; random damage to a scene never panics and always gives a located error.

use crate::common::render_frame;
use proptest::prelude::*;
use whitted_core::film::Film;
use whitted_core::frame::FrameSpec;
use whitted_core::render::RenderStats;
use whitted_core::scene::parse_str;

#[derive(Debug, Clone)]
enum Element {
    Sphere {
        at: [f64; 3],
        radius: f64,
        colour: u32,
        material: Option<[f64; 4]>,
    },
    Plane {
        at: [f64; 3],
        normal: [f64; 3],
        colour: u32,
        material: Option<[f64; 4]>,
    },
    Light {
        at: [f64; 3],
        colour: u32,
        intensity: f64,
        named: bool,
    },
}

fn coordinate() -> impl Strategy<Value = f64> {
    -20.0..20.0f64
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [coordinate(), coordinate(), coordinate()]
}

fn material() -> impl Strategy<Value = Option<[f64; 4]>> {
    proptest::option::of(
        (0.0..2.0f64, 0.0..2.0f64, 0.0..50.0f64, 0.0..=1.0f64)
            .prop_map(|(a, b, c, d)| [a, b, c, d]),
    )
}

fn element() -> impl Strategy<Value = Element> {
    prop_oneof![
        (point(), 0.01..5.0f64, any::<u32>(), material()).prop_map(
            |(at, radius, colour, material)| Element::Sphere {
                at,
                radius,
                colour,
                material
            }
        ),
        (point(), point(), any::<u32>(), material())
            .prop_filter("non-zero normal", |(_, n, _, _)| n
                .iter()
                .map(|c| c * c)
                .sum::<f64>()
                > 1e-6)
            .prop_map(|(at, normal, colour, material)| Element::Plane {
                at,
                normal,
                colour,
                material
            }),
        (point(), any::<u32>(), 0.0..500.0f64, any::<bool>()).prop_map(
            |(at, colour, intensity, named)| Element::Light {
                at,
                colour,
                intensity,
                named
            }
        ),
    ]
}

fn material_xml(m: &Option<[f64; 4]>) -> String {
    m.map_or(String::new(), |[kd, ks, n, r]| {
        format!(r#" kD="{kd:?}" kS="{ks:?}" n="{n:?}" reflectivity="{r:?}""#)
    })
}

fn scene_xml(elements: &[Element], ambient: Option<u32>) -> String {
    let mut xml = String::from("<scene>\n");
    if let Some(a) = ambient {
        xml += &format!("  <ambient-light colour=\"#{:06X}\"/>\n", a & 0xFF_FFFF);
    }
    for (i, e) in elements.iter().enumerate() {
        xml += &match e {
            Element::Sphere {
                at,
                radius,
                colour,
                material,
            } => format!(
                r##"  <sphere x="{:?}" y="{:?}" z="{:?}" radius="{radius:?}" colour="#{:06x}"{}/>"##,
                at[0],
                at[1],
                at[2],
                colour & 0xFF_FFFF,
                material_xml(material)
            ),
            Element::Plane {
                at,
                normal,
                colour,
                material,
            } => format!(
                r##"  <plane x="{:?}" y="{:?}" z="{:?}" nx="{:?}" ny="{:?}" nz="{:?}" colour="#{:06X}"{}/>"##,
                at[0],
                at[1],
                at[2],
                normal[0],
                normal[1],
                normal[2],
                colour & 0xFF_FFFF,
                material_xml(material)
            ),
            Element::Light {
                at,
                colour,
                intensity,
                named,
            } => format!(
                r##"  <point-light x="{:?}" y="{:?}" z="{:?}" colour="#{:06X}" intensity="{intensity:?}"{}/>"##,
                at[0],
                at[1],
                at[2],
                colour & 0xFF_FFFF,
                if *named {
                    format!(" name=\"l{i}\"")
                } else {
                    String::new()
                }
            ),
        };
        xml += "\n";
    }
    xml + "</scene>\n"
}

fn render_all(xml: &str, bounces: u32, shadows: bool) -> (Film, RenderStats) {
    let scene = parse_str("test.xml", xml).expect("valid");
    let spec = FrameSpec {
        width: 12,
        height: 9,
        bounces,
        shadows,
        ..FrameSpec::default()
    };
    render_frame(&scene, &spec)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn valid_scenes_load_exactly(elements in proptest::collection::vec(element(), 0..12), ambient in proptest::option::of(any::<u32>())) {
        let xml = scene_xml(&elements, ambient);
        let scene = parse_str("test.xml", &xml).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let lights = elements.iter().filter(|e| matches!(e, Element::Light { .. })).count();
        prop_assert_eq!(scene.lights.len(), lights);
        prop_assert_eq!(scene.objects.len(), elements.len() - lights);
        for (object, element) in scene.objects.iter().zip(elements.iter().filter(|e| !matches!(e, Element::Light { .. }))) {
            match (element, &object.shape) {
                (Element::Sphere { at, radius, material, .. }, whitted_core::geometry::Shape::Sphere { centre, radius: r }) => {
                    prop_assert_eq!(centre.to_array(), *at);
                    prop_assert_eq!(r, radius);
                    if let Some([kd, ks, n, refl]) = material {
                        prop_assert_eq!((object.material.kd, object.material.ks, object.material.n, object.material.reflectivity), (*kd, *ks, *n, *refl));
                    }
                }
                (Element::Plane { at, .. }, whitted_core::geometry::Shape::Plane { point, normal }) => {
                    prop_assert_eq!(point.to_array(), *at);
                    prop_assert!((normal.length() - 1.0).abs() < 1e-12);
                }
                (e, s) => prop_assert!(false, "{:?} loaded as {:?}", e, s),
            }
        }
    }

    #[test]
    fn valid_scenes_render_finite_layers_that_add_up(
        elements in proptest::collection::vec(element(), 1..8),
        bounces in 0u32..4,
        shadows in any::<bool>(),
    ) {
        let (film, stats) = render_all(&scene_xml(&elements, None), bounces, shadows);
        prop_assert!(film.data.iter().all(|v| v.is_finite()));
        prop_assert_eq!(stats.non_finite, 0);
        prop_assert!(film.beauty.iter().all(|v| v.is_finite()));
        let get = |name: &str| film.channel(name).expect(name);
        for c in ["R", "G", "B"] {
            let (beauty, direct, reflected) = (get(c), get(&format!("direct.{c}")), get(&format!("reflected.{c}")));
            for i in 0..beauty.len() {
                let sum = f64::from(direct[i]) + f64::from(reflected[i]);
                let b = f64::from(beauty[i]);
                prop_assert!((sum - b).abs() <= 1e-6 + 1e-5 * b.abs(), "pixel {}: {} vs {}", i, sum, b);
            }
        }
    }

    #[test]
    fn damaged_scenes_never_panic_and_errors_are_located(
        elements in proptest::collection::vec(element(), 1..6),
        cuts in proptest::collection::vec((any::<prop::sample::Index>(), 0usize..12, "[<>/=\"'& a-z#0-9\\n-]{0,6}"), 1..4),
    ) {
        let mut xml = scene_xml(&elements, Some(0x333333)).into_bytes();
        for (at, remove, insert) in cuts {
            let start = at.index(xml.len() + 1);
            let end = (start + remove).min(xml.len());
            xml.splice(start..end, insert.bytes());
        }
        if let Err(e) = whitted_core::scene::parse_bytes("test.xml", &xml) {
            let message = e.to_string();
            let mut parts = message.splitn(4, ':');
            prop_assert_eq!(parts.next(), Some("test.xml"));
            prop_assert!(parts.next().is_some_and(|l| l.parse::<usize>().is_ok()), "{}", message);
            prop_assert!(parts.next().is_some_and(|c| c.parse::<usize>().is_ok()), "{}", message);
        }
    }
}

#[test]
fn a_hundred_thousand_spheres_load() {
    let mut xml =
        String::from("<scene>\n<point-light x=\"0\" y=\"5\" z=\"0\" colour=\"#FFFFFF\"/>\n");
    for i in 0..100_000 {
        xml += &format!(
            "<sphere x=\"{}\" y=\"{}\" z=\"{}\" radius=\"0.05\" colour=\"#80C0FF\"/>\n",
            i % 100,
            (i / 100) % 100,
            10 + i / 10_000
        );
    }
    xml += "</scene>\n";
    let scene = parse_str("big.xml", &xml).expect("valid");
    assert_eq!(scene.objects.len(), 100_000);
}
