//! The render plan: one value built from the command line and the loaded scene that makes
//! every check (size, region, samples, layers, threads, memory, output paths, EXR names)
//! before any file is touched. `whitted render` builds it, then only runs it.

use std::path::{Path, PathBuf};

use crate::openexr::MAX_CHANNEL_NAME;
use crate::output::destination::{same_file, STDOUT};
use crate::output::exr::ExrOptions;
use crate::output::png::PngEncoding;
use whitted_core::error::{Error, Result};
use whitted_core::frame::{Frame, FrameSpec};
use whitted_core::memory;
use whitted_core::render::strip_rows;
use whitted_core::scene::Scene;
use whitted_core::tonemap::ToneMap;

/// Most worker threads accepted: far more than any machine has cores; beyond it a typo
/// would spawn threads for minutes.
pub const MAX_THREADS: usize = 1024;

/// How the PNG is to be encoded, as asked (docs/tonemap.md); checked into a `PngEncoding`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToneRequest {
    pub tonemap: ToneMap,
    pub exposure: f64,
    pub depth: u8,
    pub dither: bool,
}

impl ToneRequest {
    /// The PNG encoding asked for, or why it cannot be had.
    pub fn encoding(&self) -> Result<PngEncoding> {
        if self.dither && !self.tonemap.srgb_encoded() {
            return Err(Error::Usage(
                "--dither needs an sRGB tone map such as --tonemap clamp \
                 (tick and sigmoid are the course's exact, undithered outputs)"
                    .into(),
            ));
        }
        if self.dither && self.depth == 16 {
            return Err(Error::Usage(
                "--dither applies to 8-bit PNGs only (16 bits need none)".into(),
            ));
        }
        Ok(PngEncoding {
            tonemap: self.tonemap,
            exposure: self.exposure,
            depth: self.depth,
            dither: self.dither,
        })
    }
}

/// A render as the command line asks for it, unchecked.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderRequest {
    /// The scene file; `None` for the embedded tick2 scene.
    pub input: Option<PathBuf>,
    /// The PNG to write (`-` for standard output); `None` for no PNG.
    pub png: Option<PathBuf>,
    pub exr: Option<PathBuf>,
    /// The frame; its `aovs` are the layers the EXR is to hold.
    pub frame: FrameSpec,
    pub exr_options: ExrOptions,
    pub tone: ToneRequest,
    /// Worker threads; `None` for every core.
    pub threads: Option<usize>,
    /// Record the render time in the EXR.
    pub stamp_date: bool,
}

/// A checked render: what to compute and where it goes.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderPlan {
    pub frame: Frame,
    /// Whether the scene is the embedded tick2 (no `--input`).
    pub embedded_scene: bool,
    pub png: Option<PathBuf>,
    pub exr: Option<PathBuf>,
    pub encoding: PngEncoding,
    pub exr_options: ExrOptions,
    pub threads: Option<usize>,
    pub stamp_date: bool,
    /// Rows rendered and written at a time: whole EXR blocks, and what memory was checked for.
    pub strip_rows: u32,
}

impl RenderPlan {
    /// Checks `request` against `scene`. The layer selection is checked even without an EXR,
    /// so a misspelt name is never silently ignored; without an EXR no layer is kept (the
    /// film's f64 beauty is what the PNG is made from).
    pub fn new(request: &RenderRequest, scene: &Scene) -> Result<Self> {
        let encoding = request.tone.encoding()?;
        let frame = Frame::new(scene, &request.frame)?;
        let frame = if request.exr.is_some() {
            check_channel_names(&frame)?;
            frame
        } else {
            // The PNG is made from the film's f64 beauty, which every film has.
            frame.without_layers()
        };
        if let Some(n) = request.threads {
            if n == 0 || n > MAX_THREADS {
                return Err(Error::Usage(format!(
                    "--threads must be between 1 and {MAX_THREADS}, got {n}"
                )));
            }
        }
        let (width, height) = (frame.region().width(), frame.region().height());
        let channels = frame.channel_count();
        let strip_rows = strip_rows(width, channels, exr_block_lines(request));
        memory::check(
            memory::render_bytes(width, height, channels, request.exr.is_some(), strip_rows),
            memory::available_bytes(),
            &format!(
                "a {width}x{height} render with {channels} channels (try a smaller size or \
                 --aovs beauty)"
            ),
        )?;
        check_outputs(request)?;
        Ok(RenderPlan {
            frame,
            embedded_scene: request.input.is_none(),
            png: request.png.clone(),
            exr: request.exr.clone(),
            encoding,
            exr_options: request.exr_options,
            threads: request.threads,
            stamp_date: request.stamp_date,
            strip_rows,
        })
    }
}

