//! A Tick 1 student's three files as real students' code comes about: whitted's one finished
//! Tick 1 (`skeleton/tick1/finished/`, which grade ships) edited. A catalogue mistake, or a stage
//! left as the course's zip ships it, is a small textual edit of the finished source, kept in
//! `tests/java/tick1-mistakes.txt` (its header says the format); the year's API and rules come
//! from grade's own rule for the finished files (`whitted_grade::finished_for_year`).

use std::path::Path;

use whitted_core::course::Course;

/// The student's three files, in the order [`fixture`] gives them.
pub const FILES: [&str; 3] = ["Plane.java", "Renderer.java", "Sphere.java"];

/// The stages the course's zip ships as TODO stubs: with these, a file is as the student finds
/// it in the zip (each edit is the zip's own stub, so none is written twice).
pub const SHIPPED: [&str; 4] = [
    "spheres-missing",
    "planes-missing",
    "shading-missing",
    "reflection-ignored",
];

/// The package the finished files are in (the course's placeholder crsid).
const PACKAGE_LINE: &str = "package uk.ac.cam.cl.gfxintro.crsid.tick1;";

/// One edit of one finished file: the text found and what replaces it.
#[derive(Debug)]
pub struct Edit {
    pub id: String,
    pub file: String,
    pub found: String,
    pub replacement: String,
}

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `tests/java/tick1-mistakes.txt`'s edits, in its order, or why they cannot be read.
pub fn edits() -> Result<Vec<Edit>, String> {
    let path = root().join("tests/java/tick1-mistakes.txt");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The edits in `text` (the file's format), or the first malformed line's number and fault.
fn parse(text: &str) -> Result<Vec<Edit>, String> {
    let mut edits: Vec<Edit> = Vec::new();
    // The current edit's found lines and replacement lines so far.
    let (mut found, mut replaced) = (0, 0);
    let no_text = |edits: &[Edit], found: usize, n: usize| match edits.last() {
        Some(e) if found == 0 => Err(format!("line {n}: {} {} finds no text", e.id, e.file)),
        _ => Ok(()),
    };
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        if let Some(header) = line.strip_prefix("@ ") {
            no_text(&edits, found, n)?;
            let fields: Vec<&str> = header.split_whitespace().collect();
            let [id, file] = fields[..] else {
                return Err(format!("line {n}: `@ ID FILE`, not `{line}`"));
            };
            if !FILES.contains(&file) {
                return Err(format!("line {n}: {file} is none of {FILES:?}"));
            }
            edits.push(Edit {
                id: id.to_string(),
                file: file.to_string(),
                found: String::new(),
                replacement: String::new(),
            });
            (found, replaced) = (0, 0);
        } else if let Some(sign) = line.chars().next().filter(|c| matches!(c, '-' | '+')) {
            let part = match &line[1..] {
                "" => "",
                rest => rest
                    .strip_prefix(' ')
                    .ok_or(format!("line {n}: `{sign}` is followed by a space"))?,
            };
            let edit = edits
                .last_mut()
                .ok_or(format!("line {n}: `{sign}` before any `@ ID FILE`"))?;
            let (to, count) = match sign {
                '-' if replaced > 0 => {
                    return Err(format!("line {n}: found text after the replacement"))
                }
                '-' => (&mut edit.found, &mut found),
                _ if found == 0 => {
                    return Err(format!("line {n}: a replacement before the text found"))
                }
                _ => (&mut edit.replacement, &mut replaced),
            };
            if *count > 0 {
                to.push('\n');
            }
            to.push_str(part);
            *count += 1;
        } else if !(line.is_empty() || line.starts_with('#')) {
            return Err(format!("line {n}: neither `@`, `-`, `+`, `#` nor empty"));
        }
    }
    no_text(&edits, found, text.lines().count())?;
    Ok(edits)
}

/// Whitted's finished `name` (the template, markers and all).
fn finished(name: &str) -> Result<String, String> {
    let path = root().join("skeleton/tick1/finished").join(name);
    std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))
}

