//! Film -> one-part, scanline, multi-layer OpenEXR (docs/aovs.md, File structure and Header).

use std::fs::File;

use exr::image::write::layers::WritableLayers as _;
use exr::prelude::{self as x, AttributeValue, Text};

use exr::meta::header::Header;
use glam::DVec3;

use crate::openexr::FlatImage;
use crate::output::exr_block;
use crate::output::exr_block::StoredChannel;
use crate::output::exr_stream::ExrStream;
use whitted_core::aov::{Kind, Layer, Z_MISS};
use whitted_core::course::Course;

/// Lossless codecs offered on the command line. Lossy ones would corrupt the data layers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ExrCompression {
    None,
    Rle,
    /// ZIP, one scanline per block.
    Zips,
    /// ZIP, 16 scanlines per block (the default, as in most renderers).
    #[default]
    Zip,
    Piz,
}

impl ExrCompression {
    /// The name the command line and the recorded render command use.
    pub fn name(self) -> &'static str {
        match self {
            ExrCompression::None => "none",
            ExrCompression::Rle => "rle",
            ExrCompression::Zips => "zips",
            ExrCompression::Zip => "zip",
            ExrCompression::Piz => "piz",
        }
    }

    /// Scanlines per block, as OpenEXR defines it for each codec.
    pub fn lines_per_block(self) -> u32 {
        self.codec().scan_lines_per_block() as u32
    }

    fn codec(self) -> x::Compression {
        match self {
            ExrCompression::None => x::Compression::Uncompressed,
            ExrCompression::Rle => x::Compression::RLE,
            ExrCompression::Zips => x::Compression::ZIP1,
            ExrCompression::Zip => x::Compression::ZIP16,
            ExrCompression::Piz => x::Compression::PIZ,
        }
    }
}

/// How to store the pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExrOptions {
    pub compression: ExrCompression,
    /// Colour layers as half floats (masks and data layers stay float).
    pub half: bool,
}

/// What the header says about the render.
#[derive(Debug, Clone, PartialEq)]
pub struct ExrMetadata {
    /// `<program> <version>`.
    pub software: String,
    /// The scene file name and the command line.
    pub comments: String,
    pub bounces: u32,
    pub spp: u32,
    /// Whether shadow rays were cast (`--no-shadows` turns them off).
    pub shadows: bool,
    /// Light names, in layer order.
    pub light_names: Vec<String>,
    /// `YYYY:MM:DD hh:mm:ss` in UTC, only when asked for: without it files are reproducible.
    pub capture_date: Option<String>,
    pub world_to_ndc: [[f64; 4]; 4],
    /// What tells this render from any other: a fingerprint of the scene's bytes and of every
    /// pixel-affecting option (the recorded command, which includes the full size).
    pub identity: String,
    /// A fingerprint of the scene file's bytes.
    pub scene: String,
    /// The course year whose rules made the pixels: recorded as `render/course` unless it is
    /// the default 2016-17 (whose files stay as they were before there were years).
    pub course: Course,
}

/// The header attribute that names the course year of a render (docs/aovs.md).
pub const COURSE_ATTRIBUTE: &str = "render/course";

/// The sums a reader can check the layers against (docs/aovs.md, Invariants).
pub const INVARIANTS: &str = "RGB = direct + reflected; reflected = sum_k reflected_k; \
RGB = ambient + sum_i light_i + background; RGB = ambient + diffuse + specular + background";

/// The header of a render's EXR placed at `at` holding `layers`, and how each of its
/// channels is stored, in the file's (name) order: colour layers as half when asked, every
/// channel explicitly linear (the crate would flag every non-RGB name `pLinear`, which claims
/// perceptual encoding for linear data; docs/aovs.md).
pub fn header(
    at: Placement,
    layers: &[Layer],
    options: ExrOptions,
    metadata: &ExrMetadata,
) -> (Header, Vec<StoredChannel>) {
    let mut attributes = x::LayerAttributes {
        // The data window: where this film (a whole image, or a farm node's region) sits.
        layer_position: x::Vec2(at.origin.0, at.origin.1),
        software_name: Some(text(&metadata.software)),
        comments: Some(text(&metadata.comments)),
        world_to_camera: Some(matrix(&IDENTITY)),
        world_to_normalized_device: Some(matrix(&metadata.world_to_ndc)),
        ..x::LayerAttributes::default()
    };
    if let Some(date) = &metadata.capture_date {
        attributes.capture_date = Some(text(date));
        attributes.utc_offset = Some(0.0);
    }
    let custom = [
        (
            "colorInteropID",
            AttributeValue::Text(text("lin_rec709_scene")),
        ),
        (
            "render/bounces",
            AttributeValue::I32(clamp_i32(metadata.bounces)),
        ),
        ("render/spp", AttributeValue::I32(clamp_i32(metadata.spp))),
        (
            "render/shadows",
            AttributeValue::I32(i32::from(metadata.shadows)),
        ),
        (
            "render/lights",
            AttributeValue::Text(text(&metadata.light_names.join(","))),
        ),
        ("render/invariants", AttributeValue::Text(text(INVARIANTS))),
        ("render/zMiss", AttributeValue::F32(Z_MISS as f32)),
        (
            "render/identity",
            AttributeValue::Text(text(&metadata.identity)),
        ),
        ("render/scene", AttributeValue::Text(text(&metadata.scene))),
    ];
    for (name, value) in custom {
        attributes.other.insert(text(name), value);
    }
    if !metadata.course.is_default() {
        attributes.other.insert(
            text(COURSE_ATTRIBUTE),
            AttributeValue::Text(text(metadata.course.name())),
        );
    }

    let mut channels: Vec<(String, StoredChannel)> = layers
        .iter()
        .flat_map(|layer| {
            let half = options.half && layer.quantity.kind() == Kind::Colour;
            layer
                .channel_names()
                .into_iter()
                .map(move |name| (name, half))
        })
        .enumerate()
        .map(|(film_index, (name, half))| (name, StoredChannel { film_index, half }))
        .collect();
    channels.sort_by(|a, b| a.0.cmp(&b.0));
    let descriptions = channels
        .iter()
        .map(|(name, stored)| x::ChannelDescription {
            name: text(name),
            sample_type: if stored.half {
                x::SampleType::F16
            } else {
                x::SampleType::F32
            },
            quantize_linearly: false,
            sampling: x::Vec2(1, 1),
        })
        .collect();
    let mut image = x::ImageAttributes::new(x::IntegerBounds::new(at.display.0, at.display.1));
    image.chromaticities = Some(REC709_D65);
    let header = Header::new(text(""), at.size, descriptions)
        .with_encoding(
            options.compression.codec(),
            exr::meta::BlockDescription::ScanLines,
            x::LineOrder::Increasing,
        )
        .with_attributes(attributes)
        .with_shared_attributes(image);
    let stored = channels.into_iter().map(|(_, stored)| stored).collect();
    (header, stored)
}

