//! A student's file that declares one of the skeleton's classes (`class Vector3` pasted into
//! their Renderer.java, a `Tick2` of their own): javac then refuses the class twice declared,
//! and its first error may well be in the skeleton's file (the warm compiler reads the files
//! in name order: Renderer.java's `Vector3` comes before Vector3.java), which reads as if the
//! skeleton were broken. The student's files are read for the types they declare at their
//! top level, so that the report says plainly which file declares which of the skeleton's
//! classes.

/// One of the skeleton's classes declared by a student's file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Clash {
    /// The student's file (`Renderer.java`).
    pub file: String,
    /// `class`, `interface`, `enum` or `record`.
    pub kind: String,
    /// The class's name (`Vector3`), whose file the skeleton has.
    pub name: String,
}

/// What the student is told about `clashes`, if there are any: one line each.
pub fn message(clashes: &[Clash]) -> Option<String> {
    if clashes.is_empty() {
        return None;
    }
    let lines: Vec<String> = clashes
        .iter()
        .map(|c| {
            format!(
                "Your {} declares {} {}, which the course's skeleton provides ({}.java): \
                 remove it from {} and use the skeleton's.",
                c.file, c.kind, c.name, c.name, c.file
            )
        })
        .collect();
    Some(lines.join("\n"))
}

/// The top-level types each of `sources` (file name, bytes) declares whose name is one of
/// `skeleton_files` (`Vector3.java`, ...).
pub fn clashes<'a>(
    sources: impl IntoIterator<Item = (&'a str, &'a [u8])>,
    skeleton_files: &[&str],
) -> Vec<Clash> {
    let mut found = Vec::new();
    for (file, bytes) in sources {
        let text = String::from_utf8_lossy(bytes);
        for (kind, name) in top_level_types(&text) {
            let taken = skeleton_files
                .iter()
                .any(|f| f.strip_suffix(".java") == Some(name.as_str()));
            if taken && file.strip_suffix(".java") != Some(name.as_str()) {
                found.push(Clash {
                    file: file.to_string(),
                    kind,
                    name,
                });
            }
        }
    }
    found
}

/// The types a Java source declares outside any braces: (keyword, name). Comments, string,
/// text block and character literals are skipped; `record` counts where a name and `(` follow.
pub fn top_level_types(source: &str) -> Vec<(String, String)> {
    let words = words_at_top_level(source);
    let mut types = Vec::new();
    for (i, word) in words.iter().enumerate() {
        let kind = word.as_str();
        if !matches!(kind, "class" | "interface" | "enum" | "record") {
            continue;
        }
        let Some(name) = words.get(i + 1).filter(|w| is_identifier(w)) else {
            continue;
        };
        if kind == "record" && words.get(i + 2).map(String::as_str) != Some("(") {
            continue;
        }
        types.push((kind.to_string(), name.clone()));
    }
    types
}

fn is_identifier(word: &str) -> bool {
    word.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_' || c == '$')
}

/// The words (identifiers and keywords) and `(` of `source` at brace depth 0, in order.
fn words_at_top_level(source: &str) -> Vec<String> {
    let chars: Vec<char> = source.chars().collect();
    let mut words = Vec::new();
    let (mut i, mut depth) = (0, 0usize);
    let at = |i: usize, s: &str| {
        s.chars()
            .enumerate()
            .all(|(k, c)| chars.get(i + k) == Some(&c))
    };
    while i < chars.len() {
        let c = chars[i];
        if at(i, "//") {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if at(i, "/*") {
            i += 2;
            while i < chars.len() && !at(i, "*/") {
                i += 1;
            }
            i += 2;
        } else if at(i, "\"\"\"") {
            i += 3;
            while i < chars.len() && !at(i, "\"\"\"") {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 3;
        } else if c == '"' || c == '\'' {
            i += 1;
            while i < chars.len() && chars[i] != c && chars[i] != '\n' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
        } else if c == '{' {
            depth += 1;
            i += 1;
        } else if c == '}' {
            depth = depth.saturating_sub(1);
            i += 1;
        } else if c.is_alphanumeric() || c == '_' || c == '$' {
            let start = i;
            while i < chars.len()
                && (chars[i].is_alphanumeric() || chars[i] == '_' || chars[i] == '$')
            {
                i += 1;
            }
            if depth == 0 {
                words.push(chars[start..i].iter().collect());
            }
        } else {
            if c == '(' && depth == 0 {
                words.push("(".to_string());
            }
            i += 1;
        }
    }
    words
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_top_level_declarations_outside_comments_and_strings_count() {
        let source = r#"package gfx.tick2;
            import java.util.List; // class Commented
            /* class Blocked { } */
            @SuppressWarnings({"unchecked"})
            public class Renderer {
                class Nested {}
                String s = "class Quoted {";
                char c = '{';
                String block = """
                    class InBlock { " }
                    """;
                void f() { Object o = new Object() { }; }
            }
            final class Vector3 { double x; }
            interface Shade {}
            enum Mode { A, B }
            record Pair(int a, int b) {}
            "#;
        let types = top_level_types(source);
        let named: Vec<(&str, &str)> = types
            .iter()
            .map(|(k, n)| (k.as_str(), n.as_str()))
            .collect();
        assert_eq!(
            named,
            [
                ("class", "Renderer"),
                ("class", "Vector3"),
                ("interface", "Shade"),
                ("enum", "Mode"),
                ("record", "Pair"),
            ]
        );
    }

    #[test]
    fn a_student_file_declaring_a_skeleton_class_is_named_with_the_class() {
        let skeleton = ["Tick2.java", "Vector3.java", "Scene.java"];
        let renderer = b"package gfx.tick2; public class Renderer {} class Vector3 {}";
        let plane = b"package gfx.tick2; public class Plane {} class Helper {}";
        let found = clashes(
            [("Renderer.java", &renderer[..]), ("Plane.java", &plane[..])],
            &skeleton,
        );
        assert_eq!(
            found,
            [Clash {
                file: "Renderer.java".into(),
                kind: "class".into(),
                name: "Vector3".into()
            }]
        );
        let said = message(&found).expect("a message");
        assert!(
            said.starts_with(
                "Your Renderer.java declares class Vector3, which the course's skeleton provides"
            ),
            "{said}"
        );
        assert_eq!(message(&[]), None);
    }
}
