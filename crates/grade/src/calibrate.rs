//! `whitted grade -o OUTDIR --calibrate`: over a class already graded, how many students each
//! pair (channel tolerance, pixel allowance) would pass, and which diagnosed mistakes the
//! students it passes beyond the graded setting have, so that staff choose a tolerance with
//! the numbers in front of them. It reads the results alone (`beyond.rs`'s counts): no program
//! is run again. A result without the counts (written by an older whitted) is named and left
//! out, never guessed at.

use std::collections::BTreeMap;
use std::path::Path;

use super::beyond::CaseBeyond;
use super::result::{StudentResult, TestStatus};
use super::status::StudentStatus;
use whitted_check::check::pass_rule::{Allowance, PassRule, KEPT_TOLERANCES};
use whitted_core::error::{Error, Result};

/// The channel tolerances shown, in LSB (with the graded one).
const TOLERANCES: [u8; 7] = [0, 1, 2, 3, 4, 6, 8];

/// The allowances shown: pixels, then millionths of the image's pixels (with the graded one
/// and any `--max-beyond` given).
const PIXELS: [u64; 6] = [0, 5, 10, 20, 50, 100];
const PER_MILLION: [u64; 2] = [1_000, 10_000];

/// One student as the calibration sees them.
#[derive(Debug, Clone)]
pub struct Row {
    pub id: String,
    /// Whether every counted case passed as graded.
    pub passed_as_graded: bool,
    /// The top diagnosis' ids.
    pub diagnosis: Vec<String>,
    /// Per counted case, its counts; None for a student whose program never ran (a compile
    /// error, no files): they pass by no rule.
    pub cases: Option<Vec<CaseBeyond>>,
}

impl Row {
    /// Whether every counted case passes by `rule`.
    fn passes(&self, rule: PassRule) -> bool {
        self.cases
            .as_ref()
            .is_some_and(|cases| cases.iter().all(|c| c.passes(rule) == Some(true)))
    }
}

/// Why a result is left out.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Left {
    /// Graded by a whitted that kept no counts.
    NoCounts,
    /// Its counts do not match its cases, or lack a number: a file edited or cut.
    Inconsistent,
}

/// A result as a row, or why it cannot be one.
pub fn row(result: &StudentResult) -> std::result::Result<Row, Left> {
    let extra = &result.extra;
    let counted: Vec<bool> = result.tests.iter().map(|t| t.max_score > 0.0).collect();
    let passed_as_graded = extra.status == StudentStatus::Graded
        && !result.tests.is_empty()
        && result
            .tests
            .iter()
            .all(|t| t.max_score <= 0.0 || t.status == TestStatus::Passed);
    let cases = match (extra.status, &extra.beyond) {
        (StudentStatus::Graded, None) => return Err(Left::NoCounts),
        (StudentStatus::Graded, Some(beyond)) => {
            let consistent = beyond.len() == result.tests.len()
                && beyond.iter().zip(&result.tests).all(|(b, t)| {
                    b.case == t.name
                        && (b.status != "ok"
                            || (b.pixels.is_some()
                                && b.max_difference.is_some()
                                && b.beyond_at.len() == KEPT_TOLERANCES))
                });
            if !consistent {
                return Err(Left::Inconsistent);
            }
            let kept = beyond
                .iter()
                .zip(&counted)
                .filter(|(_, c)| **c)
                .map(|(b, _)| b.clone())
                .collect();
            Some(kept)
        }
        _ => None,
    };
    Ok(Row {
        id: extra.id.clone(),
        passed_as_graded,
        diagnosis: extra.diagnosis.clone(),
        cases,
    })
}

