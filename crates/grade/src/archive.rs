//! The files a submission gives (`Plane.java`, `Renderer.java`, and `Sphere.java` from 2017-18), found in a zip, a folder or
//! a zip inside either, without unpacking anything to disk: nothing a submission names is ever
//! a path we write to, so `../` and absolute names, links and devices cannot reach outside
//! OUTDIR (they are not even looked at as files). What is read is capped while it is
//! decompressed, whatever sizes the archive declares (a zip bomb stops at the cap).

use std::io::{Cursor, Read, Seek};
use std::path::Path;

use whitted_core::course::Course;

/// Every file a submission of some year gives, by name.
pub const WANTED: [&str; 3] = ["Plane.java", "Renderer.java", "Sphere.java"];

/// Files a later year's submission may give besides: Tick 1*'s option 1 (`BumpySphere.java`),
/// taken when it is there (by its exact name) in a Tick 1* submission and compiled over the
/// skeleton's stub.
pub const OPTIONAL: [&str; 1] = ["BumpySphere.java"];

/// The files a submission of `course` gives (docs/courses.md, "The student's program"):
/// `Sphere.java` too from 2017-18, when students write the sphere's intersection.
pub fn submitted(course: Course) -> &'static [&'static str] {
    match course.is_default() {
        true => &WANTED[..2],
        false => &WANTED,
    }
}

/// Which wanted file `name` is, and whether it is that name exactly: a near miss is a
/// browser's second download (`Renderer (1).java`), another case (`renderer.java`) or an
/// editor's extension (`Renderer.java.txt`), which a student means as the file.
pub fn wanted(name: &str) -> Option<(&'static str, bool)> {
    if let Some(exact) = WANTED.iter().chain(&OPTIONAL).find(|w| **w == name) {
        return Some((exact, true));
    }
    let lower = name.to_ascii_lowercase();
    let lower = lower.strip_suffix(".txt").unwrap_or(&lower);
    let stem = lower.strip_suffix(".java")?;
    // `Renderer (1)`, `Renderer(2)`, `Renderer - Copy`.
    let stem = match stem.trim_end().strip_suffix(')') {
        Some(open) => match open.rsplit_once('(') {
            Some((base, n)) if !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) => base,
            _ => stem,
        },
        None => stem,
    };
    let stem = stem.strip_suffix(" - copy").unwrap_or(stem).trim_end();
    WANTED
        .iter()
        .find(|w| w.to_ascii_lowercase().strip_suffix(".java") == Some(stem))
        .map(|w| (*w, false))
}

/// A source file larger than this is not a student's Plane or Renderer.
pub const MAX_SOURCE: u64 = 1 << 20;
/// A zip inside a submission is read only up to this size.
const MAX_INNER_ZIP: u64 = 64 << 20;
/// Entries looked at in one archive, and files in one folder walk.
const MAX_ENTRIES: usize = 100_000;
/// How deep a folder walk goes.
const MAX_DEPTH: usize = 16;

/// One file found: where it was, and its bytes (or why they could not be had).
#[derive(Debug, Clone)]
pub struct Found {
    /// The path in the submission, as text (lossy for names that are not UTF-8).
    pub path: String,
    pub bytes: std::result::Result<Vec<u8>, String>,
}

/// What a submission holds of the wanted files: every copy of each, and what was refused on
/// the way (said in the student's report).
#[derive(Debug, Clone, Default)]
pub struct Holdings {
    /// The submission's folder as the class has it (Moodle's `Full Name_<id>_assignsubmission_file`):
    /// where feedback goes back to.
    pub folder: String,
    pub found: Vec<Found>,
    pub notes: Vec<String>,
    /// The names of the other `.java` files it holds (its own Tick1.java, the course's classes):
    /// never compiled, but said, since a student who edited them must know it did not count.
    pub ignored_java: std::collections::BTreeSet<String>,
}

/// How many names of ignored `.java` files are kept, at most.
const MAX_IGNORED_NAMES: usize = 100;