/// `text` (the finished template of `name`) with `mistakes`' edits of `name` made, in the order
/// given, or why one cannot be: an id with no edit at all, or a text not found exactly once.
pub fn edit(
    name: &str,
    mut text: String,
    mistakes: &[&str],
    edits: &[Edit],
) -> Result<String, String> {
    for id in mistakes {
        if !edits.iter().any(|e| e.id == *id) {
            return Err(format!(
                "{id}: no such mistake in tests/java/tick1-mistakes.txt"
            ));
        }
        for e in edits.iter().filter(|e| e.id == *id && e.file == name) {
            match text.matches(e.found.as_str()).count() {
                1 => text = text.replacen(e.found.as_str(), &e.replacement, 1),
                n => {
                    return Err(format!(
                        "{id} in {name} (with {mistakes:?}): its text is there {n} times, \
                         not once:\n{}",
                        e.found
                    ))
                }
            }
        }
    }
    Ok(text)
}

/// One of the three files as `year`'s student `crsid` has it, with `mistakes` made, or why it
/// cannot be written.
pub fn student_file(
    name: &str,
    year: &str,
    crsid: &str,
    mistakes: &[&str],
) -> Result<String, String> {
    let course = Course::from_name(year).ok_or(format!("{year}: no such course year"))?;
    let text = edit(name, finished(name)?, mistakes, &edits()?)?;
    let text = whitted_grade::finished_for_year(&text, course)?;
    if !text.starts_with(PACKAGE_LINE) {
        return Err(format!("{name}: not in the placeholder package"));
    }
    Ok(text.replacen(
        PACKAGE_LINE,
        &format!("package uk.ac.cam.cl.gfxintro.{crsid}.tick1;"),
        1,
    ))
}

/// [`student_file`], which the tests' own mistakes lists must make.
pub fn fixture_file(name: &str, year: &str, crsid: &str, mistakes: &[&str]) -> String {
    student_file(name, year, crsid, mistakes).unwrap_or_else(|e| panic!("{e}"))
}

/// The three files for `year`, `mistakes` made (in the order of [`FILES`]).
pub fn fixture(year: &str, crsid: &str, mistakes: &[&str]) -> Vec<(&'static str, String)> {
    FILES
        .into_iter()
        .map(|name| (name, fixture_file(name, year, crsid, mistakes)))
        .collect()
}

