//! `whitted diff A B`: layer-aware numeric comparison for regression tests. Exit 0 when every
//! compared layer is within tolerance, 1 when not, 2 when the files cannot be compared.

use serde_json::json;

use crate::cli::DiffArgs;
use crate::compare::{compare, excess_map, LayerReport, Tolerance};
use crate::error::{Error, Result};
use crate::input::{self, Image};
use crate::numbers::compact as number;
use crate::output::destination::{refuse_clashes, Destination};
use crate::output::png::{PngImage, PngPixels};
use crate::output::stdout;

/// Returns whether the images match.
pub fn run(args: &DiffArgs) -> Result<bool> {
    let tolerance = Tolerance {
        abs: args.abs,
        rel: args.rel,
    };
    if let Some(heatmap) = &args.heatmap {
        refuse_clashes(&[&args.actual, &args.reference], &[heatmap])?;
    }
    let mut heatmap = args.heatmap.as_deref().map(Destination::open).transpose()?;
    let actual = input::read(&args.actual)?;
    let reference = input::read(&args.reference)?;
    if actual.format != reference.format {
        return Err(Error::Usage(format!(
            "cannot compare a {:?} with a {:?}: give two EXRs or two PNGs",
            actual.format, reference.format
        )));
    }
    let reports = compare(&actual, &reference, &args.layers, tolerance).map_err(|msg| {
        Error::Usage(format!(
            "{} vs {}: {msg}",
            args.actual.display(),
            args.reference.display()
        ))
    })?;
    let passed = reports.iter().all(LayerReport::passed);
    if let Some(out) = heatmap.as_mut() {
        let map = excess_map(&actual, &reference, &args.layers, tolerance);
        out.write_png(&heat_png(&map, reference.width, reference.height))?;
    }
    if let Some(out) = heatmap {
        out.commit()?;
    }
    let text = if args.json {
        serde_json::to_string_pretty(&to_json(args, &reference, &reports, passed))
            .unwrap_or_default()
    } else {
        table(args, &reference, &reports, passed)
    };
    stdout::print_line(&text)?;
    Ok(passed)
}

/// Black where equal, blue within tolerance, red to yellow past it (log scale up to 1000x).
fn heat_png(excess: &[f64], width: usize, height: usize) -> PngImage {
    let bytes = excess
        .iter()
        .flat_map(|&e| {
            if e == 0.0 {
                [0, 0, 0]
            } else if e <= 1.0 {
                [0, 0, (60.0 + 120.0 * e) as u8]
            } else {
                let t = (e.log10() / 3.0).clamp(0.0, 1.0);
                [255, (255.0 * t) as u8, 0]
            }
        })
        .collect();
    PngImage {
        width: u32::try_from(width).unwrap_or(u32::MAX),
        height: u32::try_from(height).unwrap_or(u32::MAX),
        pixels: PngPixels::Eight(bytes),
        srgb: true,
    }
}

fn psnr_text(psnr: f64) -> String {
    if psnr.is_infinite() {
        "inf".into()
    } else {
        format!("{psnr:.1}")
    }
}

fn table(args: &DiffArgs, reference: &Image, reports: &[LayerReport], passed: bool) -> String {
    let mut out = format!(
        "{} vs {} ({}x{}), a value fails when |a - b| > {} + {} * |b|\n\n",
        args.actual.display(),
        args.reference.display(),
        reference.width,
        reference.height,
        args.abs,
        args.rel
    );
    out += &format!(
        "{:<18} {:>12} {:>12} {:>9} {:>9}  first failing pixels (x, y)\n",
        "layer", "max abs", "RMSE", "PSNR dB", "failing"
    );
    for r in reports {
        let first: Vec<String> = r
            .first_failing
            .iter()
            .map(|(x, y)| format!("({x}, {y})"))
            .collect();
        out += &format!(
            "{:<18} {:>12} {:>12} {:>9} {:>9}  {}\n",
            r.layer,
            number(r.max_abs),
            number(r.rmse),
            psnr_text(r.psnr),
            r.failing,
            first.join(" ")
        );
    }
    let differing = reports.iter().filter(|r| !r.passed()).count();
    out += &if passed {
        format!("\nPASS: all {} layers within tolerance", reports.len())
    } else {
        format!("\nFAIL: {differing} of {} layers differ", reports.len())
    };
    out
}

fn to_json(
    args: &DiffArgs,
    reference: &Image,
    reports: &[LayerReport],
    passed: bool,
) -> serde_json::Value {
    let layers: Vec<serde_json::Value> = reports
        .iter()
        .map(|r| {
            json!({
                "layer": r.layer,
                "channels": r.channels,
                "max_abs": finite_or_null(r.max_abs),
                "rmse": finite_or_null(r.rmse),
                "psnr": finite_or_null(r.psnr),
                "failing": r.failing,
                "first_failing": r.first_failing.iter().map(|&(x, y)| json!([x, y])).collect::<Vec<_>>(),
                "passed": r.passed(),
            })
        })
        .collect();
    json!({
        "a": args.actual.display().to_string(),
        "b": args.reference.display().to_string(),
        "width": reference.width,
        "height": reference.height,
        "abs": args.abs,
        "rel": args.rel,
        "passed": passed,
        "layers": layers,
    })
}

/// JSON has no infinity: identical layers have PSNR `null`.
fn finite_or_null(v: f64) -> serde_json::Value {
    if v.is_finite() {
        json!(v)
    } else {
        serde_json::Value::Null
    }
}
