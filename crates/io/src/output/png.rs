//! Linear pixels -> tone map -> encoding -> quantisation -> PNG bytes (docs/tonemap.md).

use std::fs::File;
use std::io::Write;

use glam::DVec3;
use rayon::prelude::*;

use whitted_core::tonemap::{exposure_gain, sigmoid_byte, to_display, ToneMap};

/// How linear values become display bytes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PngEncoding {
    pub tonemap: ToneMap,
    /// Exposure in stops, applied first: `v * 2^EV`.
    pub exposure: f64,
    /// 8 or 16 bits per channel.
    pub depth: u8,
    /// Triangular dither before rounding (8-bit sRGB output only).
    pub dither: bool,
}

impl Default for PngEncoding {
    /// The course's PNG.
    fn default() -> Self {
        PngEncoding {
            tonemap: ToneMap::Tick,
            exposure: 0.0,
            depth: 8,
            dither: false,
        }
    }
}

/// An encoded image ready for the PNG encoder: 8- or 16-bit RGB, row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct PngImage {
    pub width: u32,
    pub height: u32,
    pub pixels: PngPixels,
    /// Whether the values are sRGB-encoded (then the file says so with an `sRGB` chunk).
    /// The `tick` output is not: the course's file carries no colour metadata.
    pub srgb: bool,
}

/// Channel values, three per pixel.
#[derive(Debug, Clone, PartialEq)]
pub enum PngPixels {
    Eight(Vec<u8>),
    Sixteen(Vec<u16>),
}

/// Tone-maps and quantises row-major linear `pixels`.
pub fn encode(pixels: &[DVec3], width: u32, height: u32, encoding: &PngEncoding) -> PngImage {
    PngImage {
        width,
        height,
        pixels: encode_rows(pixels, width, 0, encoding),
        srgb: encoding.tonemap.srgb_encoded(),
    }
}

/// The course's PNG bytes (`tick`, 8 bits, three per pixel) of linear `pixels` in any order:
/// the one tick quantisation, for code that compares bytes rather than writing a file.
pub fn tick_bytes(pixels: &[DVec3]) -> Vec<u8> {
    bytes_with(ToneMap::Tick, pixels)
}

/// The 8-bit bytes of linear `pixels` in any order under one of the course's own tone maps
/// (`tick` or the later years' `sigmoid`): what a year's program writes.
pub fn bytes_with(tonemap: ToneMap, pixels: &[DVec3]) -> Vec<u8> {
    let width = u32::try_from(pixels.len()).unwrap_or(u32::MAX).max(1);
    let encoding = PngEncoding {
        tonemap,
        ..PngEncoding::default()
    };
    match encode_rows(pixels, width, 0, &encoding) {
        PngPixels::Eight(bytes) => bytes,
        PngPixels::Sixteen(_) => unreachable!("the default encoding has 8 bits"),
    }
}

/// Tone-maps and quantises whole rows of `width` pixels, the first of them image row
/// `first_row` (which the dither depends on).
fn encode_rows(pixels: &[DVec3], width: u32, first_row: u32, encoding: &PngEncoding) -> PngPixels {
    let tick = !encoding.tonemap.srgb_encoded();
    if encoding.depth == 16 {
        PngPixels::Sixteen(quantised(
            pixels,
            width,
            first_row,
            encoding,
            65535.0,
            false,
            |c| c as u16,
        ))
    } else {
        let dither = encoding.dither && !tick;
        PngPixels::Eight(quantised(
            pixels,
            width,
            first_row,
            encoding,
            255.0,
            dither,
            |c| c as u8,
        ))
    }
}