/// The calibration of the results in `outdir`, as text; `extra` adds an allowance's column
/// (`--max-beyond` given with `--calibrate`).
pub fn run(outdir: &Path, extra: Option<Allowance>) -> Result<String> {
    let students = outdir.join("students");
    let entries = std::fs::read_dir(&students).map_err(|e| {
        Error::io(
            &students,
            "cannot read the graded students (grade the class into OUTDIR first)",
            e,
        )
    })?;
    let mut ids: Vec<String> = entries
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    ids.sort();
    let mut rows = Vec::new();
    let mut graded_at = Vec::new();
    let mut left: Vec<(String, Left)> = Vec::new();
    for id in ids {
        let Some(result) = super::read_result(&students, &id) else {
            continue;
        };
        match row(&result) {
            Ok(r) => {
                graded_at.push((result.extra.tolerance, result.extra.allowance.clone()));
                rows.push(r);
            }
            Err(why) => left.push((id, why)),
        }
    }
    if rows.is_empty() {
        return Err(Error::Usage(format!(
            "--calibrate: no result in {} holds the counts it needs{}",
            students.display(),
            skipped_words(&left)
                .map(|w| format!(": {w}"))
                .unwrap_or_default()
        )));
    }
    let graded = most_common(&graded_at);
    let mut text = table(&rows, graded, extra);
    if let Some(words) = skipped_words(&left) {
        text += &format!("\n{words}\n");
    }
    Ok(text)
}

/// The setting most results were graded at, when it can be read.
fn most_common(graded_at: &[(u8, String)]) -> Option<PassRule> {
    let mut counts: BTreeMap<&(u8, String), usize> = BTreeMap::new();
    for g in graded_at {
        *counts.entry(g).or_default() += 1;
    }
    let ((tolerance, allowance), _) = counts.into_iter().max_by_key(|(_, n)| *n)?;
    Some(PassRule {
        tolerance: *tolerance,
        allowance: Allowance::parse(allowance).ok()?,
    })
}

/// The results left out, in words; None when none is.
fn skipped_words(left: &[(String, Left)]) -> Option<String> {
    let of = |kind: Left| -> Vec<&str> {
        left.iter()
            .filter(|(_, why)| *why == kind)
            .map(|(id, _)| id.as_str())
            .collect()
    };
    let mut lines = Vec::new();
    let old = of(Left::NoCounts);
    if !old.is_empty() {
        lines.push(format!(
            "left out, graded by an older whitted that kept no counts (grade them again with \
             --rerun all to count them): {}",
            old.join(", ")
        ));
    }
    let odd = of(Left::Inconsistent);
    if !odd.is_empty() {
        lines.push(format!(
            "left out, counts that do not match their cases: {}",
            odd.join(", ")
        ));
    }
    (!lines.is_empty()).then(|| lines.join("\n"))
}

