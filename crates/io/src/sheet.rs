//! A contact sheet: every layer of an image as a captioned tile, the picture to look at
//! first. How each layer is shown is `sheet/display.rs`'s business; this file lays the tiles out.

mod display;

use crate::canvas::{fit, Canvas, LINE_HEIGHT};
use crate::input::{Image, Layer};
use crate::stats::Stats;
use display::{display_values, downsample};
use whitted_core::error::{Error, Result};
use whitted_core::numbers::compact;
use whitted_core::tonemap::ToneMap;

const MARGIN: usize = 8;
const CAPTION: usize = 2 * LINE_HEIGHT + 4;
const BACKGROUND: [u8; 3] = [32, 32, 32];
const TEXT: [u8; 3] = [230, 230, 230];
const DIM_TEXT: [u8; 3] = [150, 150, 150];

/// How the sheet is laid out and its colour layers shown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SheetOptions {
    /// Tiles per row.
    pub columns: u32,
    /// Width of each tile in pixels (never wider than the image).
    pub tile_width: u32,
    pub tonemap: ToneMap,
    /// Exposure in stops for colour layers.
    pub exposure: f64,
}

/// The layers named in `wanted`, in that order (every layer when it is empty).
pub fn select(image: &Image, wanted: &[String]) -> Result<Vec<Layer>> {
    let all = image.layers();
    if wanted.is_empty() {
        return Ok(all);
    }
    wanted
        .iter()
        .map(|name| {
            all.iter()
                .find(|l| &l.name == name)
                .cloned()
                .ok_or_else(|| {
                    let names: Vec<&str> = all.iter().map(|l| l.name.as_str()).collect();
                    Error::Usage(format!(
                        "no layer `{name}` in the file; layers: {}",
                        names.join(", ")
                    ))
                })
        })
        .collect()
}

/// Lays the tiles out in a grid of `options.columns`, each captioned with name and range.
pub fn compose(image: &Image, layers: &[Layer], options: &SheetOptions) -> Canvas {
    let tile_w = (options.tile_width as usize).min(image.width).max(1);
    let tile_h = ((image.height * tile_w) as f64 / image.width.max(1) as f64)
        .round()
        .max(1.0) as usize;
    let columns = (options.columns as usize).min(layers.len()).max(1);
    let rows = layers.len().div_ceil(columns).max(1);
    let mut sheet = Canvas::new(
        columns * tile_w + (columns + 1) * MARGIN,
        rows * (tile_h + CAPTION) + (rows + 1) * MARGIN,
        BACKGROUND,
    );
    for (i, layer) in layers.iter().enumerate() {
        let x = MARGIN + (i % columns) * (tile_w + MARGIN);
        let y = MARGIN + (i / columns) * (tile_h + CAPTION + MARGIN);
        let stats = Stats::of_layer(image, layer);
        sheet.text(x, y, &fit(&layer.name, tile_w), TEXT);
        let range = format!("{} .. {}", compact(stats.min), compact(stats.max));
        sheet.text(x, y + LINE_HEIGHT + 1, &fit(&range, tile_w), DIM_TEXT);
        let display = display_values(image, layer, options.tonemap, options.exposure);
        sheet.blit(
            x,
            y + CAPTION,
            &downsample(&display, image.width, image.height, tile_w, tile_h),
        );
    }
    sheet
}
