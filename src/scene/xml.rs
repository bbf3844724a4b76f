//! Scene XML -> `Scene` (scene-format.md). Strict: anything the format does not allow is an
//! error naming the file, the line:column of the offending element or attribute, and what was
//! expected, because a silently different picture is worse than no picture.

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use crate::error::{Error, Result};
use crate::geometry::{normalise, Shape};
use crate::scene::{Material, Object, PointLight, Scene};
use crate::suggest;

const ELEMENTS: [&str; 4] = ["sphere", "plane", "point-light", "ambient-light"];
const MATERIAL_ATTRIBUTES: [&str; 4] = ["kD", "kS", "n", "reflectivity"];
const SPHERE_ATTRIBUTES: [&str; 5] = ["x", "y", "z", "radius", "colour"];
const PLANE_ATTRIBUTES: [&str; 7] = ["x", "y", "z", "nx", "ny", "nz", "colour"];
const LIGHT_ATTRIBUTES: [&str; 6] = ["x", "y", "z", "colour", "intensity", "name"];
const AMBIENT_ATTRIBUTES: [&str; 1] = ["colour"];

/// Longest light name: keeps `unshadowed_<name>.R` within OpenEXR's 31-character channel names.
pub const MAX_LIGHT_NAME: usize = 16;

/// A plane normal shorter than this cannot be normalised meaningfully.
const MIN_NORMAL_LENGTH: f64 = 1e-12;

/// Largest scene file read: far beyond any hand-written scene (a million spheres is ~80 MB),
/// small enough that a mistaken path to a huge file fails at once.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// Most elements (objects and lights) in one scene.
pub const MAX_ELEMENTS: usize = 10_000_000;

/// Longest attribute value quoted back in an error message.
const SHOWN_CHARS: usize = 40;

/// Reads and parses the scene file at `path`. Error messages name the file as given.
pub fn load(path: &Path) -> Result<Scene> {
    let size = std::fs::metadata(path)
        .map_err(|e| Error::io(path, "cannot read scene", e))?
        .len();
    if size > MAX_FILE_BYTES {
        return Err(Error::Usage(format!(
            "{}: the scene file is {size} bytes; scenes up to {MAX_FILE_BYTES} bytes are read",
            path.display()
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, "cannot read scene", e))?;
    parse_bytes(&path.display().to_string(), &bytes)
}

/// A number as an error message shows it: plainly, or in scientific notation when tiny or huge.
fn number(v: f64) -> String {
    if v == 0.0 || (1e-6..1e15).contains(&v.abs()) {
        v.to_string()
    } else {
        format!("{v:e}")
    }
}

/// `value` as quoted in an error message: long values are cut short.
fn shown(value: &str) -> String {
    if value.chars().count() <= SHOWN_CHARS {
        value.to_string()
    } else {
        let start: String = value.chars().take(SHOWN_CHARS).collect();
        format!("{start}... ({} characters)", value.chars().count())
    }
}

/// Parses a scene from raw bytes; `file` is the name used in error messages.
pub fn parse_bytes(file: &str, bytes: &[u8]) -> Result<Scene> {
    match std::str::from_utf8(bytes) {
        Ok(text) => parse_str(file, text),
        Err(e) => {
            let valid = &bytes[..e.valid_up_to()];
            // The prefix is valid UTF-8 by construction, so this cannot fail.
            let text = std::str::from_utf8(valid).unwrap_or_default();
            let encoding = if bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]) {
                "UTF-16"
            } else {
                "not valid UTF-8"
            };
            Err(Source { file, text }.error_at(
                text.len(),
                format!("the file is {encoding} (save it as UTF-8)"),
            ))
        }
    }
}

/// Parses a scene from text; `file` is the name used in error messages.
pub fn parse_str(file: &str, text: &str) -> Result<Scene> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let source = Source { file, text };
    if text.trim().is_empty() {
        return Err(source.error_at(0, "the file is empty (expected a <scene> element)".into()));
    }
    Parser {
        source,
        builder: SceneBuilder::default(),
    }
    .run()
}

