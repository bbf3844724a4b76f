//! Scene XML -> `Scene` (docs/scene-format.md). Strict: anything the format does not allow is an
//! error naming the file, the line:column of the offending element or attribute, and what was
//! expected, because a silently different picture is worse than no picture.
//!
//! This file walks the XML events; `source` turns offsets into line:column, `attributes`
//! reads and types an element's attributes, and `elements` has one function per element.

mod attributes;
mod elements;
mod key;
mod source;
#[cfg(test)]
mod tests;

use std::path::Path;

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::scene::{Object, Scene};
use attributes::read_attributes;
use elements::{is_object, object, Element, SceneBuilder};
use source::{shown, Source};

pub use elements::MAX_LIGHT_NAME;

/// Largest scene file read: far beyond any hand-written scene (a million spheres is ~80 MB),
/// small enough that a mistaken path to a huge file fails at once.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// Most elements (objects and lights) in one scene.
pub const MAX_ELEMENTS: usize = 10_000_000;

/// Reads and parses the scene file at `path`. Error messages name the file as given.
pub fn load(path: &Path) -> Result<Scene> {
    parse_bytes(&path.display().to_string(), &read_file(path)?)
}

/// The bytes of the scene file at `path`, refusing files larger than `MAX_FILE_BYTES`.
pub fn read_file(path: &Path) -> Result<Vec<u8>> {
    let size = std::fs::metadata(path)
        .map_err(|e| Error::io(path, "cannot read scene", e))?
        .len();
    if size > MAX_FILE_BYTES {
        return Err(Error::Usage(format!(
            "{}: the scene file is {size} bytes; scenes up to {MAX_FILE_BYTES} bytes are read",
            path.display()
        )));
    }
    std::fs::read(path).map_err(|e| Error::io(path, "cannot read scene", e))
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
    let mut parser = Parser {
        source,
        builder: SceneBuilder::default(),
        pending: Vec::new(),
    };
    // An error in an element read before a later structural error is the one reported: the
    // first in the file, as if everything were read in order.
    let scanned = parser.scan();
    parser.read_pending()?;
    scanned?;
    Ok(parser.builder.finish())
}

/// Objects read at once, on every core; what the parser holds back at most.
const BATCH: usize = 16_384;

struct Parser<'a> {
    source: Source<'a>,
    builder: SceneBuilder,
    /// Object elements (`<sphere>`, `<plane>`) whose attributes are still to be read, in file
    /// order: the bulk of a large scene, read a batch at a time in parallel.
    pending: Vec<(BytesStart<'a>, usize)>,
}

/// An element still waiting for its end tag.
struct Open {
    name: String,
    offset: usize,
}

impl<'a> Parser<'a> {
    /// Walks the XML events, checking the structure and reading every element (objects into
    /// `pending`).
    fn scan(&mut self) -> Result<()> {
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
                    let name = e.name().0.to_string();
                    let offset = self.element(e, &open, &mut seen_root)?;
                    open.push(Open { name, offset });
                }
                Event::Empty(e) => {
                    self.element(e, &open, &mut seen_root)?;
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
        Ok(())
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
    fn element(&mut self, e: BytesStart<'a>, open: &[Open], seen_root: &mut bool) -> Result<usize> {
        let tag: &str = &e;
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
                read_attributes(self.source, &e, "scene", &[])?;
            }
            [_] => self.child(e, offset)?,
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

    fn child(&mut self, e: BytesStart<'a>, offset: usize) -> Result<()> {
        let count = self.builder.objects.len() + self.builder.lights.len() + self.pending.len();
        if count >= MAX_ELEMENTS {
            return Err(self.source.error_at(
                offset,
                format!(
                    "too many elements: a scene holds at most {MAX_ELEMENTS} objects and lights"
                ),
            ));
        }
        if is_object(e.name().0) {
            self.pending.push((e, offset));
            if self.pending.len() == BATCH {
                self.read_pending()?;
            }
            return Ok(());
        }
        // Lights and the rest depend on what came before them: read in order.
        self.read_pending()?;
        self.builder.add(&Element {
            tag: &e,
            name: e.name().0,
            offset,
            source: self.source,
        })
    }

    /// Reads the pending objects on every core and adds them in file order; the first
    /// error in the file if any.
    fn read_pending(&mut self) -> Result<()> {
        let source = self.source;
        let objects: Vec<Result<Object>> = self
            .pending
            .par_iter()
            .filter_map(|(tag, offset)| {
                let element = Element {
                    tag,
                    name: tag.name().0,
                    offset: *offset,
                    source,
                };
                object(&element)
            })
            .collect();
        self.pending.clear();
        for object in objects {
            self.builder.objects.push(object?);
        }
        Ok(())
    }
}
