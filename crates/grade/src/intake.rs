//! The class, read from what `SUBMISSIONS` is (docs/grade.md, "Inputs"): Moodle's zip of every
//! submission, a folder with a folder per student, or one student's project. Each student's
//! `Plane.java` and `Renderer.java` (and `Sphere.java` from 2017-18) are taken, wherever they
//! are in what they handed in, with the package they declare; nothing else of a submission is
//! used.

use std::collections::BTreeMap;
use std::fs::File;
use std::path::Path;

use super::archive::{self, Holdings};
use super::moodle;
use super::package;
use super::status::StudentStatus;
use whitted_check::check::tick1_star::{self, StarSeen};
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};

/// A student as the class lists them.
#[derive(Debug, Clone)]
pub struct Submission {
    /// What grades go back by: Moodle's id, or the folder's name. Safe as a file name.
    pub id: String,
    /// The name Moodle gives (a full name, `Participant`, a group), or the folder's name.
    pub name: String,
    /// The folder it came in (Moodle's `Full Name_<id>_assignsubmission_file`), which Moodle's
    /// feedback upload reads the participant from.
    pub folder: String,
    /// The files, or why they cannot be had.
    pub files: std::result::Result<Files, Refusal>,
    /// What was ignored on the way (links, a second copy, a file too large, a folder that is
    /// not a file submission), for the report.
    pub notes: Vec<String>,
    /// What was taken though it is not what the handout asks (a near-miss file name), for the
    /// report: the course's own tester may not take it.
    pub warnings: Vec<String>,
}

/// A submission's files, in the order of `archive::submitted`, and the package they are in.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Files {
    pub sources: Vec<(&'static str, Vec<u8>)>,
    /// The package `Renderer.java` declares (None: the default package), or `BumpySphere.java`
    /// in a hand-in without a Renderer. Read for the later years only, whose package carries
    /// the student's user id; 2016-17's is `gfx.tick2`.
    pub package: Option<String>,
    /// Whether it is a Tick 1* submission, and by what (one rule, read once here).
    pub star: Option<StarSeen>,
    /// The files a Tick 1* hand-in of its option's file alone lacks, which whitted's finished
    /// Tick 1 supplies (`finished.rs`), in the order of `archive::submitted`.
    pub completed: Vec<&'static str>,
}

/// Why a student cannot be graded: the status of docs/grade.md and a sentence.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    /// `NoFiles` or `Error`.
    pub status: StudentStatus,
    pub message: String,
}

/// Every student of `submissions`, sorted by id, with the files a submission of `course`
/// gives.
pub fn read(submissions: &Path, course: Course) -> Result<Vec<Submission>> {
    let metadata = std::fs::metadata(submissions)
        .map_err(|e| Error::io(submissions, "cannot read the submissions", e))?;
    let students = if metadata.is_file() {
        from_zip(submissions)?
    } else if metadata.is_dir() && is_project(submissions, course) {
        let name = folder_name(submissions);
        let mut holdings = Holdings {
            folder: name.clone(),
            ..Holdings::default()
        };
        archive::search_dir(submissions, &mut holdings);
        vec![(name.clone(), name, holdings)]
    } else if metadata.is_dir() {
        from_folders(submissions)?
    } else {
        return Err(Error::Usage(format!(
            "{}: give Moodle's zip of the submissions, a folder of students' folders, or one \
             project folder",
            submissions.display()
        )));
    };
    if students.is_empty() {
        return Err(Error::Usage(format!(
            "{}: no students there (give Moodle's zip of the submissions, a folder of \
             students' folders, or one project folder)",
            submissions.display()
        )));
    }
    Ok(settle(students, course))
}

/// One project: the sources at `gfx/tick2/` or `src/gfx/tick2/`; from 2017-18 a tree under
/// `uk/ac/cam/cl/gfxintro/` or `src/uk/ac/cam/cl/gfxintro/`.
fn is_project(dir: &Path, course: Course) -> bool {
    let later = ["uk/ac/cam/cl/gfxintro", "src/uk/ac/cam/cl/gfxintro"];
    let tick2 = ["gfx/tick2", "src/gfx/tick2"];
    let wanted = archive::submitted(course);
    tick2
        .iter()
        .any(|sub| wanted.iter().any(|f| dir.join(sub).join(f).is_file()))
        || !course.is_default() && later.iter().any(|sub| dir.join(sub).is_dir())
}

fn folder_name(dir: &Path) -> String {
    dir.canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "student".into())
}

