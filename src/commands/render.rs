//! `whitted render` (and the bare `whitted ...` tick command line): scene -> plan -> film ->
//! files. Every check is the plan's; this file runs it and reports.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::cli::RenderArgs;
use crate::error::{Error, Result};
use crate::film::Film;
use crate::output::atomic::AtomicFile;
use crate::output::destination::{Destination, STDOUT};
use crate::output::exr::{header, Placement};
use crate::output::exr_block::{self, StoredChannel};
use crate::output::exr_stream::ExrStream;
use crate::output::png::PngStream;
use crate::plan::RenderPlan;
use crate::progress::Progress;
use crate::render::{render_strips, RenderStats};
use crate::render_record;
use crate::scene::{self, Input};

pub fn run(args: &RenderArgs) -> Result<()> {
    let started = Instant::now();
    let input = scene::load_input(args.input.as_deref())?;
    let load_time = started.elapsed();
    let scene = &input.scene;
    let plan = RenderPlan::new(&args.request(), scene)?;
    // Open outputs before rendering, so that an unwritable path fails in milliseconds.
    let mut png = plan.png.as_deref().map(Destination::open).transpose()?;
    let mut exr_file = plan.exr.as_deref().map(AtomicFile::create).transpose()?;

    let progress = Progress::new(u64::from(plan.frame.region.height()), args.quiet);
    let started = Instant::now();
    // Both writers take each strip as it is finished, into temporary files: then rename, so
    // that there are all outputs or none.
    let (stats, exr_time) = with_threads(plan.threads, || -> Result<(RenderStats, Duration)> {
        let mut writers = Writers::open(&plan, &input, png.as_mut(), exr_file.as_mut())?;
        let stats = render_strips(
            scene,
            &plan.frame,
            plan.strip_rows,
            &|n| progress.advance(n),
            &mut |strip| writers.write(strip),
        )?;
        let exr_time = writers.finish()?;
        Ok((stats, exr_time))
    })??;
    progress.finish();
    let render_time = started.elapsed();
    if stats.non_finite > 0 {
        eprintln!(
            "warning: {} non-finite layer values (NaN or infinity) were written as 0",
            stats.non_finite
        );
    }
    // Ctrl-C while the files were being written: drop them rather than publish them.
    crate::interrupt::check()?;
    if let Some(file) = exr_file {
        file.commit()?;
    }
    if let Some(png) = png {
        png.commit()?;
    }

    if !args.quiet {
        let layers = plan.frame.layers.len();
        let times = Times {
            load: load_time,
            render: render_time,
            exr: exr_time,
        };
        eprintln!("{}", summary(&plan, &stats, layers, times));
    }
    Ok(())
}

/// The render's EXR being written, and how its channels are stored.
struct ExrOutput<'a> {
    stream: ExrStream<'a>,
    stored: Vec<StoredChannel>,
    path: PathBuf,
}

/// The outputs of one render, fed strip by strip.
struct Writers<'a> {
    png: Option<(PngStream, PathBuf)>,
    exr: Option<ExrOutput<'a>>,
    /// Time spent packing, compressing and writing EXR blocks.
    exr_time: Duration,
}

impl<'a> Writers<'a> {
    fn open(
        plan: &RenderPlan,
        input: &Input,
        png: Option<&mut Destination>,
        exr_file: Option<&'a mut AtomicFile>,
    ) -> Result<Self> {
        let region = plan.frame.region;
        let (width, height) = (region.width(), region.height());
        let png = png
            .map(|png| Ok((png.stream_png(width, height, plan.encoding)?, png.path())))
            .transpose()?;
        let exr = match exr_file {
            None => None,
            Some(file) => {
                let path = file.target().to_path_buf();
                let lights = input.scene.lights.iter().map(|l| l.name.clone()).collect();
                let metadata = render_record::metadata(plan, &input.name, &input.bytes, lights);
                let camera = &plan.frame.camera;
                let at = Placement {
                    size: (width as usize, height as usize),
                    origin: (region.x0 as i32, region.y0 as i32),
                    display: ((0, 0), (camera.width as usize, camera.height as usize)),
                };
                let (header, stored) = header(at, &plan.frame.layers, plan.exr_options, &metadata);
                let stream = ExrStream::create(file.file(), header).map_err(|msg| Error::Exr {
                    path: path.clone(),
                    msg,
                })?;
                Some(ExrOutput {
                    stream,
                    stored,
                    path,
                })
            }
        };
        Ok(Writers {
            png,
            exr,
            exr_time: Duration::ZERO,
        })
    }