/// Each pixel's three display values as codes `0..=max` (dithered if `dither`), row by row on
/// every core.
fn quantised<T: Copy + Default + Send>(
    pixels: &[DVec3],
    width: u32,
    first_row: u32,
    encoding: &PngEncoding,
    max: f64,
    dither: bool,
    code: fn(f64) -> T,
) -> Vec<T> {
    let tick = !encoding.tonemap.srgb_encoded();
    let gain = exposure_gain(encoding.exposure);
    // The course's sigmoid to bytes: exact, and without its `pow`s on nearly every channel.
    let sigmoid_bytes = encoding.tonemap == ToneMap::Sigmoid && max == 255.0;
    let row = width.max(1) as usize;
    let mut codes = vec![T::default(); pixels.len() * 3];
    codes
        .par_chunks_mut(3 * row)
        .zip(pixels.par_chunks(row))
        .enumerate()
        .for_each(|(r, (out, line))| {
            let y = first_row + r as u32;
            if sigmoid_bytes {
                // A row at a time, so that the other operators' loop stays as it was.
                for (o, c) in out
                    .iter_mut()
                    .zip(line.iter().flat_map(|&v| (v * gain).to_array()))
                {
                    *o = code(f64::from(sigmoid_byte(c)));
                }
                return;
            }
            for (x, (o, &v)) in out.chunks_exact_mut(3).zip(line).enumerate() {
                let display = to_display(v, encoding.tonemap, gain);
                for (c, (o, e)) in o.iter_mut().zip(display).enumerate() {
                    let noise = if dither {
                        triangular_noise(x as u32, y, c as u32, DITHER_SEED)
                    } else {
                        0.0
                    };
                    *o = code(quantise(e, max, tick, noise));
                }
            }
        });
    codes
}

/// `floor(max * e)` for the course's truncating tick output; `floor(max * e + 0.5 + noise)`
/// (round to nearest, optionally dithered) for encoded output; clamped to the code range.
///
/// Returns the code *before* the floor, clamped to `0..=max`: the caller's `as` conversion
/// truncates toward zero, which is the floor for these non-negative values (NaN becomes 0
/// either way). Done so because `f64::floor` is a library call on baseline x86-64, once per
/// channel of every pixel.
fn quantise(e: f64, max: f64, truncate: bool, noise: f64) -> f64 {
    let code = if truncate {
        max * e
    } else {
        max * e + 0.5 + noise
    };
    code.clamp(0.0, max)
}

/// Fixed so that the same image always dithers the same way.
const DITHER_SEED: u64 = 0x5eed;

/// Triangular noise in (-1, 1) LSB: the sum of two uniforms from a stateless hash of the
/// pixel, the channel and a seed, minus 1. Same inputs, same noise, on any thread.
pub fn triangular_noise(x: u32, y: u32, channel: u32, seed: u64) -> f64 {
    let key = (u64::from(x) << 32 | u64::from(y)) ^ (u64::from(channel) << 62) ^ seed;
    let a = splitmix64(key);
    let b = splitmix64(a ^ 0x9e37_79b9_7f4a_7c15);
    unit(a) + unit(b) - 1.0
}

/// A uniform in [0, 1) from the top 53 bits.
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 / (1u64 << 53) as f64
}

/// Sebastiano Vigna's splitmix64 finaliser: a well-mixed 64-bit hash of a 64-bit key.
fn splitmix64(key: u64) -> u64 {
    let mut z = key.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Encodes `image` as a PNG into `out`.
pub fn write_png(out: impl Write, image: &PngImage) -> Result<(), png::EncodingError> {
    let sixteen = matches!(image.pixels, PngPixels::Sixteen(_));
    let mut writer = encoder(out, image.width, image.height, image.srgb, sixteen).write_header()?;
    writer.write_image_data(&image.pixels.to_bytes())?;
    writer.finish()
}

impl PngPixels {
    /// The bytes of the PNG's rows (16-bit samples big-endian), before filtering.
    fn to_bytes(&self) -> std::borrow::Cow<'_, [u8]> {
        match self {
            PngPixels::Eight(bytes) => bytes.into(),
            PngPixels::Sixteen(values) => values
                .iter()
                .flat_map(|v| v.to_be_bytes())
                .collect::<Vec<u8>>()
                .into(),
        }
    }
}

