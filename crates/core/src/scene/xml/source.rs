//! The scene text being parsed: byte offsets -> line:column, and located errors.

use crate::error::Error;

/// Longest attribute value quoted back in an error message.
const SHOWN_CHARS: usize = 40;

/// The text being parsed, for turning byte offsets into line:column.
#[derive(Clone, Copy)]
pub(super) struct Source<'a> {
    pub(super) file: &'a str,
    pub(super) text: &'a str,
}

impl<'a> Source<'a> {
    pub(super) fn line_col(&self, offset: usize) -> (usize, usize) {
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

    pub(super) fn error_at(&self, offset: usize, msg: String) -> Error {
        let (line, col) = self.line_col(offset);
        Error::Scene {
            file: self.file.to_string(),
            line,
            col,
            msg,
        }
    }

    /// Byte offset of `part`, which must be a slice of the source text.
    pub(super) fn offset_of(&self, part: &str) -> usize {
        (part.as_ptr() as usize).saturating_sub(self.text.as_ptr() as usize)
    }

    pub(super) fn position(&self, offset: usize) -> String {
        let (line, col) = self.line_col(offset);
        format!("{line}:{col}")
    }
}

/// `value` as quoted in an error message: long values are cut short.
pub(super) fn shown(value: &str) -> String {
    if value.chars().count() <= SHOWN_CHARS {
        value.to_string()
    } else {
        let start: String = value.chars().take(SHOWN_CHARS).collect();
        format!("{start}... ({} characters)", value.chars().count())
    }
}