    fn write(&mut self, strip: &Film) -> Result<()> {
        let (png, exr) = (&mut self.png, &mut self.exr);
        let (png_written, exr_written) = rayon::join(
            || {
                png.as_mut()
                    .map(|(p, path)| {
                        p.write_rows(&strip.beauty).map_err(|e| Error::Png {
                            path: path.clone(),
                            msg: e.to_string(),
                        })
                    })
                    .transpose()
            },
            || {
                let started = Instant::now();
                let written = exr.as_mut().map(|e| {
                    let stored = &e.stored;
                    let pack = |rows| exr_block::pack(strip, rows, stored);
                    e.stream
                        .write_rows(strip.height, &pack)
                        .map_err(|msg| Error::Exr {
                            path: e.path.clone(),
                            msg,
                        })
                });
                (written.transpose(), started.elapsed())
            },
        );
        self.exr_time += exr_written.1;
        exr_written.0?;
        png_written?;
        Ok(())
    }

    /// Completes both files; returns the EXR writing time.
    fn finish(self) -> Result<Duration> {
        let started = Instant::now();
        if let Some(exr) = self.exr {
            let path = exr.path;
            exr.stream
                .finish()
                .map_err(|msg| Error::Exr { path, msg })?;
        }
        if let Some((png, path)) = self.png {
            png.finish().map_err(|e| Error::Png {
                path,
                msg: e.to_string(),
            })?;
        }
        Ok(self.exr_time + started.elapsed())
    }
}

/// Runs `work` on a pool of `threads` workers, or on rayon's global pool (all cores).
fn with_threads<T: Send>(threads: Option<usize>, work: impl FnOnce() -> T + Send) -> Result<T> {
    match threads {
        None => Ok(work()),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(|pool| pool.install(work))
            .map_err(|e| Error::Usage(format!("cannot start {n} worker threads: {e}"))),
    }
}

/// How long the phases of a render took, for the summary line.
struct Times {
    load: Duration,
    /// Hierarchy build, tracing and writing, which overlap.
    render: Duration,
    /// Packing, compressing and writing EXR blocks (on other cores while strips render).
    exr: Duration,
}

fn summary(plan: &RenderPlan, stats: &RenderStats, layers: usize, times: Times) -> String {
    let seconds = times.render.as_secs_f64();
    let rate = stats.rays as f64 / seconds.max(1e-9) / 1e6;
    let mut outputs = Vec::new();
    if let Some(exr) = &plan.exr {
        outputs.push(format!(
            "{} ({layers} layers, written in {:.2} s)",
            exr.display(),
            times.exr.as_secs_f64()
        ));
    }
    if let Some(png) = &plan.png {
        outputs.push(if png.as_os_str() == STDOUT {
            "standard output".to_string()
        } else {
            png.display().to_string()
        });
    }
    let target = if outputs.is_empty() {
        String::new()
    } else {
        format!(" -> {}", outputs.join(", "))
    };
    let frame = &plan.frame;
    let bounces = frame.trace.bounces;
    format!(
        "whitted: {}x{}, {} spp, {bounces} bounce{}, {} rays in {seconds:.2} s ({rate:.1} Mrays/s, \
         scene loaded in {:.2} s, hierarchy built in {:.2} s){target}",
        frame.region.width(),
        frame.region.height(),
        frame.spp,
        if bounces == 1 { "" } else { "s" },
        stats.rays,
        times.load.as_secs_f64(),
        stats.hierarchy_time.as_secs_f64(),
    )
}