/// The table of students passing per pair, and what each pair passes beyond the graded
/// setting.
pub fn table(rows: &[Row], graded: Option<PassRule>, extra: Option<Allowance>) -> String {
    let mut tolerances: Vec<u8> = TOLERANCES.to_vec();
    let mut allowances: Vec<Allowance> = PIXELS.iter().map(|&n| Allowance::Pixels(n)).collect();
    allowances.extend(PER_MILLION.iter().map(|&p| Allowance::PerMillion(p)));
    for a in graded.map(|g| g.allowance).into_iter().chain(extra) {
        allowances.push(a);
    }
    if let Some(g) = graded.filter(|g| usize::from(g.tolerance) < KEPT_TOLERANCES) {
        tolerances.push(g.tolerance);
    }
    tolerances.sort_unstable();
    tolerances.dedup();
    allowances.sort_by_key(|a| match *a {
        Allowance::Pixels(n) => (0, n),
        Allowance::PerMillion(p) => (1, p),
    });
    allowances.dedup();
    let graded_passing = rows.iter().filter(|r| r.passed_as_graded).count();
    let mut out = format!(
        "{} students with counts; as graded ({}), {graded_passing} pass every counted case\n\n",
        rows.len(),
        graded.map_or_else(|| "at several settings".to_string(), setting)
    );
    out += "students passing every counted case, per channel tolerance (rows, ±LSB) and pixels \
            allowed beyond it (columns, --max-beyond):\n";
    out += &format!("{:>6}", "");
    for a in &allowances {
        out += &format!("{:>8}", a.to_string());
    }
    out += "\n";
    // Per row and column, the students passing there who did not as graded (indices).
    let mut newly: Vec<Vec<Vec<usize>>> = Vec::new();
    for &tolerance in &tolerances {
        let mut cells = Vec::new();
        let mark = match graded.is_some_and(|g| g.tolerance == tolerance) {
            true => "*",
            false => " ",
        };
        out += &format!("{:>5}{mark}", format!("±{tolerance}"));
        for &allowance in &allowances {
            let rule = PassRule {
                tolerance,
                allowance,
            };
            let passing: Vec<usize> = (0..rows.len()).filter(|&i| rows[i].passes(rule)).collect();
            let here = match graded == Some(rule) {
                true => format!("{}*", passing.len()),
                false => passing.len().to_string(),
            };
            out += &format!("{here:>8}");
            cells.push(
                passing
                    .into_iter()
                    .filter(|&i| !rows[i].passed_as_graded)
                    .collect(),
            );
        }
        newly.push(cells);
        out += "\n";
    }
    out += "(* as graded)\n";
    let mut through = Vec::new();
    for (r, &tolerance) in tolerances.iter().enumerate() {
        for (c, &allowance) in allowances.iter().enumerate() {
            let here = &newly[r][c];
            let left = c > 0 && newly[r][c - 1] == *here;
            let above = r > 0 && newly[r - 1][c] == *here;
            if here.is_empty() || left || above {
                continue;
            }
            let students: Vec<&Row> = here.iter().map(|&i| &rows[i]).collect();
            let rule = PassRule {
                tolerance,
                allowance,
            };
            through.push(format!(
                "  {}: +{} ({}): {}",
                setting(rule),
                students.len(),
                mistakes(&students),
                ids(&students)
            ));
        }
    }
    if !through.is_empty() {
        out += "\nwhat a setting passes that the graded one does not (students, by their \
                diagnosis), where it changes: a setting not listed passes what the one to its \
                left or above it does:\n";
        out += &through.join("\n");
        out += "\n";
    }
    out
}

/// "±2, --max-beyond 10".
fn setting(rule: PassRule) -> String {
    format!("±{}, --max-beyond {}", rule.tolerance, rule.allowance)
}

/// Students named in a line of what a setting passes; the rest are counted.
const NAMED: usize = 5;

/// The first `NAMED` students' ids: "a, b and 3 more".
fn ids(rows: &[&Row]) -> String {
    let named: Vec<&str> = rows.iter().take(NAMED).map(|r| r.id.as_str()).collect();
    match rows.len().saturating_sub(NAMED) {
        0 => named.join(", "),
        more => format!("{} and {more} more", named.join(", ")),
    }
}

