//! The printers of a check's one result (`result.rs`): the text a student reads in a terminal
//! (one screen by default, everything with `--verbose`), the JSON (`--json`), and the HTML
//! page (`--report x.html`, and `grade`'s student pages through the same pieces). Each only
//! formats what the result holds; the words themselves are `summary.rs`'s and `words.rs`'s.

pub mod html;
pub mod html_star;
pub mod json;
pub mod screen;
pub mod text;
pub mod zoom;

use std::path::Path;

use crate::check::report::{contact_sheet, ReportRow};
use crate::check::result::CheckResult;
use whitted_core::error::Result;
use whitted_io::output::destination::Destination;

/// What `--report FILE` writes, by the file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReportFormat {
    /// The page `grade` writes for a student: one self-contained file, images inline.
    Html,
    /// The contact sheet: one row of images per failing case.
    Png,
}

impl ReportFormat {
    /// The format `path`'s extension names (`.html`, `.htm`, `.png`, in any case), or None.
    pub fn of(path: &Path) -> Option<ReportFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "html" | "htm" => Some(ReportFormat::Html),
            "png" => Some(ReportFormat::Png),
            _ => None,
        }
    }
}

/// Writes `result` into `out` in the format its name asks for (the command line refuses any
/// other name; one it did not see is written as the sheet). Nothing is visible before `out`
/// is committed.
pub fn write_report(out: &mut Destination, result: &CheckResult) -> Result<()> {
    match ReportFormat::of(&out.path()) {
        Some(ReportFormat::Html) => out.write_bytes(html::page(result).as_bytes()),
        Some(ReportFormat::Png) | None => out.write_png(&contact_sheet(&sheet_rows(result))),
    }
}

/// The contact sheet's rows: the image checked, or each failing case that wrote one.
fn sheet_rows(result: &CheckResult) -> Vec<ReportRow> {
    let single = result.image().is_some();
    result
        .cases
        .iter()
        .filter(|c| single || !c.passed())
        .filter_map(|c| {
            c.report()
                .map(|r| ReportRow::of(&c.name, r, &result.findings))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_s_format_follows_its_extension() {
        let of = |name: &str| ReportFormat::of(Path::new(name));
        assert_eq!(of("r.html"), Some(ReportFormat::Html));
        assert_eq!(of("dir/R.HTM"), Some(ReportFormat::Html));
        assert_eq!(of("r.png"), Some(ReportFormat::Png));
        for refused in ["r", "r.pdf", "html", "r.html.txt", "-"] {
            assert_eq!(of(refused), None, "{refused}");
        }
    }
}
