//! What every HTML page whitted writes needs (`check --report x.html`, `grade`'s reports and
//! index): escaping, since names, scenes and messages come from students and must never
//! become markup; and images inline as `data:` URLs, so that a page is one file that can be
//! mailed or opened from anywhere.

use crate::output::png::{write_png, PngImage, PngPixels};

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

/// Standard base64 (RFC 4648, with padding). Hand-written: the pages need only this
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

/// An 8-bit RGB image as an `<img>` whose source is its PNG, inline. An image that cannot be
/// encoded (it never happens to bytes of the right length) is said in words instead.
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

    #[test]
    fn an_image_is_an_inline_png() {
        let html = image(2, 1, vec![255, 0, 0, 0, 0, 255], "a <b>");
        assert!(html.starts_with("<img alt=\"a &lt;b&gt;\" width=\"2\" height=\"1\""));
        assert!(
            html.contains("src=\"data:image/png;base64,iVBORw0KGgo"),
            "{html}"
        );
    }
}
