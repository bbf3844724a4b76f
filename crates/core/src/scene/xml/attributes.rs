//! An element's attributes: read and checked (no duplicates, no unknown names), then typed
//! getters that know their defaults and locate their errors.

use std::borrow::Cow;

use glam::DVec3;
use quick_xml::events::BytesStart;

use super::key::Key;
use super::source::{shown, Source};
use crate::error::{Error, Result};
use crate::numbers::exact;
use crate::scene::Material;
use crate::suggest;

/// Largest coordinate or radius: differences of two stay below 2e150, and the sum of three
/// squares of those below 1.2e301, short of f64's 1.8e308.
const MAX_LENGTH: f64 = 1e150;

/// Collects the attributes of `e`, rejecting duplicates and any name not in `allowed`.
///
/// Nothing is allocated for a well-formed element: values borrow the scene text (a
/// 1M-sphere scene has 5M attributes).
pub(super) fn read_attributes<'e>(
    source: Source<'e>,
    e: &'e BytesStart,
    element: &'e str,
    allowed: &[&[Key]],
) -> Result<Attributes<'e>> {
    let tag: &str = e;
    let tag_offset = source.offset_of(tag);
    let mut values: [Option<Attribute<'e>>; Key::COUNT] = Default::default();
    let mut iter = e.attributes();
    iter.with_checks(false);
    for attr in iter {
        let attr = attr.map_err(|err| {
            use quick_xml::events::attributes::AttrError;
            let (pos, what) = match err {
                AttrError::ExpectedEq(p) => (p, "an attribute name must be followed by `=`".into()),
                AttrError::ExpectedValue(p) => (p, "`=` must be followed by a quoted value".into()),
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
            source.error_at(tag_offset + pos, format!("not well-formed XML: {what}"))
        })?;
        let name = attr.key.0;
        let offset = source.offset_of(name);
        let known = Key::from_name(name).filter(|k| allowed.iter().any(|g| g.contains(k)));
        let Some(key) = known else {
            let allowed: Vec<&str> = allowed
                .iter()
                .flat_map(|g| g.iter().map(|k| k.name()))
                .collect();
            let hint = match suggest::nearest(name, &allowed) {
                Some(s) => format!("did you mean `{s}`? "),
                None => String::new(),
            };
            let expected = if allowed.is_empty() {
                "it takes no attributes".to_string()
            } else {
                format!("expected one of {}", allowed.join(", "))
            };
            return Err(source.error_at(
                offset,
                format!(
                    "unknown attribute `{}` on <{element}> ({hint}{expected}){}",
                    shown(name),
                    later_year_hint(element, name)
                ),
            ));
        };
        if let Some(first) = &values[key as usize] {
            return Err(source.error_at(
                offset,
                format!(
                    "duplicate attribute `{name}` on <{element}> (first given at {})",
                    source.position(first.offset)
                ),
            ));
        }
        let value = if needs_normalising(&attr.value) {
            attr.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| {
                    source.error_at(
                        offset,
                        format!(
                            "`{name}` has an entity or character reference that scenes do not \
                             expand ({err}); only &lt; &gt; &amp; &quot; &apos; and &#...; are"
                        ),
                    )
                })?
        } else {
            attr.value
        };
        values[key as usize] = Some(Attribute { value, offset });
    }
    Ok(Attributes {
        source,
        element,
        values,
    })
}

/// For an attribute only a later year's scene format has (docs/courses.md), how to read it:
/// whitted's own format is 2016-17's, and a 2019-20 scene's `intensity` on the ambient light
/// is otherwise a puzzle.
pub(super) fn later_year_hint(element: &str, name: &str) -> &'static str {
    if later_year_attribute(element, name) {
        "; a scene of the course's later years: give --course YEAR, e.g. --course 2021-22 \
         (docs/courses.md)"
    } else {
        ""
    }
}

/// Whether `name` on `element` is an attribute whitted's own format refuses and only a
/// later year's loader reads (docs/courses.md, "Scenes (the loader)"). `kD`, `kS` and
/// `reflectivity` are not: whitted's own format has them too.
pub(super) fn later_year_attribute(element: &str, name: &str) -> bool {
    match element {
        "ambient-light" => name == "intensity",
        "sphere" | "plane" => matches!(name, "alphaS" | "tr" | "tg" | "tb"),
        _ => false,
    }
}

/// Whether XML 1.0's attribute-value normalisation would change `raw`: only tabs, line ends
/// and references (`&...;`) are changed (XML 1.0, 3.3.3). Checking first spares nearly every
/// value the library's pass, which a million-sphere scene would make five million times.
pub(super) fn needs_normalising(raw: &str) -> bool {
    raw.bytes()
        .any(|b| matches!(b, b'\t' | b'\r' | b'\n' | b'&'))
}

