//! A later year's scene files read as that year's loader reads them (docs/courses.md, "Scenes
//! (the loader)"): the root's child elements in document order, case-sensitive names, numbers
//! through Java's `Double.parseDouble` with the default for a missing or unparsable one, and
//! anything the year's loader does not read ignored. Where whitted's own format would stop
//! with an error, this reader renders what the course renders and says, in a warning, what it
//! ignored or defaulted.
//!
//! It stays strict where the course's program would crash (a missing or malformed colour, XML
//! that is not well-formed) and where whitted cannot render exactly (a number that is NaN or
//! infinite, a coordinate beyond 1e150): those are located errors, as in whitted's format.

use std::borrow::Cow;
use std::collections::BTreeMap;

use glam::DVec3;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use super::attributes::needs_normalising;
use super::elements::SceneBuilder;
use super::source::{shown, Source};
use super::MAX_ELEMENTS;
use crate::course::{Course, Dialect};
use crate::error::Result;
use crate::geometry::{normalise, Shape};
use crate::numbers::exact;
use crate::scene::{Material, Object, PointLight, Scene};
use crate::suggest;

/// Largest magnitude of a coordinate or radius (as in whitted's format): squared distances
/// of larger ones overflow and the object would silently vanish.
const MAX_COORDINATE: f64 = 1e150;

/// A `<bumpy-sphere>` as the scene names it: the map is read by the caller that renders it
/// (the scene reader reads no images).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BumpRef {
    /// Index into `Scene::objects`.
    pub object: usize,
    /// The `bump-map` attribute as written, if any (relative to the scene file's folder).
    pub map: Option<String>,
    /// `file:line:col` of the element, for messages.
    pub at: String,
}

impl BumpRef {
    /// The warning for bumped spheres rendered smooth, by a command that does not apply maps.
    pub fn smooth_warning(bumps: &[BumpRef]) -> Option<String> {
        let first = bumps.first()?;
        let more = match bumps.len() {
            1 => String::new(),
            n => format!(" ({n} times; the first shown)"),
        };
        Some(format!(
            "{}: <bumpy-sphere> is rendered as a smooth sphere: its bump map (Tick 1*) is not \
             applied here (`whitted render` applies it){more}",
            first.at
        ))
    }
}

/// A scene read under a course profile, with what the reader ignored or defaulted.
pub struct CourseScene {
    pub scene: Scene,
    /// The bumped spheres, in file order.
    pub bumps: Vec<BumpRef>,
    /// One line per kind of thing ignored (`file:line:col: ...`), first place and count.
    pub warnings: Vec<String>,
}

/// Reads `text` (named `file` in messages) as `course`'s loader reads it.
pub fn parse(file: &str, text: &str, course: Course) -> Result<CourseScene> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let source = Source { file, text };
    let mut reader = CourseReader {
        source,
        course,
        dialect: course.dialect(),
        builder: SceneBuilder::default(),
        ambient: None,
        warnings: BTreeMap::new(),
        bumps: Vec::new(),
    };
    reader.walk()?;
    let ambient = reader.ambient.unwrap_or(DVec3::ONE);
    let mut scene = reader.builder.finish();
    scene.ambient = ambient;
    let mut warnings: Vec<(usize, String)> = reader
        .warnings
        .into_values()
        .map(|w| {
            let more = match w.count {
                1 => String::new(),
                n => format!(" ({n} times; the first shown)"),
            };
            (
                w.offset,
                format!("{}: {}{more}", source.position(w.offset), w.text),
            )
        })
        .collect();
    warnings.sort();
    Ok(CourseScene {
        scene,
        bumps: reader.bumps,
        warnings: warnings
            .into_iter()
            .map(|(_, w)| format!("{file}:{w}"))
            .collect(),
    })
}

/// A warning of one kind: where it first applies and how often.
struct Warning {
    offset: usize,
    text: String,
    count: usize,
}

