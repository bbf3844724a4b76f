//! An element's attributes: read and checked (no duplicates, no unknown names), then typed
//! getters that know their defaults and locate their errors.

use std::borrow::Cow;

use glam::DVec3;
use quick_xml::events::BytesStart;
use smallvec::SmallVec;

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
/// Nothing is allocated for a well-formed element: keys and values borrow the scene text
/// (a 1M-sphere scene has 8M attributes).
pub(super) fn read_attributes<'e>(
    source: Source<'e>,
    e: &'e BytesStart,
    element: &'e str,
    allowed: &[&[&str]],
) -> Result<Attributes<'e>> {
    let tag: &str = e;
    let tag_offset = source.offset_of(tag);
    let mut list: SmallVec<[Attribute<'e>; 12]> = SmallVec::new();
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
        let key = attr.key.0;
        let offset = source.offset_of(key);
        if let Some(first) = list.iter().find(|a| a.key == key) {
            return Err(source.error_at(
                offset,
                format!(
                    "duplicate attribute `{key}` on <{element}> (first given at {})",
                    source.position(first.offset)
                ),
            ));
        }
        if !allowed.iter().any(|group| group.contains(&key)) {
            let allowed: Vec<&str> = allowed.iter().flat_map(|a| a.iter().copied()).collect();
            let hint = match suggest::nearest(key, &allowed) {
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
                    "unknown attribute `{}` on <{element}> ({hint}{expected})",
                    shown(key)
                ),
            ));
        }
        let value = attr
            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
            .map_err(|err| {
                source.error_at(
                    offset,
                    format!(
                        "`{key}` has an entity or character reference that scenes do not \
                             expand ({err}); only &lt; &gt; &amp; &quot; &apos; and &#...; are"
                    ),
                )
            })?;
        list.push(Attribute { key, value, offset });
    }
    Ok(Attributes {
        source,
        element,
        list,
    })
}

pub(super) struct Attribute<'e> {
    pub(super) key: &'e str,
    pub(super) value: Cow<'e, str>,
    pub(super) offset: usize,
}

/// The checked attributes of one element, with typed getters that know their defaults.
pub(super) struct Attributes<'e> {
    pub(super) source: Source<'e>,
    pub(super) element: &'e str,
    pub(super) list: SmallVec<[Attribute<'e>; 12]>,
}

impl<'e> Attributes<'e> {
    pub(super) fn get(&self, key: &str) -> Option<&Attribute<'e>> {
        self.list.iter().find(|a| a.key == key)
    }

    pub(super) fn error(&self, key: &str, msg: String) -> Error {
        let offset = self.get(key).map_or(0, |a| a.offset);
        self.source.error_at(offset, msg)
    }

    /// A finite decimal number, or `default` when the attribute is absent.
    pub(super) fn number(&self, key: &str, default: f64) -> Result<f64> {
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

    pub(super) fn non_negative(&self, key: &str, default: f64) -> Result<f64> {
        let v = self.number(key, default)?;
        if v < 0.0 {
            return Err(self.error(key, format!("`{key}` must be >= 0, got {}", exact(v))));
        }
        Ok(v)
    }

    pub(super) fn position(&self) -> Result<DVec3> {
        Ok(DVec3::new(
            self.length("x", 0.0)?,
            self.length("y", 0.0)?,
            self.length("z", 0.0)?,
        ))
    }

    /// A coordinate or radius: a number small enough that the squared distances the
    /// renderer computes from it stay finite (an overflow would make an object silently
    /// vanish).
    pub(super) fn length(&self, key: &str, default: f64) -> Result<f64> {
        let v = self.number(key, default)?;
        if v.abs() > MAX_LENGTH {
            return Err(self.error(
                key,
                format!(
                    "`{key}` = {} is too large: distances this far overflow when squared \
                     (coordinates and radii up to {MAX_LENGTH:e})",
                    exact(v)
                ),
            ));
        }
        Ok(v)
    }

    /// `colour="#RRGGBB"`, required; `element_offset` locates the error when it is missing.
    pub(super) fn required_colour(&self, element_offset: usize) -> Result<DVec3> {
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
    pub(super) fn material(&self, defaults: Material) -> Result<Material> {
        let reflectivity = self.number("reflectivity", defaults.reflectivity)?;
        if !(0.0..=1.0).contains(&reflectivity) {
            return Err(self.error(
                "reflectivity",
                format!(
                    "`reflectivity` must be between 0 and 1, got {}",
                    exact(reflectivity)
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
