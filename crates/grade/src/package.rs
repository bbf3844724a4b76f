//! The Java package a student's files declare, and the skeleton moved into it. From 2017-18
//! the course's package is `uk.ac.cam.cl.gfxintro.<crsid>.tick1`, the student's own user id
//! in it (docs/courses.md, "The student's program"), so every student's package differs: the
//! skeleton is compiled into each student's package, as the course's tester does with theirs.

/// Longest package name taken (a real one is some 35 characters).
const MAX_PACKAGE: usize = 200;

/// The package `source` declares (None: the default package), or why it cannot be used.
/// Comments are skipped; the name must be dotted Java identifiers (ASCII, so that it is safe
/// as a folder path and as the main class's name on a command line).
pub fn declared(source: &[u8]) -> std::result::Result<Option<String>, String> {
    let text = String::from_utf8_lossy(source.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(source));
    let code = without_comments(&text);
    let code = code.trim_start();
    let Some(rest) = code.strip_prefix("package") else {
        return Ok(None);
    };
    if !rest.starts_with(char::is_whitespace) {
        return Ok(None);
    }
    let Some((name, _)) = rest.split_once(';') else {
        return Err("its package declaration has no `;`".into());
    };
    let name: String = name.chars().filter(|c| !c.is_whitespace()).collect();
    let identifier = |part: &str| {
        let mut chars = part.chars();
        chars
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_' || c == '$')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$')
    };
    if name.len() > MAX_PACKAGE || !name.split('.').all(identifier) {
        let shown: String = name.chars().take(60).collect();
        return Err(format!(
            "its package `{shown}` is not a plain Java package name (dotted ASCII identifiers)"
        ));
    }
    Ok(Some(name))
}

/// `source` (a skeleton file declaring package `from`) moved into package `to`: the
/// declaration and every qualified use of `from` rewritten.
pub fn moved(source: &[u8], from: Option<&str>, to: Option<&str>) -> Vec<u8> {
    let text = String::from_utf8_lossy(source);
    let rewritten = match (from, to) {
        (Some(from), Some(to)) if from != to => text.replace(from, to),
        (Some(from), None) => text
            .replacen(&format!("package {from};"), "", 1)
            .replace(&format!("{from}."), ""),
        (None, Some(to)) => format!("package {to};\n{text}"),
        _ => return source.to_vec(),
    };
    rewritten.into_bytes()
}

/// The folder of a package's sources, relative to the source root.
pub fn folder(package: Option<&str>) -> String {
    package.map_or(String::new(), |p| format!("{}/", p.replace('.', "/")))
}

/// The fully qualified name of `class` in `package`.
pub fn qualified(package: Option<&str>, class: &str) -> String {
    match package {
        Some(p) => format!("{p}.{class}"),
        None => class.to_string(),
    }
}

/// `text` with Java's comments replaced by a space (string literals are not looked into:
/// only the start of a file, before any literal, is read for its package).
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("//") {
            rest = after.split_once('\n').map_or("", |(_, r)| r);
            out.push('\n');
        } else if let Some(after) = rest.strip_prefix("/*") {
            rest = after.split_once("*/").map_or("", |(_, r)| r);
            out.push(' ');
        } else {
            let mut chars = rest.chars();
            if let Some(c) = chars.next() {
                out.push(c);
            }
            rest = chars.as_str();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_package_is_read_past_comments_and_refused_when_not_a_name() {
        let source = b"// Renderer\n/* by ab123 */ package  uk.ac.cam.cl.gfxintro.ab123\n .tick1 ;\nimport java.util.*;";
        assert_eq!(
            declared(source),
            Ok(Some("uk.ac.cam.cl.gfxintro.ab123.tick1".into()))
        );
        assert_eq!(declared(b"import java.util.*; class A {}"), Ok(None));
        assert_eq!(declared(b"packagex;"), Ok(None));
        assert!(declared(b"package a.b-c;").is_err());
        assert!(declared(b"package a.`touch x`;").is_err());
        assert!(declared(b"package a.b").is_err());
        assert!(declared(b"package a..b;").is_err());
    }

    #[test]
    fn the_skeleton_moves_into_the_student_s_package() {
        let from = Some("uk.ac.cam.cl.gfxintro.crsid.tick1");
        let source = b"package uk.ac.cam.cl.gfxintro.crsid.tick1;\nclass A { uk.ac.cam.cl.gfxintro.crsid.tick1.B b; }";
        let to = Some("uk.ac.cam.cl.gfxintro.ab123.tick1");
        assert_eq!(
            String::from_utf8(moved(source, from, to)).expect("utf-8"),
            "package uk.ac.cam.cl.gfxintro.ab123.tick1;\nclass A { uk.ac.cam.cl.gfxintro.ab123.tick1.B b; }"
        );
        assert_eq!(
            String::from_utf8(moved(source, from, None)).expect("utf-8"),
            "\nclass A { B b; }"
        );
        assert_eq!(folder(to), "uk/ac/cam/cl/gfxintro/ab123/tick1/");
        assert_eq!(qualified(None, "Tick1"), "Tick1");
    }
}
