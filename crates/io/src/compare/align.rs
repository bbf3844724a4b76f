//! Putting two images on the same pixel grid before comparing them. Display windows must be
//! equal (else they are different frames: not comparable). Data windows may differ: an image
//! moved by `oiiotool --origin` is a difference, so both are padded with zeros to the union of
//! their data windows (as `idiff` compares them) and the comparison is marked as failed.

use std::borrow::Cow;

use crate::input::{Channel, Image, Window};
use whitted_core::memory;

/// Two images on one grid, and whether their data windows differed.
pub struct Alignment<'a> {
    pub actual: Cow<'a, Image>,
    pub reference: Cow<'a, Image>,
    /// `Some((actual's, reference's))` when the data windows differ: a failed comparison.
    pub moved: Option<(Window, Window)>,
}

/// Aligns `actual` to `reference`, or says why they cannot be compared.
pub fn align<'a>(actual: &'a Image, reference: &'a Image) -> Result<Alignment<'a>, String> {
    if actual.display_window != reference.display_window {
        return Err(format!(
            "display windows differ: {} vs {} (different frames cannot be compared)",
            actual.display_window, reference.display_window
        ));
    }
    let (a, b) = (actual.data_window, reference.data_window);
    if a == b {
        return Ok(Alignment {
            actual: Cow::Borrowed(actual),
            reference: Cow::Borrowed(reference),
            moved: None,
        });
    }
    let union = Window {
        min: [a.min[0].min(b.min[0]), a.min[1].min(b.min[1])],
        max: [a.max[0].max(b.max[0]), a.max[1].max(b.max[1])],
    };
    let (width, height) = (
        (union.max[0] - union.min[0] + 1) as usize,
        (union.max[1] - union.min[1] + 1) as usize,
    );
    let channels = (actual.channels.len() + reference.channels.len()) as u64;
    memory::check(
        (width as u64)
            .saturating_mul(height as u64)
            .saturating_mul(channels * 4),
        memory::available_bytes(),
        "the union of the two data windows",
    )
    .map_err(|e| e.to_string())?;
    Ok(Alignment {
        actual: Cow::Owned(padded(actual, union, width, height)),
        reference: Cow::Owned(padded(reference, union, width, height)),
        moved: Some((a, b)),
    })
}

/// `image` on the grid of `union` (`width` x `height`), zero outside its data window.
fn padded(image: &Image, union: Window, width: usize, height: usize) -> Image {
    let dx = (image.data_window.min[0] - union.min[0]) as usize;
    let dy = (image.data_window.min[1] - union.min[1]) as usize;
    let channels = image
        .channels
        .iter()
        .map(|c| {
            let mut values = vec![0.0f32; width * height];
            for row in 0..image.height {
                let from = row * image.width;
                let to = (row + dy) * width + dx;
                values[to..to + image.width].copy_from_slice(&c.values[from..from + image.width]);
            }
            Channel {
                name: c.name.clone(),
                pixel_type: c.pixel_type,
                values,
            }
        })
        .collect();
    Image {
        width,
        height,
        data_window: union,
        channels,
        ..image.clone_header()
    }
}
