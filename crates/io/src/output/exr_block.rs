//! One scanline block of a render's EXR: the film's rows packed the way the file stores them,
//! then compressed. The layout is OpenEXR's: line by line, and within a line each channel's
//! samples in turn (channels in name order), little-endian. ZIP is done here, with zlib-rs at
//! a fast level, because it is what every render writes by default and the `exr` crate's own
//! deflate is several times slower (bench/README.md); the other codecs go through the crate.

use exr::block::chunk::CompressedBlock;
use exr::block::{BlockIndex, UncompressedBlock};
use exr::compression::Compression;
use exr::math::Vec2;
use exr::meta::header::Header;
use exr::prelude::{f16, FlatSamples};

use crate::openexr::FlatImage;
use whitted_core::film::Film;

// The packed bytes are little-endian, which is both what the file holds and what the crate
// calls "native" for the codecs it compresses: true on every target whitted is built for.
const _: () = assert!(cfg!(target_endian = "little"));

/// zlib level for ZIP blocks: the fastest, for files a few per cent larger than OpenEXR's
/// default level makes (the levels measured are in bench/README.md).
const ZIP_LEVEL: i32 = 1;

/// Largest finite half float.
pub const HALF_MAX: f32 = 65504.0;

/// How the file stores one channel: which film channel it is and whether it is half float.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StoredChannel {
    pub film_index: usize,
    pub half: bool,
}

/// Packs rows `rows` of `strip` (strip-relative) in OpenEXR's uncompressed block layout:
/// line by line, and within a line each stored channel's samples in turn, little-endian.
/// Channel by channel within a line, so that each inner loop writes one run of samples of one
/// type (a line of the film is a few hundred KiB at most and stays in cache meanwhile); the
/// film is walked pixel by pixel, which compiles to a plain strided load per sample.
pub fn pack(strip: &Film, rows: std::ops::Range<u32>, stored: &[StoredChannel]) -> Vec<u8> {
    let width = strip.width as usize;
    let channels = strip.channel_count();
    let sample_bytes = |c: &StoredChannel| if c.half { 2 } else { 4 };
    let line_bytes: usize = stored.iter().map(|c| width * sample_bytes(c)).sum();
    let mut out = vec![0u8; rows.len() * line_bytes];
    for (row, packed) in rows.zip(out.chunks_exact_mut(line_bytes.max(1))) {
        let line = &strip.data[row as usize * width * channels..][..width * channels];
        let mut rest = packed;
        for channel in stored {
            let (samples, tail) = rest.split_at_mut(width * sample_bytes(channel));
            rest = tail;
            let c = channel.film_index;
            let values = line.chunks_exact(channels.max(1)).map(|pixel| pixel[c]);
            if channel.half {
                for (o, v) in samples.chunks_exact_mut(2).zip(values) {
                    let h = f16::from_f32(v.clamp(-HALF_MAX, HALF_MAX));
                    o.copy_from_slice(&h.to_le_bytes());
                }
            } else {
                for (o, v) in samples.chunks_exact_mut(4).zip(values) {
                    o.copy_from_slice(&v.to_le_bytes());
                }
            }
        }
    }
    out
}

/// The bytes stored for a packed block of `header`'s image whose top line is `line` lines
/// below the top of the data window.
pub fn compress(
    packed: Vec<u8>,
    header: &Header,
    line: usize,
    lines: usize,
) -> Result<Vec<u8>, String> {
    match header.compression {
        Compression::Uncompressed => Ok(packed),
        Compression::ZIP16 | Compression::ZIP1 => Ok(zip(packed)),
        _ => {
            let block = UncompressedBlock {
                data: packed,
                index: BlockIndex {
                    layer: 0,
                    pixel_position: Vec2(0, line),
                    pixel_size: Vec2(header.layer_size.0, lines),
                    level: Vec2(0, 0),
                },
            };
            let chunk = block
                .compress_to_chunk(std::slice::from_ref(header))
                .map_err(|e| e.to_string())?;
            match chunk.compressed_block {
                CompressedBlock::ScanLine(block) => Ok(block.compressed_pixels_le),
                _ => Err("the EXR codec returned a block that is not a scanline block".into()),
            }
        }
    }
}

/// Packs rows `rows` of a flat image (each channel a row-major plane, in name order) in
/// OpenEXR's uncompressed block layout.
pub fn pack_planes(image: &FlatImage, rows: std::ops::Range<u32>) -> Vec<u8> {
    let width = image.layer_data.size.0;
    let channels = &image.layer_data.channel_data.list;
    let mut out = Vec::new();
    for row in rows {
        let span = row as usize * width..(row as usize + 1) * width;
        for channel in channels {
            match &channel.sample_data {
                FlatSamples::F16(v) => v[span.clone()]
                    .iter()
                    .for_each(|s| out.extend_from_slice(&s.to_le_bytes())),
                FlatSamples::F32(v) => v[span.clone()]
                    .iter()
                    .for_each(|s| out.extend_from_slice(&s.to_le_bytes())),
                FlatSamples::U32(v) => v[span.clone()]
                    .iter()
                    .for_each(|s| out.extend_from_slice(&s.to_le_bytes())),
            }
        }
    }
    out
}

