//! Walking the XML events of a scene: the structure is checked here (one `<scene>` root,
//! elements directly inside it, no text), and the root's children are handed on, in file
//! order and with their attributes still unread, a batch at a time.

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use super::attributes::read_attributes;
use super::elements::is_counted;
use super::source::{shown, Source};
use super::MAX_ELEMENTS;
use crate::error::{Error, Result};

/// An element directly inside `<scene>`, its attributes not yet read.
pub(super) struct Child<'a> {
    pub(super) tag: BytesStart<'a>,
    /// Where its `<` is.
    pub(super) offset: usize,
}

/// An element still waiting for its end tag.
struct Open {
    name: String,
    offset: usize,
}

/// A walk through the scene text that can stop after any number of children and go on.
pub(super) struct Scanner<'a> {
    source: Source<'a>,
    reader: Reader<&'a [u8]>,
    open: Vec<Open>,
    seen_root: bool,
    /// Objects and lights so far: what `MAX_ELEMENTS` limits.
    counted: usize,
}

impl<'a> Scanner<'a> {
    pub(super) fn new(source: Source<'a>) -> Self {
        Scanner {
            source,
            reader: Reader::from_str(source.text),
            open: Vec::new(),
            seen_root: false,
            counted: 0,
        }
    }

    /// Walks on until `limit` more children are in `children` (`Ok(false)`) or the file has
    /// ended well-formed (`Ok(true)`). On an error, `children` holds those before it.
    pub(super) fn scan(&mut self, children: &mut Vec<Child<'a>>, limit: usize) -> Result<bool> {
        let goal = children.len() + limit;
        while children.len() < goal {
            let event = self.reader.read_event().map_err(|e| {
                let offset = usize::try_from(self.reader.error_position()).unwrap_or(usize::MAX);
                self.source
                    .error_at(offset, format!("not well-formed XML: {e}"))
            })?;
            match event {
                Event::Start(e) => {
                    let name = e.name().0.to_string();
                    let offset = self.element(e, children)?;
                    self.open.push(Open { name, offset });
                }
                Event::Empty(e) => {
                    self.element(e, children)?;
                }
                Event::End(_) => {
                    self.open.pop();
                }
                Event::Text(t) => {
                    let content: &str = &t;
                    if !content.trim().is_empty() {
                        let offset = self.source.offset_of(content)
                            + (content.len() - content.trim_start().len());
                        return Err(self.unexpected_text(offset, content.trim()));
                    }
                }
                Event::CData(t) => {
                    let offset = self.source.offset_of(&t);
                    return Err(self.unexpected_text(offset, "<![CDATA[...]]>"));
                }
                Event::GeneralRef(r) => {
                    let offset = self.source.offset_of(&r).saturating_sub(1);
                    return Err(self.unexpected_text(offset, &format!("&{};", &*r)));
                }
                Event::Comment(_) | Event::Decl(_) | Event::PI(_) | Event::DocType(_) => {}
                Event::Eof => return self.at_end().map(|()| true),
            }
        }
        Ok(false)
    }

    /// What the end of the file may not leave: an open element, or no root at all.
    fn at_end(&self) -> Result<()> {
        if let Some(unclosed) = self.open.last() {
            return Err(self.source.error_at(
                unclosed.offset,
                format!(
                    "<{}> is never closed (expected </{}> or a self-closing <{} .../>)",
                    unclosed.name, unclosed.name, unclosed.name
                ),
            ));
        }
        if !self.seen_root {
            return Err(self.source.error_at(
                self.source.text.len(),
                "no <scene> element (expected <scene> ... </scene>)".into(),
            ));
        }
        Ok(())
    }

    fn unexpected_text(&self, offset: usize, text: &str) -> Error {
        let text = shown(text);
        let place = match self.open.last() {
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

    /// Handles a start or empty-element tag (a child of the root goes to `children`);
    /// returns the offset of its `<`.
    fn element(&mut self, e: BytesStart<'a>, children: &mut Vec<Child<'a>>) -> Result<usize> {
        let tag: &str = &e;
        let offset = self.source.offset_of(tag).saturating_sub(1);
        let name = e.name().0;
        match self.open.as_slice() {
            [] => {
                if self.seen_root {
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
                self.seen_root = true;
                read_attributes(self.source, &e, "scene", &[])?;
            }
            [_] => {
                if self.counted >= MAX_ELEMENTS {
                    return Err(self.source.error_at(
                        offset,
                        format!(
                            "too many elements: a scene holds at most {MAX_ELEMENTS} objects \
                             and lights"
                        ),
                    ));
                }
                if is_counted(name) {
                    self.counted += 1;
                }
                children.push(Child { tag: e, offset });
            }
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
}