/// A PNG written as its rows arrive, strip by strip, so that the whole image is never held.
pub struct PngStream {
    writer: png::StreamWriter<'static, File>,
    encoding: PngEncoding,
    width: u32,
    rows: u32,
}

impl PngStream {
    /// Writes the header of a `width` x `height` PNG into `file`.
    pub fn new(
        file: File,
        width: u32,
        height: u32,
        encoding: PngEncoding,
    ) -> Result<Self, png::EncodingError> {
        let srgb = encoding.tonemap.srgb_encoded();
        let encoder = encoder(file, width, height, srgb, encoding.depth == 16);
        Ok(PngStream {
            writer: encoder.write_header()?.into_stream_writer()?,
            encoding,
            width,
            rows: 0,
        })
    }

    /// Encodes and writes the next whole rows of the image.
    pub fn write_rows(&mut self, pixels: &[DVec3]) -> Result<(), png::EncodingError> {
        let encoded = encode_rows(pixels, self.width, self.rows, &self.encoding);
        self.writer.write_all(&encoded.to_bytes())?;
        self.rows += (pixels.len() / self.width.max(1) as usize) as u32;
        Ok(())
    }

    /// Ends the image; an error if rows are missing.
    pub fn finish(self) -> Result<(), png::EncodingError> {
        self.writer.finish()
    }
}

