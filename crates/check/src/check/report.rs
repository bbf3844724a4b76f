//! What a student sees rather than reads: a heat map of where their image differs, and a
//! contact sheet with one row per failing case (their image, the reference, the heat map and
//! a caption with the case, the verdict and the top diagnosis).

use crate::check::bump::PIXEL_TOLERANCE;
use crate::check::difference::pixel_difference;
use crate::check::program::{CaseOutcome, RunStatus, SuiteRun};
use crate::check::star_run::StarImage;
use crate::check::student_png::Rgb8;
use crate::check::summary::{fits, largest};
use crate::check::{CaseReport, Findings};
use whitted_io::canvas::{wrap, Canvas, LINE_HEIGHT};
use whitted_io::output::png::{PngImage, PngPixels};

/// The colour of a pixel `d` LSB off: black when equal, blue within the tolerance, then red
/// to yellow on a log scale up to 255.
fn heat(d: u8, tolerance: u8) -> [u8; 3] {
    if d == 0 {
        return [0, 0, 0];
    }
    if d <= tolerance {
        return [40, 80, 255];
    }
    let t = (f64::from(d).ln() / 255f64.ln()).clamp(0.0, 1.0);
    [255, (255.0 * t) as u8, 0]
}

fn heat_pixels(student: &Rgb8, reference: &Rgb8, tolerance: u8) -> Vec<[u8; 3]> {
    (0..student.bytes.len() / 3)
        .map(|i| {
            heat(
                pixel_difference(&student.bytes, &reference.bytes, i),
                tolerance,
            )
        })
        .collect()
}

/// The heat map as a PNG of the images' size.
pub fn heat_map(student: &Rgb8, reference: &Rgb8, tolerance: u8) -> PngImage {
    PngImage {
        width: student.width,
        height: student.height,
        pixels: PngPixels::Eight(
            heat_pixels(student, reference, tolerance)
                .into_iter()
                .flatten()
                .collect(),
        ),
        srgb: false,
    }
}

/// One row of the contact sheet.
pub struct ReportRow {
    pub caption: Vec<String>,
    pub tiles: [Canvas; 3],
}

/// Tiles are at most this wide; larger images are shown reduced (nearest pixel).
const TILE_WIDTH: usize = 320;

fn tile(width: u32, height: u32, pixel: impl Fn(u32, u32) -> [u8; 3]) -> Canvas {
    let step = (width as usize).div_ceil(TILE_WIDTH).max(1);
    let (w, h) = (width as usize / step, height as usize / step);
    let mut canvas = Canvas::new(w.max(1), h.max(1), [0; 3]);
    for y in 0..h {
        for x in 0..w {
            canvas.pixels[y * w + x] = pixel((x * step) as u32, (y * step) as u32);
        }
    }
    canvas
}

impl ReportRow {
    /// The row of one case, captioned with its part of the suite's `findings`.
    pub fn of(case_name: &str, case: &CaseReport, findings: &Findings) -> Self {
        let d = &case.difference;
        let heat = heat_pixels(
            &case.student,
            &case.reference,
            case.difference.rule.tolerance,
        );
        let width = case.student.width;
        let tiles = [
            tile(width, case.student.height, |x, y| case.student.pixel(x, y)),
            tile(width, case.student.height, |x, y| {
                case.reference.pixel(x, y)
            }),
            tile(width, case.student.height, |x, y| {
                heat[y as usize * width as usize + x as usize]
            }),
        ];
        let mut caption = vec![
            format!("{case_name}: {}", crate::check::words::verdict_name(case)),
            format!("{} pixels differ, {}", d.differing_pixels, largest(d)),
        ];
        // What explains most first: the best fit beyond the catalogue when the catalogue
        // explains little.
        let weak = findings.weak();
        if weak {
            caption.extend(fits(findings).into_iter().take(1));
        }
        match case.diagnosis.first() {
            Some(top) => {
                caption.push(format!(
                    "{}looks like {} ({:.0}% explained)",
                    if weak { "weakly " } else { "" },
                    top.mistakes.ids().join(" + "),
                    100.0 * top.explained
                ));
                caption.extend(
                    top.mistakes
                        .bugs()
                        .iter()
                        .flat_map(|b| b.advice(top.course)),
                );
            }
            None => caption.push("no catalogued mistake fits".into()),
        }
        ReportRow { caption, tiles }
    }
}