/// Where a plain RGBA image's pixels sit: its size, the data window's top-left corner, and
/// the display window (top-left corner and size).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    pub size: (usize, usize),
    pub origin: (i32, i32),
    pub display: ((i32, i32), (usize, usize)),
}

/// Writes a plain linear RGBA image (alpha 1) with Rec.709 chromaticities: what `relight`
/// makes.
pub fn write_rgba(file: &mut File, at: Placement, pixels: &[DVec3]) -> Result<(), String> {
    let channel = |name: &str, values: Vec<f32>| x::AnyChannel {
        name: text(name),
        sample_data: x::FlatSamples::F32(values),
        quantize_linearly: false,
        sampling: x::Vec2(1, 1),
    };
    let plane = |c: usize| pixels.iter().map(|p| p.to_array()[c] as f32).collect();
    let mut channels = x::SmallVec::new();
    channels.push(channel("A", vec![1.0; pixels.len()]));
    channels.push(channel("B", plane(2)));
    channels.push(channel("G", plane(1)));
    channels.push(channel("R", plane(0)));
    let attributes = x::LayerAttributes {
        layer_position: x::Vec2(at.origin.0, at.origin.1),
        software_name: Some(text(&format!("whitted {}", env!("CARGO_PKG_VERSION")))),
        ..x::LayerAttributes::default()
    };
    let encoding = x::Encoding {
        compression: ExrCompression::Zip.codec(),
        blocks: x::Blocks::ScanLines,
        line_order: x::LineOrder::Increasing,
    };
    let layer = x::Layer::new(
        at.size,
        attributes,
        encoding,
        x::AnyChannels::sort(channels),
    );
    let bounds = x::IntegerBounds::new(at.display.0, at.display.1);
    let mut image = x::Image::new(x::ImageAttributes::new(bounds), layer);
    image.attributes.chromaticities = Some(REC709_D65);
    write_image(file, &image)
}

/// Writes any flat single-part image as a scanline EXR into `file` (positioned at its
/// start) through the same writer as renders, so that a merged render has the bytes of the
/// full one.
pub fn write_image(file: &mut File, image: &FlatImage) -> Result<(), String> {
    let header = image
        .layer_data
        .infer_headers(&image.attributes)
        .into_iter()
        .next()
        .ok_or("an EXR image without a layer")?;
    let compression = header.compression;
    let header = header.with_encoding(
        compression,
        exr::meta::BlockDescription::ScanLines,
        x::LineOrder::Increasing,
    );
    let mut stream = ExrStream::create(file, header)?;
    let rows = image.layer_data.size.1 as u32;
    stream.write_rows(rows, &|range| exr_block::pack_planes(image, range))?;
    stream.finish().map(|_| ())
}

/// Rec.709 primaries with a D65 white point: the linear sRGB the renderer works in.
const REC709_D65: x::attribute::Chromaticities = x::attribute::Chromaticities {
    red: x::Vec2(0.64, 0.33),
    green: x::Vec2(0.30, 0.60),
    blue: x::Vec2(0.15, 0.06),
    white: x::Vec2(0.3127, 0.3290),
};

/// World space is camera space: the course's camera sits at the origin looking along +z.
const IDENTITY: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

fn matrix(m: &[[f64; 4]; 4]) -> x::attribute::Matrix4x4 {
    let mut out = [0.0f32; 16];
    for (o, v) in out.iter_mut().zip(m.iter().flatten()) {
        *o = *v as f32;
    }
    out
}

/// OpenEXR strings are bytes; we store UTF-8, as OpenImageIO and OpenEXR read them. (The
/// crate's checked constructor would panic on a non-Latin-1 file name.)
fn text(s: &str) -> Text {
    Text::from_slice_unchecked(s.as_bytes())
}

fn clamp_i32(v: u32) -> i32 {
    i32::try_from(v).unwrap_or(i32::MAX)
}
