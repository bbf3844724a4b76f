//! What a layer looks like, as display values in [0, 1]: colour layers tone-mapped, masks as
//! grey, normals as (N + 1) / 2, object ids as distinct colours, other data (depth, positions)
//! normalised to their range. Which layer is which is asked of `aov`.

use glam::DVec3;

use crate::canvas::Canvas;
use crate::input::{suffix, Format, Image, Layer};
use whitted_core::aov::{self, Role};
use whitted_core::tonemap::{self, ToneMap};

/// What a layer looks like, as display values in [0, 1] per pixel.
pub(super) fn display_values(
    image: &Image,
    layer: &Layer,
    tone_map: ToneMap,
    exposure: f64,
) -> Vec<[f64; 3]> {
    let channel = |suffix_name: &str| {
        layer
            .channels
            .iter()
            .map(|&i| &image.channels[i])
            .find(|c| suffix(&c.name) == suffix_name)
    };
    let pixels = image.width * image.height;
    let gain = tonemap::exposure_gain(exposure);
    let values = |i: usize| &image.channels[layer.channels[i]].values;
    if image.is_colour(layer) {
        let (r, g, b) = (channel("R"), channel("G"), channel("B"));
        let (Some(r), Some(g), Some(b)) = (r, g, b) else {
            return vec![[0.0; 3]; pixels];
        };
        return (0..pixels)
            .map(|p| {
                let v = DVec3::new(
                    f64::from(r.values[p]),
                    f64::from(g.values[p]),
                    f64::from(b.values[p]),
                );
                match image.format {
                    Format::Exr | Format::Hdr => tonemap::to_display(v, tone_map, gain),
                    // Already display values (PNG, JPEG, TIFF): shown as they are.
                    _ => v.clamp(DVec3::ZERO, DVec3::ONE).to_array(),
                }
            })
            .collect();
    }
    match aov::role_of_layer(&layer.name) {
        Some(Role::Normal) if layer.channels.len() == 3 => {
            return (0..pixels)
                .map(|p| [0, 1, 2].map(|c| ((f64::from(values(c)[p]) + 1.0) / 2.0).clamp(0.0, 1.0)))
                .collect();
        }
        Some(Role::ObjectId) => return values(0).iter().map(|&id| id_colour(id)).collect(),
        Some(Role::Mask) if layer.channels.len() == 1 => {
            return values(0)
                .iter()
                .map(|&v| [f64::from(v).clamp(0.0, 1.0); 3])
                .collect();
        }
        _ => {}
    }
    // Data: each channel normalised over its non-zero finite values below the depth of a
    // miss; 0 and that depth (a miss) stay black.
    let normalised: Vec<Vec<f64>> = (0..layer.channels.len().min(3))
        .map(|c| {
            let v = values(c);
            let hits = v.iter().filter(|&&x| is_hit(x)).map(|&x| f64::from(x));
            let (lo, hi) = hits.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
            let span = if hi > lo { hi - lo } else { 1.0 };
            v.iter()
                .map(|&x| {
                    if !is_hit(x) {
                        0.0
                    } else {
                        0.2 + 0.8 * (f64::from(x) - lo) / span
                    }
                })
                .collect()
        })
        .collect();
    (0..pixels)
        .map(|p| match normalised.len() {
            1 => [normalised[0][p]; 3],
            2 => [normalised[0][p], normalised[1][p], 0.0],
            _ => [normalised[0][p], normalised[1][p], normalised[2][p]],
        })
        .collect()
}

/// A stable, well-spread colour for an object id; 0 (no object) is black.
fn id_colour(id: f32) -> [f64; 3] {
    if id.is_nan() || id <= 0.0 {
        return [0.0; 3];
    }
    let hue = (f64::from(id) * 0.618_033_988_749_895).fract();
    let channel =
        |offset: f64| 0.35 + 0.55 * (0.5 + 0.5 * (std::f64::consts::TAU * (hue + offset)).cos());
    [channel(0.0), channel(1.0 / 3.0), channel(2.0 / 3.0)]
}

/// Box-filters display values down (or nearest-samples up) to a tile.
pub(super) fn downsample(
    values: &[[f64; 3]],
    width: usize,
    height: usize,
    tile_w: usize,
    tile_h: usize,
) -> Canvas {
    let mut tile = Canvas::new(tile_w, tile_h, [0; 3]);
    for ty in 0..tile_h {
        let (y0, y1) = (
            ty * height / tile_h,
            ((ty + 1) * height / tile_h).max(ty * height / tile_h + 1),
        );
        for tx in 0..tile_w {
            let (x0, x1) = (
                tx * width / tile_w,
                ((tx + 1) * width / tile_w).max(tx * width / tile_w + 1),
            );
            let mut sum = [0.0; 3];
            let mut n = 0.0;
            for y in y0..y1.min(height) {
                for x in x0..x1.min(width) {
                    let v = values[y * width + x];
                    for c in 0..3 {
                        sum[c] += v[c];
                    }
                    n += 1.0;
                }
            }
            tile.pixels[ty * tile_w + tx] =
                sum.map(|s| (255.0 * s / f64::max(n, 1.0) + 0.5).clamp(0.0, 255.0) as u8);
        }
    }
    tile
}

/// Whether a data value is a surface's: not 0, not the depth of a miss, finite.
fn is_hit(x: f32) -> bool {
    x.is_finite() && x != 0.0 && f64::from(x) < aov::Z_MISS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_get_distinct_colours_and_zero_is_black() {
        assert_eq!(id_colour(0.0), [0.0; 3]);
        let colours: Vec<[f64; 3]> = (1..8).map(|i| id_colour(i as f32)).collect();
        for (i, a) in colours.iter().enumerate() {
            for b in &colours[i + 1..] {
                assert!(a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() > 0.05);
            }
        }
    }

    #[test]
    fn downsampling_averages_boxes() {
        let values = vec![
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        let tile = downsample(&values, 2, 2, 1, 1);
        assert_eq!(tile.pixels, [[128, 0, 0]]);
    }
}
