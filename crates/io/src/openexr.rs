//! Facts about the OpenEXR format that the reader, the writer and merge share, and the one
//! call that reads a file's first part with the `exr` crate.

use std::io::{Read, Seek};

use exr::prelude::{self as x, ReadChannels as _, ReadLayers as _};

/// The four bytes every OpenEXR file starts with.
pub const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// Longest channel name OpenEXR 2 readers accept (the 1.x header limit that many tools keep).
pub const MAX_CHANNEL_NAME: usize = 31;

/// A name or text from an OpenEXR header as UTF-8, which is what OpenEXR specifies (the
/// `exr` crate's `Display` shows each byte as a Latin-1 character, so `é` would read `Ã©`
/// and never match the name a user types). Invalid UTF-8 is shown with replacement
/// characters.
pub fn text(t: &x::Text) -> String {
    String::from_utf8_lossy(t.bytes()).into_owned()
}

/// One part with every channel as flat samples, and its header.
pub type FlatImage = x::Image<x::Layer<x::AnyChannels<x::FlatSamples>>>;

/// Reads the first valid part of an OpenEXR stream (scanline or tiled, any pixel types, the
/// largest resolution level), with every header attribute.
pub fn read_first_part(reader: impl Read + Seek + Send) -> Result<FlatImage, x::Error> {
    x::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::BufReader::new(reader))
}

/// Every part of an OpenEXR stream, each with its channels as flat samples.
pub fn read_all_parts(
    reader: impl Read + Seek + Send,
) -> Result<x::Image<x::Layers<x::AnyChannels<x::FlatSamples>>>, x::Error> {
    x::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_buffered(std::io::BufReader::new(reader))
}

/// The pixel type of a channel as OpenEXR names it.
pub fn pixel_type(samples: &x::FlatSamples) -> &'static str {
    match samples {
        x::FlatSamples::F16(_) => "half",
        x::FlatSamples::F32(_) => "float",
        x::FlatSamples::U32(_) => "uint",
    }
}

/// Memory that decoding every part of a file with these headers takes at its peak: every
/// channel's samples as stored, plus the f32 copy `input` makes. Saturating, so a header
/// declaring an absurd size gives `u64::MAX` rather than wrapping to something small.
pub fn decoded_bytes(meta: &exr::meta::MetaData) -> u64 {
    meta.headers
        .iter()
        .map(|header| {
            let size = header.layer_size;
            let pixels = (size.0 as u64).saturating_mul(size.1 as u64);
            let per_pixel: u64 = header
                .channels
                .list
                .iter()
                .map(|c| c.sample_type.bytes_per_sample() as u64 + 4)
                .fold(0, u64::saturating_add);
            pixels.saturating_mul(per_pixel)
        })
        .fold(0, u64::saturating_add)
}