impl Holdings {
    fn add(&mut self, path: String, bytes: std::result::Result<Vec<u8>, String>) {
        self.found.push(Found { path, bytes });
    }

    /// Notes `name` if it is a Java source the grade does not take.
    fn saw(&mut self, name: &str) {
        if name.ends_with(".java")
            && wanted(name).is_none()
            && self.ignored_java.len() < MAX_IGNORED_NAMES
        {
            self.ignored_java.insert(name.to_string());
        }
    }
}

/// The file name of a path in an archive (either separator).
fn file_name(path: &str) -> &str {
    path.rsplit(['/', '\\']).next().unwrap_or(path)
}

fn is_zip_name(path: &str) -> bool {
    file_name(path).to_ascii_lowercase().ends_with(".zip")
}

/// Reads at most `cap` bytes of `reader`; Err when there are more.
fn read_capped(reader: impl Read, cap: u64, what: &str) -> std::result::Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    match reader.take(cap + 1).read_to_end(&mut bytes) {
        Ok(_) if bytes.len() as u64 > cap => Err(format!("{what} is larger than {cap} bytes")),
        Ok(_) => Ok(bytes),
        Err(e) => Err(format!("{what} cannot be read: {e}")),
    }
}

/// The entries of a zip, grouped by their first path component (Moodle's folder per
/// student): (folder, path within it, index). Entries at the top level have an empty folder.
pub fn top_folders<R: Read + Seek>(zip: &mut zip::ZipArchive<R>) -> Vec<(String, String, usize)> {
    (0..zip.len().min(MAX_ENTRIES))
        .filter_map(|i| {
            let entry = zip.by_index_raw(i).ok()?;
            let name = String::from_utf8_lossy(entry.name_raw()).into_owned();
            let trimmed = name.trim_start_matches(['/', '\\']);
            Some(match trimmed.split_once(['/', '\\']) {
                Some((folder, rest)) => (folder.to_string(), rest.to_string(), i),
                None => (String::new(), trimmed.to_string(), i),
            })
        })
        .collect()
}

/// Looks in entries `indices` of `zip` (paths `paths`) for the wanted files and for zips to
/// look into (one level: a zip in a zip in a zip is a note, not a search).
pub fn search_zip<R: Read + Seek>(
    zip: &mut zip::ZipArchive<R>,
    entries: &[(String, usize)],
    holdings: &mut Holdings,
    nested: bool,
) {
    for (path, i) in entries {
        let name = file_name(path);
        let wanted = wanted(name).is_some();
        if !wanted && !is_zip_name(path) {
            holdings.saw(name);
            continue;
        }
        let entry = match zip.by_index(*i) {
            Ok(entry) => entry,
            Err(e) => {
                holdings
                    .notes
                    .push(format!("{path}: cannot be read from the zip ({e})"));
                continue;
            }
        };
        // Links, devices and folders are never read as files.
        let regular = entry.is_file()
            && entry
                .unix_mode()
                .is_none_or(|mode| mode & 0o170000 == 0o100000 || mode & 0o170000 == 0);
        if !regular {
            holdings
                .notes
                .push(format!("{path}: not a regular file, ignored"));
            continue;
        }
        if wanted {
            let bytes = read_capped(entry, MAX_SOURCE, path);
            holdings.add(path.clone(), bytes);
        } else if nested {
            holdings.notes.push(format!(
                "{path}: a zip inside a zip inside the submission, not opened"
            ));
        } else {
            match read_capped(entry, MAX_INNER_ZIP, path) {
                Ok(bytes) => search_inner_zip(path, bytes, holdings),
                Err(e) => holdings.notes.push(e),
            }
        }
    }
}