/// One of the three files as the course's zip of `year` ships it.
pub fn shipped_file(name: &str, year: &str, crsid: &str) -> String {
    fixture_file(name, year, crsid, &SHIPPED)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common::{javac_into, process_dir, write_file};

    /// Every mistake's id, once each, in the file's order.
    fn ids(edits: &[Edit]) -> Vec<&str> {
        let mut ids: Vec<&str> = Vec::new();
        for e in edits {
            if !ids.contains(&e.id.as_str()) {
                ids.push(&e.id);
            }
        }
        ids
    }

    /// Each mistake alone finds each of its texts once in the finished Tick 1 and changes it;
    /// the zip's stubs together make all three files.
    #[test]
    fn every_mistake_is_an_edit_of_text_the_finished_tick1_has() {
        let edits = edits().expect("the mistakes");
        let ids = ids(&edits);
        assert!(ids.len() >= 18, "{ids:?}");
        for id in &ids {
            let mut changed = 0;
            for name in FILES {
                let text = edit(name, finished(name).expect("finished"), &[id], &edits)
                    .unwrap_or_else(|e| panic!("{e}"));
                changed += usize::from(text != finished(name).expect("finished"));
            }
            assert!(changed > 0, "{id} edits nothing");
        }
        for name in FILES {
            let shipped =
                edit(name, finished(name).expect("finished"), &SHIPPED, &edits).expect("the zip");
            assert!(shipped.contains("// TODO"), "{name}");
        }
    }

    /// A text the finished code no longer has, or has twice, an id with no edit, and a malformed
    /// line are errors that say where, never an edit that silently does nothing.
    #[test]
    fn an_edit_that_cannot_be_made_is_an_error() {
        let text =
            "# a comment\n\n@ one Plane.java\n- a\n-\n- b\n+ c\n\n@ two Plane.java\n- x\n+ y\n";
        let edits = parse(text).expect("parses");
        assert_eq!(edits.len(), 2);
        assert_eq!(
            (edits[0].found.as_str(), edits[0].replacement.as_str()),
            ("a\n\nb", "c")
        );
        let source = "a\n\nb x".to_string();
        assert_eq!(
            edit("Plane.java", source.clone(), &["one"], &edits),
            Ok("c x".into())
        );
        // The other file's edits are not made; none is missed there.
        assert_eq!(
            edit("Sphere.java", "q".into(), &["one"], &edits),
            Ok("q".into())
        );
        let gone = edit("Plane.java", "a b x".into(), &["one"], &edits).expect_err("gone");
        assert!(
            gone.contains("one in Plane.java") && gone.contains("0 times"),
            "{gone}"
        );
        let twice = edit("Plane.java", "x x".into(), &["two"], &edits).expect_err("twice");
        assert!(twice.contains("2 times"), "{twice}");
        let unknown = edit("Plane.java", source, &["three"], &edits).expect_err("unknown");
        assert!(unknown.contains("three: no such mistake"), "{unknown}");
        for (bad, said) in [
            ("- a\n", "line 1: `-` before any"),
            ("@ one\n- a\n", "line 1: `@ ID FILE`"),
            ("@ one Tick1.java\n- a\n", "line 1: Tick1.java is none of"),
            (
                "@ one Plane.java\n+ a\n",
                "line 2: a replacement before the text found",
            ),
            (
                "@ one Plane.java\n- a\n+ b\n- c\n",
                "line 4: found text after the replacement",
            ),
            (
                "@ one Plane.java\n@ two Plane.java\n- a\n",
                "line 2: one Plane.java finds no text",
            ),
            ("@ one Plane.java\n", "line 1: one Plane.java finds no text"),
            (
                "@ one Plane.java\n-a\n",
                "line 2: `-` is followed by a space",
            ),
            ("@ one Plane.java\n- a\nb\n", "line 3: neither"),
        ] {
            let err = parse(bad).expect_err(bad);
            assert!(err.contains(said), "{bad:?}: {err}");
        }
    }

    /// Every mistake alone, and the zip's stubs, compile against each API's clean-room skeleton
    /// (2017-18's T1, 2018-19's T2, 2021-22's T3, 2023-24's T4): each in a package of its own,
    /// one javac a year.
    #[test]
    fn every_mistake_compiles_in_every_year_s_api() {
        let edits = edits().expect("the mistakes");
        let mut sets: Vec<Vec<&str>> = ids(&edits).into_iter().map(|id| vec![id]).collect();
        sets.push(SHIPPED.to_vec());
        let dir = process_dir("tick1-mistakes");
        for year in ["2017-18", "2018-19", "2021-22", "2023-24"] {
            let course = Course::from_name(year).expect("course");
            let src = dir.join(year).join("src");
            let mut paths = Vec::new();
            for (n, set) in sets.iter().enumerate() {
                let crsid = format!("m{n}");
                let package = format!("uk.ac.cam.cl.gfxintro.{crsid}.tick1");
                let skeleton =
                    whitted_grade::clean_room_skeleton(course, Some(&package)).expect("skeleton");
                let folder = package.replace('.', "/");
                let theirs = FILES.map(|name| {
                    let text = fixture_file(name, year, &crsid, set);
                    (format!("{folder}/{name}"), text.into_bytes())
                });
                for (path, bytes) in skeleton.into_iter().chain(theirs) {
                    let path = src.join(path);
                    write_file(&path, bytes);
                    if !paths.contains(&path) {
                        paths.push(path);
                    }
                }
            }
            javac_into(&dir.join(year).join("classes"), &paths);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
