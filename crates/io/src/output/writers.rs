//! The outputs of one render, fed strip by strip as the renderer finishes them: the PNG's
//! rows and the EXR's blocks, written side by side on the render's threads.

use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::output::atomic::AtomicFile;
use crate::output::destination::Destination;
use crate::output::exr::{header, ExrMetadata, ExrOptions, Placement};
use crate::output::exr_block::{self, StoredChannel};
use crate::output::exr_stream::ExrStream;
use crate::output::png::{PngEncoding, PngStream};
use whitted_core::aov::Layer;
use whitted_core::error::{Error, Result};
use whitted_core::film::Film;

/// The render's EXR being written, and how its channels are stored.
struct ExrOutput<'a> {
    stream: ExrStream<'a>,
    stored: Vec<StoredChannel>,
    path: PathBuf,
}

/// The outputs of one render, fed strip by strip.
pub struct Writers<'a> {
    png: Option<(PngStream, PathBuf)>,
    exr: Option<ExrOutput<'a>>,
}

/// What a render's writers write, as plain data the render command builds: where the pixels
/// sit, the layers, how the PNG is encoded, how the EXR is stored and what its header records
/// (`None` without an EXR).
pub struct Outputs<'a> {
    pub placement: Placement,
    pub layers: &'a [Layer],
    pub encoding: PngEncoding,
    pub exr_options: ExrOptions,
    pub metadata: Option<ExrMetadata>,
}

impl<'a> Writers<'a> {
    pub fn open(
        outputs: &Outputs,
        png: Option<&mut Destination>,
        exr_file: Option<&'a mut AtomicFile>,
    ) -> Result<Self> {
        let at = outputs.placement;
        let (width, height) = (at.size.0 as u32, at.size.1 as u32);
        let png = png
            .map(|png| Ok((png.stream_png(width, height, outputs.encoding)?, png.path())))
            .transpose()?;
        let exr = match (exr_file, &outputs.metadata) {
            (Some(file), Some(metadata)) => {
                let path = file.target().to_path_buf();
                let (header, stored) = header(at, outputs.layers, outputs.exr_options, metadata);
                let stream =
                    ExrStream::create(file.file(), header).map_err(|msg| exr_error(&path, msg))?;
                Some(ExrOutput {
                    stream,
                    stored,
                    path,
                })
            }
            _ => None,
        };
        Ok(Writers { png, exr })
    }

    pub fn write(&mut self, strip: &Film) -> Result<()> {
        let (png, exr) = (&mut self.png, &mut self.exr);
        let (png_written, exr_written) = rayon::join(
            || {
                png.as_mut().map_or(Ok(()), |(p, path)| {
                    p.write_rows(&strip.beauty).map_err(|e| png_error(path, e))
                })
            },
            || {
                exr.as_mut().map_or(Ok(()), |e| {
                    let stored = &e.stored;
                    let pack = |rows| exr_block::pack(strip, rows, stored);
                    let written = e.stream.write_rows(strip.height, &pack);
                    written.map_err(|msg| exr_error(&e.path, msg))
                })
            },
        );
        exr_written?;
        png_written
    }

    /// Completes both files; returns the EXR's share of the threads' time (packing,
    /// compressing and writing, summed over threads: it overlaps the render).
    pub fn finish(self) -> Result<Duration> {
        let mut exr_time = Duration::ZERO;
        if let Some(exr) = self.exr {
            let finished = exr.stream.finish();
            exr_time = finished.map_err(|msg| exr_error(&exr.path, msg))?;
        }
        if let Some((png, path)) = self.png {
            png.finish().map_err(|e| png_error(&path, e))?;
        }
        Ok(exr_time)
    }
}

fn exr_error(path: &Path, msg: String) -> Error {
    Error::Exr {
        path: path.to_path_buf(),
        msg,
    }
}

fn png_error(path: &Path, e: png::EncodingError) -> Error {
    Error::Png {
        path: path.to_path_buf(),
        msg: e.to_string(),
    }
}