/// An encoder for an RGB image, set up as every PNG whitted writes is.
fn encoder<W: Write>(
    out: W,
    width: u32,
    height: u32,
    srgb: bool,
    sixteen: bool,
) -> png::Encoder<'static, W> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(if sixteen {
        png::BitDepth::Sixteen
    } else {
        png::BitDepth::Eight
    });
    // fdeflate's PNG-tuned mode: the whole tick2 run takes a quarter less time than with
    // `Balanced`, for a file a third larger (132 KB); PNGs are judged by their pixels.
    encoder.set_compression(png::Compression::Fast);
    if srgb {
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        // The gAMA and cHRM values the PNG spec (11.3.2.5) asks for beside sRGB, for readers
        // that do not know the sRGB chunk; the encoder writes them only when set to these.
        encoder.set_source_gamma(png::ScaledFloat::from_scaled(45455));
        let xy = |x, y| {
            (
                png::ScaledFloat::from_scaled(x),
                png::ScaledFloat::from_scaled(y),
            )
        };
        encoder.set_source_chromaticities(png::SourceChromaticities {
            white: xy(31270, 32900),
            red: xy(64000, 33000),
            green: xy(30000, 60000),
            blue: xy(15000, 6000),
        });
    }
    encoder
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The course's byte for one linear pixel, through the whole PNG encoding.
    fn tick(v: DVec3) -> [u8; 3] {
        match encode(&[v], 1, 1, &PngEncoding::default()).pixels {
            PngPixels::Eight(bytes) => [bytes[0], bytes[1], bytes[2]],
            PngPixels::Sixteen(_) => unreachable!("the default is 8-bit"),
        }
    }

    #[test]
    fn tick_truncates_clamps_and_zeroes_nan() {
        assert_eq!(tick(DVec3::new(0.0, 1.0, 0.5)), [0, 255, 127]);
        assert_eq!(tick(DVec3::new(-3.0, 7.0, f64::NAN)), [0, 255, 0]);
        assert_eq!(tick(DVec3::new(0.18, 4.0, 100.0)), [45, 255, 255]);
        assert_eq!(
            tick(DVec3::new(254.999 / 255.0, 1.0 / 255.0, 0.999 / 255.0)),
            [254, 1, 0]
        );
        assert_eq!(tick(DVec3::splat(f64::INFINITY)), [255, 255, 255]);
    }

    fn eight(image: &PngImage) -> &[u8] {
        match &image.pixels {
            PngPixels::Eight(b) => b,
            PngPixels::Sixteen(_) => panic!("16-bit"),
        }
    }

    #[test]
    fn tick_truncates_and_srgb_rounds() {
        let px = [DVec3::new(0.18, 1.0, 0.5)];
        let tick = encode(&px, 1, 1, &PngEncoding::default());
        assert_eq!(eight(&tick), [45, 255, 127]);
        assert!(!tick.srgb);
        let clamp = encode(
            &px,
            1,
            1,
            &PngEncoding {
                tonemap: ToneMap::Clamp,
                ..PngEncoding::default()
            },
        );
        // sRGB(0.18) = 0.46135 -> 117.64 + 0.5 -> 118; sRGB(0.5) = 0.73536 -> 188.
        assert_eq!(eight(&clamp), [118, 255, 188]);
        assert!(clamp.srgb);
    }

    #[test]
    fn sixteen_bit_uses_the_full_range() {
        let px = [DVec3::new(0.0, 1.0, 0.18)];
        let enc = PngEncoding {
            tonemap: ToneMap::Clamp,
            depth: 16,
            ..PngEncoding::default()
        };
        let PngPixels::Sixteen(v) = encode(&px, 1, 1, &enc).pixels else {
            panic!("8-bit")
        };
        let want = (65535.0 * whitted_core::tonemap::srgb_oetf(0.18) + 0.5).floor() as u16;
        assert_eq!(v, [0, 65535, want]);
    }

    #[test]
    fn exposure_is_applied_before_the_operator() {
        let px = [DVec3::splat(0.25)];
        let enc = PngEncoding {
            exposure: 2.0,
            ..PngEncoding::default()
        };
        assert_eq!(eight(&encode(&px, 1, 1, &enc)), [255, 255, 255]);
        let enc = PngEncoding {
            exposure: -1.0,
            ..PngEncoding::default()
        };
        assert_eq!(eight(&encode(&px, 1, 1, &enc)), [31, 31, 31]);
    }

    #[test]
    fn noise_is_triangular_and_stateless() {
        let samples: Vec<f64> = (0..20_000)
            .map(|i| triangular_noise(i % 200, i / 200, i % 3, 7))
            .collect();
        assert!(samples.iter().all(|&n| (-1.0..1.0).contains(&n)));
        let mean = samples.iter().sum::<f64>() / samples.len() as f64;
        assert!(mean.abs() < 0.01, "mean {mean}");
        // Triangular on (-1, 1): variance 1/6.
        let var = samples.iter().map(|n| n * n).sum::<f64>() / samples.len() as f64;
        assert!((var - 1.0 / 6.0).abs() < 0.01, "variance {var}");
        assert_eq!(triangular_noise(3, 4, 1, 7), triangular_noise(3, 4, 1, 7));
        assert_ne!(triangular_noise(3, 4, 1, 7), triangular_noise(3, 4, 2, 7));
    }

    #[test]
    fn dither_removes_the_mean_quantisation_error_of_flat_areas() {
        // Flat patches at levels between codes: rounding alone is off by up to 0.5 LSB; the
        // dithered mean lands on the true level.
        for fraction in [0.1, 0.3, 0.5, 0.7, 0.9] {
            let e: f64 = (100.0 + fraction) / 255.0;
            let linear =
                <palette::encoding::Srgb as palette::encoding::IntoLinear<f64, f64>>::into_linear(
                    e,
                );
            let px = vec![DVec3::splat(linear); 64 * 64];
            let enc = PngEncoding {
                tonemap: ToneMap::Clamp,
                dither: true,
                ..PngEncoding::default()
            };
            let image = encode(&px, 64, 64, &enc);
            let bytes = eight(&image);
            let mean = bytes.iter().map(|&b| f64::from(b)).sum::<f64>() / bytes.len() as f64;
            assert!(
                (mean - 255.0 * e).abs() < 0.1,
                "level {fraction}: mean {mean}"
            );
            let plain = encode(
                &px,
                64,
                64,
                &PngEncoding {
                    dither: false,
                    ..enc
                },
            );
            assert_eq!(eight(&plain)[0], (255.0 * e + 0.5).floor() as u8);
        }
    }
}
