//! Comparing whole files: every part of a multi-part OpenEXR file, matched by name (or by
//! position when unnamed), each aligned to the other's pixel grid first.

use super::{align, compare, Criteria, LayerReport};
use crate::input::{Format, Image, Window};

/// The comparison of one part (the only one, for most files).
#[derive(Debug, Clone, PartialEq)]
pub struct PartReport {
    /// The part's name, or its position when it has none.
    pub part: String,
    pub width: usize,
    pub height: usize,
    /// `Some((actual's, reference's))` when the data windows differ: the part fails.
    pub moved: Option<(Window, Window)>,
    pub layers: Vec<LayerReport>,
}

impl PartReport {
    pub fn passed(&self) -> bool {
        self.moved.is_none() && self.layers.iter().all(|l| l.passed)
    }

    pub fn warnings(&self) -> usize {
        self.layers.iter().map(|l| l.warnings).sum()
    }
}

/// Compares every part of `actual` with the matching part of `reference`. Errors (not
/// failures) when the files cannot be compared: linear EXR against a display-referred raster,
/// different part counts or names, different display windows, missing layers or channels.
pub fn compare_files(
    actual: &[Image],
    reference: &[Image],
    layers: &[String],
    criteria: Criteria,
) -> Result<Vec<PartReport>, String> {
    let is_exr = |parts: &[Image]| parts.first().is_some_and(|p| p.format == Format::Exr);
    if is_exr(actual) != is_exr(reference) {
        return Err(
            "cannot compare an OpenEXR file (linear) with a display-referred image \
             (PNG, JPEG, TIFF, HDR)"
                .into(),
        );
    }
    if actual.len() != reference.len() {
        return Err(format!(
            "the files have {} and {} parts",
            actual.len(),
            reference.len()
        ));
    }
    reference
        .iter()
        .enumerate()
        .map(|(index, b)| {
            let a = matching_part(actual, index, b)?;
            let label = b.part.clone().unwrap_or_else(|| index.to_string());
            let aligned = align(a, b).map_err(|e| format!("part {label}: {e}"))?;
            let reports = compare(&aligned.actual, &aligned.reference, layers, criteria)?;
            Ok(PartReport {
                part: label,
                width: aligned.reference.width,
                height: aligned.reference.height,
                moved: aligned.moved,
                layers: reports,
            })
        })
        .collect()
}

/// The part of `actual` that part `index` of the reference, `b`, is compared with: the one of
/// the same name, or the one at the same position when unnamed.
pub fn matching_part<'a>(
    actual: &'a [Image],
    index: usize,
    b: &Image,
) -> Result<&'a Image, String> {
    match &b.part {
        Some(name) => actual
            .iter()
            .find(|p| p.part.as_ref() == Some(name))
            .ok_or_else(|| format!("part `{name}` is missing from the first file")),
        None => actual
            .get(index)
            .ok_or_else(|| format!("part {index} is missing from the first file")),
    }
}