/// OpenEXR's ZIP: the bytes split into even and odd positions, delta-coded, then zlib. A block
/// that does not shrink is stored as it is, which readers recognise by its size.
fn zip(mut packed: Vec<u8>) -> Vec<u8> {
    let predicted = predict(&packed);
    // The packed bytes are needed again only if the block does not shrink, and then they are
    // recovered from the predicted ones: so their buffer takes the compressed bytes. With the
    // predictor working in place, a block fills two fresh buffers instead of four (every
    // fresh page costs a fault: this took a third of the system time off a tick2 full-AOV
    // run, and 5 MiB off its peak).
    let config = zlib_rs::DeflateConfig::new(ZIP_LEVEL);
    let (compressed, code) = zlib_rs::compress_slice(&mut packed, &predicted, config);
    let length = compressed.len();
    // A full buffer (`BufError`) means the block did not shrink.
    if code != zlib_rs::ReturnCode::Ok || length >= predicted.len() {
        return unpredict(&predicted);
    }
    packed.truncate(length);
    packed.shrink_to_fit();
    packed
}

/// OpenEXR's ZIP predictor (ImfZip.cpp): bytes at even positions, then those at odd ones,
/// each then replaced by its difference from the one before plus 128, modulo 256. Written out
/// here because it is the file format itself and the `exr` crate keeps its copy private; two
/// simple passes (split, then difference) rather than one fused loop, because each of them
/// compiles to vector instructions: a tenth of the instructions per byte.
fn predict(raw: &[u8]) -> Vec<u8> {
    let n = raw.len();
    let mut out = vec![0u8; n];
    let (even, odd) = out.split_at_mut(n.div_ceil(2));
    // Each pair of bytes read as one little-endian u16: its low and high bytes.
    let pairs = raw
        .chunks_exact(2)
        .map(|p| u16::from_le_bytes([p[0], p[1]]));
    for ((e, o), pair) in even.iter_mut().zip(odd.iter_mut()).zip(pairs) {
        *e = pair as u8;
        *o = (pair >> 8) as u8;
    }
    if n % 2 == 1 {
        even[n / 2] = raw[n - 1];
    }
    // In place, carrying each byte's original value on to the next (this form vectorises
    // under whole-program optimisation too; `windows(2)` over a copy did not).
    if let Some((&mut first, rest)) = out.split_first_mut() {
        let mut previous = first;
        for byte in rest {
            let current = *byte;
            *byte = current.wrapping_sub(previous).wrapping_add(128);
            previous = current;
        }
    }
    out
}

/// The packed bytes back from `predict`'s output: the running sum undoes the differences,
/// then the two halves are interleaved again. Only blocks that do not shrink need it.
fn unpredict(predicted: &[u8]) -> Vec<u8> {
    let n = predicted.len();
    let mut split = predicted.to_vec();
    for i in 1..n {
        split[i] = split[i].wrapping_add(split[i - 1]).wrapping_sub(128);
    }
    let (even, odd) = split.split_at(n.div_ceil(2));
    let mut raw = Vec::with_capacity(n);
    for (i, &e) in even.iter().enumerate() {
        raw.push(e);
        if let Some(&o) = odd.get(i) {
            raw.push(o);
        }
    }
    raw
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The predictor as ImfZip.cpp spells it: split, then difference.
    fn reference(raw: &[u8]) -> Vec<u8> {
        let mut t: Vec<u8> = raw.iter().step_by(2).copied().collect();
        t.extend(raw.iter().skip(1).step_by(2));
        let mut out = t.clone();
        for i in 1..t.len() {
            out[i] = t[i].wrapping_sub(t[i - 1]).wrapping_add(128);
        }
        out
    }

    #[test]
    fn the_predictor_splits_then_differences() {
        assert_eq!(predict(&[10, 20, 11, 22, 12]), [10, 129, 129, 136, 130]);
        assert_eq!(predict(&[]), Vec::<u8>::new());
        let bytes: Vec<u8> = (0u32..41).map(|i| (i * i * 37 % 251) as u8).collect();
        for n in 0..bytes.len() {
            assert_eq!(predict(&bytes[..n]), reference(&bytes[..n]), "{n} bytes");
            assert_eq!(unpredict(&predict(&bytes[..n])), &bytes[..n], "{n} bytes");
        }
    }

    #[test]
    fn incompressible_blocks_are_stored_raw_and_others_shrink() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let noise: Vec<u8> = (0..4096)
            .map(|_| {
                // xorshift64: bytes no deflate can shrink.
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 24) as u8
            })
            .collect();
        assert_eq!(zip(noise.clone()), noise);
        // An odd length too: the raw bytes come back through the inverse predictor.
        assert_eq!(zip(noise[..4095].to_vec()), &noise[..4095]);
        let flat = vec![7u8; 4096];
        let packed = zip(flat.clone());
        assert!(packed.len() < 100, "{}", packed.len());
        let inflated = zlib_rs::decompress_slice(
            &mut vec![0; 4096],
            &packed,
            zlib_rs::InflateConfig::default(),
        )
        .0
        .to_vec();
        assert_eq!(inflated, predict(&flat));
    }
}
