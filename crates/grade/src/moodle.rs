//! The folder names of Moodle's "Download all submissions": `Full Name_<id>_assignsubmission_file`
//! (Moodle 3.x adds a trailing `_`), `Participant_<id>_assignsubmission_file` under blind
//! marking, `<Group>_<groupid>_assignsubmission_file` for teams. docs/grade.md's pattern
//! `^(.+)_(\d+)_assignsubmission_([a-z]+)_?$`, matched by hand: it is one split from the right.

/// A folder's student: the name as Moodle wrote it, and the id grades go back by.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Folder {
    pub name: String,
    pub id: String,
    /// Moodle's submission plugin: `file` for uploaded files; `onlinetext`, `comments` and
    /// the like hold no files to grade.
    pub plugin: String,
}

impl Folder {
    /// Whether the folder holds the student's uploaded files.
    pub fn is_files(&self) -> bool {
        self.plugin == "file"
    }
}

/// The student of a Moodle folder name, or None for a name of another shape.
pub fn parse(folder: &str) -> Option<Folder> {
    let folder = folder.strip_suffix('_').unwrap_or(folder);
    let (head, plugin) = folder.rsplit_once("_assignsubmission_")?;
    if plugin.is_empty() || !plugin.bytes().all(|b| b.is_ascii_lowercase()) {
        return None;
    }
    let (name, id) = head.rsplit_once('_')?;
    if name.is_empty() || id.is_empty() || !id.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(Folder {
        name: name.to_string(),
        id: id.to_string(),
        plugin: plugin.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str, id: &str) -> Option<Folder> {
        Some(Folder {
            name: name.into(),
            id: id.into(),
            plugin: "file".into(),
        })
    }

    #[test]
    fn moodle_folder_names_give_the_id() {
        assert_eq!(
            parse("Ada Lovelace_1234_assignsubmission_file"),
            folder("Ada Lovelace", "1234")
        );
        // Moodle 3.x's trailing underscore, blind marking, teams, onlinetext.
        assert_eq!(
            parse("Ada Lovelace_1234_assignsubmission_file_"),
            folder("Ada Lovelace", "1234")
        );
        assert_eq!(
            parse("Participant_987654_assignsubmission_file_"),
            folder("Participant", "987654")
        );
        let online = parse("Team_Rocket_55_assignsubmission_onlinetext").expect("a folder");
        assert_eq!(
            (online.name.as_str(), online.id.as_str()),
            ("Team_Rocket", "55")
        );
        assert!(!online.is_files());
        // A name with underscores and digits of its own keeps them.
        assert_eq!(
            parse("Jo_2_Smith_77_assignsubmission_file"),
            folder("Jo_2_Smith", "77")
        );
        for other in [
            "ada",
            "Ada_12_assignsubmission_",
            "Ada_x1_assignsubmission_file",
            "_12_assignsubmission_file",
            "Ada_12_assignsubmission_File",
            "Ada__assignsubmission_file",
        ] {
            assert_eq!(parse(other), None, "{other}");
        }
    }
}