/// (id, name) of a student's folder: Moodle's when the name has its shape, else the name.
fn student_of(folder: &str) -> (String, String) {
    match moodle::parse(folder) {
        Some(f) => (f.id, f.name),
        None => (folder.to_string(), folder.to_string()),
    }
}

/// A Moodle folder that holds no files (`_onlinetext_`, `_comments_`): its student and a note.
fn not_files(folder: &str) -> Option<(String, String, String)> {
    let parsed = moodle::parse(folder).filter(|f| !f.is_files())?;
    let note = format!(
        "Moodle's folder {folder} holds the {} plugin's submission, not files: ignored",
        parsed.plugin
    );
    Some((parsed.id, parsed.name, note))
}

/// The students of the folders: the file folders, with each ignored folder's note given to
/// its student (a student with no file folder at all is still listed, with nothing to grade).
fn with_ignored(
    mut students: Vec<(String, String, Holdings)>,
    ignored: Vec<(String, String, String)>,
) -> Vec<(String, String, Holdings)> {
    for (id, name, note) in ignored {
        match students.iter_mut().find(|(i, ..)| *i == id) {
            Some((_, _, holdings)) => holdings.notes.push(note),
            None => {
                let holdings = Holdings {
                    notes: vec![note],
                    ..Holdings::default()
                };
                // No file folder: feedback goes back to Moodle's usual name for one.
                let holdings = Holdings {
                    folder: format!("{name}_{id}_assignsubmission_file_"),
                    ..holdings
                };
                students.push((id, name, holdings));
            }
        }
    }
    students
}

/// Moodle's zip: a folder per student at the top (files at the top make one student).
fn from_zip(path: &Path) -> Result<Vec<(String, String, Holdings)>> {
    let file = File::open(path).map_err(|e| Error::io(path, "cannot read", e))?;
    let mut zip = zip::ZipArchive::new(std::io::BufReader::new(file)).map_err(|e| {
        Error::Usage(format!(
            "{}: not a zip that can be read ({e})",
            path.display()
        ))
    })?;
    let mut folders: BTreeMap<String, Vec<(String, usize)>> = BTreeMap::new();
    let mut loose = Vec::new();
    for (folder, rest, i) in archive::top_folders(&mut zip) {
        if folder.is_empty() {
            loose.push((rest, i));
        } else {
            folders.entry(folder).or_default().push((rest, i));
        }
    }
    let mut students = Vec::new();
    if !loose.is_empty() && folders.is_empty() {
        let stem = folder_name(path);
        let (id, name) = student_of(stem.trim_end_matches(".zip"));
        let mut holdings = Holdings {
            folder: stem.trim_end_matches(".zip").to_string(),
            ..Holdings::default()
        };
        archive::search_zip(&mut zip, &loose, &mut holdings, false);
        students.push((id, name, holdings));
        return Ok(students);
    }
    let mut ignored = Vec::new();
    for (folder, entries) in folders {
        let Some((id, name, mut holdings)) = student_folder(&folder, &mut ignored) else {
            continue;
        };
        archive::search_zip(&mut zip, &entries, &mut holdings, false);
        students.push((id, name, holdings));
    }
    Ok(with_ignored(students, ignored))
}

/// The student a submission folder is, with nothing found yet; None (and a line in `ignored`)
/// for a folder Moodle made for something other than files.
fn student_folder(
    folder: &str,
    ignored: &mut Vec<(String, String, String)>,
) -> Option<(String, String, Holdings)> {
    if let Some(not) = not_files(folder) {
        ignored.push(not);
        return None;
    }
    let (id, name) = student_of(folder);
    let holdings = Holdings {
        folder: folder.to_string(),
        ..Holdings::default()
    };
    Some((id, name, holdings))
}

/// A folder with a folder per student (links and files beside them are not students).
fn from_folders(dir: &Path) -> Result<Vec<(String, String, Holdings)>> {
    let entries =
        std::fs::read_dir(dir).map_err(|e| Error::io(dir, "cannot read the submissions", e))?;
    let mut students = Vec::new();
    let mut ignored = Vec::new();
    for entry in entries.flatten() {
        if !entry.file_type().is_ok_and(|t| t.is_dir()) {
            continue;
        }
        let folder = entry.file_name().to_string_lossy().into_owned();
        let Some((id, name, mut holdings)) = student_folder(&folder, &mut ignored) else {
            continue;
        };
        archive::search_dir(&entry.path(), &mut holdings);
        students.push((id, name, holdings));
    }
    Ok(with_ignored(students, ignored))
}