/// The text being parsed, for turning byte offsets into line:column.
#[derive(Clone, Copy)]
struct Source<'a> {
    file: &'a str,
    text: &'a str,
}

impl<'a> Source<'a> {
    fn line_col(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let line = before.matches('\n').count() + 1;
        let col = before[line_start..].chars().count() + 1;
        (line, col)
    }

    fn error_at(&self, offset: usize, msg: String) -> Error {
        let (line, col) = self.line_col(offset);
        Error::Scene {
            file: self.file.to_string(),
            line,
            col,
            msg,
        }
    }

    /// Byte offset of `part`, which must be a slice of the source text.
    fn offset_of(&self, part: &str) -> usize {
        (part.as_ptr() as usize).saturating_sub(self.text.as_ptr() as usize)
    }

    fn position(&self, offset: usize) -> String {
        let (line, col) = self.line_col(offset);
        format!("{line}:{col}")
    }
}

struct Parser<'a> {
    source: Source<'a>,
    builder: SceneBuilder,
}

/// An element still waiting for its end tag.
struct Open {
    name: String,
    offset: usize,
}

impl<'a> Parser<'a> {
    fn run(mut self) -> Result<Scene> {
        let mut reader = Reader::from_str(self.source.text);
        let mut open: Vec<Open> = Vec::new();
        let mut seen_root = false;
        loop {
            let event = reader.read_event().map_err(|e| {
                let offset = usize::try_from(reader.error_position()).unwrap_or(usize::MAX);
                self.source
                    .error_at(offset, format!("not well-formed XML: {e}"))
            })?;
            match event {
                Event::Start(e) => {
                    let offset = self.element(&e, &open, &mut seen_root)?;
                    open.push(Open {
                        name: e.name().0.to_string(),
                        offset,
                    });
                }
                Event::Empty(e) => {
                    self.element(&e, &open, &mut seen_root)?;
                }
                Event::End(_) => {
                    open.pop();
                }
                Event::Text(t) => {
                    let content: &str = &t;
                    if !content.trim().is_empty() {
                        let offset = self.source.offset_of(content)
                            + (content.len() - content.trim_start().len());
                        return Err(self.unexpected_text(offset, content.trim(), &open));
                    }
                }
                Event::CData(t) => {
                    let offset = self.source.offset_of(&t);
                    return Err(self.unexpected_text(offset, "<![CDATA[...]]>", &open));
                }
                Event::GeneralRef(r) => {
                    let offset = self.source.offset_of(&r).saturating_sub(1);
                    return Err(self.unexpected_text(offset, &format!("&{};", &*r), &open));
                }
                Event::Comment(_) | Event::Decl(_) | Event::PI(_) | Event::DocType(_) => {}
                Event::Eof => break,
            }
        }
        if let Some(unclosed) = open.last() {
            return Err(self.source.error_at(
                unclosed.offset,
                format!(
                    "<{}> is never closed (expected </{}> or a self-closing <{} .../>)",
                    unclosed.name, unclosed.name, unclosed.name
                ),
            ));
        }
        if !seen_root {
            return Err(self.source.error_at(
                self.source.text.len(),
                "no <scene> element (expected <scene> ... </scene>)".into(),
            ));
        }
        Ok(self.builder.finish())
    }

    fn unexpected_text(&self, offset: usize, text: &str, open: &[Open]) -> Error {
        let text = shown(text);
        let place = match open.last() {
            Some(o) => format!("inside <{}>", o.name),
            None => "outside <scene>".into(),
        };
        self.source.error_at(
            offset,
            format!(
                "unexpected text `{text}` {place} (a scene holds only elements with attributes)"
            ),
        )
    }

