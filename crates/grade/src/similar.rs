//! Identical submissions: two students whose `Plane.java` and `Renderer.java` are the same once
//! comments and whitespace are gone (renamed nothing, reformatted, recommented) share a
//! fingerprint, and the class page lists each group of two or more for a person to look at.
//! Near-identical code (renamed variables, reordered methods) needs a token-level tool such as
//! JPlag or MOSS; none fits whitted's dependencies (docs/grade.md, "Similar submissions").

use super::intake::Files;

/// The fingerprint of a submission's files, comments and whitespace aside (and the package,
/// which carries each student's own user id from 2017-18).
pub fn fingerprint(files: &Files) -> String {
    let bare = |s: &[u8]| normalised(s.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(s));
    let mut parts: Vec<Vec<u8>> = Vec::new();
    for (_, source) in &files.sources {
        let mut source = bare(source);
        if let Some(package) = &files.package {
            source = String::from_utf8_lossy(&source)
                .replacen(&format!("package{package};"), "", 1)
                .into_bytes();
        }
        // Each file's length first, so that moving code from one file to the next changes it.
        parts.push((source.len() as u64).to_le_bytes().to_vec());
        parts.push(source);
    }
    let slices: Vec<&[u8]> = parts.iter().map(Vec::as_slice).collect();
    whitted_core::fingerprint::fingerprint(&slices)
}

/// `source` without Java's comments and without whitespace outside string and character
/// literals.
pub fn normalised(source: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(source.len());
    let mut i = 0;
    while i < source.len() {
        let (c, next) = (source[i], source.get(i + 1).copied());
        match (c, next) {
            (b'/', Some(b'/')) => {
                while i < source.len() && source[i] != b'\n' {
                    i += 1;
                }
            }
            (b'/', Some(b'*')) => {
                i += 2;
                while i < source.len() && !(source[i] == b'*' && source.get(i + 1) == Some(&b'/')) {
                    i += 1;
                }
                i += 2;
            }
            (b'"' | b'\'', _) => {
                // A literal as it is, escapes included.
                out.push(c);
                i += 1;
                while i < source.len() && source[i] != c && source[i] != b'\n' {
                    if source[i] == b'\\' && i + 1 < source.len() {
                        out.push(source[i]);
                        i += 1;
                    }
                    out.push(source[i]);
                    i += 1;
                }
                if i < source.len() {
                    out.push(source[i]);
                    i += 1;
                }
            }
            (c, _) if c.is_ascii_whitespace() => i += 1,
            (c, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_whitespace_do_not_count_and_literals_do() {
        let a = b"class A { // mine\n  int x = 1; /* a\n block */ String s = \"a b\"; }";
        let b = b"class A{int x=1;\n\n   String s=\"a b\";}  // reformatted";
        assert_eq!(normalised(a), normalised(b));
        let c = b"class A{int x=1;String s=\"ab\";}";
        assert_ne!(normalised(a), normalised(c));
        assert_eq!(normalised(b"char c = '\\''; // x"), b"charc='\\'';");
    }
}
