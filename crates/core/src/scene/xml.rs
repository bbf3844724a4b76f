//! Scene XML -> `Scene` (docs/scene-format.md). Strict: anything the format does not allow is an
//! error naming the file, the line:column of the offending element or attribute, and what was
//! expected, because a silently different picture is worse than no picture.
//!
//! This file runs the parse: `scan` walks the XML events and checks the structure, `source`
//! turns offsets into line:column, `attributes` reads and types an element's attributes, and
//! `elements` has one function per element.

mod attributes;
pub mod course;
mod elements;
mod key;
mod scan;
mod source;
#[cfg(test)]
mod tests;

use std::path::Path;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::scene::{Object, Scene};
use elements::{object, Element, SceneBuilder};
use scan::{Child, Scanner};
use source::Source;

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

/// Whether the scene carries an attribute only the later years' loaders read (an ambient
/// light's `intensity`, `alphaS`, 2023-24's `tr tg tb`): the scene is of a later year, not
/// whitted's own. A file that is not well-formed says nothing here; its reader reports it.
pub fn has_later_year_attributes(bytes: &[u8]) -> bool {
    let mut reader = quick_xml::Reader::from_reader(bytes);
    let mut buffer = Vec::new();
    loop {
        let tag = match reader.read_event_into(&mut buffer) {
            Ok(quick_xml::events::Event::Start(tag) | quick_xml::events::Event::Empty(tag)) => tag,
            Ok(quick_xml::events::Event::Eof) | Err(_) => return false,
            Ok(_) => {
                buffer.clear();
                continue;
            }
        };
        let name = tag.name();
        let element: &str = name.as_ref();
        let later = tag
            .attributes()
            .flatten()
            .any(|a| attributes::later_year_attribute(element, a.key.as_ref()));
        if later {
            return true;
        }
        buffer.clear();
    }
}

/// Parses a scene from raw bytes; `file` is the name used in error messages.
pub fn parse_bytes(file: &str, bytes: &[u8]) -> Result<Scene> {
    parse_str(file, utf8(file, bytes)?)
}

/// The scene file's text, or a located error where it stops being UTF-8.
pub fn utf8<'a>(file: &str, bytes: &'a [u8]) -> Result<&'a str> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text),
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
    let mut scanner = Scanner::new(source);
    let mut builder = SceneBuilder::default();
    let mut batch = Vec::with_capacity(BATCH);
    let mut scanned = scanner.scan(&mut batch, BATCH);
    // A batch's attributes are read on every core while the scanner walks on to the next:
    // the walk is one thread's work, and the reading would otherwise wait for it.
    loop {
        let more = matches!(scanned, Ok(false));
        let mut next = Vec::with_capacity(if more { BATCH } else { 0 });
        let (added, next_scanned) = rayon::join(
            || add_batch(&mut builder, &batch, source),
            || {
                if more {
                    scanner.scan(&mut next, BATCH)
                } else {
                    Ok(true)
                }
            },
        );
        // An error in an element read before a later structural error is the one reported:
        // the first in the file, as if everything were read in order.
        added?;
        scanned?;
        if !more {
            break;
        }
        (batch, scanned) = (next, next_scanned);
    }
    Ok(builder.finish())
}

/// Child elements scanned at once, then read on every core; what the parser holds back at
/// most (twice: one batch being read, the next being scanned).
const BATCH: usize = 16_384;

/// Adds `children` to the scene in file order, reading the objects' attributes in parallel
/// first (an object needs nothing from the rest of the scene); the first error in the file
/// if any.
fn add_batch(builder: &mut SceneBuilder, children: &[Child], source: Source) -> Result<()> {
    let objects: Vec<Option<Result<Object>>> = children
        .par_iter()
        .map(|child| object(&element(child, source)))
        .collect();
    for (child, object) in children.iter().zip(objects) {
        match object {
            Some(object) => builder.objects.push(object?),
            // Lights and the rest depend on what came before them: added in order.
            None => builder.add(&element(child, source))?,
        }
    }
    Ok(())
}

fn element<'e, 'a>(child: &'e Child<'e>, source: Source<'a>) -> Element<'e, 'a> {
    Element {
        tag: &child.tag,
        name: child.tag.name().0,
        offset: child.offset,
        source,
    }
}