    /// Handles a start or empty-element tag; returns the offset of its `<`.
    fn element(&mut self, e: &BytesStart, open: &[Open], seen_root: &mut bool) -> Result<usize> {
        let tag: &str = e;
        let offset = self.source.offset_of(tag).saturating_sub(1);
        let name = e.name().0;
        match open {
            [] => {
                if *seen_root {
                    return Err(self.source.error_at(
                        offset,
                        format!(
                            "a second root element <{}> (a file holds one <scene>)",
                            shown(name)
                        ),
                    ));
                }
                if name != "scene" {
                    return Err(self.source.error_at(
                        offset,
                        format!("the root element is <{}>, expected <scene>", shown(name)),
                    ));
                }
                *seen_root = true;
                self.attributes(e, "scene", &[])?;
            }
            [_] => self.child(e, name, offset)?,
            [.., parent] => {
                return Err(self.source.error_at(
                    offset,
                    format!(
                        "<{}> is nested inside <{}> (elements go directly inside <scene>)",
                        shown(name),
                        shown(&parent.name)
                    ),
                ));
            }
        }
        Ok(offset)
    }

    fn child(&mut self, e: &BytesStart, name: &str, offset: usize) -> Result<()> {
        if self.builder.objects.len() + self.builder.lights.len() >= MAX_ELEMENTS {
            return Err(self.source.error_at(
                offset,
                format!(
                    "too many elements: a scene holds at most {MAX_ELEMENTS} objects and lights"
                ),
            ));
        }
        match name {
            "sphere" => {
                let a = self.attributes(e, name, &[&SPHERE_ATTRIBUTES, &MATERIAL_ATTRIBUTES])?;
                let colour = a.required_colour(offset)?;
                let radius = a.number("radius", 1.0)?;
                if radius <= 0.0 {
                    return Err(a.error(
                        "radius",
                        format!("`radius` must be > 0, got {}", number(radius)),
                    ));
                }
                let shape = Shape::Sphere {
                    centre: a.position()?,
                    radius,
                };
                let material = a.material(Material::sphere(colour))?;
                self.builder.objects.push(Object { shape, material });
            }
            "plane" => {
                let a = self.attributes(e, name, &[&PLANE_ATTRIBUTES, &MATERIAL_ATTRIBUTES])?;
                let colour = a.required_colour(offset)?;
                let n = DVec3::new(
                    a.number("nx", 0.0)?,
                    a.number("ny", 0.0)?,
                    a.number("nz", 0.0)?,
                );
                if n.length().is_nan() || n.length() <= MIN_NORMAL_LENGTH {
                    return Err(self.source.error_at(
                        offset,
                        format!(
                            "<plane> normal (nx, ny, nz) = ({}, {}, {}) has (near) zero length \
                             (give nx, ny, nz for a non-zero normal)",
                            number(n.x),
                            number(n.y),
                            number(n.z)
                        ),
                    ));
                }
                let shape = Shape::Plane {
                    point: a.position()?,
                    normal: normalise(n),
                };
                let material = a.material(Material::plane(colour))?;
                self.builder.objects.push(Object { shape, material });
            }
            "point-light" => {
                let a = self.attributes(e, name, &[&LIGHT_ATTRIBUTES])?;
                let colour = a.required_colour(offset)?;
                let intensity = a.number("intensity", 100.0)?;
                if intensity < 0.0 {
                    return Err(a.error(
                        "intensity",
                        format!("`intensity` must be >= 0, got {}", number(intensity)),
                    ));
                }
                let index = self.builder.lights.len();
                let name = match a.get("name") {
                    Some(attr) => {
                        let name = attr.value.trim();
                        self.builder
                            .check_light_name(&self.source, name, attr.offset)?;
                        name.to_string()
                    }
                    None => index.to_string(),
                };
                let position = a.position()?;
                self.builder.lights.push(PointLight {
                    position,
                    colour,
                    intensity,
                    name,
                });
            }
            "ambient-light" => {
                let a = self.attributes(e, name, &[&AMBIENT_ATTRIBUTES])?;
                if let Some(first) = self.builder.ambient_at {
                    return Err(self.source.error_at(
                        offset,
                        format!(
                            "a second <ambient-light> (the first is at {}; a scene has at most one)",
                            self.source.position(first)
                        ),
                    ));
                }
                self.builder.ambient = Some(a.required_colour(offset)?);
                self.builder.ambient_at = Some(offset);
            }
            other => {
                let hint = match suggest::nearest(other, &ELEMENTS) {
                    Some(s) => format!("did you mean <{s}>? "),
                    None => String::new(),
                };
                return Err(self.source.error_at(
                    offset,
                    format!(
                        "unknown element <{}> ({hint}expected one of <{}>)",
                        shown(other),
                        ELEMENTS.join(">, <")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Collects the attributes of `e`, rejecting duplicates and any name not in `allowed`.
    fn attributes(
        &self,
        e: &BytesStart,
        element: &str,
        allowed: &[&[&str]],
    ) -> Result<Attributes<'a>> {
        let tag: &str = e;
        let tag_offset = self.source.offset_of(tag);
        let allowed: Vec<&str> = allowed.iter().flat_map(|a| a.iter().copied()).collect();
        let mut list: Vec<Attribute> = Vec::new();
        let mut iter = e.attributes();
        iter.with_checks(false);
        for attr in iter {
            let attr = attr.map_err(|err| {
                use quick_xml::events::attributes::AttrError;
                let (pos, what) = match err {
                    AttrError::ExpectedEq(p) => {
                        (p, "an attribute name must be followed by `=`".into())
                    }
                    AttrError::ExpectedValue(p) => {
                        (p, "`=` must be followed by a quoted value".into())
                    }
                    AttrError::UnquotedValue(p) => (
                        p,
                        "attribute values must be in quotes (\"...\" or '...')".into(),
                    ),
                    AttrError::ExpectedQuote(p, q) => (
                        p,
                        format!("the attribute value has no closing {}", q as char),
                    ),
                    AttrError::Duplicated(p, _) => (p, "duplicate attribute".into()),
                };
                self.source
                    .error_at(tag_offset + pos, format!("not well-formed XML: {what}"))
            })?;
            let key = attr.key.0;
            let offset = self.source.offset_of(key);
            if let Some(first) = list.iter().find(|a| a.key == key) {
                return Err(self.source.error_at(
                    offset,
                    format!(
                        "duplicate attribute `{key}` on <{element}> (first given at {})",
                        self.source.position(first.offset)
                    ),
                ));
            }
            if !allowed.contains(&key) {
                let hint = match suggest::nearest(key, &allowed) {
                    Some(s) => format!("did you mean `{s}`? "),
                    None => String::new(),
                };
                let expected = if allowed.is_empty() {
                    "it takes no attributes".to_string()
                } else {
                    format!("expected one of {}", allowed.join(", "))
                };
                return Err(self.source.error_at(
                    offset,
                    format!(
                        "unknown attribute `{}` on <{element}> ({hint}{expected})",
                        shown(key)
                    ),
                ));
            }
            let value = attr
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| {
                    self.source.error_at(
                        offset,
                        format!(
                            "`{key}` has an entity or character reference that scenes do not \
                                 expand ({err}); only &lt; &gt; &amp; &quot; &apos; and &#...; are"
                        ),
                    )
                })?
                .into_owned();
            list.push(Attribute {
                key: key.to_string(),
                value,
                offset,
            });
        }
        Ok(Attributes {
            source: self.source,
            element: element.to_string(),
            list,
        })
    }
}

struct Attribute {
    key: String,
    value: String,
    offset: usize,
}

/// The checked attributes of one element, with typed getters that know their defaults.
struct Attributes<'a> {
    source: Source<'a>,
    element: String,
    list: Vec<Attribute>,
}

impl<'a> Attributes<'a> {
    fn get(&self, key: &str) -> Option<&Attribute> {
        self.list.iter().find(|a| a.key == key)
    }

    fn error(&self, key: &str, msg: String) -> Error {
        let offset = self.get(key).map_or(0, |a| a.offset);
        self.source.error_at(offset, msg)
    }

    /// A finite decimal number, or `default` when the attribute is absent.
    fn number(&self, key: &str, default: f64) -> Result<f64> {
        let Some(attr) = self.get(key) else {
            return Ok(default);
        };
        match attr.value.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.error(
                key,
                format!(
                    "`{key}` must be a finite number, got `{}`",
                    shown(&attr.value)
                ),
            )),
            Err(_) => Err(self.error(
                key,
                format!(
                    "`{key}` must be a number (like 1.5 or -.4), got `{}`",
                    shown(&attr.value)
                ),
            )),
        }
    }

    fn non_negative(&self, key: &str, default: f64) -> Result<f64> {
        let v = self.number(key, default)?;
        if v < 0.0 {
            return Err(self.error(key, format!("`{key}` must be >= 0, got {}", number(v))));
        }
        Ok(v)
    }

    fn position(&self) -> Result<DVec3> {
        Ok(DVec3::new(
            self.number("x", 0.0)?,
            self.number("y", 0.0)?,
            self.number("z", 0.0)?,
        ))
    }

    /// `colour="#RRGGBB"`, required; `element_offset` locates the error when it is missing.
    fn required_colour(&self, element_offset: usize) -> Result<DVec3> {
        let Some(attr) = self.get("colour") else {
            return Err(self.source.error_at(
                element_offset,
                format!(
                    "<{}> needs a `colour` attribute (#RRGGBB, e.g. colour=\"#FF1D25\")",
                    self.element
                ),
            ));
        };
        parse_colour(attr.value.trim()).ok_or_else(|| {
            self.error(
                "colour",
                format!(
                    "`colour` must be #RRGGBB with six hex digits, got `{}`",
                    shown(&attr.value)
                ),
            )
        })
    }

    /// The material attributes, over the course's defaults for this shape.
    fn material(&self, defaults: Material) -> Result<Material> {
        let reflectivity = self.number("reflectivity", defaults.reflectivity)?;
        if !(0.0..=1.0).contains(&reflectivity) {
            return Err(self.error(
                "reflectivity",
                format!(
                    "`reflectivity` must be between 0 and 1, got {}",
                    number(reflectivity)
                ),
            ));
        }
        Ok(Material {
            colour: defaults.colour,
            kd: self.non_negative("kD", defaults.kd)?,
            ks: self.non_negative("kS", defaults.ks)?,
            n: self.non_negative("n", defaults.n)?,
            reflectivity,
        })
    }
}

/// `#RRGGBB` (either case) -> channels as byte / 255.
fn parse_colour(text: &str) -> Option<DVec3> {
    let hex = text.strip_prefix('#')?;
    if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let channel = |i: usize| {
        u8::from_str_radix(&hex[i..i + 2], 16)
            .ok()
            .map(|b| f64::from(b) / 255.0)
    };
    Some(DVec3::new(channel(0)?, channel(2)?, channel(4)?))
}

/// The scene as it is being read, plus what is needed to reject repeats.
#[derive(Default)]
struct SceneBuilder {
    objects: Vec<Object>,
    lights: Vec<PointLight>,
    ambient: Option<DVec3>,
    ambient_at: Option<usize>,
    light_names: HashMap<String, usize>,
}

impl SceneBuilder {
    fn check_light_name(&mut self, source: &Source, name: &str, offset: usize) -> Result<()> {
        let mut chars = name.chars();
        let well_formed = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
            && name.len() <= MAX_LIGHT_NAME;
        if !well_formed {
            return Err(source.error_at(
                offset,
                format!(
                    "light name `{}` must be a letter followed by letters, digits or _ \
                     ([A-Za-z][A-Za-z0-9_]*), at most {MAX_LIGHT_NAME} characters",
                    shown(name)
                ),
            ));
        }
        if let Some(&first) = self.light_names.get(name) {
            return Err(source.error_at(
                offset,
                format!(
                    "duplicate light name `{name}` (first used at {}; names must be unique)",
                    source.position(first)
                ),
            ));
        }
        self.light_names.insert(name.to_string(), offset);
        Ok(())
    }

    fn finish(self) -> Scene {
        Scene {
            objects: self.objects,
            lights: self.lights,
            ambient: self.ambient.unwrap_or(DVec3::ONE),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