/// Lines per block of the EXR asked for, if any.
fn exr_block_lines(request: &RenderRequest) -> Option<u32> {
    request
        .exr
        .as_ref()
        .map(|_| request.exr_options.compression.lines_per_block())
}

/// Every channel name fits OpenEXR's limit. Scene light names are short enough that this
/// holds for every scene the loader accepts; the check keeps the writer's rule with the writer.
fn check_channel_names(frame: &Frame) -> Result<()> {
    let long = frame
        .layers()
        .iter()
        .flat_map(|l| l.channel_names())
        .find(|name| name.len() > MAX_CHANNEL_NAME);
    match long {
        Some(name) => Err(Error::Usage(format!(
            "the EXR channel `{name}` is longer than OpenEXR's {MAX_CHANNEL_NAME} characters \
             (give the light a shorter name)"
        ))),
        None => Ok(()),
    }
}

/// Outputs that cannot all be written as asked: an EXR to stdout, two outputs on one file,
/// or an output over the scene being read.
fn check_outputs(request: &RenderRequest) -> Result<()> {
    let to_stdout = |p: &Path| p.as_os_str() == STDOUT;
    let png = request.png.as_deref();
    if let Some(exr) = &request.exr {
        if to_stdout(exr) {
            return Err(Error::Usage(
                "--exr cannot write to standard output (an EXR is written with seeks); give a file name"
                    .into(),
            ));
        }
        if png.is_some_and(|png| !to_stdout(png) && same_file(png, exr)) {
            return Err(Error::Usage(format!(
                "--output and --exr are both `{}`; give them different paths",
                exr.display()
            )));
        }
    }
    if let Some(input) = &request.input {
        for output in png.into_iter().chain(request.exr.as_deref()) {
            if !to_stdout(output) && same_file(output, input) {
                return Err(Error::Usage(format!(
                    "the output `{}` is the scene file being read; give another path",
                    output.display()
                )));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request() -> RenderRequest {
        RenderRequest {
            input: None,
            png: Some("out.png".into()),
            exr: None,
            frame: FrameSpec::default(),
            exr_options: ExrOptions::default(),
            tone: ToneRequest {
                tonemap: ToneMap::Tick,
                exposure: 0.0,
                depth: 8,
                dither: false,
            },
            threads: None,
            stamp_date: false,
        }
    }

    fn scene() -> Scene {
        whitted_core::scene::parse_str("t.xml", whitted_core::scene::EMBEDDED_TICK2).expect("tick2")
    }

    #[test]
    fn without_an_exr_only_the_beauty_is_kept_but_the_selection_is_checked() {
        let plan = RenderPlan::new(&request(), &scene()).expect("plan");
        assert!(plan.frame.layers().is_empty());
        let mut bad = request();
        bad.frame.aovs = "direct,nope".into();
        assert!(RenderPlan::new(&bad, &scene()).is_err());
        let mut exr = request();
        exr.exr = Some("out.exr".into());
        assert!(
            RenderPlan::new(&exr, &scene())
                .expect("plan")
                .frame
                .layers()
                .len()
                == 20
        );
    }

    #[test]
    fn impossible_outputs_threads_and_encodings_are_refused() {
        let mut stdout_exr = request();
        stdout_exr.exr = Some("-".into());
        let mut same = request();
        same.exr = Some("out.png".into());
        let mut threads = request();
        threads.threads = Some(MAX_THREADS + 1);
        let mut dither = request();
        dither.tone.dither = true;
        for bad in [stdout_exr, same, threads, dither] {
            let err = RenderPlan::new(&bad, &scene()).unwrap_err();
            assert!(matches!(err, Error::Usage(_)), "{err}");
        }
    }
}
