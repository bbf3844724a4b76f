//! What the pages `grade` writes share: escaping (names and messages come from submissions and
//! must never become markup), images inline as data URIs (a report is one file that can be
//! mailed), and one style sheet.

use std::collections::HashMap;
use std::sync::Mutex;

use whitted_io::output::png::{write_png, PngImage, PngPixels};

/// `text` safe in HTML text and in a quoted attribute.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// Standard base64 (RFC 4648, with padding). Hand-written: the reports need only this
/// encoder, twenty lines, against a dependency every build of whitted would compile.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The images every student's report shows (a case's reference), encoded once per run and
/// kept by what they are: their size, their bytes' fingerprint and their caption.
#[derive(Default)]
pub struct SharedImages {
    encoded: Mutex<HashMap<(u32, u32, String, String), String>>,
}

impl SharedImages {
    /// Images kept: a suite's references, with room for hidden scenes.
    const KEPT: usize = 64;

    /// [`image`] of `rgb`, encoded the first time it is asked for.
    pub fn image(&self, width: u32, height: u32, rgb: &[u8], alt: &str) -> String {
        let key = (
            width,
            height,
            whitted_core::fingerprint::fingerprint(&[rgb]),
            alt.to_string(),
        );
        if let Some(html) = self.encoded.lock().ok().and_then(|c| c.get(&key).cloned()) {
            return html;
        }
        let html = image(width, height, rgb.to_vec(), alt);
        if let Ok(mut c) = self.encoded.lock() {
            if c.len() < Self::KEPT {
                c.insert(key, html.clone());
            }
        }
        html
    }
}

/// An 8-bit RGB image as an `<img>` whose source is its PNG, inline.
pub fn image(width: u32, height: u32, rgb: Vec<u8>, alt: &str) -> String {
    let png = PngImage {
        width,
        height,
        pixels: PngPixels::Eight(rgb),
        srgb: false,
    };
    let mut bytes = Vec::new();
    if write_png(&mut bytes, &png).is_err() {
        return format!("<span>({} could not be encoded)</span>", escape(alt));
    }
    format!(
        "<img alt=\"{}\" width=\"{width}\" height=\"{height}\" src=\"data:image/png;base64,{}\">",
        escape(alt),
        base64(&bytes)
    )
}

/// The style of every page: readable, printable, no fonts or scripts from anywhere.
pub const STYLE: &str = "body{font:15px/1.45 system-ui,sans-serif;margin:2em auto;max-width:70em;\
padding:0 1em;color:#1b1b1b}h1{font-size:1.5em}h2{font-size:1.15em;margin-top:1.6em}\
table{border-collapse:collapse}td,th{padding:.25em .6em;border-bottom:1px solid #ddd;\
text-align:left;vertical-align:top}.pass{color:#17663a}.fail{color:#a4161a}\
pre{background:#f4f4f4;padding:.6em;overflow:auto;white-space:pre-wrap}\
figure{display:inline-block;margin:.3em}figcaption{font-size:.85em;color:#555}\
img{image-rendering:pixelated;max-width:100%;height:auto}.bar{fill:#3a6ea5}\
.stage{fill:#c77d2e}svg text{font:12px system-ui,sans-serif}";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_rfc_vectors() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }

    #[test]
    fn names_never_become_markup() {
        assert_eq!(
            escape("<script>\"x\"&'y'"),
            "&lt;script&gt;&quot;x&quot;&amp;&#39;y&#39;"
        );
    }
}