struct CourseReader<'a> {
    source: Source<'a>,
    course: Course,
    dialect: Dialect,
    builder: SceneBuilder,
    /// The last `<ambient-light>`'s colour times its intensity: the last one wins.
    ambient: Option<DVec3>,
    /// Keyed by kind, so a thousand spheres with `kd` make one line.
    warnings: BTreeMap<String, Warning>,
    bumps: Vec<BumpRef>,
}

/// An element's attributes as written: name, value (references expanded) and offset.
struct Attributes<'e> {
    element: &'e str,
    offset: usize,
    values: Vec<(&'e str, Cow<'e, str>, usize)>,
}

impl<'a> CourseReader<'a> {
    fn warn(&mut self, kind: String, offset: usize, text: String) {
        self.warnings
            .entry(kind)
            .and_modify(|w| w.count += 1)
            .or_insert(Warning {
                offset,
                text,
                count: 1,
            });
    }

    /// Walks the document: the root's direct children are the scene's elements.
    fn walk(&mut self) -> Result<()> {
        let source = self.source;
        if source.text.trim().is_empty() {
            return Err(source.error_at(0, "the file is empty (expected a <scene> element)".into()));
        }
        let mut reader = Reader::from_str(source.text);
        let mut depth = 0usize;
        let mut roots = 0usize;
        let mut counted = 0usize;
        loop {
            let event = reader.read_event().map_err(|e| {
                let offset = usize::try_from(reader.error_position()).unwrap_or(usize::MAX);
                source.error_at(offset, format!("not well-formed XML: {e}"))
            })?;
            let (tag, opens) = match event {
                Event::Start(tag) => (tag, true),
                Event::Empty(tag) => (tag, false),
                Event::End(_) => {
                    depth = depth.saturating_sub(1);
                    continue;
                }
                Event::Eof => break,
                _ => continue,
            };
            let name: &str = &tag;
            let offset = source.offset_of(name).saturating_sub(1);
            match depth {
                0 => {
                    roots += 1;
                    if roots > 1 {
                        return Err(source.error_at(
                            offset,
                            "not well-formed XML: a second root element".into(),
                        ));
                    }
                    let root = element_name(&tag);
                    if root != "scene" {
                        self.warn(
                            "root".into(),
                            offset,
                            format!("the root element is <{}>, not <scene>: its children are read all the same, as the course's loader does", shown(root)),
                        );
                    }
                }
                1 => {
                    counted += 1;
                    if counted > MAX_ELEMENTS {
                        return Err(source.error_at(
                            offset,
                            format!("more than {MAX_ELEMENTS} elements in one scene"),
                        ));
                    }
                    self.element(&tag, offset)?;
                }
                _ => self.warn(
                    "nested".into(),
                    offset,
                    format!(
                        "ignored <{}>, inside another element (the course's loader reads only the root's children)",
                        shown(element_name(&tag))
                    ),
                ),
            }
            if opens {
                depth += 1;
            }
        }
        if roots == 0 {
            return Err(source.error_at(
                source.text.len(),
                "not well-formed XML: no root element (expected <scene>)".into(),
            ));
        }
        Ok(())
    }

    /// Reads one child of the root.
    fn element(&mut self, tag: &BytesStart, offset: usize) -> Result<()> {
        let name = element_name(tag);
        let a = self.attributes(tag, name, offset)?;
        match name {
            "sphere" | "bumpy-sphere" => {
                let object = self.sphere(&a)?;
                self.builder.objects.push(object);
            }
            "plane" => {
                if let Some(object) = self.plane(&a)? {
                    self.builder.objects.push(object);
                }
            }
            "point-light" => self.point_light(&a)?,
            "ambient-light" => self.ambient_light(&a)?,
            other => {
                let hint = suggest::nearest(other, &ELEMENTS)
                    .map_or(String::new(), |s| format!("; did you mean <{s}>?"));
                self.warn(
                    format!("element {other}"),
                    offset,
                    format!(
                        "ignored <{}>: the {} loader reads <{}>{hint}",
                        shown(other),
                        self.course,
                        ELEMENTS.join(">, <")
                    ),
                );
            }
        }
        Ok(())
    }

