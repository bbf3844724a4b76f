//! The shape of a Java class as the course's API describes it (docs/grade.md, "The Tick 1
//! skeleton's API"): which methods, constructors and fields it has and who may see them. Read
//! without a Java parser, from the text: comments and literals blanked, then the declarations
//! at the class body's depth. That is enough for the course's plain classes, and it is what
//! tells the years apart (`year.rs`) and names what a project's class changed (`compare.rs`).

/// Who may see a member.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Visibility {
    Private,
    Package,
    Protected,
    Public,
}

/// What a member is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    Constructor,
    Method,
    Field,
}

/// One member: its kind, its name and, for a method or constructor, its parameter types.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Member {
    pub kind: Kind,
    pub name: String,
    pub params: Vec<String>,
    pub visibility: Visibility,
}

impl Member {
    /// As a reader names it: `power(double)`, `Sphere(Vector3, double, ColorRGB)`, `field fov`.
    pub fn shown(&self) -> String {
        match self.kind {
            Kind::Field => format!("field {}", self.name),
            _ => format!("{}({})", self.name, self.params.join(", ")),
        }
    }

    /// Whether code outside the class can use it (the API compares these only).
    pub fn visible(&self) -> bool {
        self.visibility != Visibility::Private
    }
}

/// The members declared in the body of the first top-level type of `source`, in order.
pub fn members(source: &str) -> Vec<Member> {
    let code = blank(source, true);
    let Some(open) = body_start(&code) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    let mut depth = 1;
    let mut start = open + 1;
    let mut i = open + 1;
    while i < bytes.len() && depth > 0 {
        match bytes[i] {
            b'{' if depth == 1 => {
                let head = &code[start..i];
                if has_assignment(head) {
                    // A field whose initializer holds braces (an array, an anonymous class):
                    // read on to its `;`.
                    i = skip_block(bytes, i);
                    continue;
                }
                out.extend(declaration(head));
                i = skip_block(bytes, i);
                start = i;
                continue;
            }
            b'{' => depth += 1,
            b'}' => depth -= 1,
            b';' if depth == 1 => {
                out.extend(declaration(&code[start..i]));
                start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    if !out.iter().any(|m| m.kind == Kind::Constructor) {
        if let Some(default) = implicit_constructor(&code[..open]) {
            out.insert(0, default);
        }
    }
    out
}

/// Java's default constructor of a class that declares none: `Name()`, as visible as the
/// class. The course's `Scene` declares `public Scene() {}` where a clean-room one may leave
/// it implicit; the two are one API, so a comparison must not tell them apart.
fn implicit_constructor(head: &str) -> Option<Member> {
    let at = find_word(head, "class")?;
    let name: String = head[at + "class".len()..]
        .trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '$')
        .collect();
    if name.is_empty() {
        return None;
    }
    let visibility = match find_word(&head[..at], "public") {
        Some(_) => Visibility::Public,
        None => Visibility::Package,
    };
    Some(Member {
        kind: Kind::Constructor,
        name,
        params: Vec::new(),
        visibility,
    })
}

/// `source` without comments (and, with `literals`, with the insides of string and character
/// literals blanked), its line breaks kept, so that braces and semicolons in them are not read
/// as code.
pub fn blank(source: &str, literals: bool) -> String {
    let mut out = String::with_capacity(source.len());
    let mut chars = source.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                chars.next();
                let mut last = ' ';
                for c in chars.by_ref() {
                    if last == '*' && c == '/' {
                        break;
                    }
                    out.push(if c == '\n' { '\n' } else { ' ' });
                    last = c;
                }
                out.push(' ');
            }
            '"' | '\'' => {
                out.push(c);
                let mut escaped = false;
                for d in chars.by_ref() {
                    if !escaped && d == c {
                        out.push(d);
                        break;
                    }
                    escaped = !escaped && d == '\\';
                    out.push(if literals { ' ' } else { d });
                }
            }
            _ => out.push(c),
        }
    }
    out
}

/// Where the first top-level type's body opens: the first `{` after `class`, `interface` or
/// `enum`.
fn body_start(code: &str) -> Option<usize> {
    let words = ["class", "interface", "enum"];
    let at = words.iter().filter_map(|w| find_word(code, w)).min()?;
    code[at..].find('{').map(|i| at + i)
}

