//! The folder names of Moodle's "Download all submissions": `Full Name_<id>_assignsubmission_file`
//! (Moodle 3.x adds a trailing `_`), `Participant_<id>_assignsubmission_file` under blind
//! marking, `<Group>_<groupid>_assignsubmission_file` for teams. docs/grade.md's pattern
//! `^(.+)_(\d+)_assignsubmission_([a-z]+)_?$`, matched by hand: it is one split from the right.
//! And the dates Moodle's worksheets write.

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

/// "Last modified (grade)" as Moodle writes it in its worksheets: `Wednesday, 2 December 2026,
/// 9:15 AM`, in UTC.
pub fn modified_now() -> String {
    let seconds = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    moodle_date(seconds)
}

/// `seconds` since 1970 (UTC) in Moodle's worksheet format.
fn moodle_date(seconds: u64) -> String {
    const DAYS: [&str; 7] = [
        "Thursday",
        "Friday",
        "Saturday",
        "Sunday",
        "Monday",
        "Tuesday",
        "Wednesday",
    ];
    const MONTHS: [&str; 12] = [
        "January",
        "February",
        "March",
        "April",
        "May",
        "June",
        "July",
        "August",
        "September",
        "October",
        "November",
        "December",
    ];
    let days = (seconds / 86_400) as i64;
    let (hour, minute) = ((seconds % 86_400) / 3600, (seconds % 3600) / 60);
    let (year, month, day) = whitted_core::calendar::civil_from_days(days);
    let (h12, half) = match hour {
        0 => (12, "AM"),
        1..=11 => (hour, "AM"),
        12 => (12, "PM"),
        _ => (hour - 12, "PM"),
    };
    format!(
        "{}, {day} {} {year}, {h12}:{minute:02} {half}",
        DAYS[days.rem_euclid(7) as usize],
        MONTHS[(month - 1) as usize]
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moodle_dates_are_civil_dates() {
        assert_eq!(moodle_date(0), "Thursday, 1 January 1970, 12:00 AM");
        // 2026-12-02 09:15 UTC.
        assert_eq!(
            moodle_date(1_796_202_900),
            "Wednesday, 2 December 2026, 9:15 AM"
        );
        // 2024-02-29 13:05 UTC, a leap day.
        assert_eq!(
            moodle_date(1_709_211_900),
            "Thursday, 29 February 2024, 1:05 PM"
        );
    }

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
