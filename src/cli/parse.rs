//! Parsers for option values: syntax and plain ranges, with messages that say what was
//! expected. Checks that depend on other options or on the scene are the plan's.

use super::MAX_THREADS;
use whitted_check::check::pass_rule::Allowance;
use whitted_core::frame::{limits, Region};

/// A whole number, or the message saying that `what` was expected.
fn whole(s: &str, what: &str) -> Result<i64, String> {
    s.trim()
        .parse()
        .map_err(|_| format!("expected a whole number of {what}, got `{s}`"))
}

pub(super) fn parse_bounces(s: &str) -> Result<u32, String> {
    limits::bounces(whole(s, "bounces")?)
}

pub(super) fn parse_side(s: &str) -> Result<u32, String> {
    limits::side(whole(s, "pixels")?)
}

pub(super) fn parse_spp(s: &str) -> Result<u32, String> {
    limits::samples(whole(s, "samples")?)
}

pub(super) fn parse_exposure(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(ev) if ev.is_finite() && ev.abs() <= 64.0 => Ok(ev),
        _ => Err(format!(
            "expected an exposure in stops between -64 and 64, got `{s}`"
        )),
    }
}

pub(super) fn parse_region(s: &str) -> Result<Region, String> {
    let numbers: Vec<u32> = s
        .split(',')
        .map(|n| n.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("expected X0,Y0,X1,Y1 in whole pixels, got `{s}`"))?;
    match numbers[..] {
        [x0, y0, x1, y1] if x0 < x1 && y0 < y1 => Ok(Region { x0, y0, x1, y1 }),
        [_, _, _, _] => Err(format!("the region `{s}` is empty (X0 < X1 and Y0 < Y1)")),
        _ => Err(format!("expected four numbers X0,Y0,X1,Y1, got `{s}`")),
    }
}

/// `--max-beyond`: `N` pixels or `P%` of the image's pixels (`pass_rule.rs`).
pub(super) fn parse_allowance(s: &str) -> Result<Allowance, String> {
    Allowance::parse(s)
}

pub(super) fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(t),
        _ => Err(format!("expected a tolerance >= 0, got `{s}`")),
    }
}

pub(super) fn parse_percent(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(p) if (0.0..=100.0).contains(&p) => Ok(p),
        _ => Err(format!("expected a percentage from 0 to 100, got `{s}`")),
    }
}

pub(super) fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let values: Vec<u32> = s
        .split(',')
        .map(|n| n.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("expected X,Y in whole pixels, got `{s}`"))?;
    match values[..] {
        [x, y] => Ok((x, y)),
        _ => Err(format!("expected two numbers X,Y, got `{s}`")),
    }
}

pub(super) fn parse_gain(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(g) if g.is_finite() => Ok(g),
        _ => Err(format!("expected a finite gain, got `{s}`")),
    }
}

/// `NAME=G` or `NAME=R,G,B`.
pub(super) fn parse_light_gain(s: &str) -> Result<(String, [f64; 3]), String> {
    let (name, gain) = s
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=GAIN or NAME=R,G,B, got `{s}`"))?;
    let values: Vec<f64> = gain.split(',').map(parse_gain).collect::<Result<_, _>>()?;
    match values[..] {
        [g] => Ok((name.trim().to_string(), [g; 3])),
        [r, g, b] => Ok((name.trim().to_string(), [r, g, b])),
        _ => Err(format!("expected one gain or three (R,G,B), got `{gain}`")),
    }
}

pub(super) fn parse_depth(s: &str) -> Result<u8, String> {
    match s.trim() {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("PNG depth is 8 or 16, got `{s}`")),
    }
}

pub(super) fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected a number of threads >= 1 and <= {MAX_THREADS}, got `{s}`"
        )),
    }
}

/// `check --report`'s file: its format follows the extension (`.html` or `.png`); any other
/// name is refused before anything runs.
pub(super) fn parse_report(s: &str) -> Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(s);
    match whitted_check::check::print::ReportFormat::of(&path) {
        Some(_) => Ok(path),
        None => Err(format!(
            "`{s}`: the report's format follows its extension: REPORT.html (a page with the \
             images) or REPORT.png (a contact sheet)"
        )),
    }
}

pub(super) fn parse_timeout(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(n) if (1..=86_400).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected a whole number of seconds from 1 to 86400, got `{s}`"
        )),
    }
}

pub(super) fn parse_bug(s: &str) -> Result<whitted_check::mistakes::Bug, String> {
    whitted_check::mistakes::Bug::from_id(s.trim()).ok_or_else(|| {
        let ids: Vec<&str> = whitted_check::mistakes::Bug::ALL
            .iter()
            .map(|b| b.id())
            .collect();
        let hint = whitted_core::suggest::nearest(s.trim(), &ids)
            .map_or(String::new(), |n| format!("did you mean `{n}`? "));
        format!("unknown mistake `{s}`; {hint}`whitted check --list-bugs` lists them")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_enforced() {
        assert_eq!(parse_bounces("3"), Ok(3));
        assert!(parse_bounces("-1").unwrap_err().contains(">= 0"));
        assert!(parse_bounces("101").is_err());
        assert!(parse_side("0").is_err());
        assert!(parse_side("70000").is_err());
        assert_eq!(parse_side("640"), Ok(640));
        assert!(parse_threads("0").is_err());
        assert_eq!(parse_spp("16"), Ok(16));
        assert!(parse_spp("8").unwrap_err().contains("square"));
        assert!(parse_spp("0").is_err());
        assert_eq!(parse_exposure("-1.5"), Ok(-1.5));
        assert!(parse_exposure("nan").is_err());
        assert!(parse_depth("12").is_err());
    }
}