/// `text` without leading and trailing whitespace; the common case, a value starting and
/// ending with a visible ASCII character, is decided from two bytes.
pub(super) fn trimmed(text: &str) -> &str {
    let bytes = text.as_bytes();
    match (bytes.first(), bytes.last()) {
        (Some(first), Some(last)) if first.is_ascii_graphic() && last.is_ascii_graphic() => text,
        _ => text.trim(),
    }
}

pub(super) struct Attribute<'e> {
    pub(super) value: Cow<'e, str>,
    /// Where its name starts in the scene text.
    pub(super) offset: usize,
}

/// The checked attributes of one element, with typed getters that know their defaults.
pub(super) struct Attributes<'e> {
    pub(super) source: Source<'e>,
    pub(super) element: &'e str,
    /// Indexed by `Key as usize`.
    values: [Option<Attribute<'e>>; Key::COUNT],
}

impl<'e> Attributes<'e> {
    pub(super) fn get(&self, key: Key) -> Option<&Attribute<'e>> {
        self.values[key as usize].as_ref()
    }

    pub(super) fn error(&self, key: Key, msg: String) -> Error {
        let offset = self.get(key).map_or(0, |a| a.offset);
        self.source.error_at(offset, msg)
    }

    /// A finite decimal number, or `default` when the attribute is absent.
    pub(super) fn number(&self, key: Key, default: f64) -> Result<f64> {
        let Some(attr) = self.get(key) else {
            return Ok(default);
        };
        let name = key.name();
        match trimmed(&attr.value).parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.error(
                key,
                format!(
                    "`{name}` must be a finite number, got `{}`",
                    shown(&attr.value)
                ),
            )),
            Err(_) => Err(self.error(
                key,
                format!(
                    "`{name}` must be a number (like 1.5 or -.4), got `{}`",
                    shown(&attr.value)
                ),
            )),
        }
    }

    pub(super) fn non_negative(&self, key: Key, default: f64) -> Result<f64> {
        let v = self.number(key, default)?;
        if v < 0.0 {
            let name = key.name();
            return Err(self.error(key, format!("`{name}` must be >= 0, got {}", exact(v))));
        }
        Ok(v)
    }

    pub(super) fn position(&self) -> Result<DVec3> {
        Ok(DVec3::new(
            self.length(Key::X, 0.0)?,
            self.length(Key::Y, 0.0)?,
            self.length(Key::Z, 0.0)?,
        ))
    }

    /// A coordinate or radius: a number small enough that the squared distances the
    /// renderer computes from it stay finite (an overflow would make an object silently
    /// vanish).
    pub(super) fn length(&self, key: Key, default: f64) -> Result<f64> {
        let v = self.number(key, default)?;
        if v.abs() > MAX_LENGTH {
            return Err(self.error(
                key,
                format!(
                    "`{}` = {} is too large: distances this far overflow when squared \
                     (coordinates and radii up to {MAX_LENGTH:e})",
                    key.name(),
                    exact(v)
                ),
            ));
        }
        Ok(v)
    }

    /// `colour="#RRGGBB"`, required; `element_offset` locates the error when it is missing.
    pub(super) fn required_colour(&self, element_offset: usize) -> Result<DVec3> {
        let Some(attr) = self.get(Key::Colour) else {
            return Err(self.source.error_at(
                element_offset,
                format!(
                    "<{}> needs a `colour` attribute (#RRGGBB, e.g. colour=\"#FF1D25\")",
                    self.element
                ),
            ));
        };
        parse_colour(trimmed(&attr.value)).ok_or_else(|| {
            self.error(
                Key::Colour,
                format!(
                    "`colour` must be #RRGGBB with six hex digits, got `{}`",
                    shown(&attr.value)
                ),
            )
        })
    }

    /// The material attributes, over the course's defaults for this shape.
    pub(super) fn material(&self, defaults: Material) -> Result<Material> {
        let reflectivity = self.number(Key::Reflectivity, defaults.reflectivity)?;
        if !(0.0..=1.0).contains(&reflectivity) {
            return Err(self.error(
                Key::Reflectivity,
                format!(
                    "`reflectivity` must be between 0 and 1, got {}",
                    exact(reflectivity)
                ),
            ));
        }
        Ok(Material {
            colour: defaults.colour,
            kd: self.non_negative(Key::KD, defaults.kd)?,
            ks: self.non_negative(Key::KS, defaults.ks)?,
            n: self.non_negative(Key::N, defaults.n)?,
            reflectivity,
        })
    }
}

/// `#RRGGBB` (either case) -> channels as byte / 255.
pub(super) fn parse_colour(text: &str) -> Option<DVec3> {
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