/// The diagnosed mistakes of `rows`, with how many students have each: "specular-gated 2,
/// no diagnosis 1".
fn mistakes(rows: &[&Row]) -> String {
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for r in rows {
        match r.diagnosis.is_empty() {
            true => *counts.entry("no diagnosis").or_default() += 1,
            false => {
                for id in &r.diagnosis {
                    *counts.entry(id.as_str()).or_default() += 1;
                }
            }
        }
    }
    let mut by_count: Vec<(&str, usize)> = counts.into_iter().collect();
    by_count.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
    by_count
        .iter()
        .map(|(id, n)| format!("{id} {n}"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(max: u8, beyond_at: [u64; KEPT_TOLERANCES]) -> CaseBeyond {
        CaseBeyond {
            case: "tick2.xml -b 2".into(),
            status: "ok".into(),
            pixels: Some(640 * 480),
            max_difference: Some(max),
            beyond_at: beyond_at.to_vec(),
        }
    }

    fn student(id: &str, passed: bool, diagnosis: &[&str], cases: Vec<CaseBeyond>) -> Row {
        Row {
            id: id.into(),
            passed_as_graded: passed,
            diagnosis: diagnosis.iter().map(|d| d.to_string()).collect(),
            cases: Some(cases),
        }
    }

    /// A class: one identical, one finished but 57 pixels beyond 2 (5 beyond 3), one with a
    /// 2-LSB mistake on thousands of pixels, one with a mistake of 27, one that never ran.
    fn class() -> Vec<Row> {
        vec![
            student("a", true, &[], vec![case(0, [0; 9])]),
            student(
                "b",
                false,
                &[],
                vec![case(0, [0; 9]), case(4, [200, 90, 57, 5, 0, 0, 0, 0, 0])],
            ),
            student(
                "c",
                true,
                &["specular-gated"],
                vec![case(2, [11000, 9000, 0, 0, 0, 0, 0, 0, 0])],
            ),
            student(
                "d",
                false,
                &["reflect-unclamped"],
                vec![case(
                    27,
                    [15000, 14000, 13000, 12000, 11000, 10000, 9000, 8000, 7000],
                )],
            ),
            Row {
                id: "e".into(),
                passed_as_graded: false,
                diagnosis: Vec::new(),
                cases: None,
            },
        ]
    }

    #[test]
    fn counts_the_students_each_pair_passes() {
        let rows = class();
        let at = |tolerance, allowance| {
            rows.iter()
                .filter(|r| {
                    r.passes(PassRule {
                        tolerance,
                        allowance,
                    })
                })
                .map(|r| r.id.as_str())
                .collect::<Vec<_>>()
        };
        assert_eq!(at(0, Allowance::Pixels(0)), ["a"]);
        assert_eq!(at(2, Allowance::Pixels(0)), ["a", "c"]);
        assert_eq!(at(2, Allowance::Pixels(50)), ["a", "c"]);
        assert_eq!(at(2, Allowance::Pixels(57)), ["a", "b", "c"]);
        assert_eq!(at(3, Allowance::Pixels(5)), ["a", "b", "c"]);
        assert_eq!(at(4, Allowance::Pixels(0)), ["a", "b", "c"]);
        // 1% of 307200 is 3072: 7000 beyond 8 is still too many.
        assert_eq!(at(8, Allowance::PerMillion(10_000)), ["a", "b", "c"]);
        assert_eq!(at(1, Allowance::PerMillion(10_000)), ["a", "b"]);
    }

    #[test]
    fn the_table_marks_the_graded_setting_and_names_what_looser_ones_pass() {
        let text = table(
            &class(),
            Some(PassRule::strict(2)),
            Some(Allowance::Pixels(57)),
        );
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            "5 students with counts; as graded (±2, --max-beyond 0), 2 pass every counted case"
        );
        let header = lines[3].split_whitespace().collect::<Vec<_>>();
        assert_eq!(
            header,
            ["0", "5", "10", "20", "50", "57", "100", "0.1%", "1%"]
        );
        let row = |t: &str| {
            lines
                .iter()
                .find(|l| l.trim_start().starts_with(t))
                .map(|l| l.split_whitespace().skip(1).collect::<Vec<_>>())
                .unwrap_or_default()
        };
        // 0.1% of the pixels lets b's 200 differing pixels through even at ±0.
        assert_eq!(row("±0 "), ["1", "1", "1", "1", "1", "1", "1", "2", "2"]);
        assert_eq!(row("±2*"), ["2*", "2", "2", "2", "2", "3", "3", "3", "3"]);
        assert_eq!(row("±4 "), ["3"; 9]);
        assert!(
            text.contains("  ±2, --max-beyond 57: +1 (no diagnosis 1): b"),
            "{text}"
        );
        assert!(
            text.contains("  ±0, --max-beyond 0.1%: +1 (no diagnosis 1): b"),
            "{text}"
        );
        // The same students as the setting to the left: not listed again.
        assert!(!text.contains("±2, --max-beyond 100:"), "{text}");
        assert!(
            !text.contains("reflect-unclamped"),
            "no setting shown passes a mistake of 27: {text}"
        );
    }

    #[test]
    fn a_result_without_counts_is_left_out_and_named() {
        let words = skipped_words(&[
            ("old".into(), Left::NoCounts),
            ("cut".into(), Left::Inconsistent),
        ])
        .expect("words");
        assert!(
            words.contains("older whitted") && words.contains(": old"),
            "{words}"
        );
        assert!(words.contains("do not match their cases: cut"), "{words}");
        assert_eq!(skipped_words(&[]), None);
    }
}