/// The id as a file name: letters, digits, `-`, `_`, `.` kept, anything else `_`, never `.` or
/// `..` or empty.
/// What is said of the other `.java` files a submission holds: not graded, the year's own
/// classes used instead, as in the course's tester.
/// `star`: a Tick 1* submission, whose `BumpySphere.java` is taken too.
fn ignored_note(names: &std::collections::BTreeSet<String>, course: Course, star: bool) -> String {
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut taken = archive::submitted(course).to_vec();
    if star {
        taken.extend(archive::OPTIONAL);
    }
    let taken = taken.join(", ");
    format!(
        "{}: not graded. Only {taken} are taken from a submission; every other class is the \
         course's own, so changes to {} do not count",
        names.join(", "),
        if names.len() == 1 { "it" } else { "them" }
    )
}

pub fn safe_id(id: &str) -> String {
    let safe: String = id
        .chars()
        .map(|c| match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' | '-' | '_' | '.' => c,
            _ => '_',
        })
        .take(100)
        .collect();
    match safe.trim_matches('.') {
        "" => "_".repeat(safe.len().max(1)),
        _ => safe,
    }
}

/// Each student's two files chosen, ids made safe, and two students of one id refused both.
fn settle(students: Vec<(String, String, Holdings)>, course: Course) -> Vec<Submission> {
    let mut count: BTreeMap<String, usize> = BTreeMap::new();
    for (id, ..) in &students {
        *count.entry(safe_id(id)).or_default() += 1;
    }
    let mut settled: Vec<Submission> = students
        .into_iter()
        .map(|(id, name, holdings)| {
            let safe = safe_id(&id);
            let mut notes = holdings.notes.clone();
            let mut warnings = Vec::new();
            let files = if count[&safe] > 1 {
                Err(Refusal {
                    status: StudentStatus::Error,
                    message: format!(
                        "{} submissions have the id {id}: none is graded until one is left",
                        count[&safe]
                    ),
                })
            } else {
                choose(&holdings, &mut notes, &mut warnings, course)
            };
            if !holdings.ignored_java.is_empty() {
                let star = files.as_ref().is_ok_and(|f| f.star.is_some());
                notes.push(ignored_note(&holdings.ignored_java, course, star));
            }
            Submission {
                id: safe,
                name,
                folder: holdings.folder.clone(),
                files,
                notes,
                warnings,
            }
        })
        .collect();
    settled.sort_by(|a, b| a.id.cmp(&b.id).then(a.name.cmp(&b.name)));
    settled
}

