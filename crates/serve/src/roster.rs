//! The class list `--roster FILE` gives: a CSV with a header row, as Moodle's participants
//! export and its grading worksheet are, whose id column is found by its name (names and
//! emails taken where the file has them); or a plain list, one id a line. Ids are kept as the
//! class lists them, minus the `Participant ` Moodle's worksheet puts before its number, so
//! that the worksheet exported later goes back to the same rows.

use whitted_core::error::{Error, Result};

/// One student of the roster.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Member {
    pub id: String,
    pub name: String,
    pub email: String,
}

/// The headers an id column may have, most specific first (compared without case).
const ID_HEADERS: [&str; 8] = [
    "identifier",
    "id number",
    "idnumber",
    "username",
    "crsid",
    "user id",
    "student id",
    "id",
];

/// The longest id taken: an id names a folder and a URL, never a paragraph.
const MAX_ID: usize = 64;

/// The members `text` lists, in its order, each id once; `origin` names the file in errors.
pub fn parse(origin: &str, text: &str) -> Result<Vec<Member>> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    let members = match first.contains([',', ';', '\t']) || is_header(first) {
        true => table(origin, text)?,
        false => text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'))
            .map(|id| Member {
                id: id.to_string(),
                name: String::new(),
                email: String::new(),
            })
            .collect(),
    };
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for member in members {
        check_id(origin, &member.id)?;
        if seen.insert(member.id.clone()) {
            out.push(member);
        }
    }
    if out.is_empty() {
        return Err(Error::Usage(format!(
            "{origin}: the roster lists no student"
        )));
    }
    Ok(out)
}

fn is_header(line: &str) -> bool {
    let line = line.trim().to_ascii_lowercase();
    ID_HEADERS.contains(&line.as_str())
}

/// An id is printable ASCII without spaces or separators: it stands in folder names and URLs.
fn check_id(origin: &str, id: &str) -> Result<()> {
    let ok = !id.is_empty()
        && id.len() <= MAX_ID
        && id
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_.@".contains(&b))
        && !id.starts_with('.');
    match ok {
        true => Ok(()),
        false => Err(Error::Usage(format!(
            "{origin}: `{id}` is not an id whitted takes (letters, digits, `-_.@`, at most \
             {MAX_ID} characters)"
        ))),
    }
}

/// A CSV (or `;`/tab separated) table with a header row.
fn table(origin: &str, text: &str) -> Result<Vec<Member>> {
    let first = text.lines().next().unwrap_or("");
    let delimiter = [b',', b';', b'\t']
        .into_iter()
        .max_by_key(|d| first.bytes().filter(|b| b == d).count())
        .unwrap_or(b',');
    let mut reader = csv::ReaderBuilder::new()
        .delimiter(delimiter)
        .flexible(true)
        .from_reader(text.as_bytes());
    let headers: Vec<String> = reader
        .headers()
        .map_err(|e| Error::Usage(format!("{origin}: cannot read the header row: {e}")))?
        .iter()
        .map(|h| h.trim().to_ascii_lowercase())
        .collect();
    let column = |names: &[&str]| {
        names
            .iter()
            .find_map(|n| headers.iter().position(|h| h == n))
    };
    let Some(id) = column(&ID_HEADERS) else {
        return Err(Error::Usage(format!(
            "{origin}: no id column in the header (one of: {})",
            ID_HEADERS.join(", ")
        )));
    };
    let full = column(&["full name", "name"]);
    let (first_name, last_name) = (column(&["first name"]), column(&["last name", "surname"]));
    let email = column(&["email address", "email"]);
    let mut members = Vec::new();
    for (row, record) in reader.records().enumerate() {
        let record = record.map_err(|e| Error::Usage(format!("{origin}: row {}: {e}", row + 2)))?;
        let cell = |i: Option<usize>| i.and_then(|i| record.get(i)).unwrap_or("").trim();
        let raw = cell(Some(id));
        if raw.is_empty() {
            continue;
        }
        let id = raw.strip_prefix("Participant ").unwrap_or(raw).to_string();
        let name = match full {
            Some(_) => cell(full).to_string(),
            None => format!("{} {}", cell(first_name), cell(last_name))
                .trim()
                .to_string(),
        };
        members.push(Member {
            id,
            name,
            email: cell(email).to_string(),
        });
    }
    Ok(members)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moodles_grading_worksheet_gives_ids_names_and_emails() {
        let text = "\u{feff}Identifier,Full name,Email address,Status,Grade\n\
                    Participant 1201,Ada Lovelace,al1@cam.ac.uk,Submitted,\n\
                    Participant 1202,\"Turing, Alan\",at2@cam.ac.uk,,\n";
        let members = parse("w.csv", text).expect("parsed");
        assert_eq!(
            members,
            vec![
                Member {
                    id: "1201".into(),
                    name: "Ada Lovelace".into(),
                    email: "al1@cam.ac.uk".into()
                },
                Member {
                    id: "1202".into(),
                    name: "Turing, Alan".into(),
                    email: "at2@cam.ac.uk".into()
                },
            ]
        );
    }

    #[test]
    fn a_participants_export_finds_its_id_column_by_name_wherever_it_is() {
        let text = "First name;Last name;ID number;Email address\nGrace;Hopper;gh7;\n";
        let members = parse("p.csv", text).expect("parsed");
        assert_eq!(members[0].id, "gh7");
        assert_eq!(members[0].name, "Grace Hopper");
        assert_eq!(members[0].email, "");
    }

    #[test]
    fn one_id_a_line_with_blanks_comments_and_repeats() {
        let members = parse("ids.txt", "ab123\n\n# late joiners\ncd456\r\nab123\n").expect("ok");
        let ids: Vec<&str> = members.iter().map(|m| m.id.as_str()).collect();
        assert_eq!(ids, ["ab123", "cd456"]);
        let with_header = parse("ids.txt", "crsid\nef789\n").expect("ok");
        assert_eq!(with_header[0].id, "ef789");
    }

    #[test]
    fn a_table_without_an_id_column_an_empty_list_and_hostile_ids_are_refused() {
        let no_id = parse("x.csv", "Full name,Email address\nA,b@c\n").unwrap_err();
        assert!(no_id.to_string().contains("no id column"), "{no_id}");
        assert!(parse("e.txt", "\n\n").is_err());
        for id in ["../etc", "a b", ".hidden", "x/y", &"a".repeat(65)] {
            assert!(parse("h.txt", &format!("{id}\n")).is_err(), "{id}");
        }
    }
}