    /// The attributes of `tag`, duplicates refused (not well-formed XML), references
    /// expanded, and every name the year's loader does not read warned about.
    fn attributes<'e>(
        &mut self,
        tag: &'e BytesStart,
        element: &'e str,
        offset: usize,
    ) -> Result<Attributes<'e>> {
        let source = self.source;
        let tag_text: &str = tag;
        let tag_offset = source.offset_of(tag_text);
        let mut values = Vec::new();
        for attr in tag.attributes() {
            let attr = attr.map_err(|err| {
                source.error_at(tag_offset, format!("not well-formed XML: {err}"))
            })?;
            let key: &str = attr.key.0;
            let at = source.offset_of(key);
            let value = if needs_normalising(&attr.value) {
                let normalised = attr
                    .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                    .map_err(|err| {
                        source.error_at(at, format!("not well-formed XML in `{key}`: {err}"))
                    })?;
                Cow::Owned(normalised.into_owned())
            } else {
                attr.value
            };
            values.push((key, value, at));
        }
        let known = self.known_attributes(element);
        for (key, _, at) in &values {
            if !known.contains(key) && known_element(element) {
                let hint = suggest::nearest(key, &known)
                    .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
                self.warn(
                    format!("attribute {element} {key}"),
                    *at,
                    format!(
                        "ignored `{}` on <{element}>: the {} loader does not read it{hint}",
                        shown(key),
                        self.course
                    ),
                );
            }
        }
        Ok(Attributes {
            element,
            offset,
            values,
        })
    }

    /// The attribute names the year's loader reads on `element` (and light names, whitted's
    /// own, which only name the EXR's layers).
    fn known_attributes(&self, element: &str) -> Vec<&'static str> {
        let d = &self.dialect;
        let mut keys: Vec<&'static str> = match element {
            "sphere" | "bumpy-sphere" => vec!["x", "y", "z", "radius", "colour"],
            "plane" => vec!["x", "y", "z", "nx", "ny", "nz", "colour"],
            "point-light" => vec!["x", "y", "z", "colour", "intensity", "name"],
            "ambient-light" => vec!["colour"],
            _ => Vec::new(),
        };
        let object = matches!(element, "sphere" | "bumpy-sphere" | "plane");
        if d.materials && object {
            keys.extend(["kD", "kS", "alphaS", "reflectivity"]);
        }
        if d.transmittance && element == "sphere" {
            keys.extend(["tr", "tg", "tb"]);
        }
        if element == "bumpy-sphere" {
            keys.push("bump-map");
        }
        if d.ambient_intensity && element == "ambient-light" {
            keys.push("intensity");
        }
        keys
    }

    /// The value of `key` if given.
    fn raw<'e>(a: &'e Attributes, key: &str) -> Option<(&'e str, usize)> {
        a.values
            .iter()
            .find(|(k, _, _)| *k == key)
            .map(|(_, v, at)| (v.as_ref(), *at))
    }

    /// `key` as `Double.parseDouble` reads it; `default` when missing or unparsable (with a
    /// warning for the unparsable). NaN and infinities are refused: whitted renders finite
    /// scenes only.
    fn number(&mut self, a: &Attributes, key: &str, default: f64) -> Result<f64> {
        let Some((text, at)) = Self::raw(a, key) else {
            return Ok(default);
        };
        let Some(value) = java_parse_double(text) else {
            self.warn(
                format!("number {} {key}", a.element),
                at,
                format!(
                    "`{key}` on <{}> is \"{}\", which Java's Double.parseDouble refuses: the course's loader uses the default, {}",
                    a.element,
                    shown(text),
                    exact(default)
                ),
            );
            return Ok(default);
        };
        if !value.is_finite() {
            return Err(self.source.error_at(
                at,
                format!(
                    "`{key}` on <{}> is \"{}\", which is {}: whitted renders finite numbers only",
                    a.element,
                    shown(text),
                    exact(value)
                ),
            ));
        }
        Ok(value)
    }

    /// A coordinate or radius: a number, at most `MAX_COORDINATE` in magnitude.
    fn coordinate(&mut self, a: &Attributes, key: &str, default: f64) -> Result<f64> {
        let value = self.number(a, key, default)?;
        if value.abs() > MAX_COORDINATE {
            let at = Self::raw(a, key).map_or(a.offset, |(_, at)| at);
            return Err(self.source.error_at(
                at,
                format!(
                    "`{key}` = {} is beyond {MAX_COORDINATE:e} (squared distances would overflow and the object vanish)",
                    exact(value)
                ),
            ));
        }
        Ok(value)
    }

    fn position(&mut self, a: &Attributes) -> Result<DVec3> {
        Ok(DVec3::new(
            self.coordinate(a, "x", 0.0)?,
            self.coordinate(a, "y", 0.0)?,
            self.coordinate(a, "z", 0.0)?,
        ))
    }

    /// The colour: `#` and six hex digits, any after them ignored (as the course reads it).
    /// The course's program stops on a missing or shorter one, so this is an error.
    fn colour(&self, a: &Attributes) -> Result<DVec3> {
        let Some((text, at)) = Self::raw(a, "colour") else {
            return Err(self.source.error_at(
                a.offset,
                format!(
                    "<{}> has no `colour` (the course's program stops on it; give #RRGGBB)",
                    a.element
                ),
            ));
        };
        let hex = text.trim().strip_prefix('#').and_then(|h| h.get(..6));
        let channel = |h: &str, i: usize| u8::from_str_radix(&h[i..i + 2], 16).ok();
        match hex.filter(|h| h.bytes().all(|b| b.is_ascii_hexdigit())) {
            Some(h) => Ok(DVec3::new(
                f64::from(channel(h, 0).unwrap_or(0)) / 255.0,
                f64::from(channel(h, 2).unwrap_or(0)) / 255.0,
                f64::from(channel(h, 4).unwrap_or(0)) / 255.0,
            )),
            None => Err(self.source.error_at(
                at,
                format!(
                    "`colour` on <{}> is \"{}\"; the course reads # and six hex digits (#RRGGBB) and its program stops on anything else",
                    a.element,
                    shown(text)
                ),
            )),
        }
    }

    /// The material: the year's defaults, and its attributes where the year reads them.
    fn material(&mut self, a: &Attributes, defaults: Material, colour: DVec3) -> Result<Material> {
        let mut m = Material { colour, ..defaults };
        if self.dialect.materials {
            m.kd = self.number(a, "kD", m.kd)?;
            m.ks = self.number(a, "kS", m.ks)?;
            m.n = self.number(a, "alphaS", m.n)?;
            m.reflectivity = self.number(a, "reflectivity", m.reflectivity)?;
        }
        Ok(m)
    }

    fn sphere(&mut self, a: &Attributes) -> Result<Object> {
        let centre = self.position(a)?;
        // The course squares the radius and never uses its sign: -r is the sphere r.
        let radius = self.coordinate(a, "radius", 1.0)?.abs();
        let colour = self.colour(a)?;
        let material = self.material(a, self.dialect.sphere, colour)?;
        if a.element == "bumpy-sphere" {
            let map = a
                .values
                .iter()
                .find(|(name, _, _)| *name == "bump-map")
                .map(|(_, value, _)| value.to_string());
            self.bumps.push(BumpRef {
                object: self.builder.objects.len(),
                map,
                at: format!("{}:{}", self.source.file, self.source.position(a.offset)),
            });
        }
        Ok(Object {
            shape: Shape::Sphere { centre, radius },
            material,
        })
    }

    /// A plane, or none for a normal of zero length: the course's plane then has a NaN
    /// normal, which no ray ever hits, so leaving it out renders the same image.
    fn plane(&mut self, a: &Attributes) -> Result<Option<Object>> {
        let point = self.position(a)?;
        let n = DVec3::new(
            self.coordinate(a, "nx", 0.0)?,
            self.coordinate(a, "ny", 0.0)?,
            self.coordinate(a, "nz", 0.0)?,
        );
        let colour = self.colour(a)?;
        let material = self.material(a, self.dialect.plane, colour)?;
        let normal = normalise(n);
        if !normal.is_finite() {
            self.warn(
                "plane normal".into(),
                a.offset,
                "a <plane> whose normal (nx, ny, nz) has zero length is hit by no ray, in the course's program as here: left out".into(),
            );
            return Ok(None);
        }
        Ok(Some(Object {
            shape: Shape::Plane { point, normal },
            material,
        }))
    }

    fn point_light(&mut self, a: &Attributes) -> Result<()> {
        let position = self.position(a)?;
        let colour = self.colour(a)?;
        let intensity = self.number(a, "intensity", 100.0)?;
        let index = self.builder.lights.len();
        let name = match Self::raw(a, "name") {
            Some((name, at)) => {
                let name = name.trim();
                self.builder.check_light_name(&self.source, name, at)?;
                name.to_string()
            }
            None => index.to_string(),
        };
        self.builder.lights.push(PointLight {
            position,
            colour,
            intensity,
            name,
        });
        Ok(())
    }

    fn ambient_light(&mut self, a: &Attributes) -> Result<()> {
        let colour = self.colour(a)?;
        let ambient = if self.dialect.ambient_intensity {
            colour * self.number(a, "intensity", 1.0)?
        } else {
            colour
        };
        if self.ambient.is_some() {
            self.warn(
                "ambient".into(),
                a.offset,
                "a second <ambient-light>: the last one wins, as in the course's loader".into(),
            );
        }
        self.ambient = Some(ambient);
        Ok(())
    }
}