/// The first place `word` stands as a whole word in `code`.
fn find_word(code: &str, word: &str) -> Option<usize> {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_' || c == '$';
    code.match_indices(word).map(|(i, _)| i).find(|&i| {
        let before = code[..i].chars().next_back().is_none_or(|c| !is_ident(c));
        let after = code[i + word.len()..]
            .chars()
            .next()
            .is_none_or(|c| !is_ident(c));
        before && after
    })
}

/// The index just past the block that opens at `open` (a `{`), or past the `;` that ends a
/// field whose initializer the block is part of.
fn skip_block(bytes: &[u8], open: usize) -> usize {
    let mut depth = 0;
    let mut i = open;
    while i < bytes.len() {
        match bytes[i] {
            b'{' => depth += 1,
            b'}' => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    i
}

/// Whether a declaration's head assigns (a field's initializer) before any parenthesis.
fn has_assignment(head: &str) -> bool {
    match (head.find('='), head.find('(')) {
        (Some(eq), Some(paren)) => eq < paren,
        (Some(_), None) => true,
        _ => false,
    }
}

/// The members one declaration (its text up to `;` or its body's `{`) declares: none for an
/// initializer block or a nested type.
fn declaration(head: &str) -> Vec<Member> {
    let head = without_annotations(head);
    let head = head.trim();
    if head.is_empty()
        || ["class", "interface", "enum"]
            .iter()
            .any(|w| find_word(head, w).is_some())
    {
        return Vec::new();
    }
    let visibility = visibility(head);
    match (head.find('('), has_assignment(head)) {
        (Some(paren), false) => {
            let name = last_identifier(&head[..paren]);
            let Some(close) = head.rfind(')') else {
                return Vec::new();
            };
            let before: Vec<&str> = head[..paren].split_whitespace().collect();
            let returns = before.iter().filter(|w| !MODIFIERS.contains(w)).count() > 1;
            vec![Member {
                kind: if returns {
                    Kind::Method
                } else {
                    Kind::Constructor
                },
                name,
                params: params(&head[paren + 1..close]),
                visibility,
            }]
        }
        _ => fields(head, visibility),
    }
}

const MODIFIERS: [&str; 11] = [
    "public",
    "protected",
    "private",
    "static",
    "final",
    "abstract",
    "synchronized",
    "native",
    "transient",
    "volatile",
    "default",
];

fn visibility(head: &str) -> Visibility {
    let words: Vec<&str> = head.split_whitespace().collect();
    if words.contains(&"public") {
        Visibility::Public
    } else if words.contains(&"protected") {
        Visibility::Protected
    } else if words.contains(&"private") {
        Visibility::Private
    } else {
        Visibility::Package
    }
}

/// The fields of `double a, b = 2, c`: each name before an `=` or a `,` at the top level.
fn fields(head: &str, visibility: Visibility) -> Vec<Member> {
    split_top(head)
        .iter()
        .enumerate()
        .filter_map(|(i, part)| {
            let left = part.split('=').next().unwrap_or("");
            let name = last_identifier(
                left.trim_end_matches(|c: char| c == '[' || c == ']' || c.is_whitespace()),
            );
            // The first part holds the type too; a later one is a name alone.
            let ok = !name.is_empty() && (i > 0 || left.split_whitespace().count() > 1);
            ok.then(|| Member {
                kind: Kind::Field,
                name,
                params: Vec::new(),
                visibility,
            })
        })
        .collect()
}

/// A parameter list's types: generics and names left out (`List<PointLight> lights` is
/// `List`), `final` and annotations too.
fn params(list: &str) -> Vec<String> {
    split_top(list)
        .iter()
        .filter_map(|p| {
            let plain = strip_generics(p);
            let words: Vec<&str> = plain.split_whitespace().filter(|w| *w != "final").collect();
            let (_, types) = words.split_last()?;
            let shown = types.join("").replace(' ', "");
            (!shown.is_empty()).then_some(shown)
        })
        .collect()
}

/// `text` split at the commas outside `<>`, `()` and `{}`.
fn split_top(text: &str) -> Vec<String> {
    let mut parts = vec![String::new()];
    let mut depth = 0i32;
    for c in text.chars() {
        match c {
            '<' | '(' | '{' | '[' => depth += 1,
            '>' | ')' | '}' | ']' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(String::new());
                continue;
            }
            _ => {}
        }
        if let Some(last) = parts.last_mut() {
            last.push(c);
        }
    }
    parts.retain(|p| !p.trim().is_empty());
    parts
}

fn strip_generics(text: &str) -> String {
    let mut out = String::new();
    let mut depth = 0;
    for c in text.chars() {
        match c {
            '<' => depth += 1,
            '>' => depth -= 1,
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// Annotations (`@Override`, `@SuppressWarnings("x")`) taken out of a declaration.
fn without_annotations(head: &str) -> String {
    let mut out = String::new();
    let mut chars = head.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '@' {
            out.push(c);
            continue;
        }
        while chars
            .peek()
            .is_some_and(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
        {
            chars.next();
        }
        while chars.peek().is_some_and(|c| c.is_whitespace()) {
            chars.next();
        }
        if chars.peek() == Some(&'(') {
            let mut depth = 0;
            for c in chars.by_ref() {
                match c {
                    '(' => depth += 1,
                    ')' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
            }
        }
        out.push(' ');
    }
    out
}

/// The last identifier in `text` (the name before a `(` or an `=`).
fn last_identifier(text: &str) -> String {
    let text = text.trim_end();
    let start = text
        .char_indices()
        .rev()
        .find(|(_, c)| !(c.is_alphanumeric() || *c == '_' || *c == '$'))
        .map_or(0, |(i, c)| i + c.len_utf8());
    text[start..].to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shown(source: &str) -> Vec<String> {
        members(source)
            .iter()
            .filter(|m| m.visible())
            .map(Member::shown)
            .collect()
    }

    #[test]
    fn a_class_without_constructors_has_java_s_default_one() {
        let implicit = "package a; public class Scene { public void add(Sphere s) {} }";
        let explicit =
            "package a; public class Scene { public Scene() {} public void add(Sphere s) {} }";
        assert_eq!(members(implicit), members(explicit));
        assert_eq!(shown(implicit), ["Scene()", "add(Sphere)"]);
        let hidden = members("class Helper { }");
        assert_eq!(hidden[0].visibility, Visibility::Package);
        assert!(members("public interface Shape { void f(); }")
            .iter()
            .all(|m| m.kind != Kind::Constructor));
        let declared = members("public class Ray { public Ray(Vector3 o, Vector3 d) {} }");
        assert_eq!(
            declared.len(),
            1,
            "a declared constructor means no default one"
        );
    }

    #[test]
    fn a_course_class_s_members_are_read_with_their_parameter_types() {
        let source = r#"package a.b; // the { in a comment
            import java.util.List;
            /** A { brace } in javadoc. */
            public class Scene {
                private List<PointLight> lights = new ArrayList<>();
                protected double phong_kD, phong_kS = 0.5;
                double fov = 45;
                static final int[] SIZES = {1, 2};
                public Scene() { String s = "}"; }
                @Override
                public final RaycastHit findClosestIntersection(final Ray ray) { if (x) { } return null; }
                public List<PointLight> getPointLights() { return lights; }
                public abstract Vector3 getNormalAt(Vector3 position);
                private void helper(Map<String, Integer> m, int... xs) {}
                static { System.out.println("{"); }
                private static class Inner { public void hidden() {} }
            }"#;
        assert_eq!(
            shown(source),
            [
                "field phong_kD",
                "field phong_kS",
                "field fov",
                "field SIZES",
                "Scene()",
                "findClosestIntersection(Ray)",
                "getPointLights()",
                "getNormalAt(Vector3)",
            ]
        );
        let all = members(source);
        let helper = all.iter().find(|m| m.name == "helper").expect("helper");
        assert_eq!(helper.params, ["Map", "int..."]);
        assert_eq!(helper.visibility, Visibility::Private);
        assert_eq!(all[0].name, "lights");
        assert_eq!(
            all.iter().find(|m| m.name == "Scene").map(|m| m.kind),
            Some(Kind::Constructor)
        );
    }

    #[test]
    fn literals_and_comments_are_blanked_without_moving_anything() {
        let source = "a /* x */ \"b;{\" 'c' // d\ne";
        let blanked = blank(source, true);
        assert_eq!(blanked.lines().count(), 2);
        assert!(!blanked.contains(';') && !blanked.contains('x') && !blanked.contains('d'));
        assert!(blank(source, false).contains("\"b;{\""));
    }
}