/// Looks into a zip found inside a submission.
fn search_inner_zip(path: &str, bytes: Vec<u8>, holdings: &mut Holdings) {
    match zip::ZipArchive::new(Cursor::new(bytes)) {
        Ok(mut inner) => {
            let entries: Vec<(String, usize)> = top_folders(&mut inner)
                .into_iter()
                .map(|(folder, rest, i)| {
                    let inside = if folder.is_empty() {
                        rest
                    } else {
                        format!("{folder}/{rest}")
                    };
                    (format!("{path}/{inside}"), i)
                })
                .collect();
            search_zip(&mut inner, &entries, holdings, true);
        }
        Err(e) => holdings
            .notes
            .push(format!("{path}: not a zip that can be read ({e})")),
    }
}

/// Looks in folder `dir` (and zips in it) for the wanted files, in file-name order (walkdir).
/// Links are not followed and nothing but regular files is opened (a FIFO would wait for ever).
pub fn search_dir(dir: &Path, holdings: &mut Holdings) {
    let walk = walkdir::WalkDir::new(dir)
        .min_depth(1)
        .max_depth(MAX_DEPTH + 1)
        .follow_links(false)
        .sort_by_file_name();
    for (seen, entry) in walk.into_iter().enumerate() {
        if seen >= MAX_ENTRIES {
            holdings
                .notes
                .push("more files than are looked at; the rest ignored".into());
            return;
        }
        let entry = match entry {
            Ok(entry) => entry,
            Err(e) => {
                let at = e.path().unwrap_or(dir);
                holdings
                    .notes
                    .push(format!("{}: cannot be read", shown(dir, at)));
                continue;
            }
        };
        let (path, kind) = (entry.path(), entry.file_type());
        let name = entry.file_name().to_string_lossy().into_owned();
        if kind.is_file() {
            holdings.saw(&name);
        }
        if kind.is_file() && (wanted(&name).is_some() || is_zip_name(&name)) {
            let label = shown(dir, path);
            let cap = if is_zip_name(&name) {
                MAX_INNER_ZIP
            } else {
                MAX_SOURCE
            };
            let bytes = read_regular(path, cap, &label);
            match (is_zip_name(&name), bytes) {
                (true, Ok(bytes)) => search_inner_zip(&label, bytes, holdings),
                (true, Err(e)) => holdings.notes.push(e),
                (false, bytes) => holdings.add(label, bytes),
            }
        } else if !kind.is_dir() && wanted(&name).is_some() {
            holdings
                .notes
                .push(format!("{}: not a regular file, ignored", shown(dir, path)));
        }
    }
}

/// At most `cap` bytes of the regular file at `path`: opened without following a link and
/// without waiting (a FIFO put there since the folder was listed opens at once, and is then
/// refused as not regular).
fn read_regular(path: &Path, cap: u64, label: &str) -> std::result::Result<Vec<u8>, String> {
    use std::os::unix::fs::OpenOptionsExt;
    let flags = rustix::fs::OFlags::NOFOLLOW | rustix::fs::OFlags::NONBLOCK;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(flags.bits() as i32)
        .open(path)
        .map_err(|e| format!("{label} cannot be read: {e}"))?;
    match file.metadata() {
        Ok(m) if m.is_file() => read_capped(file, cap, label),
        _ => Err(format!("{label}: not a regular file, ignored")),
    }
}

/// `path` relative to the submission's folder, for the report.
fn shown(dir: &Path, path: &Path) -> String {
    path.strip_prefix(dir)
        .unwrap_or(path)
        .to_string_lossy()
        .into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_miss_names_are_the_wanted_files() {
        assert_eq!(wanted("Renderer.java"), Some(("Renderer.java", true)));
        for near in [
            "Renderer (1).java",
            "Renderer(2).java",
            "renderer.java",
            "RENDERER.JAVA",
            "Renderer.java.txt",
            "Renderer - Copy.java",
        ] {
            assert_eq!(wanted(near), Some(("Renderer.java", false)), "{near}");
        }
        assert_eq!(wanted("plane (3).java"), Some(("Plane.java", false)));
        for other in [
            "Renderer.class",
            "MyRenderer.java",
            "Renderer (x).java",
            "Plane.txt",
        ] {
            assert_eq!(wanted(other), None, "{other}");
        }
    }
}