/// The elements a course loader reads.
const ELEMENTS: [&str; 5] = [
    "sphere",
    "plane",
    "point-light",
    "ambient-light",
    "bumpy-sphere",
];

fn known_element(name: &str) -> bool {
    ELEMENTS.contains(&name)
}

fn element_name<'e>(tag: &'e BytesStart) -> &'e str {
    tag.name().0
}

/// `Double.parseDouble(text)`: surrounding characters <= U+0020 trimmed, an optional sign,
/// then `NaN`, `Infinity`, or a decimal number (digits with at most one point, at least one
/// digit, an optional exponent) with an optional `f`/`F`/`d`/`D` suffix, rounded to nearest
/// as Java does. `None` where Java throws. Hexadecimal floats (`0x1p3`) are not read: they are
/// `None` here (the default), where Java would read them.
pub fn java_parse_double(text: &str) -> Option<f64> {
    let t = text.trim_matches(|c: char| c <= ' ');
    let (negative, body) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let magnitude = match body {
        "NaN" => f64::NAN,
        "Infinity" => f64::INFINITY,
        _ => {
            let digits = body.strip_suffix(['f', 'F', 'd', 'D']).unwrap_or(body);
            if !is_java_decimal(digits) {
                return None;
            }
            digits.parse::<f64>().ok()?
        }
    };
    Some(if negative { -magnitude } else { magnitude })
}

