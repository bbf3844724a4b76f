//! `whitted diff A B`: layer-aware numeric comparison for regression tests. Exit 0 when every
//! part and layer passes (with or without warnings), 1 when not, 2 when the files cannot be
//! compared. (`idiff` uses 1 for warnings and 2 for failures; ours keeps 2 for "cannot
//! compare", like `diff(1)` and `cmp(1)`.)

use serde_json::json;

use crate::cli::DiffArgs;
use whitted_core::error::{Error, Result};
use whitted_core::numbers::{compact as number, finite_or_null};
use whitted_io::compare::{align, compare_files, excess_map, matching_part, PartReport};
use whitted_io::input;
use whitted_io::output::destination::{refuse_clashes, Destination};
use whitted_io::output::png::{PngImage, PngPixels};
use whitted_io::output::stdout;

/// Returns whether the images match.
pub fn run(args: &DiffArgs) -> Result<bool> {
    let criteria = args.criteria();
    if let Some(heatmap) = &args.heatmap {
        refuse_clashes(&[&args.actual, &args.reference], &[heatmap])?;
    }
    let mut heatmap = args.heatmap.as_deref().map(Destination::open).transpose()?;
    let actual = input::read_parts(&args.actual)?;
    let reference = input::read_parts(&args.reference)?;
    let cannot = |msg: String| {
        Error::Usage(format!(
            "{} vs {}: {msg}",
            args.actual.display(),
            args.reference.display()
        ))
    };
    let reports = compare_files(&actual, &reference, &args.layers, criteria).map_err(cannot)?;
    let passed = reports.iter().all(PartReport::passed);
    if let Some(out) = heatmap.as_mut() {
        // The reference's first part and the part it was compared with, on the grid both
        // share.
        let b = reference
            .first()
            .ok_or_else(|| cannot("the reference has no parts".into()))?;
        let a = matching_part(&actual, 0, b).map_err(cannot)?;
        let aligned = align(a, b).map_err(cannot)?;
        let (a, b) = (&aligned.actual, &aligned.reference);
        let map = excess_map(a, b, &args.layers, criteria.tolerance);
        out.write_png(&heat_png(&map, b.width, b.height))?;
    }
    if let Some(out) = heatmap {
        out.commit()?;
    }
    let text = if args.json {
        // serde_json cannot fail to print a Value it built itself.
        serde_json::to_string_pretty(&to_json(args, &reports, passed)).unwrap_or_default()
    } else {
        table(args, &reports, passed)
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

fn table(args: &DiffArgs, parts: &[PartReport], passed: bool) -> String {
    let mut out = format!(
        "{} vs {}, a value fails when |a - b| > {} + {} * |b|\n",
        args.actual.display(),
        args.reference.display(),
        args.abs,
        args.rel
    );
    for part in parts {
        out += &format!("\npart {} ({}x{})\n", part.part, part.width, part.height);
        if let Some((a, b)) = part.moved {
            out += &format!("data windows differ: {a} vs {b} (the image moved)\n");
        }
        out += &format!(
            "{:<18} {:>12} {:>12} {:>9} {:>9} {:>9}  first failing pixels (x, y)\n",
            "layer", "max abs", "RMSE", "PSNR dB", "failing", "warnings"
        );
        for r in &part.layers {
            let first: Vec<String> = r
                .first_failing
                .iter()
                .map(|(x, y)| format!("({x}, {y})"))
                .collect();
            out += &format!(
                "{:<18} {:>12} {:>12} {:>9} {:>9} {:>9}  {}{}\n",
                r.layer,
                number(r.max_abs),
                number(r.rmse),
                psnr_text(r.psnr),
                r.failing,
                r.warnings,
                if r.passed { "" } else { "FAIL " },
                first.join(" ")
            );
        }
    }
    let layers: usize = parts.iter().map(|p| p.layers.len()).sum();
    let differing: usize = parts
        .iter()
        .map(|p| p.layers.iter().filter(|l| !l.passed).count())
        .sum();
    let moved = parts.iter().filter(|p| p.moved.is_some()).count();
    let warnings: usize = parts.iter().map(PartReport::warnings).sum();
    out += &if passed && warnings > 0 {
        format!("\nPASS with {warnings} warnings: all {layers} layers within tolerance")
    } else if passed {
        format!("\nPASS: all {layers} layers within tolerance")
    } else if differing == 0 {
        format!("\nFAIL: {moved} parts moved (their data windows differ)")
    } else {
        format!("\nFAIL: {differing} of {layers} layers differ")
    };
    out
}

fn to_json(args: &DiffArgs, parts: &[PartReport], passed: bool) -> serde_json::Value {
    let window = |w: input::Window| json!({ "min": w.min, "max": w.max });
    let parts: Vec<serde_json::Value> = parts
        .iter()
        .map(|part| {
            let layers: Vec<serde_json::Value> = part
                .layers
                .iter()
                .map(|r| {
                    json!({
                        "layer": r.layer,
                        "channels": r.channels,
                        "max_abs": finite_or_null(r.max_abs),
                        "rmse": finite_or_null(r.rmse),
                        "psnr": finite_or_null(r.psnr),
                        "pixels": r.pixels,
                        "failing": r.failing,
                        "warnings": r.warnings,
                        "hard_failures": r.hard_failures,
                        "first_failing": r.first_failing.iter().map(|&(x, y)| json!([x, y])).collect::<Vec<_>>(),
                        "passed": r.passed,
                    })
                })
                .collect();
            json!({
                "part": part.part,
                "width": part.width,
                "height": part.height,
                "data_windows": part.moved.map(|(a, b)| json!([window(a), window(b)])),
                "passed": part.passed(),
                "layers": layers,
            })
        })
        .collect();
    let first = parts.first().cloned().unwrap_or_default();
    json!({
        "a": args.actual.display().to_string(),
        "b": args.reference.display().to_string(),
        "width": first["width"],
        "height": first["height"],
        "abs": args.abs,
        "rel": args.rel,
        "fail_percent": args.fail_percent,
        "allow_failures": args.allow_failures,
        "hard_fail": args.hard_fail,
        "warn": args.warn,
        "passed": passed,
        "layers": first["layers"],
        "parts": parts,
    })
}
