//! Reading a large scene on every core: the text is cut before `<sphere` and `<plane` tags
//! into chunks of a few megabytes, the first read by the ordinary parser and the others by a
//! reader that accepts nothing but objects, whitespace, comments and the closing `</scene>`.
//! Anything else in a later chunk (a light, an error, a cut that fell inside a comment) gives
//! up, and the caller reads the whole file in order: every error is reported by that reader,
//! so messages and their order are the same as ever.

use quick_xml::events::Event;
use quick_xml::Reader;
use rayon::prelude::*;

use super::elements::{object, Element, SceneBuilder};
use super::source::Source;
use super::{Parser, MAX_ELEMENTS};
use crate::scene::{Object, Scene};

/// Text per chunk, and the smallest scene worth cutting.
const CHUNK_BYTES: usize = 4 << 20;

/// What one chunk gave.
enum Chunk {
    /// The first: everything the ordinary parser read, lights and ambient included.
    First(SceneBuilder),
    Objects(Vec<Object>),
}

/// The scene, if it could be read in chunks; `None` means: read it in order.
pub(super) fn parse_in_chunks(source: Source) -> Option<Scene> {
    let text = source.text;
    if text.len() < 2 * CHUNK_BYTES {
        return None;
    }
    let cuts = cuts(text);
    if cuts.len() < 3 {
        return None;
    }
    let last = cuts.len() - 2;
    let chunks: Vec<Option<Chunk>> = (0..=last)
        .into_par_iter()
        .map(|k| {
            if k == 0 {
                first_chunk(source, cuts[1])
            } else {
                objects(source, cuts[k]..cuts[k + 1], k == last).map(Chunk::Objects)
            }
        })
        .collect();
    let mut chunks = chunks.into_iter();
    let Some(Some(Chunk::First(mut builder))) = chunks.next() else {
        return None;
    };
    let mut later = Vec::with_capacity(chunks.len());
    for chunk in chunks {
        let Some(Chunk::Objects(objects)) = chunk else {
            return None;
        };
        later.push(objects);
    }
    builder
        .objects
        .reserve_exact(later.iter().map(Vec::len).sum());
    later
        .into_iter()
        .for_each(|objects| builder.objects.extend(objects));
    // Over the limit: the ordinary reader says where.
    if builder.objects.len() + builder.lights.len() > MAX_ELEMENTS {
        return None;
    }
    Some(builder.finish())
}

/// Chunk boundaries: 0, then the first `<sphere` or `<plane` at least `CHUNK_BYTES` after the
/// previous boundary, and so on, then the end of the text.
fn cuts(text: &str) -> Vec<usize> {
    let bytes = text.as_bytes();
    let mut cuts = vec![0];
    let mut from = CHUNK_BYTES;
    while from < bytes.len() {
        let Some(at) = next_object_tag(bytes, from) else {
            break;
        };
        cuts.push(at);
        from = at + CHUNK_BYTES;
    }
    cuts.push(bytes.len());
    cuts
}

/// The position of the next `<` that starts `sphere` or `plane`, from `from` on.
fn next_object_tag(bytes: &[u8], from: usize) -> Option<usize> {
    let mut at = from;
    loop {
        at += bytes.get(at..)?.iter().position(|&b| b == b'<')?;
        let rest = &bytes[at + 1..];
        if rest.starts_with(b"sphere") || rest.starts_with(b"plane") {
            return Some(at);
        }
        at += 1;
    }
}

/// The first chunk, read by the ordinary parser; it must end inside `<scene>`.
fn first_chunk(source: Source, end: usize) -> Option<Chunk> {
    let mut parser = Parser::new(source, end, true);
    parser.scan().ok()?;
    parser.read_pending().ok()?;
    Some(Chunk::First(parser.builder))
}

/// The objects of a later chunk, or `None` if it holds anything else; the last chunk must
/// close `<scene>` and hold nothing after it but whitespace and comments.
fn objects(source: Source, range: std::ops::Range<usize>, last: bool) -> Option<Vec<Object>> {
    let mut reader = Reader::from_str(&source.text[range.clone()]);
    // Its `<scene>` opened in the first chunk.
    reader.config_mut().allow_unmatched_ends = true;
    // Room for the shortest object tags there could be, so that the vector never moves.
    let mut objects = Vec::with_capacity(range.len() / 48);
    let mut closed = false;
    loop {
        match reader.read_event().ok()? {
            Event::Empty(e) if !closed => {
                let tag: &str = &e;
                let element = Element {
                    tag: &e,
                    name: e.name().0,
                    offset: source.offset_of(tag).saturating_sub(1),
                    source,
                };
                objects.push(object(&element)?.ok()?);
            }
            Event::Text(t) if t.trim().is_empty() => {}
            Event::Comment(_) => {}
            Event::End(e) if last && !closed && e.name().0 == "scene" => closed = true,
            Event::Eof => break,
            _ => return None,
        }
    }
    (closed == last).then_some(objects)
}