/// The copy of each wanted file to grade: one of that exact name before a near miss
/// (`Renderer (1).java`, taken with a warning), the one under the course's package folder
/// (`gfx/tick2/`, `tick1/`) first, else the one nearest the top; the others are noted.
fn choose(
    holdings: &Holdings,
    notes: &mut Vec<String>,
    warnings: &mut Vec<String>,
    course: Course,
) -> std::result::Result<Files, Refusal> {
    let mut chosen = Vec::new();
    let name_of = |f: &archive::Found| archive::wanted(f.path.rsplit(['/', '\\']).next()?);
    let package_folder = match course.is_default() {
        true => "gfx/tick2/",
        false => "tick1/",
    };
    // Tick 1*'s optional file, when the year has it (its skeleton ships the stub it replaces).
    let optional: &[&'static str] = match course.is_default() {
        true => &[],
        false => &archive::OPTIONAL,
    };
    let files = archive::submitted(course)
        .iter()
        .map(|w| (*w, true))
        .chain(optional.iter().map(|w| (*w, false)));
    let mut missing = Vec::new();
    for (wanted, required) in files {
        let mut copies: Vec<&archive::Found> = holdings
            .found
            .iter()
            .filter(|f| name_of(f).is_some_and(|(w, _)| w == wanted))
            .collect();
        copies.sort_by_key(|f| {
            let in_package = f.path.replace('\\', "/").contains(package_folder);
            let exact = name_of(f).is_some_and(|(_, exact)| exact);
            (
                !exact,
                !in_package,
                f.path.matches(['/', '\\']).count(),
                f.path.clone(),
            )
        });
        let Some(first) = copies.first() else {
            if required {
                missing.push(wanted);
            }
            continue;
        };
        if name_of(first).is_some_and(|(_, exact)| !exact) {
            warnings.push(format!(
                "{} was taken as {wanted}: name it {wanted} (the course's tester looks for that \
                 name and may not find this one)",
                first.path
            ));
        }
        for other in &copies[1..] {
            notes.push(format!(
                "{} also found at {}; {} graded",
                wanted, other.path, first.path
            ));
        }
        match &first.bytes {
            Ok(bytes) => chosen.push((wanted, bytes.clone())),
            Err(e) => {
                return Err(Refusal {
                    status: StudentStatus::NoFiles,
                    message: e.clone(),
                })
            }
        }
    }
    let package = match course.is_default() {
        true => None,
        false => declared_package(&chosen)?,
    };
    let theirs: Vec<(&str, &[u8])> = chosen.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    let bumpy = chosen.iter().any(|(name, _)| optional.contains(name));
    let star = match tick1_star::in_sources(package.as_deref(), &theirs) {
        // A Tick 1* file without the Tick 1 it extends is a hand-in of its option's file; so
        // is option 1's file alone whatever its package: no Tick 1 submission is a
        // BumpySphere alone.
        seen if !missing.is_empty() && (seen.is_some() || bumpy) => Some(StarSeen::HandIn),
        seen => seen,
    };
    if let Some(&first) = missing.first() {
        let handed: Vec<&str> = chosen.iter().map(|(name, _)| *name).collect();
        match star {
            Some(_) => notes.push(super::finished::note(&handed, &missing, course)),
            None => {
                return Err(Refusal {
                    status: StudentStatus::NoFiles,
                    message: no_files(first, &handed, course),
                })
            }
        }
    }
    // A BumpySphere.java is Tick 1*'s only in a Tick 1* submission; elsewhere it is the
    // skeleton's stub a whole project carries (2023-24's as shipped does not compile).
    if star.is_none() {
        let before = chosen.len();
        chosen.retain(|(name, _)| !optional.contains(name));
        if chosen.len() < before {
            notes.push(
                "BumpySphere.java: not graded (only a Tick 1* submission's is: a tick1star \
                 package, or a Renderer with SHADOW_RAY_COUNT or DOF_RAY_COUNT); the \
                 skeleton's is used"
                    .into(),
            );
        }
    }
    Ok(Files {
        sources: chosen,
        package,
        star,
        completed: missing,
    })
}

/// The package the submission's files declare: `Renderer.java`'s, else (a Tick 1* hand-in
/// of option 1's file alone) `BumpySphere.java`'s; None for the default package.
fn declared_package(
    chosen: &[(&'static str, Vec<u8>)],
) -> std::result::Result<Option<String>, Refusal> {
    let declaring = ["Renderer.java", "BumpySphere.java"]
        .iter()
        .find_map(|wanted| chosen.iter().find(|(name, _)| name == wanted));
    match declaring {
        None => Ok(None),
        Some((name, bytes)) => package::declared(bytes).map_err(|why| Refusal {
            status: StudentStatus::Error,
            message: format!("{name}: {why}"),
        }),
    }
}

/// Why a submission without `first` cannot be graded: a Tick 1 hand-in must be whole (only a
/// Tick 1* option's file alone is completed with whitted's finished Tick 1).
fn no_files(first: &str, handed: &[&str], course: Course) -> String {
    match (course.is_default(), handed) {
        (true, _) | (false, []) => format!("no {first} in the submission"),
        (false, _) => format!(
            "no {first} in the submission (it holds {} only): a Tick 1 submission is {}; a \
             Tick 1* hand-in of one file (BumpySphere.java, or a Renderer.java with \
             SHADOW_RAY_COUNT or DOF_RAY_COUNT, or in a tick1star package) is graded on \
             whitted's finished Tick 1",
            handed.join(", "),
            archive::submitted(course).join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_safe_file_names() {
        assert_eq!(safe_id("1234"), "1234");
        assert_eq!(safe_id("../etc"), ".._etc");
        assert_eq!(safe_id(".."), "__");
        assert_eq!(safe_id("a/b c"), "a_b_c");
        assert_eq!(safe_id(""), "_");
        assert_eq!(safe_id("é"), "_");
    }

    #[test]
    fn a_tick1_star_submission_s_note_says_its_bumpy_sphere_is_taken_too() {
        let names = std::collections::BTreeSet::from(["Tick1.java".to_string()]);
        let plain = ignored_note(&names, Course::Y2021, false);
        assert!(
            plain.contains("Only Plane.java, Renderer.java, Sphere.java are taken"),
            "{plain}"
        );
        let star = ignored_note(&names, Course::Y2021, true);
        assert!(
            star.contains(
                "Only Plane.java, Renderer.java, Sphere.java, BumpySphere.java are taken"
            ),
            "{star}"
        );
    }
}