/// Digits with at most one `.` and at least one digit, then optionally `e`/`E`, a sign and
/// at least one digit: the decimal form Java reads (Rust's parser also takes `inf` and `nan`,
/// which Java does not).
fn is_java_decimal(s: &str) -> bool {
    let (mantissa, exponent) = match s.find(['e', 'E']) {
        Some(i) => (&s[..i], Some(&s[i + 1..])),
        None => (s, None),
    };
    let mut points = 0;
    let mut digits = 0;
    for b in mantissa.bytes() {
        match b {
            b'0'..=b'9' => digits += 1,
            b'.' => points += 1,
            _ => return false,
        }
    }
    if digits == 0 || points > 1 {
        return false;
    }
    match exponent {
        None => true,
        Some(e) => {
            let e = e.strip_prefix(['+', '-']).unwrap_or(e);
            !e.is_empty() && e.bytes().all(|b| b.is_ascii_digit())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_read_as_java_reads_them() {
        assert_eq!(java_parse_double(" 1.5 "), Some(1.5));
        assert_eq!(java_parse_double("-.4"), Some(-0.4));
        assert_eq!(java_parse_double("1."), Some(1.0));
        assert_eq!(java_parse_double("2e3"), Some(2000.0));
        assert_eq!(java_parse_double("0.1f"), Some(0.1));
        assert_eq!(java_parse_double("+7D"), Some(7.0));
        assert_eq!(java_parse_double("-Infinity"), Some(f64::NEG_INFINITY));
        assert!(java_parse_double("NaN").is_some_and(f64::is_nan));
        for bad in [
            "", "abc", "inf", "nan", "1e", "1..2", ".", "1,5", "e3", "0x1p3",
        ] {
            assert_eq!(java_parse_double(bad), None, "{bad}");
        }
    }

    #[test]
    fn the_2021_22_test1_loads_as_the_course_loads_it() {
        let text = include_str!("../../../scenes/courses/2020-21/test1.xml");
        let read = parse("test1.xml", text, Course::Y2021).expect("loads");
        let scene = read.scene;
        assert_eq!(scene.objects.len(), 4);
        assert_eq!(scene.lights.len(), 2);
        assert_eq!(
            scene.ambient,
            DVec3::new(208.0, 208.0, 255.0) / 255.0 * 0.05
        );
        // kD 0.8 default (the file's `kd` is ignored), kS 0.8 and alphaS 50 read.
        let sphere = scene.objects[0].material;
        assert_eq!(
            (sphere.kd, sphere.ks, sphere.n, sphere.reflectivity),
            (0.8, 0.8, 50.0, 0.3)
        );
        // The plane: the sphere's defaults but the kS it gives.
        let plane = scene.objects[3].material;
        assert_eq!(
            (plane.kd, plane.ks, plane.n, plane.reflectivity),
            (0.8, 0.8, 10.0, 0.3)
        );
        assert_eq!(read.warnings.len(), 1, "{:?}", read.warnings);
        assert!(
            read.warnings[0].starts_with("test1.xml:5:77:")
                && read.warnings[0].contains("ignored `kd` on <sphere>")
                && read.warnings[0].contains("did you mean `kD`?")
                && read.warnings[0].contains("3 times"),
            "{}",
            read.warnings[0]
        );
    }

    #[test]
    fn each_year_reads_its_own_attributes() {
        let text = r##"<scene><ambient-light colour="#FFFFFF" intensity="0.5"/>
            <plane nx="0" ny="1" nz="0" colour="#808080" kD="0.3"/></scene>"##;
        let later = parse("s.xml", text, Course::Y2019).expect("loads");
        assert_eq!(later.scene.ambient, DVec3::splat(0.5));
        assert_eq!(later.scene.objects[0].material.kd, 0.3);
        assert!(later.warnings.is_empty(), "{:?}", later.warnings);
        let early = parse("s.xml", text, Course::Y2018).expect("loads");
        assert_eq!(early.scene.ambient, DVec3::ONE);
        assert_eq!(early.scene.objects[0].material.kd, 0.6);
        assert_eq!(early.warnings.len(), 2, "{:?}", early.warnings);
    }

    #[test]
    fn what_the_course_would_crash_on_is_a_located_error() {
        let missing = parse(
            "s.xml",
            "<scene>\n  <sphere x=\"1\"/></scene>",
            Course::Y2020,
        );
        let msg = missing.err().expect("an error").to_string();
        assert!(
            msg.contains("s.xml:2:3") && msg.contains("no `colour`"),
            "{msg}"
        );
        let nan = parse(
            "s.xml",
            r##"<scene><sphere x="NaN" colour="#000000"/></scene>"##,
            Course::Y2020,
        );
        assert!(nan.err().expect("an error").to_string().contains("finite"));
        let unparsable = parse(
            "s.xml",
            r##"<scene><sphere x="one" colour="#102030ff"/></scene>"##,
            Course::Y2020,
        )
        .expect("loads");
        assert_eq!(unparsable.warnings.len(), 1);
        let Shape::Sphere { centre, .. } = unparsable.scene.objects[0].shape else {
            panic!("a sphere")
        };
        assert_eq!(centre, DVec3::ZERO);
        assert_eq!(
            unparsable.scene.objects[0].material.colour,
            DVec3::new(16.0, 32.0, 48.0) / 255.0
        );
    }
}