impl ReportRow {
    /// The row of a Tick 1* option's case: its image whatever the verdict (a random image is
    /// not seen again by running the program again), and beside it the render it was
    /// compared with and where they differ when the verdict has one (option 1's handout
    /// method), else blank tiles; captioned with the option and its verdict, as
    /// `print/html_star.rs` heads its block.
    pub fn of_star(case_name: &str, star: &StarImage) -> Self {
        let shown = &star.image;
        let (w, h) = (shown.width, shown.height);
        let blank = || tile(w, h, |_, _| [0; 3]);
        let [reference, heat] = match &star.reference {
            Some(reference) if reference.width == w && reference.height == h => {
                let heat = heat_pixels(shown, reference, PIXEL_TOLERANCE);
                [
                    tile(w, h, |x, y| reference.pixel(x, y)),
                    tile(w, h, |x, y| heat[y as usize * w as usize + x as usize]),
                ]
            }
            _ => [blank(), blank()],
        };
        ReportRow {
            caption: vec![
                format!("{case_name}: {}", star.option.what()),
                star.verdict.line(),
            ],
            tiles: [tile(w, h, |x, y| shown.pixel(x, y)), reference, heat],
        }
    }
}

/// The rows of a `--program` run's failing cases, in suite order.
pub fn failing_rows(run: &SuiteRun, shown: impl Fn(&CaseOutcome) -> bool) -> Vec<ReportRow> {
    run.cases
        .iter()
        .filter(|c| shown(c))
        .filter_map(|c| match &c.status {
            RunStatus::Ok(case) if !case.difference.verdict.passes() => {
                Some(ReportRow::of(&c.name, case, &run.findings))
            }
            _ => None,
        })
        .collect()
}

/// Rows of [student | reference | heat map], each with its caption below.
pub fn contact_sheet(rows: &[ReportRow]) -> PngImage {
    const GAP: usize = 8;
    let tile_width = rows
        .iter()
        .flat_map(|r| r.tiles.iter().map(|t| t.width))
        .max()
        .unwrap_or(TILE_WIDTH);
    let width = 3 * tile_width + 4 * GAP;
    let heading = ["your image", "reference", "difference"];
    // Captions wrap at the sheet's width: a fix's line of code is read whole, never cut.
    let caption = |r: &ReportRow| -> Vec<String> {
        r.caption
            .iter()
            .flat_map(|text| wrap(text, width - 2 * GAP))
            .collect()
    };
    let row_height =
        |r: &ReportRow| r.tiles[0].height + (caption(r).len() + 1) * LINE_HEIGHT + 2 * GAP;
    let height = GAP
        + LINE_HEIGHT
        + rows
            .iter()
            .map(row_height)
            .sum::<usize>()
            .max(LINE_HEIGHT * 2);
    let mut sheet = Canvas::new(width, height, [24, 24, 24]);
    for (i, h) in heading.iter().enumerate() {
        sheet.text(GAP + i * (tile_width + GAP), GAP, h, [200, 200, 200]);
    }
    let mut y = GAP + LINE_HEIGHT + GAP;
    if rows.is_empty() {
        sheet.text(GAP, y, "every case passes", [120, 220, 120]);
    }
    for row in rows {
        for (i, t) in row.tiles.iter().enumerate() {
            sheet.blit(GAP + i * (tile_width + GAP), y, t);
        }
        let mut line = y + row.tiles[0].height + GAP / 2;
        for text in caption(row) {
            sheet.text(GAP, line, &text, [235, 235, 235]);
            line += LINE_HEIGHT;
        }
        y += row_height(row);
    }
    let mut png = sheet.into_png();
    png.srgb = false;
    png
}
