//! What an upload may be, decided before anything is kept: the course scenes' output PNGs
//! (each header read, never decoded here), or a project, as `.java` files or one zip of them.
//! The names a student gives are shown back to them, never used as a path: images are kept as
//! `image-<n>.png`, and a project's files under their class's name (`Renderer.java`), which
//! must be a Java class name, whatever folders the zip put it in.

use whitted_core::frame::limits::MAX_SIDE;

/// The largest request body taken: more is refused before it is read.
pub const MAX_BODY: u64 = 32 << 20;
/// The largest file in it.
pub const MAX_FILE: u64 = 16 << 20;
/// Files in one upload.
pub const MAX_FILES: usize = 20;
/// A zip's entries, and the bytes its Java files may expand to, together.
pub const MAX_ENTRIES: usize = 500;
pub const MAX_EXPANDED: u64 = 8 << 20;
/// The most pixels an uploaded PNG may declare: far more than any render of the course (a
/// PNG bomb declares billions in a few bytes, and is refused from its header).
pub const MAX_PIXELS: u64 = 16 << 20;

/// An upload, sorted out.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Submission {
    /// PNGs, with the names they were given.
    Images(Vec<(String, Vec<u8>)>),
    /// Java sources, by their file names (`Renderer.java`).
    Project(Vec<(String, Vec<u8>)>),
}

/// What an upload is, or the sentence that says why it is refused.
pub fn classify(files: Vec<(String, Vec<u8>)>) -> Result<Submission, String> {
    let files: Vec<(String, Vec<u8>)> = files.into_iter().filter(|(n, _)| !n.is_empty()).collect();
    if files.is_empty() {
        return Err(
            "choose the PNGs your program wrote, or your .java files or a zip of your \
                    project, before pressing Check"
                .into(),
        );
    }
    if files.len() > MAX_FILES {
        return Err(format!("at most {MAX_FILES} files at once"));
    }
    let ext = |name: &str| {
        name.rsplit_once('.')
            .map(|(_, e)| e.to_ascii_lowercase())
            .unwrap_or_default()
    };
    let kinds: Vec<String> = files.iter().map(|(n, _)| ext(n)).collect();
    if kinds.iter().all(|k| k == "png") {
        for (name, bytes) in &files {
            png_size(bytes).map_err(|why| format!("{}: {why}", shown(name)))?;
        }
        return Ok(Submission::Images(
            files.into_iter().map(|(n, b)| (shown(&n), b)).collect(),
        ));
    }
    if !kinds.iter().all(|k| k == "java" || k == "zip") {
        return Err("upload PNG images, or .java files or a zip of your project (not both)".into());
    }
    let mut sources = Vec::new();
    for (name, bytes) in files {
        match ext(&name).as_str() {
            "zip" => sources.extend(super::zip_in::java_files(&bytes)?),
            _ => sources.push((java_name(&name)?, bytes)),
        }
    }
    for (i, (name, _)) in sources.iter().enumerate() {
        if sources[..i].iter().any(|(n, _)| n == name) {
            return Err(format!(
                "two files are named {name}: upload one of each class"
            ));
        }
    }
    if sources.is_empty() {
        return Err("the zip holds no .java file".into());
    }
    Ok(Submission::Project(sources))
}

/// A name as the student gave it, cut to its last part and 100 characters, for the pages.
pub fn shown(name: &str) -> String {
    let last = name.rsplit(['/', '\\']).next().unwrap_or(name);
    last.chars().filter(|c| !c.is_control()).take(100).collect()
}

/// The class file name of a source named `name` (any folders dropped), or the refusal.
pub fn java_name(name: &str) -> Result<String, String> {
    let last = shown(name);
    let stem = last.strip_suffix(".java").unwrap_or("");
    let ok = !stem.is_empty()
        && stem.len() <= 64
        && stem
            .bytes()
            .next()
            .is_some_and(|b| b.is_ascii_alphabetic() || b == b'_')
        && stem.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_');
    match ok {
        true => Ok(last),
        false => Err(format!(
            "{last}: not the name of a Java class's source file"
        )),
    }
}

/// A PNG's size from its header, refusing what is not a PNG and sizes no render has.
pub fn png_size(bytes: &[u8]) -> Result<(u32, u32), String> {
    const SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];
    if bytes.len() < 24 || bytes[..8] != SIGNATURE || &bytes[12..16] != b"IHDR" {
        return Err("not a PNG (upload the .png files your program wrote)".into());
    }
    let word = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    let (width, height) = (word(16), word(20));
    let pixels = u64::from(width) * u64::from(height);
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE || pixels > MAX_PIXELS {
        return Err(format!(
            "a PNG of {width} x {height} pixels, which no render of the course has"
        ));
    }
    Ok((width, height))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32) -> Vec<u8> {
        let mut bytes = vec![
            0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n', 0, 0, 0, 13,
        ];
        bytes.extend_from_slice(b"IHDR");
        bytes.extend_from_slice(&width.to_be_bytes());
        bytes.extend_from_slice(&height.to_be_bytes());
        bytes.extend_from_slice(&[8, 2, 0, 0, 0]);
        bytes
    }

    #[test]
    fn pngs_are_images_and_sources_a_project_named_by_their_class() {
        let images = classify(vec![("out/../tick.png".into(), png(640, 480))]).expect("images");
        assert_eq!(
            images,
            Submission::Images(vec![("tick.png".into(), png(640, 480))])
        );
        let project = classify(vec![
            (
                "C:\\work\\Renderer.java".into(),
                b"class Renderer {}".to_vec(),
            ),
            ("Plane.java".into(), b"class Plane {}".to_vec()),
        ])
        .expect("project");
        let Submission::Project(files) = project else {
            panic!("not a project");
        };
        assert_eq!(files[0].0, "Renderer.java");
    }

    #[test]
    fn every_refusal_says_why() {
        for (files, why) in [
            (vec![], "choose the PNGs"),
            (
                vec![("a.png".to_string(), png(70_000, 70_000))],
                "no render",
            ),
            (vec![("a.png".to_string(), b"GIF89a".to_vec())], "not a PNG"),
            (
                vec![
                    ("a.png".to_string(), png(640, 480)),
                    ("R.java".to_string(), vec![]),
                ],
                "not both",
            ),
            (vec![("../../etc/passwd".to_string(), vec![])], "not both"),
            (
                vec![("../x/1nope.java".to_string(), vec![])],
                "not the name of a Java",
            ),
            (
                vec![("evil$.java".to_string(), vec![])],
                "not the name of a Java",
            ),
            (
                vec![
                    ("a/R.java".to_string(), vec![]),
                    ("b/R.java".to_string(), vec![]),
                ],
                "two files are named R.java",
            ),
            (
                vec![("x.png".to_string(), png(1, 1)); MAX_FILES + 1],
                "at most",
            ),
        ] {
            let refused = classify(files).expect_err(why);
            assert!(refused.contains(why), "{refused}");
        }
    }
}
